// SPDX-License-Identifier: Apache-2.0
// phasor — `phasor compare` (compare.h, docs/compare.md). The scene is parsed once and built once
// per integrator (any integrator of the registry, or one the scene defines by name: a new
// integrator joins without changes here). Each run renders in-process with the render loop's own
// cancellation: at the end of a time budget, or on Ctrl-C. Between the render loop's passes the
// film is resolved at roughly geometric sample counts for the convergence plot. The reference is
// statistically independent of every compared run (other seeds, more samples, or no noise at all)
// and of the same physics as the runs it grades. Every output is staged at the end and committed
// together (core/image/output_file.h).
//
// RunCompare's steps, in order, are the methods of Comparison (compare.h): Load, PrepareDirectory,
// RenderCompared, RenderReference, Report, Write. CompareHooks replace what is the command line's
// own (signals, stderr, the scene file) for the Python module's phasor.compare.
//
// Under MPI (docs/distributed.md) every rank runs RunCompare: with more runs than ranks each rank
// renders whole runs and rank 0 gathers them, else every run's tiles are shared by all ranks; the
// reference is rendered by rank 0 alone; rank 0 reads the reference image and writes everything.

#include "app/compare.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <optional>
#include <thread>

#include "app/bytes.h"
#include "app/compare_report.h"
#include "app/distributed.h"
#include "app/plot.h"
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
// The reference: this many times the compared runs' samples, in this many independent renders
// (their spread is the reference's own noise, honest whatever the sampler).
constexpr int ReferenceSppFactor = 4;
constexpr int ReferenceReplicas = 4;

// Sets `stop` when the time budget is spent (budget > 0) or `stopRequest` is set, polling every
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
                if (stopRequest->load() || (budget > 0 && Clock::now() >= deadline_)) stop_.store(true);
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

// Every integrator a name may pick: the registry's plug-ins and the scene's named integrators.
std::vector<std::string> IntegratorChoices(const SceneDesc &desc) {
    std::vector<std::string> names = Registry<Integrator>::Names();
    for (const SceneEntity &e : desc.entities)
        if (e.keyword == "Integrator" && !e.name.empty() &&
            std::find(names.begin(), names.end(), e.name) == names.end())
            names.push_back(e.name);
    return names;
}

// "3" or "1–4": a list of consecutive seeds.
std::string SeedText(const std::vector<unsigned long long> &seeds) {
    if (seeds.empty()) return "";
    if (seeds.size() == 1) return std::to_string(seeds[0]);
    return fmt::format("{}–{}", seeds.front(), seeds.back());
}

// The combination of a reference's independent renders: their mean, every channel (`samples`
// dropped), with `variance` the variance of the mean of `intensity` from their spread, s²/K.
Image CombineReplicas(const std::vector<Image> &replicas) {
    Image out = replicas.front();
    const std::size_t k = replicas.size();
    const int samples = out.ChannelIndex("samples");
    if (samples >= 0) {  // (each replica's own count; the combination's is their sum)
        Image kept = out;
        kept.channels.erase(kept.channels.begin() + samples);
        kept.data.clear();
        const std::size_t nc = out.channels.size();
        for (std::size_t i = 0; i < out.data.size(); ++i)
            if (int(i % nc) != samples) kept.data.push_back(out.data[i]);
        out = kept;
    }
    const std::size_t nc = out.channels.size(), n = std::size_t(out.width) * out.height;
    const int intensity = out.ChannelIndex("intensity"), variance = out.ChannelIndex("variance");
    for (std::size_t p = 0; p < n; ++p)
        for (std::size_t c = 0; c < nc; ++c) {
            double sum = 0;
            for (const Image &r : replicas) sum += r.data[p * r.channels.size() + r.ChannelIndex(out.channels[c])];
            out.data[p * nc + c] = float(sum / double(k));
        }
    if (intensity >= 0 && variance >= 0) {
        for (std::size_t p = 0; p < n; ++p) {
            const double mean = out.data[p * nc + intensity];
            double ss = 0;
            for (const Image &r : replicas) {
                const double d = r.data[p * r.channels.size() + r.ChannelIndex("intensity")] - mean;
                ss += d * d;
            }
            out.data[p * nc + variance] = k > 1 ? float(ss / double(k - 1) / double(k)) : 0.0f;
        }
    }
    return out;
}

// Renders `scene` into `film` for `run`; on the integrator's error marks the run failed, prints the
// error when `print` (`label`: the run's progress label; `bar`: a progress bar was drawn) and
// returns nullopt.
std::optional<RenderStats> RenderFilm(CompareRun &run, const Scene &scene, Film &film, const RenderOptions &opt,
                                      const std::string &label, bool bar, bool print) {
    try {
        RenderStats st = scene.GetIntegrator().Render(scene, film, opt);
        if (bar) std::cerr << "\n";
        return st;
    } catch (const Error &e) {
        if (bar) std::cerr << "\n";
        run.status = CompareRun::Status::Failed;
        run.error = e.Message();
        if (print) {
            std::cerr << label << ": failed:\n";
            PrintError(e);
        }
        return std::nullopt;
    }
}

// A compared run as bytes, from the rank that rendered it (whole runs under MPI) to rank 0.
std::string SerializeRun(const CompareRun &r) {
    ByteWriter w;
    w.Put(int32_t(dist::Rank()));
    w.Put(int32_t(r.status));
    w.PutString(r.error);
    w.PutString(r.work);
    for (int v : {int(r.deterministic), int(r.waveOptical), r.sppRequested, r.sppReached, int(r.snapshotsCut),
                  int(r.image.has_value())})
        w.Put(int32_t(v));
    w.Put(r.seconds);
    w.PutVector(r.seeds);
    w.PutStrings(r.warnings);
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
    r.waveOptical = in.Get<int32_t>() != 0;
    r.sppRequested = in.Get<int32_t>();
    r.sppReached = in.Get<int32_t>();
    r.snapshotsCut = in.Get<int32_t>() != 0;
    const bool hasImage = in.Get<int32_t>() != 0;
    r.seconds = in.Get<double>();
    r.seeds = in.GetVector<unsigned long long>();
    r.warnings = in.GetStrings();
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

Comparison::Comparison(const CliOptions &o, CompareHooks hooks)
    : o_(o),
      c_(o_.compare),
      hooks_(std::move(hooks)),
      dir_(!o.output.empty() ? o.output : "out/" + fs::path(o.scene).stem().string() + "_compare"),
      parseDiag_(o.strict) {}

// Removes the output directory again if it was made here and nothing was written in it.
Comparison::~Comparison() {
    if (dirCreated_) {
        std::error_code e;
        if (fs::is_empty(dir_, e)) fs::remove(dir_, e);
    }
}

const SceneDesc &Comparison::Desc() const { return hooks_.desc ? *hooks_.desc : *desc_; }

bool Comparison::Stopped() const { return (hooks_.stop ? *hooks_.stop : StopFlag()).load(); }

void Comparison::RemoveHandlers() const {
    if (!hooks_.stop) RemoveStopHandlers();
}

bool Comparison::Fail(const std::string &message) {
    failure_ = message;
    if (hooks_.print) std::cerr << "error: " << message << "\n";
    return false;
}

std::function<void(int, int)> Comparison::Progress(const std::string &label, bool deterministic, long long pixels,
                                                   double budget) const {
    if (hooks_.progress) return hooks_.progress(label, deterministic, pixels, budget);
    if (!o_.quiet && isatty(2)) return ProgressBar(label, deterministic, pixels, budget);
    return {};
}

// A run's warnings while it renders: kept for the page, and shown (after a carriage return that
// ends the progress bar's line when `bar`).
std::function<void(const std::string &)> Comparison::Warn(CompareRun &run, bool bar) const {
    return [this, &run, bar](const std::string &w) {
        run.warnings.push_back(w);
        if (hooks_.warn) hooks_.warn(run.name + ": " + w);
        else std::cerr << (bar ? "\r" : "") << "warning: " << w << "\n";
    };
}

bool Comparison::Load() {
    if (!hooks_.desc) desc_ = ParseScene(o_, parseDiag_);
    if (!hooks_.desc && (!desc_ || parseDiag_.HasErrors())) {
        if (desc_) {
            BuildScene(o_, *desc_, parseDiag_, "");  // report the build's errors too
        } else {
            parseDiag_.Print(std::cerr, Colour());
            std::cerr << parseDiag_.ErrorCount() << " error" << (parseDiag_.ErrorCount() == 1 ? "" : "s") << " in '"
                      << o_.scene << "'\n";
        }
        return false;
    }
    // Every name must pick an integrator, before anything is rendered. `all`: every integrator of
    // the registry, in its order (a new integrator joins the comparison by being registered).
    const std::vector<std::string> choices = IntegratorChoices(Desc());
    integrators_ = c_.integrators == std::vector<std::string>{"all"} ? Registry<Integrator>::Names() : c_.integrators;
    std::vector<std::string> names = integrators_;
    if (!c_.referenceIntegrator.empty()) names.push_back(c_.referenceIntegrator);
    for (const std::string &n : names)
        if (std::find(choices.begin(), choices.end(), n) == choices.end()) {
            const std::string sug = Suggest(n, choices);
            return Fail(fmt::format("unknown integrator '{}'{} (integrators: {})", n,
                                    sug.empty() ? "" : "; did you mean '" + sug + "'?", fmt::join(choices, " ")));
        }
    int bad = 0;
    if (hooks_.referenceImage) {
        refImage_ = std::move(hooks_.referenceImage);
        hooks_.referenceImage.reset();
        ref_.values = ChannelValues(*refImage_, "intensity");
    } else if (!c_.reference.empty() && !NoReference() && dist::Root()) {  // rank 0 alone reads it
        try {
            refImage_ = ReadImage(c_.reference);
            ref_.values = ChannelValues(*refImage_, "intensity");
        } catch (const Error &e) {
            Fail("reference '" + c_.reference + "': " + e.Message());
            bad = 1;
        }
    }
    if (dist::Agree(bad)) return false;
    for (const std::string &n : integrators_) {
        CompareRun r;
        r.name = n;
        r.file = FileStem(n);
        runs_.push_back(std::move(r));
    }
    return true;
}

bool Comparison::PrepareDirectory() {
    std::error_code ec;
    int bad = 0;
    if (dist::Root()) {  // rank 0 alone writes
        dirCreated_ = !fs::exists(dir_, ec);
        try {
            CheckWritable((fs::path(dir_) / "index.html").string());
        } catch (const Error &e) {
            failure_ = e.Message();
            if (hooks_.print) PrintError(e);
            bad = 1;
        }
    }
    if (dist::Agree(bad)) return false;
    if (!o_.quiet) {
        const std::string budget = c_.seconds > 0 ? fmt::format(", {} s each", c_.seconds)
                                   : o_.spp > 0   ? fmt::format(", {} spp each", o_.spp)
                                                  : std::string(", the scene's spp");
        std::cerr << fmt::format("compare: {} with {}{} -> {}/\n", o_.scene, fmt::join(integrators_, " "), budget, dir_);
    }
    return true;
}

// Builds the scene with `run`'s integrator: nullptr (the run failed, its error kept) on errors.
// The first scene built records the detector and the render settings every run shares.
std::shared_ptr<const Scene> Comparison::Build(CompareRun &run) {
    Diagnostics d(o_.strict);
    std::shared_ptr<const Scene> scene =
        hooks_.build ? hooks_.build(run.name, d) : std::shared_ptr<const Scene>(BuildScene(o_, Desc(), d, run.name));
    for (const std::string &w : WarningsOf(d)) run.warnings.push_back(w);
    if (!scene) {
        run.status = CompareRun::Status::Failed;
        for (const Diagnostic &x : d.All())
            if (x.severity == Severity::Error) {
                run.error = x.message;
                break;
            }
        return nullptr;
    }
    run.deterministic = scene->GetIntegrator().Deterministic();
    run.waveOptical = scene->GetIntegrator().WaveOptical();
    if (width_ == 0) {
        const Detector &det = scene->GetDetector();
        width_ = det.Width();
        height_ = det.Height();
        radiometric_ = det.Response().GetKind() == SensorResponse::Kind::Radiometric;
        detectorName_ = det.name;
        exposure_ = det.Exposure();
        CliOptions plain = o_;
        plain.spp = -1;
        const RenderOptions opt = OptionsFor(*scene, plain);
        sceneSpp_ = opt.spp;
        seed_ = OptionsFor(*scene, o_).seed;
        sampler_ = opt.sampler;
    }
    return scene;
}

// Renders one compared run (the scene already built for its integrator) and fills `run`; its
// warnings are printed and kept for the page. With `shared`, every MPI rank renders the run's tiles
// together (rank 0 keeps the time budget and fills `run`).
void Comparison::RenderRun(CompareRun &run, const Scene &scene, int index, double budget, bool shared) {
    const Detector &det = scene.GetDetector();
    RenderOptions opt = OptionsFor(scene, o_);
    const bool timed = budget > 0 && !run.deterministic;  // rs takes no samples: it runs to the end
    if (timed) opt.spp = TimeModeSpp;
    run.sppRequested = opt.spp;
    run.seeds = {opt.seed};
    const bool helper = shared && !dist::Root();
    Watchdog watchdog(timed && !helper ? budget : 0, hooks_.stop ? hooks_.stop : &StopFlag());
    opt.cancel = watchdog.Flag();
    std::unique_ptr<dist::Share> share = shared ? dist::MakeShare(watchdog.Flag()) : nullptr;
    if (share) {
        opt.work = share.get();
        opt.cancel = share->Stop();
    }

    const std::string label = fmt::format("[{}/{}] {}", index, runs_.size(), run.name);
    const std::function<void(int, int)> progress =
        dist::Root() ? Progress(label, run.deterministic, (long long)det.Width() * det.Height(), timed ? budget : 0)
                     : nullptr;
    const bool bar = progress && !hooks_.progress;
    // (A timed run takes no work estimate: its pilot would spend the budget.)
    if (!timed) opt.warn = Warn(run, bar);

    Film film(det.Width(), det.Height(), det.Response());
    // Snapshots of `intensity` at roughly geometric sample counts (×1.5), taken between passes;
    // the time they take is left out of the times reported.
    const auto start = Clock::now();
    double snapshotCost = 0;
    int next = 1;
    const double pixels = double(det.Width()) * det.Height();
    opt.progress = [&](int done, int total) {
        if (progress) progress(done, total);
        if (run.deterministic || run.snapshotsCut || done < next) return;
        if (!snap_.reference && snap_.bytesLeft < pixels * sizeof(float)) {
            run.snapshotsCut = true;
            return;
        }
        const auto t0 = Clock::now();
        const Image img = film.Resolve();
        CompareSnapshot s;
        s.spp = done;
        s.seconds = std::chrono::duration<double>(t0 - start).count() - snapshotCost;
        const std::vector<double> values = ChannelValues(img, "intensity");
        if (snap_.reference) {
            s.metrics = ErrorMetrics(values, *snap_.reference);
        } else {
            s.intensity.assign(values.begin(), values.end());
            snap_.bytesLeft -= pixels * sizeof(float);
        }
        run.snapshots.push_back(std::move(s));
        next = std::max(done + 1, int(std::ceil(done * 1.5)));
        const double cost = std::chrono::duration<double>(Clock::now() - t0).count();
        snapshotCost += cost;
        if (timed) watchdog.Extend(cost);
    };

    const std::optional<RenderStats> rendered = RenderFilm(run, scene, film, opt, label, bar, hooks_.print);
    const int remoteSignal = share ? share->Signal() : 0;
    share.reset();
    if (!rendered || helper) return;  // (rank 0 holds a shared run)
    const RenderStats &st = *rendered;
    // Equal time: the time since the budget started (the watchdog's clock, which the deadline is
    // on), so that a run stopped by its budget reports at least the budget; otherwise the render's own.
    const double spent = timed ? std::chrono::duration<double>(Clock::now() - watchdog.Start()).count() : st.seconds;
    run.seconds = std::max(0.0, spent - snapshotCost);
    run.sppReached = st.sppReached;
    run.work = st.work;
    // A run stopped by its time budget is complete; one stopped by a signal is not.
    const bool interrupted = st.cancelled && (Stopped() || remoteSignal != 0);
    if (!st.hasImage) {  // rs stopped before it had anything honest to show
        run.status = CompareRun::Status::Interrupted;
        if (hooks_.print) std::cerr << label << ": interrupted (" << st.work << "); no image\n";
        return;
    }
    run.status = interrupted ? CompareRun::Status::Interrupted : CompareRun::Status::Done;
    Image img = film.Resolve();
    StampMetadata(img, scene, o_.scene, opt, st);
    if (timed) img.metadata["phasor:time_budget_seconds"] = std::to_string(budget);
    run.intensity = ChannelValues(img, "intensity");
    run.variance = img.ChannelIndex("variance") >= 0 ? ChannelValues(img, "variance") : std::vector<double>{};
    if (!run.deterministic && (run.snapshots.empty() || run.snapshots.back().spp != st.sppReached)) {
        CompareSnapshot last;
        last.spp = st.sppReached;
        last.seconds = run.seconds;
        if (snap_.reference) last.metrics = ErrorMetrics(run.intensity, *snap_.reference);
        else last.intensity.assign(run.intensity.begin(), run.intensity.end());  // (the image is kept anyway)
        run.snapshots.push_back(std::move(last));
    }
    if (run.snapshotsCut)
        Warn(run, false)(fmt::format("the convergence plot stops at {} spp (its snapshots would not fit in memory; "
                                     "give --reference to compare them at once)",
                                     run.snapshots.back().spp));
    run.image = std::move(img);
    if (!o_.quiet) {
        std::string line = label + ": " + (interrupted ? "interrupted: " : "") +
                           (run.deterministic ? st.work : std::to_string(st.sppReached) + " spp") + " in " +
                           FormatDuration(run.seconds) + (timed ? " (the time budget)" : "");
        if (!run.deterministic && run.seconds > 0)
            line += fmt::format(" ({:.3g} samples/s)", double(st.sppReached) * pixels / run.seconds);
        std::cerr << line << "\n";
    }
    for (const std::string &w : o_.quiet ? RenderWarnings(scene, st, *run.image)
                                         : PrintRenderWarnings(scene, st, *run.image))
        run.warnings.push_back(w);
}

// The first scene built: a given reference must match the detector, and its film must fit in
// memory on every rank. False (after the error) when the comparison must stop.
bool Comparison::CheckFirstScene(const Scene &scene) {
    std::string why;
    if (refImage_ && (refImage_->width != width_ || refImage_->height != height_)) {
        why = fmt::format("reference '{}' is {}x{} pixels but detector '{}' renders {}x{}", c_.reference,
                          refImage_->width, refImage_->height, detectorName_, width_, height_);
    } else {
        try {
            CheckMemory(scene);
        } catch (const Error &e) {
            why = e.Message();
        }
    }
    if (dist::AllOk(why.empty(), why, &why)) return true;
    if (dist::Root() && !why.empty()) Fail(why);
    return false;
}

bool Comparison::RenderCompared() {
    if (!hooks_.stop) InstallStopHandlers(!o_.quiet && dist::Root());
    // Snapshots for the convergence plot: compared at once with a reference image; else kept
    // (float per pixel) within a quarter of the available memory, at most 1 GB.
    snap_.reference = refImage_ ? &ref_.values : nullptr;
    snap_.bytesLeft = std::min(1e9, AvailableMemory() / 4);
    // Under MPI: with more runs than ranks each rank renders whole runs and rank 0 gathers them (if
    // a run fits in a message to rank 0); else every run's tiles are shared by all ranks, one run
    // after another.
    bool whole = dist::Size() > 1 && int(runs_.size()) > dist::Size();
    if (whole) {
        for (CompareRun &run : runs_)
            if (auto scene = Build(run)) {
                if (!CheckFirstScene(*scene)) return false;
                break;
            }
        for (CompareRun &run : runs_) {  // (built again where rendered)
            run.status = CompareRun::Status::NotRun;
            run.warnings.clear();
        }
        whole = double(width_) * height_ <= dist::MaxWholeRenderPixels;
    }
    if (!whole) {
        bool checked = false;
        for (CompareRun &run : runs_) {
            if (dist::Agree(Stopped() ? 1 : 0)) break;  // rank 0's word; the rest stay NotRun
            auto scene = Build(run);
            if (!scene) continue;
            if (!checked) {
                checked = true;
                if (!CheckFirstScene(*scene)) return false;
            }
            RenderRun(run, *scene, Index(run), c_.seconds, dist::Size() > 1);
        }
        return true;
    }
    dist::ForEachUnit(
        int(runs_.size()),
        [&](int u) {
            CompareRun &run = runs_[std::size_t(u)];
            if (auto scene = Build(run)) RenderRun(run, *scene, u + 1, c_.seconds, false);
            return SerializeRun(run);
        },
        [&](int u, std::string &&bytes) {
            CompareRun &run = runs_[std::size_t(u)];
            const int rank = DeserializeRun(bytes, run);
            if (rank != 0 && !o_.quiet)  // (rank 0's own runs said so as they ended)
                std::cerr << fmt::format("[{}/{}] {}: rendered on rank {}{}\n", u + 1, runs_.size(), run.name, rank,
                                         run.status == CompareRun::Status::Failed ? ": failed: " + run.error : "");
        },
        hooks_.stop ? hooks_.stop : &StopFlag());
    return true;
}

// The integrator of the reference render: --reference-integrator, else the first compared
// wave-optical sampling integrator that rendered, else the first sampling one ("" when none did).
std::string Comparison::ReferenceIntegrator() const {
    if (!c_.referenceIntegrator.empty()) return c_.referenceIntegrator;
    for (int wave = 1; wave >= 0; --wave)
        for (const CompareRun &r : runs_)
            if (r.image && !r.deterministic && r.waveOptical == bool(wave)) return r.name;
    return "";
}

// The reference's samples per pixel in all: --reference-spp, else 4× those of the compared runs
// (equal time: 4× what that integrator reached in its own run, else the scene's).
int Comparison::ReferenceSpp(const std::string &integrator, const Scene &scene) const {
    if (c_.referenceSpp > 0) return c_.referenceSpp;
    int base = o_.spp > 0 ? o_.spp : OptionsFor(scene, o_).spp;
    if (c_.seconds > 0) {
        base = sceneSpp_ > 0 ? sceneSpp_ : base;
        for (const CompareRun &r : runs_)
            if (r.name == integrator && r.image && !r.deterministic) base = std::max(1, r.sppReached);
    }
    const long long total = (long long)ReferenceSppFactor * base;
    return int(std::min<long long>(total, TimeModeSpp - 1));
}

void Comparison::DescribeReferenceImage() {
    ref_.kind = CompareReference::Kind::Image;
    ref_.name = "reference image";
    ref_.image = &*refImage_;
    ref_.description = "the image '" + c_.reference + "'";
    const auto meta = [&](const char *key) -> std::string {
        const auto it = refImage_->metadata.find(key);
        return it == refImage_->metadata.end() ? "" : it->second;
    };
    if (const std::string optics = meta("phasor:optics"); !optics.empty()) ref_.waveOptical = optics == "wave";
    const std::string seed = meta("phasor:seed"), integrator = meta("phasor:integrator");
    if (!integrator.empty()) ref_.description += " (" + integrator + ")";
    // Its noise: the spread of independent renders when phasor combined some, else its variance
    // channel (the i.i.d. estimate), else unknown; none for a deterministic render.
    if (!integrator.empty() && seed.empty()) {  // a deterministic phasor render (rs)
        SetNoiseFloor(ref_, std::vector<double>(ref_.values.size(), 0.0), "deterministic: no sampling noise");
    } else if (refImage_->ChannelIndex("variance") >= 0) {
        const std::string how = meta("phasor:variance");
        SetNoiseFloor(ref_, ChannelValues(*refImage_, "variance"),
                      how.empty() ? "its variance channel: the i.i.d. estimate, which overstates the noise of "
                                    "Owen-scrambled Sobol' samples"
                                  : how);
    } else {
        ref_.noiseSource = "unknown: the image has no variance channel";
    }
    if (seed.empty()) {
        ref_.independence = integrator.empty() ? "an image from elsewhere: its independence of the compared runs is "
                                                 "not known"
                                               : "deterministic: it draws no random numbers";
    } else if (std::to_string(seed_) == seed) {
        ref_.independence = "rendered with seed " + seed + ", the compared runs' own";
        ref_.warnings.push_back("the reference image was rendered with seed " + seed +
                                ", the seed of the compared runs: integrators that draw the same random numbers "
                                "share its noise, which makes their errors look far smaller than they are and "
                                "hides a bias from the test; render the reference with another --seed");
    } else {
        ref_.independence = "rendered with seed " + seed + ", not the compared runs' (" + std::to_string(seed_) +
                            "): its noise is independent of theirs";
    }
}

void Comparison::RenderReference() {
    if (refImage_) {
        DescribeReferenceImage();
        return;
    }
    if (NoReference()) {
        ref_.description = "none was asked for (--reference none): the runs are shown side by side, without errors";
        return;
    }
    if (Stopped()) return;
    // Without --reference-integrator, a complete deterministic wave-optical run (rs) is the
    // reference: it has no noise at all.
    if (c_.referenceIntegrator.empty())
        for (CompareRun &r : runs_)
            if (r.deterministic && r.waveOptical && r.image && r.status == CompareRun::Status::Done) {
                r.isReference = true;
                ref_.description = r.name + ", deterministic (no sampling noise; no reference was given)";
                ref_.independence = "deterministic: it draws no random numbers, so its errors are independent of "
                                    "every run's";
                return;
            }
    const std::string name = ReferenceIntegrator();
    if (name.empty()) {
        ref_.description = "no sampling run finished, so none could be rendered again as the reference";
        return;
    }
    CompareRun run;
    run.name = name;
    run.file = "reference_" + FileStem(name);
    run.isReferenceRun = true;
    runs_.push_back(std::move(run));
    CompareRun &r = runs_.back();
    auto scene = Build(r);
    if (!scene) {
        ref_.description = "the reference run (" + name + ") failed: " + r.error;
        return;
    }
    const int total = r.deterministic ? 0 : ReferenceSpp(name, *scene);
    const int replicas = r.deterministic ? 1 : std::max(1, std::min(ReferenceReplicas, total));
    const int each = r.deterministic ? 0 : (total + replicas - 1) / replicas;
    const Detector &det = scene->GetDetector();
    const std::string label = fmt::format("[{}/{}] {} (reference)", runs_.size(), runs_.size(), name);
    std::vector<Image> images;
    RenderStats last;
    for (int k = 0; k < replicas && !Stopped(); ++k) {
        RenderOptions opt = OptionsFor(*scene, o_);
        if (hooks_.stop) opt.cancel = hooks_.stop;
        if (!r.deterministic) {
            opt.spp = each;
            opt.seed = seed_ + 1 + (unsigned long long)k;  // never a compared run's seed
        }
        opt.progress = Progress(replicas > 1 ? fmt::format("{} {}/{}", label, k + 1, replicas) : label,
                                r.deterministic, (long long)det.Width() * det.Height(), 0);
        const bool bar = opt.progress && !hooks_.progress;
        opt.warn = Warn(r, bar);
        Film film(det.Width(), det.Height(), det.Response());
        const std::optional<RenderStats> rendered = RenderFilm(r, *scene, film, opt, label, bar, hooks_.print);
        if (!rendered) {
            ref_.description = "the reference run (" + name + ") failed: " + r.error;
            return;
        }
        last = *rendered;
        if (!last.hasImage || (last.cancelled && Stopped())) break;  // an incomplete replica is dropped
        Image img = film.Resolve();
        StampMetadata(img, *scene, o_.scene, opt, last);
        images.push_back(std::move(img));
        if (!r.deterministic) r.seeds.push_back(opt.seed);
        r.seconds += last.seconds;
        r.work = last.work;
    }
    if (images.empty()) {
        r.status = Stopped() ? CompareRun::Status::Interrupted : CompareRun::Status::Failed;
        ref_.description = "the reference run (" + name + ") was stopped before it had an image";
        return;
    }
    r.status = int(images.size()) < replicas ? CompareRun::Status::Interrupted : CompareRun::Status::Done;
    r.sppRequested = r.sppReached = each * int(images.size());
    Image combined = CombineReplicas(images);
    if (!r.deterministic) {
        combined.metadata["phasor:spp_reached"] = std::to_string(r.sppReached);
        combined.metadata["phasor:spp_max"] = std::to_string(r.sppReached);
        combined.metadata["phasor:spp_requested"] = std::to_string(r.sppRequested);
        combined.metadata["phasor:seed"] = SeedText(r.seeds);
        combined.metadata["phasor:replicas"] = std::to_string(images.size());
        combined.metadata["phasor:variance"] =
            fmt::format("the spread of {} independent renders (seeds {}): the variance of their mean", images.size(),
                        SeedText(r.seeds));
    }
    r.intensity = ChannelValues(combined, "intensity");
    r.variance = combined.ChannelIndex("variance") >= 0 ? ChannelValues(combined, "variance") : std::vector<double>{};
    r.image = std::move(combined);
    for (const std::string &w : o_.quiet ? RenderWarnings(*scene, last, *r.image)
                                         : PrintRenderWarnings(*scene, last, *r.image))
        r.warnings.push_back(w);
    const bool automatic = c_.referenceIntegrator.empty();
    if (r.deterministic) {
        ref_.description = name + ", deterministic (--reference-integrator)";
        ref_.independence = "deterministic: it draws no random numbers";
        SetNoiseFloor(ref_, std::vector<double>(r.intensity.size(), 0.0), "deterministic: no sampling noise");
    } else {
        ref_.description =
            fmt::format("{} at {} spp: {} independent render{} of {} spp ({})", name, r.sppReached, images.size(),
                        images.size() == 1 ? "" : "s", each,
                        !automatic             ? std::string("--reference-integrator")
                        : c_.referenceSpp > 0 ? fmt::format("automatic: the first {}-optical integrator compared",
                                                            r.waveOptical ? "wave" : "ray")
                                              : fmt::format("automatic: the first {}-optical integrator compared, at "
                                                            "{}× the samples",
                                                            r.waveOptical ? "wave" : "ray", ReferenceSppFactor));
        ref_.independence = fmt::format("its seeds ({}) differ from the compared runs' ({}): its noise is independent "
                                        "of theirs",
                                        SeedText(r.seeds), seed_);
        if (images.size() > 1)
            SetNoiseFloor(ref_, r.variance, fmt::format("the spread of its {} independent renders", images.size()));
        else
            ref_.noiseSource = "unknown: one render has no spread (--reference-spp 1)";
    }
    if (!o_.quiet)
        std::cerr << label << ": " << (r.deterministic ? r.work : std::to_string(r.sppReached) + " spp") << " in "
                  << FormatDuration(r.seconds) << "\n";
}

bool Comparison::Report() {
    const bool any = std::any_of(runs_.begin(), runs_.end(), [](const CompareRun &r) { return r.image.has_value(); });
    if (!any) {
        RemoveHandlers();
        if (Stopped()) {
            failure_ = "interrupted before any integrator finished";
            if (hooks_.print) std::cerr << failure_ << "; nothing written\n";
            return false;
        }
        return Fail("no integrator could render '" + o_.scene + "'; nothing written");
    }
    ComputeErrors(runs_, ref_);

    CompareReport &rep = report_;
    rep.scene = o_.scene;
    rep.dir = dir_;
    rep.version = PHASOR_VERSION;
    rep.width = width_;
    rep.height = height_;
    rep.radiometric = radiometric_;
    rep.detector = detectorName_;
    rep.seed = seed_;
    rep.sampler = sampler_;
    rep.defines = o_.defines;
    rep.modeKind = c_.seconds > 0 ? "time" : "spp";
    rep.seconds = c_.seconds;
    rep.spp = o_.spp > 0 ? o_.spp : sceneSpp_;
    rep.modeText = c_.seconds > 0 ? "equal time: " + FormatSeconds(c_.seconds) + " per integrator"
                   : o_.spp > 0   ? fmt::format("equal samples: {} spp per integrator", o_.spp)
                                  : fmt::format("equal samples: the scene's {} spp per integrator", sceneSpp_);
    rep.stopped = hooks_.stop       ? (Stopped() ? hooks_.stopName : "")
                  : StopSignal() == 0 ? ""
                  : StopSignal() == SIGINT ? "Ctrl-C"
                                           : "SIGTERM";
    rep.row = c_.row;
    rep.column = c_.column;
    // One exposure for every camera image: the reference's (else the first run's).
    const Image *basis = ref_.image;
    for (const CompareRun &r : runs_)
        if (!basis && r.image) basis = &*r.image;
    rep.autoExposure = exposure_.automatic;
    rep.exposureStops = radiometric_ ? 0 : exposure_.ev + (exposure_.automatic ? AutoExposureStops(*basis) : 0);
    // The scene's warnings: the parser's, and those every run repeats (a build warning).
    rep.sceneWarnings = WarningsOf(parseDiag_);
    std::vector<CompareRun *> rendered;
    for (CompareRun &r : runs_)
        if (r.status != CompareRun::Status::NotRun) rendered.push_back(&r);
    const std::vector<std::string> first = rendered.size() < 2 ? std::vector<std::string>{} : rendered.front()->warnings;
    for (const std::string &w : first) {
        const auto has = [&](const CompareRun *r) {
            return std::find(r->warnings.begin(), r->warnings.end(), w) != r->warnings.end();
        };
        if (!std::all_of(rendered.begin(), rendered.end(), has)) continue;
        rep.sceneWarnings.push_back(w);
        for (CompareRun *r : rendered) r->warnings.erase(std::find(r->warnings.begin(), r->warnings.end(), w));
    }
    // The command, to rerun it (WriteTo adds its -o).
    std::string cmd = fmt::format("phasor compare {} --integrators {}", o_.scene, fmt::join(c_.integrators, ","));
    if (c_.seconds > 0) cmd += fmt::format(" --time {}", c_.seconds);
    if (o_.spp > 0) cmd += fmt::format(" --spp {}", o_.spp);
    if (!c_.reference.empty()) cmd += " --reference " + c_.reference;
    if (!c_.referenceIntegrator.empty()) cmd += " --reference-integrator " + c_.referenceIntegrator;
    if (c_.referenceSpp > 0) cmd += fmt::format(" --reference-spp {}", c_.referenceSpp);
    for (const auto &[k, v] : o_.defines) cmd += " -D " + k + "=" + v;
    if (o_.seed >= 0) cmd += fmt::format(" --seed {}", o_.seed);
    if (!o_.sampler.empty()) cmd += " --sampler " + o_.sampler;
    if (c_.row >= 0) cmd += fmt::format(" --row {}", c_.row);
    if (c_.column >= 0) cmd += fmt::format(" --column {}", c_.column);
    rep.command = cmd;
    return true;
}

std::vector<std::string> Comparison::WriteTo(const std::string &dir) {
    CompareReport report = report_;
    report.dir = dir;
    report.command += " -o " + dir;
    OutputFiles files;
    std::vector<std::string> written = StageCompareOutputs(files, runs_, ref_, refImage_ ? &*refImage_ : nullptr, report);
    files.Commit();
    return written;
}

int Comparison::Write() {
    std::vector<std::string> written;
    try {
        written = WriteTo(dir_);
    } catch (const Error &e) {
        RemoveStopHandlers();
        std::cerr << "error: " << e.Message() << "\n";
        return 1;
    }
    RemoveStopHandlers();
    std::vector<std::string> failed;
    for (const CompareRun &r : runs_)
        if (r.status == CompareRun::Status::Failed) failed.push_back(r.name);
    if (!o_.quiet) {
        std::cerr << "reference: " << (ref_.kind == CompareReference::Kind::None ? "none — " : "") << ref_.description
                  << "\n";
        for (const std::string &w : ref_.warnings) std::cerr << "warning: " << w << "\n";
        PrintSummary(std::cerr, runs_, ref_);
        const bool page = std::find(written.begin(), written.end(), "index.html") != written.end();
        std::cerr << fmt::format("wrote {} and {} other files in {}/\n",
                                 (fs::path(dir_) / (page ? "index.html" : "results.md")).string(), written.size() - 1,
                                 dir_);
    }
    if (!failed.empty()) std::cerr << fmt::format("error: {} failed (see above and the table)\n", fmt::join(failed, ", "));
    if (StopSignal()) return StoppedStatus();
    return failed.empty() ? 0 : 1;
}

int RunCompare(const CliOptions &o) {
    Comparison comparison(o);
    if (!comparison.Load() || !comparison.PrepareDirectory()) return 1;
    if (!comparison.RenderCompared()) {
        RemoveStopHandlers();
        return dist::Agree(1);
    }
    if (!dist::Root()) {  // rank 0 renders the reference, reports and writes
        RemoveStopHandlers();
        return dist::Agree(0);
    }
    comparison.RenderReference();
    if (!comparison.Report()) return dist::Agree(StopSignal() ? StoppedStatus() : 1);
    return dist::Agree(comparison.Write());
}

}  // namespace phasor
