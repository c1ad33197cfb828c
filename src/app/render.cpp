// SPDX-License-Identifier: Apache-2.0
// phasor — `phasor render` (render.h; README "Using phasor", docs/distributed.md).
//
// One render: every rank loads the scene (errors are printed by rank 0; a rank that fails alone is
// named by rank 0), rank 0 checks the outputs, all ranks render together (tiles shared through
// dist::MakeShare), and rank 0 writes the EXR and PNG all or nothing and, with --checkpoint, the
// film's accumulators every SECONDS, on a stop and at the end. A sweep renders one image per value
// (per combination of values): with more renders than ranks each rank takes whole renders (rank 0
// writes them as they come back), else the renders run one after another with their tiles shared.
#include "app/render.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include "app/bytes.h"
#include "app/checkpoint.h"
#include "app/distributed.h"
#include "app/plot.h"
#include "app/render_common.h"
#include "core/image/image_io.h"
#include "core/image/output_file.h"
#include "core/render/scene.h"
#include "core/render/work.h"
#include "parser/parser.h"

namespace phasor {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// ---- outputs --------------------------------------------------------------------------------------

// The files of one render: OUT.exr, OUT.png beside it, OUT.dop.png with Stokes output.
struct OutputPaths {
    fs::path exr, png, dop;
    bool stokes = false;
};

// The paths for -o OUT (.exr or .png); false when OUT ends otherwise.
bool PathsFor(const std::string &out, bool stokes, OutputPaths *p) {
    p->exr = p->png = out;
    if (p->exr.extension() == ".png") p->exr.replace_extension(".exr");
    else p->png.replace_extension(".png");
    p->dop = p->png;
    p->dop.replace_extension(".dop.png");
    p->stokes = stokes;
    return p->exr.extension() == ".exr";
}

std::string OutputOf(const CliOptions &o, const Scene &scene) {
    const RenderSettings &rs = scene.Settings();
    return !o.output.empty() ? o.output
           : !rs.output.empty() ? rs.output
                                : "out/" + fs::path(o.scene).stem().string() + ".exr";
}

// Rank 0 before rendering: the outputs can be created (a long render never ends in an unwritable
// path). Prints the error and returns false otherwise.
bool CheckOutputs(const std::string &out, const OutputPaths &p, const std::string &checkpoint) {
    if (p.exr.extension() != ".exr") {
        std::cerr << "error: output '" << out << "' must end in .exr or .png\n";
        return false;
    }
    try {
        CheckWritable(p.exr.string());
        CheckWritable(p.png.string());
        if (p.stokes) CheckWritable(p.dop.string());
        if (!checkpoint.empty()) CheckWritable(checkpoint);
    } catch (const Error &e) {
        PrintError(e);
        return false;
    }
    return true;
}

// The exit status of a render stopped by signal `sig` (0: not stopped).
int StatusAfter(int sig) { return sig ? 128 + sig : 0; }

// Rank 0: writes a finished or stopped render's EXR and PNG all or nothing and says what was done.
// Returns 0, 1 after a failed write, or the status of the stop `sig`.
int WriteRender(const CliOptions &o, const Scene &scene, const Film &film, const RenderOptions &opt,
                const RenderStats &st, const OutputPaths &p, const std::string &label, int sig) {
    const Integrator &integrator = scene.GetIntegrator();
    const Detector &det = scene.GetDetector();
    if (!st.hasImage) {  // cancelled before anything honest could be written (rs)
        std::cerr << label << "interrupted: " << integrator.name << " " << st.work << "; no image written\n";
        return StatusAfter(sig ? sig : SIGINT);
    }
    Image img = ResolvedImage(film, scene, o.scene, opt, st);
    if (!o.run.resume.empty()) img.metadata["phasor:resumed_from"] = o.run.resume;
    const double stops = DisplayStops(det, img);
    StampDisplayExposure(img, det, stops);
    // The EXR and the PNG are written all or nothing (core/image/output_file.h): if either fails,
    // neither appears (and earlier files of those names are left as they were).
    std::string shown, dopWritten;
    try {
        OutputFiles files;
        WriteExr(files, p.exr.string(), img);
        shown = StageDisplayPng(files, p.png.string(), img,
                                det.Response().GetKind() == SensorResponse::Kind::Radiometric, integrator.name,
                                fs::path(o.scene).filename().string() + ": intensity", 0, stops);
        if (p.stokes && img.ChannelIndex("DoP") >= 0) {
            const SheetResult r = StageDegreeOfPolarizationPng(files, p.dop.string(), img);
            if (!r.textDrawn) std::cerr << "warning: " << r.textProblem << "; '" << p.dop.string() << "' has no text\n";
            dopWritten = p.dop.string();
        }
        files.Commit();
    } catch (const Error &e) {
        std::cerr << label << "error: " << e.Message() << "\n";
        return 1;
    }
    if (shown != p.png.string())
        std::cerr << "warning: " << MatplotlibMissing() << "; '" << p.png.string() << "' not drawn, its data is in '"
                  << shown << "'\n";
    if (!o.quiet) {
        std::cerr << label << (st.cancelled ? "interrupted: " : "");
        if (integrator.Deterministic())
            std::cerr << integrator.name << " " << st.work << " in " << FormatDuration(st.seconds) << "\n";
        else
            std::cerr << "rendered " << st.sppReached << " spp"
                      << (st.sppMax > st.sppReached ? " (" + std::to_string(st.sppMax) + " in some pixels)" : "")
                      << " in " << FormatDuration(st.seconds) << " with " << integrator.name << "\n";
        PrintRenderWarnings(scene, st, img);
        std::cerr << label << "wrote " << p.exr.string() << (dopWritten.empty() ? " and " : ", ") << shown
                  << (dopWritten.empty() ? "" : " and " + dopWritten) << "\n";
    }
    return StatusAfter(sig);
}

// The first error of a failed load, as Diagnostics formats it.
std::string FirstError(const Diagnostics &diag) {
    for (const Diagnostic &d : diag.All())
        if (d.severity == Severity::Error) return diag.Format(d);
    return "the scene did not load";
}

// ---- checkpoints ----------------------------------------------------------------------------------

// The command line of a resume, as text every rank applies (rank 0 read the checkpoint).
std::string CommandText(const CheckpointRender &r) {
    std::string s = "scene=" + r.scene + "\noutput=" + r.output + "\nintegrator=" + r.integratorName +
                    "\nsampler=" + r.sampler + "\nseed=" + std::to_string(r.seed) + "\nspp=" + std::to_string(r.spp) +
                    "\ncheckpoint=" + std::to_string(r.checkpointSeconds) + "\n";
    for (const auto &[name, value] : r.defines) s += "define=" + name + "=" + value + "\n";
    return s;
}

// What the command line of a resume leaves out is the checkpoint's: the scene, the -D values (all of
// them, unless some are given), --integrator, --sampler, --seed, --spp, -o and --checkpoint.
void ApplyCommand(const std::string &text, CliOptions &o) {
    std::istringstream in(text);
    std::vector<std::pair<std::string, std::string>> defines;
    const bool ownDefines = !o.defines.empty();
    for (std::string line; std::getline(in, line);) {
        const std::size_t eq = line.find('=');
        const std::string key = line.substr(0, eq), value = line.substr(eq + 1);
        if (key == "scene" && o.scene.empty()) o.scene = value;
        else if (key == "output" && o.output.empty()) o.output = value;
        else if (key == "integrator" && o.integrator.empty()) o.integrator = value;
        else if (key == "sampler" && o.sampler.empty()) o.sampler = value;
        else if (key == "seed" && o.seed < 0) o.seed = std::stoll(value);
        else if (key == "spp" && o.spp < 0) o.spp = std::stoi(value);
        else if (key == "checkpoint" && !(o.run.checkpoint > 0)) o.run.checkpoint = std::stod(value);
        else if (key == "define" && !ownDefines) {
            const std::size_t e2 = value.find('=');
            defines.emplace_back(value.substr(0, e2), value.substr(e2 + 1));
        }
    }
    if (!ownDefines) o.defines = defines;
}

// Writes a checkpoint of a sampling render's passes every `seconds` while they run (rank 0), and
// passes everything else on to the other ranks' share (or does it here).
class PeriodicCheckpoints final : public WorkShare {
  public:
    using Write = std::function<void(const TilePasses &)>;
    PeriodicCheckpoints(WorkShare *inner, double seconds, Write write)
        : inner_(inner), seconds_(seconds), write_(std::move(write)) {}
    ~PeriodicCheckpoints() override { StopTimer(); }
    bool Coordinates() const override { return !inner_ || inner_->Coordinates(); }
    void BeginTiles(TilePasses &passes) override {
        if (inner_) inner_->BeginTiles(passes);
        timer_ = std::thread([this, &passes] {
            std::unique_lock<std::mutex> lock(mutex_);
            for (;;) {
                const auto next = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                     std::chrono::duration<double>(seconds_));
                if (cv_.wait_until(lock, next, [&] { return done_; })) return;
                lock.unlock();
                write_(passes);
                lock.lock();
            }
        });
    }
    void EndTiles() override {
        StopTimer();
        if (inner_) inner_->EndTiles();
    }
    TileSource *HelperTiles(Film &film) override { return inner_ ? inner_->HelperTiles(film) : nullptr; }
    bool Batches(std::vector<double> &values, int units, const BatchFunction &compute,
                 const std::function<bool(int)> &done, const std::atomic<bool> *cancel) override {
        return inner_ ? inner_->Batches(values, units, compute, done, cancel)
                      : RunBatchesLocally(values, units, compute, done, cancel);
    }

  private:
    void StopTimer() {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            done_ = true;
        }
        cv_.notify_all();
        if (timer_.joinable()) timer_.join();
    }
    WorkShare *inner_;
    double seconds_;
    Write write_;
    std::mutex mutex_;
    std::condition_variable cv_;
    bool done_ = false;
    std::thread timer_;
};

// ---- one render -----------------------------------------------------------------------------------

// One render of `o` (with a sweep's defines) to `out` ("" = -o, the Render block's, else the
// default): every rank takes part, rank 0 writes. `label` starts rank 0's lines in a sweep.
// Returns the exit status, the same on every rank.
int RenderOnce(CliOptions o, const std::string &out, const std::string &label) {
    const bool root = dist::Root();
    // --resume: rank 0 reads the checkpoint; the command it records fills in what the command line
    // leaves out, on every rank.
    std::optional<Checkpoint> resume;
    if (!o.run.resume.empty()) {
        std::string command;
        int bad = 0;
        if (root) try {
                resume = ReadCheckpoint(o.run.resume);
                command = CommandText(resume->render);
            } catch (const Error &e) {
                PrintError(e);
                bad = 1;
            }
        if (dist::Agree(bad)) return 1;
        dist::Broadcast(command);
        ApplyCommand(command, o);
    }

    Diagnostics diag(o.strict);
    SceneDesc desc;
    std::unique_ptr<Scene> scene = Load(o, diag, &desc);
    std::string failure;
    if (!dist::AllOk(scene != nullptr, FirstError(diag), &failure)) {
        if (root && scene) std::cerr << "error: " << failure << "\n";
        return 1;
    }
    const Detector &det = scene->GetDetector();
    const Integrator &integrator = scene->GetIntegrator();
    const bool deterministic = integrator.Deterministic();
    RenderOptions opt = OptionsFor(*scene, o);
    const std::string output = out.empty() ? OutputOf(o, *scene) : out;
    OutputPaths paths;
    PathsFor(output, det.Polarization().stokes, &paths);
    const bool checkpoints = o.run.checkpoint > 0;
    const std::string ckptPath = checkpoints ? CheckpointPath(paths.exr.string()) : "";

    // What determines the image, for a checkpoint and for the one resumed.
    CheckpointRender now;
    if (checkpoints || resume) {
        now.version = PHASOR_VERSION;
        now.fingerprint = SceneFingerprint(desc);
        now.width = det.Width();
        now.height = det.Height();
        now.integrator = integrator.ToString();
        now.sampler = opt.sampler;
        now.seed = opt.seed;
        now.stokes = det.Polarization().stokes && integrator.Support().polarization;
        std::error_code ec;
        now.scene = fs::absolute(o.scene, ec).string();
        now.output = fs::absolute(paths.exr, ec).string();
        now.defines = o.defines;
        now.integratorName = o.integrator;
        now.spp = opt.spp;
        now.checkpointSeconds = o.run.checkpoint;
    }
    int status = 0;
    if (root) {
        if (deterministic && (checkpoints || resume)) {
            std::cerr << "error: " << integrator.name << " takes no samples: its field integral has no checkpoint "
                      << "(it is shared over MPI ranks instead; docs/distributed.md)\n";
            status = 1;
        } else if (!CheckOutputs(output, paths, ckptPath)) {
            status = 1;
        } else if (resume) {
            const std::string why = CheckpointMismatch(resume->render, now);
            long long most = 0;
            for (const Film::PixelState &px : resume->pixels) most = std::max(most, (long long)px.n);
            if (!why.empty()) {
                std::cerr << "error: checkpoint '" << o.run.resume << "' does not continue this render: " << why << "\n";
                status = 1;
            } else if (opt.spp < most) {
                std::cerr << "error: checkpoint '" << o.run.resume << "' has " << most
                          << " samples in some pixels; --spp " << opt.spp << " cannot continue it (give at least "
                          << most << ")\n";
                status = 1;
            } else if (det.StratifiesAcrossSamples() && !SameStratification(resume->render.spp, opt.spp)) {
                std::cerr << "warning: resuming a " << resume->render.spp << "-spp render to " << opt.spp
                          << " spp: detector '" << det.name
                          << "' lays its directions on a lattice of the sample count when it is a square (theory "
                             "§0 D4b), so the image is an unbiased estimate but not bit for bit a fresh "
                          << opt.spp << "-spp render\n";
            }
        }
    }
    if (dist::Agree(status)) return 1;
    try {
        CheckMemory(*scene);  // every rank holds a film
        failure.clear();
    } catch (const Error &e) {
        failure = e.Message();
        if (root) PrintError(e);
    }
    if (!dist::AllOk(failure.empty(), failure, &failure)) {
        if (root && !failure.empty()) std::cerr << "error: " << failure << "\n";
        return 1;
    }

    Film film(det.Width(), det.Height(), det.Response());
    if (resume && root) {
        if (resume->render.stokes) film.EnableStokes();
        film.SetPixels(0, 0, film.Width(), film.Height(), resume->pixels.data());
    }
    std::unique_ptr<dist::Share> share = dist::MakeShare(&StopFlag());
    if (share) {
        opt.work = share.get();
        opt.cancel = share->Stop();
    }
    // Checkpoints (rank 0): every `--checkpoint` seconds while the passes run, from a consistent
    // copy of the film (TilePasses::Snapshot).
    const auto start = Clock::now();
    const double baseSeconds = resume ? resume->seconds : 0;
    const long long baseRays = resume ? resume->rays : 0;
    const RenderCounters baseCounters = resume ? resume->counters : RenderCounters{};
    bool ckptWarned = false;
    auto writeCheckpoint = [&](Checkpoint &c) {
        c.render = now;
        c.rays += baseRays;
        c.counters += baseCounters;
        c.seconds = baseSeconds + std::chrono::duration<double>(Clock::now() - start).count();
        try {
            WriteCheckpoint(ckptPath, c);
            return true;
        } catch (const Error &e) {
            if (!ckptWarned) std::cerr << "\nwarning: " << e.Message() << " (the render goes on; the previous checkpoint stays)\n";
            ckptWarned = true;
            return false;
        }
    };
    std::unique_ptr<PeriodicCheckpoints> periodic;
    if (root && checkpoints) {
        periodic = std::make_unique<PeriodicCheckpoints>(opt.work, o.run.checkpoint, [&](const TilePasses &passes) {
            Checkpoint c;
            passes.Snapshot(c.pixels, &c.rays, &c.counters);
            writeCheckpoint(c);
        });
        opt.work = periodic.get();
    }
    const bool bar = root && !o.quiet && isatty(2);
    if (bar) opt.progress = ProgressBar(label, deterministic, (long long)det.Width() * det.Height());
    if (root) opt.warn = [&](const std::string &w) { std::cerr << (bar ? "\r" : "") << "warning: " << w << "\n"; };
    RenderStats st;
    try {
        st = integrator.Render(*scene, film, opt);
    } catch (const Error &e) {
        if (bar) std::cerr << "\n";
        if (root) PrintError(e);
        status = 1;
    }
    if (bar) std::fprintf(stderr, "\n");
    periodic.reset();
    const int sig = StopSignal() ? StopSignal() : share ? share->Signal() : 0;
    if (share && root) {  // who did what (docs/distributed.md): units of work by rank
        std::string by;
        for (long long c : share->WorkByRank()) by += (by.empty() ? "" : ",") + std::to_string(c);
        st.metadata["phasor:mpi_ranks"] = std::to_string(dist::Size());
        st.metadata["phasor:mpi_work"] = by;
    }
    share.reset();
    if (!root || status != 0) return dist::Agree(status);

    bool ckptWritten = false;
    if (checkpoints && st.hasImage) {  // the film as it ends: stopped, or finished (more spp later)
        Checkpoint c;
        c.pixels.resize(std::size_t(film.Width()) * std::size_t(film.Height()));
        film.GetPixels(0, 0, film.Width(), film.Height(), c.pixels.data());
        c.rays = st.rays;
        c.counters = st.counters;
        ckptWritten = writeCheckpoint(c);
    }
    if (resume) {  // the counts of the runs before
        st.rays += baseRays;
        st.counters += baseCounters;
        st.counters.ToMetadata(st.metadata);
        st.seconds += baseSeconds;
    }
    status = WriteRender(o, *scene, film, opt, st, paths, label, sig);
    if (ckptWritten && !o.quiet)
        std::cerr << label << "checkpoint " << ckptPath << " (" << st.sppReached << " spp; continue with: phasor render --resume "
                  << ckptPath << (st.cancelled ? "" : " --spp N") << ")\n";
    return dist::Agree(status);
}

// ---- sweeps ---------------------------------------------------------------------------------------

// A file-name-safe form of a value as written: double quotes dropped, every character but letters,
// digits and . _ + - replaced by '_'.
std::string FileSafe(const std::string &value) {
    std::string s;
    for (char c : value) {
        if (c == '"') continue;
        s += std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '+' || c == '-' ? c : '_';
    }
    return s;
}

// A whole render on whichever rank takes it, for rank 0 to write (the sweep's unit): its film's
// accumulators, its statistics, or the error that stopped it.
struct UnitResult {
    std::string error;
    RenderStats st;
    bool stokes = false;
    std::vector<Film::PixelState> pixels;
};

std::string Serialize(const UnitResult &r) {
    ByteWriter w;
    w.PutString(r.error);
    const RenderStats &s = r.st;
    for (int v : {s.sppReached, s.sppMax, int(s.cancelled), int(s.hasImage), int(r.stokes)}) w.Put(int32_t(v));
    w.PutString(s.work);
    w.PutMap(s.metadata);
    w.Put(s.seconds);
    w.Put(int64_t(s.invalidSamples));
    w.Put(int64_t(s.rays));
    w.Put(s.counters.n);
    w.PutVector(r.pixels);
    return std::move(w.bytes);
}

UnitResult Deserialize(const std::string &bytes) {
    UnitResult r;
    ByteReader in(bytes);
    r.error = in.GetString();
    RenderStats &s = r.st;
    s.sppReached = in.Get<int32_t>();
    s.sppMax = in.Get<int32_t>();
    s.cancelled = in.Get<int32_t>() != 0;
    s.hasImage = in.Get<int32_t>() != 0;
    r.stokes = in.Get<int32_t>() != 0;
    s.work = in.GetString();
    s.metadata = in.GetMap();
    s.seconds = in.Get<double>();
    s.invalidSamples = in.Get<int64_t>();
    s.rays = in.Get<int64_t>();
    s.counters.n = in.Get<decltype(s.counters.n)>();
    r.pixels = in.GetVector<Film::PixelState>();
    return r;
}

// Loads a sweep's scene without printing (its diagnostics were shown when the sweep was checked).
std::unique_ptr<Scene> LoadQuietly(const CliOptions &o, std::string *error) {
    Diagnostics diag(o.strict);
    diag.SetPermissive(o.permissive);
    ParseOptions parse;
    parse.defines = o.defines;
    std::unique_ptr<Scene> scene;
    try {
        if (auto desc = ParseSceneFile(o.scene, parse, diag); desc && !diag.HasErrors())
            scene = BuildSceneQuietly(o.scene, *desc, diag, o.integrator);
    } catch (const std::bad_alloc &) {  // (the parser's; BuildSceneQuietly reports the build's)
        scene.reset();
        *error = "out of memory while loading the scene";
        return nullptr;
    }
    if (!scene || diag.HasErrors()) {
        *error = FirstError(diag);
        return nullptr;
    }
    return scene;
}

// One whole render of a sweep on this rank alone, with all its threads.
std::string RenderWhole(const CliOptions &o) {
    UnitResult r;
    std::unique_ptr<Scene> scene = LoadQuietly(o, &r.error);
    if (scene) {
        const Detector &det = scene->GetDetector();
        Film film(det.Width(), det.Height(), det.Response());
        RenderOptions opt = OptionsFor(*scene, o);
        try {
            r.st = scene->GetIntegrator().Render(*scene, film, opt);
            r.st.metadata["phasor:mpi_rank"] = std::to_string(dist::Rank());  // who rendered it
            r.stokes = film.HasStokes();
            r.pixels.resize(std::size_t(film.Width()) * film.Height());
            film.GetPixels(0, 0, film.Width(), film.Height(), r.pixels.data());
        } catch (const Error &e) {
            r.error = e.Message();
        }
    }
    return Serialize(r);
}

int RunSweep(const CliOptions &o) {
    const bool root = dist::Root();
    const auto renders = SweepRenders(o.run.sweeps);
    const int n = int(renders.size());
    // Every render's scene loads, and no two renders share a file name, before anything renders
    // (rank 0; its diagnostics are printed once).
    const auto count = static_cast<std::size_t>(n);
    std::vector<CliOptions> runs(count);
    std::vector<std::string> outputs(count), labels(count);
    int status = 0;
    std::string base;
    double largest = 0;  // pixels of the largest render
    for (int i = 0; i < n; ++i) {
        CliOptions &r = runs[std::size_t(i)];
        r = o;
        r.run.sweeps.clear();
        for (const auto &d : renders[std::size_t(i)].first) r.defines.push_back(d);
        std::string what;
        for (const auto &[name, value] : renders[std::size_t(i)].first) what += (what.empty() ? "" : " ") + name + "=" + value;
        labels[std::size_t(i)] = "[" + std::to_string(i + 1) + "/" + std::to_string(n) + "] " + what + ": ";
    }
    if (root) {
        for (int i = 0; i < n && status == 0; ++i) {
            Diagnostics diag(o.strict);
            std::unique_ptr<Scene> scene = Load(runs[std::size_t(i)], diag);
            if (!scene) {
                std::cerr << "error: the sweep's render " << labels[std::size_t(i)] << "does not load; nothing rendered\n";
                status = 1;
                break;
            }
            if (i == 0) base = OutputOf(o, *scene);
            largest = std::max(largest, double(scene->GetDetector().Width()) * scene->GetDetector().Height());
            fs::path p(base);
            const std::string ext = p.extension() == ".png" ? ".exr" : p.extension().string();
            p.replace_extension();
            outputs[std::size_t(i)] = p.string() + renders[std::size_t(i)].second + ext;
            OutputPaths paths;
            PathsFor(outputs[std::size_t(i)], scene->GetDetector().Polarization().stokes, &paths);
            if (!CheckOutputs(outputs[std::size_t(i)], paths, "")) status = 1;
            for (int k = 0; k < i && status == 0; ++k)
                if (outputs[std::size_t(k)] == outputs[std::size_t(i)]) {
                    std::cerr << "error: the sweep's renders " << labels[std::size_t(k)] << "and "
                              << labels[std::size_t(i)] << "would both write '" << outputs[std::size_t(i)]
                              << "' (their values differ only in characters a file name cannot hold)\n";
                    status = 1;
                }
        }
    }
    if (dist::Agree(status)) return 1;
    for (std::string &out : outputs) dist::Broadcast(out);
    // Whole renders when there are more renders than ranks and each fits in a message to rank 0.
    const bool whole = dist::Agree(dist::Size() > 1 && n > dist::Size() && largest <= dist::MaxWholeRenderPixels) != 0;
    if (root && !o.quiet) {
        std::cerr << "sweep: " << n << " render" << (n == 1 ? "" : "s") << " of " << o.scene;
        if (dist::Size() > 1)
            std::cerr << (whole ? ", whole renders shared over " : ", each render's tiles shared over ") << dist::Size()
                      << " ranks";
        std::cerr << "\n";
    }
    int failed = 0, worst = 0;
    if (!whole) {
        for (int i = 0; i < n && !StopFlag().load(); ++i) {
            const int s = RenderOnce(runs[std::size_t(i)], outputs[std::size_t(i)], labels[std::size_t(i)]);
            if (s == 1) ++failed;
            worst = std::max(worst, s);
            if (s > 128) break;  // stopped by a signal
        }
    } else {
        // Whole renders: each rank renders with its own threads; rank 0 writes each as it comes back.
        dist::ForEachUnit(
            n, [&](int u) { return RenderWhole(runs[std::size_t(u)]); },
            [&](int u, std::string &&bytes) {
                const UnitResult r = Deserialize(bytes);
                const CliOptions &ro = runs[std::size_t(u)];
                const std::string &label = labels[std::size_t(u)];
                std::string error = r.error;
                std::unique_ptr<Scene> scene = error.empty() ? LoadQuietly(ro, &error) : nullptr;
                if (!scene) {
                    std::cerr << label << "error: " << error << "\n";
                    ++failed;
                    worst = std::max(worst, 1);
                    return;
                }
                const Detector &det = scene->GetDetector();
                Film film(det.Width(), det.Height(), det.Response());
                if (r.stokes) film.EnableStokes();
                film.SetPixels(0, 0, film.Width(), film.Height(), r.pixels.data());
                OutputPaths paths;
                PathsFor(outputs[std::size_t(u)], det.Polarization().stokes, &paths);
                const RenderOptions opt = OptionsFor(*scene, ro);
                const int s = WriteRender(ro, *scene, film, opt, r.st, paths, label,
                                          r.st.cancelled && StopSignal() ? StopSignal() : 0);
                if (s == 1) ++failed;
                worst = std::max(worst, s);
            },
            &StopFlag());
    }
    if (!root) return dist::Agree(0);
    if (failed > 0) std::cerr << "error: " << failed << " of " << n << " renders of the sweep failed (see above)\n";
    if (StopSignal()) worst = std::max(worst, StoppedStatus());
    return dist::Agree(worst);
}

}  // namespace

std::vector<std::pair<std::vector<std::pair<std::string, std::string>>, std::string>>
SweepRenders(const std::vector<std::pair<std::string, std::vector<std::string>>> &sweeps) {
    std::vector<std::pair<std::vector<std::pair<std::string, std::string>>, std::string>> out{{{}, ""}};
    for (const auto &[name, values] : sweeps) {
        std::vector<std::pair<std::vector<std::pair<std::string, std::string>>, std::string>> next;
        for (const auto &prefix : out)
            for (const std::string &v : values) {
                auto r = prefix;
                r.first.emplace_back(name, v);
                r.second += "-" + name + "=" + FileSafe(v);
                next.push_back(std::move(r));
            }
        out = std::move(next);
    }
    return out;
}

int RunRender(const CliOptions &o) {
    // The stop handlers stay installed until the outputs are written, so that a signal during the
    // writes cannot leave a temporary file behind. Every rank catches them (mpirun passes a Ctrl-C
    // on as SIGTERM to every rank); rank 0 alone says it is stopping.
    InstallStopHandlers(dist::Root() && !o.quiet);
    const int status = o.run.sweeps.empty() ? RenderOnce(o, "", "") : RunSweep(o);
    RemoveStopHandlers();
    return status;
}

}  // namespace phasor
