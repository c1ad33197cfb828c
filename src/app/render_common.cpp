// SPDX-License-Identifier: Apache-2.0
// phasor — what `render` and `compare` share (render_common.h).

#include "app/render_common.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <new>

#include "app/distributed.h"
#include "app/profile.h"
#include "core/image/image_io.h"
#include "parser/parser.h"

namespace phasor {
namespace {

// The first SIGINT or SIGTERM asks the render to stop; it finishes the pixels in progress and the
// partial image is written. A second signal ends the program at once (the default action).
std::atomic<bool> gCancel{false};
volatile std::sig_atomic_t gSignal = 0;    // the first signal received, 0 if none
volatile std::sig_atomic_t gAnnounce = 0;  // print "stopping…" when the first signal arrives

extern "C" void OnStopSignal(int sig) {
    if (gSignal == 0) gSignal = sig;
    gCancel.store(true);
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    if (gAnnounce) {  // write(2) is async-signal-safe; iostreams are not
        static const char msg[] = "\nstopping: finishing the pixels in progress (Ctrl-C again to quit at once)\n";
        ssize_t ignored = ::write(2, msg, sizeof msg - 1);
        (void)ignored;
    }
}

}  // namespace

void InstallStopHandlers(bool announce) {
    gAnnounce = announce;
    std::signal(SIGINT, OnStopSignal);
    std::signal(SIGTERM, OnStopSignal);
}

void RemoveStopHandlers() {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
}

const std::atomic<bool> &StopFlag() { return gCancel; }
int StopSignal() { return int(gSignal); }
int StoppedStatus() { return 128 + (gSignal ? int(gSignal) : SIGINT); }

bool Colour() { return isatty(2) && !std::getenv("NO_COLOR"); }

std::optional<SceneDesc> ParseScene(const CliOptions &o, Diagnostics &diag) {
    diag.SetPermissive(o.permissive);
    ParseOptions parse;
    parse.defines = o.defines;
    parse.partial = true;
    return ParseSceneFile(o.scene, parse, diag);
}

std::unique_ptr<Scene> BuildSceneQuietly(const std::string &scenePath, const SceneDesc &desc, Diagnostics &diag,
                                         const std::string &integrator) {
    std::unique_ptr<Scene> scene;
    try {
        scene = Scene::Build(desc, diag, integrator);
    } catch (const std::bad_alloc &) {  // (what was allocated is released by now)
        scene.reset();
        diag.Error(FileLoc{scenePath, 0, 0, 1},
                   "out of memory while loading the scene (a scene takes about 60 bytes of memory per byte "
                   "of text, more for long inline lists: put large meshes in mesh files; docs/wscene.md §7)");
    }
    return scene;
}

std::unique_ptr<Scene> BuildScene(const CliOptions &o, const SceneDesc &desc, Diagnostics &diag,
                                  const std::string &integrator) {
    std::unique_ptr<Scene> scene = BuildSceneQuietly(o.scene, desc, diag, integrator);
    // --sampler names a sampler plug-in or one of the scene's Sampler blocks.
    if (scene && !o.sampler.empty() && !scene->NewSampler(o.sampler, 0)) {
        const std::string s = Suggest(o.sampler, scene->SamplerNames());
        diag.Error(FileLoc{"<command line>", 0, 0, 1},
                   "unknown sampler '" + o.sampler + "'" + (s.empty() ? "" : "; did you mean '" + s + "'?"));
        scene.reset();
    }
    diag.Print(std::cerr, Colour());
    if (diag.HasErrors()) {
        std::cerr << diag.ErrorCount() << " error" << (diag.ErrorCount() == 1 ? "" : "s") << " in '" << o.scene
                  << "'\n";
        return nullptr;
    }
    return scene;
}

std::unique_ptr<Scene> Load(const CliOptions &o, Diagnostics &diag, SceneDesc *descOut) {
    std::optional<SceneDesc> desc;
    try {
        desc = ParseScene(o, diag);
    } catch (const std::bad_alloc &) {
        diag.Error(FileLoc{o.scene, 0, 0, 1},
                   "out of memory while loading the scene (a scene takes about 60 bytes of memory per byte "
                   "of text, more for long inline lists: put large meshes in mesh files; docs/wscene.md §7)");
    }
    if (!desc) {
        diag.Print(std::cerr, Colour());
        std::cerr << diag.ErrorCount() << " error" << (diag.ErrorCount() == 1 ? "" : "s") << " in '" << o.scene
                  << "'\n";
        return nullptr;
    }
    std::unique_ptr<Scene> scene = BuildScene(o, *desc, diag, o.integrator);
    if (descOut) *descOut = std::move(*desc);
    return scene;
}

void PrintError(const Error &e) {
    // A place in a scene (a line): file:line:col with its source line. An error about a whole file
    // (an output that cannot be written) names the file in its message: printed once.
    if (e.Loc().Known() && e.Loc().line > 0) {
        Diagnostics located;
        located.Report(e);
        located.Print(std::cerr);
    } else {
        std::cerr << "error: " << e.Message() << "\n";
    }
}

std::string FormatDuration(double s) {
    char buf[32];
    if (s < 60)
        std::snprintf(buf, sizeof buf, "%.1fs", s);
    else if (s < 3600)
        std::snprintf(buf, sizeof buf, "%dm%02ds", int(s) / 60, int(s) % 60);
    else
        std::snprintf(buf, sizeof buf, "%dh%02dm", int(s) / 3600, (int(s) / 60) % 60);
    return buf;
}

void CheckWritable(const std::string &path) {
    namespace fs = std::filesystem;
    MakeParentDirectory(path);
    fs::path p(path);
    std::error_code ec;
    if (fs::is_directory(p, ec)) throw Error("cannot write '" + path + "': it is a directory");
    fs::path probe = p;
    probe += ".phasor-probe";
    FILE *f = std::fopen(probe.c_str(), "wb");
    if (!f) throw Error("cannot write '" + path + "': " + std::strerror(errno));
    std::fclose(f);
    fs::remove(probe, ec);
}

void CheckMemory(const Scene &scene) {
    const Detector &det = scene.GetDetector();
    if (const double need = Film::MemoryNeeded(det.Width(), det.Height()), avail = AvailableMemory(); need > avail) {
        char buf[256];
        std::snprintf(buf, sizeof buf,
                      "detector '%s': %dx%d pixels need about %.3g GB of memory (%.0f bytes per pixel) but only "
                      "%.3g GB are available; lower its 'resolution' (or raise its 'pitch')",
                      det.name.c_str(), det.Width(), det.Height(), need / 1e9, need / det.Width() / det.Height(),
                      avail / 1e9);
        throw Error(scene.Where(&det), buf);
    }
}

RenderOptions OptionsFor(const Scene &scene, const CliOptions &o) {
    RenderOptions opt = scene.Settings().options;  // the Render block's spp, seed, sampler
    if (o.spp > 0) opt.spp = o.spp;
    if (o.seed >= 0) opt.seed = uint64_t(o.seed);
    if (!o.sampler.empty()) opt.sampler = o.sampler;
    // Under MPI, ranks sharing a node share its cores (distributed.h DefaultThreads).
    opt.threads = o.threads > 0 ? o.threads : dist::DefaultThreads();
    opt.cancel = &gCancel;
    return opt;
}

std::string ProgressText(const std::string &label, bool deterministic, long long pixels, double budgetSeconds,
                         int done, int total, double t) {
    const double frac = budgetSeconds > 0 ? std::min(1.0, t / budgetSeconds) : double(done) / total;
    const int width = 30, filled = int(frac * width);
    // rs counts its own steps (batches of field nodes) and has no sample rate.
    char rate[48] = "";
    if (!deterministic)
        std::snprintf(rate, sizeof rate, "  %.2f Msamples/s", double(done) * pixels / std::max(t, 1e-9) * 1e-6);
    char count[48];
    if (budgetSeconds > 0 && !deterministic)
        std::snprintf(count, sizeof count, "%d spp", done);
    else
        std::snprintf(count, sizeof count, "%d/%d %s", done, total, deterministic ? "steps" : "spp");
    char line[512];
    std::snprintf(line, sizeof line, "%s%s[%s%s] %3d%% %s  %s elapsed  %s %s%s   ", label.c_str(),
                  label.empty() ? "" : " ", std::string(filled, '=').c_str(), std::string(width - filled, ' ').c_str(),
                  int(frac * 100), count, FormatDuration(t).c_str(), budgetSeconds > 0 ? "left" : "ETA",
                  FormatDuration(budgetSeconds > 0 ? std::max(0.0, budgetSeconds - t)
                                 : frac > 0        ? t / frac - t
                                                   : 0)
                      .c_str(),
                  rate);
    return line;
}

std::function<void(int, int)> ProgressBar(const std::string &label, bool deterministic, long long pixels,
                                          double budgetSeconds) {
    const auto start = std::chrono::steady_clock::now();
    return [=](int done, int total) {
        const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::fprintf(stderr, "\r%s",
                     ProgressText(label, deterministic, pixels, budgetSeconds, done, total, t).c_str());
        std::fflush(stderr);
    };
}

Image ResolvedImage(const Film &film, const Scene &scene, const std::string &scenePath, const RenderOptions &opt,
                    const RenderStats &st) {
    Image img = film.Resolve();
    StampMetadata(img, scene, scenePath, opt, st);
    return img;
}

RenderResult RenderToImage(const Scene &scene, const std::string &scenePath, const RenderOptions &opt) {
    const Detector &det = scene.GetDetector();
    Film film(det.Width(), det.Height(), det.Response());
    RenderResult r;
    r.stats = scene.GetIntegrator().Render(scene, film, opt);
    if (r.stats.hasImage) {
        r.image = ResolvedImage(film, scene, scenePath, opt, r.stats);
        StampDisplayExposure(*r.image, det, DisplayStops(det, *r.image));
    }
    return r;
}

void StampMetadata(Image &img, const Scene &scene, const std::string &scenePath, const RenderOptions &opt,
                   const RenderStats &st) {
    const Integrator &integrator = scene.GetIntegrator();
    img.metadata["phasor:scene"] = scenePath;
    img.metadata["phasor:integrator"] = integrator.ToString();
    img.metadata["phasor:optics"] = integrator.WaveOptical() ? "wave" : "ray";  // (`compare` reads it)
    if (integrator.Deterministic()) {
        img.metadata.erase("phasor:samples_per_pixel");  // rs takes no samples
    } else {
        img.metadata["phasor:spp_requested"] = std::to_string(opt.spp);
        img.metadata["phasor:spp_reached"] = std::to_string(st.sppReached);
        img.metadata["phasor:spp_max"] = std::to_string(st.sppMax);
        img.metadata["phasor:seed"] = std::to_string(opt.seed);
        img.metadata["phasor:sampler"] = opt.sampler;
    }
    for (const auto &[key, value] : st.metadata) img.metadata[key] = value;
    img.metadata["phasor:render_seconds"] = std::to_string(st.seconds);
    img.metadata["phasor:cancelled"] = st.cancelled ? "true" : "false";
    if (const SensorPlaneGeometry *sp = scene.GetDetector().SensorPlane()) {  // pixel centres, for `profile`
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.17g", sp->PixelCenter(0, 0).x);
        img.metadata["phasor:x0_m"] = buf;
        std::snprintf(buf, sizeof buf, "%.17g", sp->pitchX);
        img.metadata["phasor:pitch_m"] = buf;
    }
}

double DisplayStops(const Detector &det, const Image &basis) {
    if (det.Response().GetKind() == SensorResponse::Kind::Radiometric) return 0;
    return det.Exposure().ev + (det.Exposure().automatic ? AutoExposureStops(basis) : 0);
}

void StampDisplayExposure(Image &img, const Detector &det, double stops) {
    if (det.Response().GetKind() == SensorResponse::Kind::Radiometric) return;
    char buf[64];
    // Every digit (%.17g reads back as the same double): a reader of the EXR (the Python module's
    // display, `phasor compare`) shows exactly the PNG this program wrote.
    std::snprintf(buf, sizeof buf, "%.17g", stops);
    img.metadata["phasor:display_exposure"] = buf;
    img.metadata["phasor:auto_exposure"] = det.Exposure().automatic ? "true" : "false";
}

std::string StageDisplayPng(OutputFiles &files, const std::string &png, const Image &img, bool radiometric,
                            const std::string &label, const std::string &title, double zeroDb, double stops) {
    if (img.height == 1) {
        // A one-row image as a PNG would be N×1 pixels: `phasor profile`'s line plot of its
        // intensity instead (x in metres from the metadata for sensor planes).
        CliOptions plot;
        plot.quiet = true;
        plot.profile.inputs = {png};
        plot.profile.plot = png;
        plot.profile.labels = {label};
        plot.profile.title = title;
        std::string data;
        if (RunProfile(plot, {&img}, &files, &data) != 0) throw Error("cannot write '" + png + "'");
        return data.empty() ? png : data;
    }
    if (radiometric) {
        const SheetResult r = WriteFalseColorPng(files, png, img, "intensity", 40, zeroDb);
        if (!r.textDrawn) std::cerr << "warning: " << r.textProblem << "; '" << png << "' has no text\n";
    } else {
        DisplayOptions display;
        display.exposure = stops;
        WritePng(files, png, img, display);
    }
    return png;
}

std::vector<std::string> RenderWarnings(const Scene &scene, const RenderStats &st, const Image &img) {
    std::vector<std::string> out = st.counters.Warnings();
    if (!st.cancelled && std::all_of(img.data.begin(), img.data.end(), [](float v) { return v == 0; }))
        out.push_back("the image is black: " + scene.DarkImageCause());
    if (st.invalidSamples > 0)
        out.push_back(std::to_string(st.invalidSamples) +
                      " samples were NaN, negative or beyond the float range of the image (|v| > 3.4e38) and were "
                      "discarded (counted in phasor:invalid_samples)");
    return out;
}

std::vector<std::string> PrintRenderWarnings(const Scene &scene, const RenderStats &st, const Image &img) {
    std::vector<std::string> warnings = RenderWarnings(scene, st, img);
    for (const std::string &w : warnings) std::cerr << "warning: " << w << "\n";
    return warnings;
}

std::vector<std::string> WarningsOf(const Diagnostics &diag) {
    std::vector<std::string> out;
    for (const Diagnostic &d : diag.All())
        if (d.severity == Severity::Warning)
            out.push_back((d.loc.Known() ? d.loc.ToString() + ": " : std::string()) + d.message);
    return out;
}

}  // namespace phasor
