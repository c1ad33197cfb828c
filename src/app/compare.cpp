// SPDX-License-Identifier: Apache-2.0
// phasor — `phasor compare` (compare.h, docs/compare.md). The scene is parsed once and built once
// per integrator (any integrator of the registry, or one the scene defines by name: a new
// integrator joins without changes here). Each run renders in-process with the render loop's own
// cancellation: at the end of a time budget, or on Ctrl-C. Between the render loop's passes the
// film is resolved at roughly geometric sample counts for the convergence plot. Every output is
// staged at the end and committed together (core/image/output_file.h).

#include "app/compare.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "app/bytes.h"
#include "app/compare_report.h"
#include "app/distributed.h"
#include "app/plot.h"
#include "app/profile.h"
#include "app/render_common.h"
#include "core/image/image_io.h"

namespace phasor {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Samples per pixel asked of a sampling integrator in an equal-time run: far more than any budget
// reaches (the budget stops it), and not a perfect square, so that detectors do not lay a lattice
// over the pixel (detector.h StratifiedPixelSample) that a stopped render would only partly visit.
constexpr int TimeModeSpp = (1 << 25) + 1;

// Sets `stop` when the time budget is spent (budget > 0) or a stop was requested, polling every
// 5 ms from its own thread, so that a render is stopped within a pixel's batch of the deadline.
// Extend moves the deadline (time spent on snapshots does not count against the budget).
class Watchdog {
  public:
    Watchdog(double budget, const std::atomic<bool> *stopRequest)
        : start_(Clock::now()),
          deadline_(start_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(budget))) {
        thread_ = std::thread([this, budget, stopRequest] {
            std::unique_lock<std::mutex> lock(mutex_);
            while (!done_) {
                cv_.wait_for(lock, std::chrono::milliseconds(5));
                if ((stopRequest && stopRequest->load()) || (budget > 0 && Clock::now() >= deadline_))
                    stop_.store(true);
            }
        });
    }
    ~Watchdog() {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            done_ = true;
        }
        cv_.notify_all();
        thread_.join();
    }
    const std::atomic<bool> *Flag() const { return &stop_; }
    Clock::time_point Start() const { return start_; }
    void Extend(double seconds) {
        std::lock_guard<std::mutex> lock(mutex_);
        deadline_ += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    }

  private:
    Clock::time_point start_;
    Clock::time_point deadline_;
    std::atomic<bool> stop_{false};
    std::mutex mutex_;
    std::condition_variable cv_;
    bool done_ = false;
    std::thread thread_;
};

// A file name from an integrator's name (letters, digits, '_' and '-' kept).
std::string FileStem(const std::string &name) {
    std::string s;
    for (char c : name) s += std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' ? c : '_';
    return s.empty() ? "run" : s;
}

// Renders one run for the program: RenderCompareRun with the command line's options, a progress bar
// and the run's messages on stderr.
// With `shared`, every MPI rank renders the run's tiles together (rank 0 keeps the time budget and
// fills `run`).
void RenderRun(CompareRun &run, const Scene &scene, const CliOptions &o, int index, int count, double budget,
               SnapshotContext &snap, bool shared) {
    const Integrator &integrator = scene.GetIntegrator();
    const Detector &det = scene.GetDetector();
    CompareRunSettings s;
    s.options = OptionsFor(scene, o);
    s.budget = budget;
    s.scenePath = o.scene;
    s.stop = &StopFlag();
    s.shared = shared;
    const bool timed = budget > 0 && !integrator.Deterministic();
    const std::string label = "[" + std::to_string(index) + "/" + std::to_string(count) + "] " + run.name;
    const bool bar = !o.quiet && isatty(2) && dist::Root();
    if (bar)
        s.options.progress =
            ProgressBar(label, integrator.Deterministic(), (long long)det.Width() * det.Height(), timed ? budget : 0);
    if (!timed) s.options.warn = [&](const std::string &w) { std::cerr << (bar ? "\r" : "") << "warning: " << w << "\n"; };
    RenderStats st;
    try {
        st = RenderCompareRun(run, scene, s, snap);
    } catch (const Error &e) {
        if (bar) std::cerr << "\n";
        std::cerr << label << ": failed:\n";
        PrintError(e);
        return;
    }
    if (bar) std::cerr << "\n";
    if (shared && !dist::Root()) return;  // rank 0 holds the run
    if (!run.image) {  // rs stopped before it had anything honest to show
        std::cerr << label << ": interrupted (" << st.work << "); no image\n";
        return;
    }
    if (run.snapshotsCut)
        std::cerr << "warning: " << run.name << ": the convergence plot stops at " << run.snapshots.back().spp
                  << " spp (its snapshots would not fit in memory; give --reference to compare them at once)\n";
    if (!o.quiet) {
        std::cerr << label << ": " << (run.status == CompareRun::Status::Interrupted ? "interrupted: " : "");
        if (run.deterministic)
            std::cerr << st.work;
        else
            std::cerr << st.sppReached << " spp";
        std::cerr << " in " << FormatDuration(run.seconds) << (timed ? " (the time budget)" : "");
        if (!run.deterministic && run.seconds > 0) {
            char rate[48];
            std::snprintf(rate, sizeof rate, " (%.3g samples/s)",
                          double(st.sppReached) * det.Width() * det.Height() / run.seconds);
            std::cerr << rate;
        }
        std::cerr << "\n";
        PrintRenderWarnings(scene, st, *run.image);
    }
}

}  // namespace

std::vector<std::string> IntegratorChoices(const SceneDesc &desc) {
    std::vector<std::string> names = Registry<Integrator>::Names();
    for (const SceneEntity &e : desc.entities)
        if (e.keyword == "Integrator" && !e.name.empty() &&
            std::find(names.begin(), names.end(), e.name) == names.end())
            names.push_back(e.name);
    return names;
}

RenderStats RenderCompareRun(CompareRun &run, const Scene &scene, const CompareRunSettings &s, SnapshotContext &snap) {
    const Integrator &integrator = scene.GetIntegrator();
    const Detector &det = scene.GetDetector();
    run.deterministic = integrator.Deterministic();
    RenderOptions opt = s.options;
    const double budget = s.budget;
    const bool timed = budget > 0 && !run.deterministic;  // rs takes no samples: it runs to the end
    if (timed) opt.spp = TimeModeSpp;
    run.sppRequested = opt.spp;
    const bool helper = s.shared && !dist::Root();
    Watchdog watchdog(timed && !helper ? budget : 0, s.stop);
    opt.cancel = watchdog.Flag();
    std::unique_ptr<dist::Share> share = s.shared ? dist::MakeShare(watchdog.Flag()) : nullptr;
    if (share) {
        opt.work = share.get();
        opt.cancel = share->Stop();
    }

    Film film(det.Width(), det.Height(), det.Response());
    // Snapshots of `intensity` at roughly geometric sample counts (×1.5), taken between passes;
    // the time they take is left out of the times reported.
    const auto start = Clock::now();
    double snapshotCost = 0;
    int next = 1;
    const double pixels = double(det.Width()) * det.Height();
    // (the reference run itself needs none)
    const bool snapshots = !run.deterministic && !run.isReferenceRun;
    const std::function<void(int, int)> progress = s.options.progress;
    opt.progress = [&](int done, int total) {
        if (progress) progress(done, total);
        if (!snapshots || run.snapshotsCut || done < next) return;
        if (!snap.reference && snap.bytesLeft < pixels * sizeof(float)) {
            run.snapshotsCut = true;
            return;
        }
        const auto t0 = Clock::now();
        const Image img = film.Resolve();
        CompareSnapshot sn;
        sn.spp = done;
        sn.seconds = std::chrono::duration<double>(t0 - start).count() - snapshotCost;
        const std::vector<double> values = ChannelValues(img, "intensity");
        if (snap.reference) {
            sn.metrics = ErrorMetrics(values, *snap.reference);
        } else {
            sn.intensity.assign(values.begin(), values.end());
            snap.bytesLeft -= pixels * sizeof(float);
        }
        run.snapshots.push_back(std::move(sn));
        next = std::max(done + 1, int(std::ceil(done * 1.5)));
        const double cost = std::chrono::duration<double>(Clock::now() - t0).count();
        snapshotCost += cost;
        if (timed) watchdog.Extend(cost);
    };

    RenderStats st;
    try {
        st = integrator.Render(scene, film, opt);
    } catch (const Error &e) {
        run.status = CompareRun::Status::Failed;
        run.error = e.Message();
        throw;
    }
    const int remoteSignal = share ? share->Signal() : 0;
    share.reset();
    if (helper) return st;  // rank 0 holds the run
    // Equal time: the time since the budget started (the watchdog's clock, which the deadline is
    // on), so that a run stopped by its budget reports at least the budget; otherwise the render's own.
    const double spent = timed ? std::chrono::duration<double>(Clock::now() - watchdog.Start()).count() : st.seconds;
    run.seconds = std::max(0.0, spent - snapshotCost);
    run.sppReached = st.sppReached;
    run.work = st.work;
    // A run stopped by its time budget is complete; one stopped by a stop request (here or on
    // another rank) is not.
    const bool interrupted = st.cancelled && ((s.stop && s.stop->load()) || remoteSignal != 0);
    if (!st.hasImage) {  // rs stopped before it had anything honest to show
        run.status = CompareRun::Status::Interrupted;
        return st;
    }
    run.status = interrupted ? CompareRun::Status::Interrupted : CompareRun::Status::Done;
    Image img = film.Resolve();
    StampMetadata(img, scene, s.scenePath, opt, st);
    if (timed) img.metadata["phasor:time_budget_seconds"] = std::to_string(budget);
    run.intensity = ChannelValues(img, "intensity");
    run.variance = img.ChannelIndex("variance") >= 0 ? ChannelValues(img, "variance") : std::vector<double>{};
    if (snapshots && (run.snapshots.empty() || run.snapshots.back().spp != st.sppReached)) {
        CompareSnapshot last;
        last.spp = st.sppReached;
        last.seconds = run.seconds;
        if (snap.reference) last.metrics = ErrorMetrics(run.intensity, *snap.reference);
        else last.intensity.assign(run.intensity.begin(), run.intensity.end());  // (the image is kept anyway)
        run.snapshots.push_back(std::move(last));
    }
    run.image = std::move(img);
    return st;
}

namespace {

// A run as bytes, from the rank that rendered it (whole runs under MPI) to rank 0.
std::string SerializeRun(const CompareRun &r) {
    ByteWriter w;
    w.Put(int32_t(dist::Rank()));
    w.Put(int32_t(r.status));
    w.PutString(r.error);
    w.PutString(r.work);
    for (int v : {int(r.deterministic), r.sppRequested, r.sppReached, int(r.snapshotsCut), int(r.image.has_value())})
        w.Put(int32_t(v));
    w.Put(r.seconds);
    if (r.image) {
        w.Put(int32_t(r.image->width));
        w.Put(int32_t(r.image->height));
        w.PutStrings(r.image->channels);
        w.PutVector(r.image->data);
        w.PutMap(r.image->metadata);
    }
    w.PutVector(r.intensity);
    w.PutVector(r.variance);
    w.Put(uint64_t(r.snapshots.size()));
    for (const CompareSnapshot &snap : r.snapshots) {
        w.Put(int32_t(snap.spp));
        w.Put(snap.seconds);
        w.Put(int32_t(snap.metrics.has_value()));
        if (snap.metrics) w.Put(*snap.metrics);
        w.PutVector(snap.intensity);
    }
    return std::move(w.bytes);
}

// Fills `r` (its name and file are rank 0's) from SerializeRun's bytes; returns the rank that rendered it.
int DeserializeRun(const std::string &bytes, CompareRun &r) {
    ByteReader in(bytes);
    const int rank = in.Get<int32_t>();
    r.status = CompareRun::Status(in.Get<int32_t>());
    r.error = in.GetString();
    r.work = in.GetString();
    r.deterministic = in.Get<int32_t>() != 0;
    r.sppRequested = in.Get<int32_t>();
    r.sppReached = in.Get<int32_t>();
    r.snapshotsCut = in.Get<int32_t>() != 0;
    const bool hasImage = in.Get<int32_t>() != 0;
    r.seconds = in.Get<double>();
    r.image.reset();
    if (hasImage) {
        Image img;
        img.width = in.Get<int32_t>();
        img.height = in.Get<int32_t>();
        img.channels = in.GetStrings();
        img.data = in.GetVector<float>();
        img.metadata = in.GetMap();
        r.image = std::move(img);
    }
    r.intensity = in.GetVector<double>();
    r.variance = in.GetVector<double>();
    r.snapshots.resize(std::size_t(in.Get<uint64_t>()));
    for (CompareSnapshot &snap : r.snapshots) {
        snap.spp = in.Get<int32_t>();
        snap.seconds = in.Get<double>();
        if (in.Get<int32_t>()) snap.metrics = in.Get<CompareMetrics>();
        snap.intensity = in.GetVector<float>();
    }
    return rank;
}

}  // namespace

int RunCompare(const CliOptions &o) {
    const CliOptions::CompareOptions &c = o.compare;
    const std::string dir = !o.output.empty() ? o.output : "out/" + fs::path(o.scene).stem().string() + "_compare";
    // The scene, parsed once.
    Diagnostics diag(o.strict);
    std::optional<SceneDesc> desc;
    desc = ParseScene(o, diag);
    if (!desc || diag.HasErrors()) {
        if (desc)
            BuildScene(o, *desc, diag, "");  // report the build's errors too
        else {
            diag.Print(std::cerr, Colour());
            std::cerr << diag.ErrorCount() << " error" << (diag.ErrorCount() == 1 ? "" : "s") << " in '" << o.scene
                      << "'\n";
        }
        return 1;
    }
    // Every name must pick an integrator, before anything is rendered. `all`: every integrator of
    // the registry, in its order (a new integrator joins the comparison by being registered).
    const std::vector<std::string> choices = IntegratorChoices(*desc);
    const std::vector<std::string> integrators =
        c.integrators == std::vector<std::string>{"all"} ? Registry<Integrator>::Names() : c.integrators;
    std::vector<std::string> names = integrators;
    if (!c.referenceIntegrator.empty()) names.push_back(c.referenceIntegrator);
    for (const std::string &n : names)
        if (std::find(choices.begin(), choices.end(), n) == choices.end()) {
            const std::string sug = Suggest(n, choices);
            std::cerr << "error: unknown integrator '" << n << "'"
                      << (sug.empty() ? "" : "; did you mean '" + sug + "'?") << " (integrators:";
            for (const std::string &k : choices) std::cerr << " " << k;
            std::cerr << ")\n";
            return 1;
        }

    // A reference image, read and checked before rendering (its size once the detector is known).
    // Under MPI rank 0 alone reads it and writes the outputs.
    const bool root = dist::Root();
    CompareReference ref;
    std::optional<Image> refImage;
    int bad = 0;
    if (!c.reference.empty() && root) {
        try {
            refImage = ReadImage(c.reference);
            ref.values = ChannelValues(*refImage, "intensity");
        } catch (const Error &e) {
            std::cerr << "error: reference '" << c.reference << "': " << e.Message() << "\n";
            bad = 1;
        }
    }
    if (dist::Agree(bad)) return 1;

    // The output directory, created and tried before anything is rendered; removed again (if it
    // was made here and is still empty) when nothing is written.
    std::error_code ec;
    const bool dirExisted = fs::exists(dir, ec);
    struct RemoveIfEmpty {
        std::string dir;
        bool keep;
        ~RemoveIfEmpty() {
            std::error_code e;
            if (!keep && fs::is_empty(dir, e)) fs::remove(dir, e);
        }
    } cleanup{dir, dirExisted || !root};
    if (root) try {
            CheckWritable((fs::path(dir) / "index.html").string());
        } catch (const Error &e) {
            PrintError(e);
            bad = 1;
        }
    if (dist::Agree(bad)) return 1;

    std::vector<CompareRun> runs;
    if (!c.referenceIntegrator.empty()) {
        CompareRun r;
        r.name = c.referenceIntegrator;
        r.file = "reference_" + FileStem(r.name);
        r.isReferenceRun = true;
        runs.push_back(std::move(r));
    }
    for (const std::string &n : integrators) {
        CompareRun r;
        r.name = n;
        r.file = FileStem(n);
        runs.push_back(std::move(r));
    }
    if (!o.quiet) {
        std::cerr << "compare: " << o.scene << " with";
        for (const std::string &n : integrators) std::cerr << " " << n;
        if (c.seconds > 0)
            std::cerr << ", " << c.seconds << " s each";
        else if (o.spp > 0)
            std::cerr << ", " << o.spp << " spp each";
        else
            std::cerr << ", the scene's spp";
        std::cerr << " -> " << dir << "/\n";
    }

    // Snapshots for the convergence plot: compared at once with a reference image; else kept
    // (float per pixel) within a quarter of the available memory, at most 1 GB.
    SnapshotContext snap;
    snap.reference = refImage ? &ref.values : nullptr;
    snap.bytesLeft = std::min(1e9, AvailableMemory() / 4);

    InstallStopHandlers(!o.quiet && root);
    int width = 0, height = 0, sceneSpp = 0;
    bool radiometric = false;
    std::string detectorName;
    // The detector of the first run that builds sets the comparison's size: a reference image of
    // another size, or a film that does not fit in memory on any rank, stops it before rendering.
    auto firstScene = [&](const Scene &scene) {
        const Detector &det = scene.GetDetector();
        width = det.Width();
        height = det.Height();
        radiometric = det.Response().GetKind() == SensorResponse::Kind::Radiometric;
        detectorName = det.name;
        CliOptions plain = o;
        plain.spp = -1;
        sceneSpp = OptionsFor(scene, plain).spp;
        std::string why;
        if (refImage && (refImage->width != width || refImage->height != height)) {
            std::cerr << "error: reference '" << c.reference << "' is " << refImage->width << "x" << refImage->height
                      << " pixels but detector '" << det.name << "' renders " << width << "x" << height << "\n";
            why = "reference size";
        }
        if (why.empty()) try {
                CheckMemory(scene);
            } catch (const Error &e) {
                PrintError(e);
                why = e.Message();
            }
        if (dist::AllOk(why.empty(), why, &why)) return true;
        if (root && !why.empty()) std::cerr << "error: " << why << "\n";
        return false;
    };
    auto build = [&](CompareRun &run) {
        Diagnostics d(o.strict);
        auto scene = BuildScene(o, *desc, d, run.name);
        if (!scene) {
            run.status = CompareRun::Status::Failed;
            for (const Diagnostic &x : d.All())
                if (x.severity == Severity::Error) {
                    run.error = x.message;
                    break;
                }
        }
        return scene;
    };
    auto render = [&](std::size_t i, const Scene &scene, bool shared) {
        CompareRun &run = runs[i];
        const double budget = run.isReferenceRun ? 0 : c.seconds;
        CliOptions ro = o;
        if (run.isReferenceRun) ro.spp = c.referenceSpp;  // 0: the scene's
        RenderRun(run, scene, ro, int(i) + 1, int(runs.size()), budget, snap, shared);
        if (run.isReferenceRun && run.image && run.status == CompareRun::Status::Done) snap.reference = &run.intensity;
    };
    // Under MPI (docs/distributed.md): with more runs than ranks each rank renders whole runs and
    // rank 0 gathers them (if a run fits in a message to rank 0); else every run's tiles are shared
    // by all ranks, one run after another.
    bool whole = dist::Size() > 1 && int(runs.size()) > dist::Size();
    if (whole) {
        for (CompareRun &run : runs)
            if (auto scene = build(run)) {
                if (!firstScene(*scene)) {
                    RemoveStopHandlers();
                    return 1;
                }
                break;
            }
        for (CompareRun &run : runs) run.status = CompareRun::Status::NotRun;  // (built again where rendered)
        whole = double(width) * height <= dist::MaxWholeRenderPixels;
    }
    if (!whole) {
        for (std::size_t i = 0; i < runs.size(); ++i) {
            if (dist::Agree(StopFlag().load() ? 1 : 0)) break;  // rank 0's word; the rest stay NotRun
            auto scene = build(runs[i]);
            if (!scene) continue;
            if (width == 0 && !firstScene(*scene)) {
                RemoveStopHandlers();
                return 1;
            }
            render(i, *scene, dist::Size() > 1);
        }
    } else {
        dist::ForEachUnit(
            int(runs.size()),
            [&](int u) {
                if (auto scene = build(runs[std::size_t(u)])) render(std::size_t(u), *scene, false);
                return SerializeRun(runs[std::size_t(u)]);
            },
            [&](int u, std::string &&bytes) {
                CompareRun &run = runs[std::size_t(u)];
                const int rank = DeserializeRun(bytes, run);
                if (rank != 0 && !o.quiet)  // (rank 0's own runs said so as they ended)
                    std::cerr << "[" << u + 1 << "/" << runs.size() << "] " << run.name << ": rendered on rank " << rank
                              << (run.status == CompareRun::Status::Failed ? ": failed: " + run.error : "") << "\n";
            },
            &StopFlag());
    }
    if (!root) {
        RemoveStopHandlers();
        return dist::Agree(0);
    }

    // Nothing to show: every run failed (their errors are printed) or none finished.
    const bool any = std::any_of(runs.begin(), runs.end(), [](const CompareRun &r) { return r.image.has_value(); });
    if (!any) {
        RemoveStopHandlers();
        if (StopSignal()) {
            std::cerr << "interrupted before any integrator finished; nothing written\n";
            return dist::Agree(StoppedStatus());
        }
        std::cerr << "error: no integrator could render '" << o.scene << "'; nothing written\n";
        return dist::Agree(1);
    }

    // The reference: the image given, the reference run, else the best-converged run.
    if (refImage) {
        ref.description = "the image '" + c.reference + "'";
        ref.name = "reference image";
        ref.image = &*refImage;
    }
    ComputeErrors(runs, ref);

    CompareReport report;
    report.scene = o.scene;
    report.dir = dir;
    report.width = width;
    report.height = height;
    report.radiometric = radiometric;
    report.detector = detectorName;
    report.mode = c.seconds > 0 ? "equal time: " + FormatSeconds(c.seconds) + " per integrator"
                  : o.spp > 0   ? "equal samples: " + std::to_string(o.spp) + " spp per integrator"
                                : "equal samples: the scene's " + std::to_string(sceneSpp) + " spp per integrator";
    report.stopped = StopSignal() != 0;
    report.row = c.row;
    report.column = c.column;
    std::ostringstream cmd;
    cmd << "phasor compare " << o.scene << " --integrators ";
    for (std::size_t k = 0; k < c.integrators.size(); ++k) cmd << (k ? "," : "") << c.integrators[k];
    if (c.seconds > 0) cmd << " --time " << c.seconds;
    if (o.spp > 0) cmd << " --spp " << o.spp;
    if (!c.reference.empty()) cmd << " --reference " << c.reference;
    if (!c.referenceIntegrator.empty()) {
        cmd << " --reference-integrator " << c.referenceIntegrator;
        if (c.referenceSpp > 0) cmd << " --reference-spp " << c.referenceSpp;
    }
    for (const auto &[k, v] : o.defines) cmd << " -D " << k << "=" << v;
    if (o.seed >= 0) cmd << " --seed " << o.seed;
    if (!o.sampler.empty()) cmd << " --sampler " << o.sampler;
    if (c.row >= 0) cmd << " --row " << c.row;
    if (c.column >= 0) cmd << " --column " << c.column;
    cmd << " -o " << dir;
    report.command = cmd.str();

    std::vector<std::string> written;
    try {
        OutputFiles files;
        written = StageCompareOutputs(files, runs, ref, refImage ? &*refImage : nullptr, report);
        files.Commit();
    } catch (const Error &e) {
        RemoveStopHandlers();
        std::cerr << "error: " << e.Message() << "\n";
        return dist::Agree(1);
    }
    RemoveStopHandlers();
    const bool failed = std::any_of(runs.begin(), runs.end(),
                                    [](const CompareRun &r) { return r.status == CompareRun::Status::Failed; });
    if (!o.quiet) {
        std::cerr << "reference: " << ref.description << "\n";
        PrintSummary(std::cerr, runs);
        std::cerr << "wrote " << (fs::path(dir) / "index.html").string() << " and " << written.size() - 1
                  << " other files in " << dir << "/\n";
    }
    if (failed) {
        std::cerr << "error: ";
        bool first = true;
        for (const CompareRun &r : runs)
            if (r.status == CompareRun::Status::Failed) {
                std::cerr << (first ? "" : ", ") << r.name;
                first = false;
            }
        std::cerr << " failed (see above and the table)\n";
    }
    if (StopSignal()) return dist::Agree(StoppedStatus());
    return dist::Agree(failed ? 1 : 0);
}

}  // namespace phasor
