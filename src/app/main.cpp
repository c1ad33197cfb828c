// SPDX-License-Identifier: Apache-2.0
// phasor — the command-line program: render, check, format, list, describe, profile, probe.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <new>
#include <sstream>

#include "app/cli.h"
#include "app/probe.h"
#include "app/profile.h"
#include "core/image/image_io.h"
#include "core/render/registry.h"
#include "core/render/scene.h"
#include "parser/parser.h"

using namespace phasor;

namespace {

// Cancellation (README "Using phasor"): the first SIGINT (Ctrl-C) or SIGTERM (`timeout`, batch
// schedulers) asks the render to stop; it finishes the pixels in progress and the partial image is
// written. A second signal ends the program at once (the default action).
std::atomic<bool> gCancel{false};
volatile std::sig_atomic_t gSignal = 0;  // the first signal received, 0 if none
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

// Exit status of a render stopped by `sig`: 128 + the signal number, as a shell reports a
// process killed by it (130 for SIGINT, 143 for SIGTERM).
int StoppedStatus(int sig) { return 128 + sig; }

// The usage text, in two parts around the list of families (from the registry).
const char *kUsageHead =
    "usage: phasor <command> [options]\n"
    "\n"
    "commands:\n"
    "  render SCENE [-o FILE] [--spp N] [--threads N] [--seed S] [--integrator NAME]\n"
    "               [--sampler sobol|independent] [-D name=value ...] [--strict | --permissive]\n"
    "               [--quiet]\n"
    "                      render SCENE to FILE (.exr; a .png is written beside it)\n"
    "  check SCENE [-D name=value ...] [--strict | --permissive]\n"
    "                      load and validate only; exit status 0 if the scene is valid\n"
    "                      (unknown parameters and -D names that match no Define are errors;\n"
    "                      --permissive makes them warnings, --strict makes every warning an error)\n"
    "  format SCENE        print SCENE in canonical form\n"
    "  list [FAMILY]       list the plug-ins of every family or of FAMILY, one of\n";
const char *kUsageTail =
    "  describe [FAMILY] NAME print a plug-in's parameters (FAMILY only if NAME is in several)\n"
    "  describe --markdown    print every plug-in's parameters as Markdown (docs/plugins.md)\n"
    "  profile IMAGE.exr [IMAGE.exr ...] [--row N] [--channel NAME] [--csv FILE|-] [--plot FILE.png]\n"
    "          [--label NAME ...] [--x0 M --pitch M] [--diff-scale N] [--title TEXT]\n"
    "                      one row (default: the middle one) of a channel (default: intensity) of\n"
    "                      each image as CSV (stdout unless --csv/--plot) and/or a line plot; with\n"
    "                      two images also |a - b| and max |a - b| / max(b)\n"
    "  probe SCENE --material NAME --theta ANGLE [--phi ANGLE] --lambda LENGTH [--uv U V]\n"
    "        [--samples N] [--seed S] [--ray] [--csv FILE|-] [--plot FILE.png] [-D name=value ...]\n"
    "                      one kernel of SCENE lit from (theta, phi) at wavelength lambda (e.g. 30deg,\n"
    "                      550nm): reflectance R and transmittance T (power; continuous lobes by Monte\n"
    "                      Carlo with a standard error), each near-delta lobe's direction and efficiency;\n"
    "                      --ray: the ray-optics limit; --plot: the angular distribution\n"
    "  --version, --help\n";

std::string Usage() {
    std::string families;
    for (const FamilyInfo &f : AllFamilies()) families += " " + f.family;
    return kUsageHead + std::string("                     ") + families + "\n" + kUsageTail;
}

bool Colour() { return isatty(2) && !std::getenv("NO_COLOR"); }

// Parses and builds; prints diagnostics. Returns nullptr on error. What was read cleanly is
// built even after errors, so one run reports the scene's parse, resolve and build errors.
std::unique_ptr<Scene> Load(const CliOptions &o, Diagnostics &diag) {
    diag.SetPermissive(o.permissive);
    ParseOptions parse;
    parse.defines = o.defines;
    parse.partial = true;
    std::unique_ptr<Scene> scene;
    try {
        auto desc = ParseSceneFile(o.scene, parse, diag);
        if (desc) scene = Scene::Build(*desc, diag, o.integrator);
    } catch (const std::bad_alloc &) {  // (what was allocated is released by now)
        scene.reset();
        diag.Error(FileLoc{o.scene, 0, 0, 1},
                   "out of memory while loading the scene (a scene takes about 60 bytes of memory per byte "
                   "of text, more for long inline lists: put large meshes in mesh files; docs/wscene.md §7)");
    }
    diag.Print(std::cerr, Colour());
    if (diag.HasErrors()) {
        std::cerr << diag.ErrorCount() << " error" << (diag.ErrorCount() == 1 ? "" : "s") << " in '" << o.scene
                  << "'\n";
        return nullptr;
    }
    return scene;
}

std::string FormatDuration(double s) {
    char buf[32];
    if (s < 60) std::snprintf(buf, sizeof buf, "%.1fs", s);
    else if (s < 3600) std::snprintf(buf, sizeof buf, "%dm%02ds", int(s) / 60, int(s) % 60);
    else std::snprintf(buf, sizeof buf, "%dh%02dm", int(s) / 3600, (int(s) / 60) % 60);
    return buf;
}

// Verifies before rendering that `path` can be created (so a long render never ends in an
// unwritable path), creating missing parent directories.
void CheckWritable(const std::string &path) {
    namespace fs = std::filesystem;
    fs::path p(path);
    std::error_code ec;
    if (p.has_parent_path()) fs::create_directories(p.parent_path(), ec);
    if (ec) throw Error("cannot write '" + path + "': cannot create directory '" + p.parent_path().string() +
                        "': " + ec.message());
    if (fs::is_directory(p, ec)) throw Error("cannot write '" + path + "': it is a directory");
    fs::path probe = p;
    probe += ".phasor-probe";
    FILE *f = std::fopen(probe.c_str(), "wb");
    if (!f) throw Error("cannot write '" + path + "': " + std::strerror(errno));
    std::fclose(f);
    fs::remove(probe, ec);
}

int Render(const CliOptions &o) {
    Diagnostics diag(o.strict);
    auto scene = Load(o, diag);
    if (!scene) return 1;
    RenderSettings &rs = scene->Settings();
    RenderOptions opt;
    opt.spp = o.spp > 0 ? o.spp : rs.spp;
    opt.seed = o.seed >= 0 ? uint64_t(o.seed) : rs.seed;
    opt.threads = o.threads;
    opt.sampler = o.sampler.empty() ? rs.sampler : o.sampler;
    opt.cancel = &gCancel;
    std::string out = !o.output.empty() ? o.output
                      : !rs.output.empty() ? rs.output
                                           : "out/" + std::filesystem::path(o.scene).stem().string() + ".exr";
    std::filesystem::path exr(out), png(out);
    if (exr.extension() == ".png") exr.replace_extension(".exr");
    else png.replace_extension(".png");
    if (exr.extension() != ".exr") {
        std::cerr << "error: output '" << out << "' must end in .exr or .png\n";
        return 1;
    }
    try {
        CheckWritable(exr.string());
        CheckWritable(png.string());
    } catch (const Error &e) {
        std::cerr << "error: " << e.Message() << "\n";
        return 1;
    }

    const Detector &det = scene->GetDetector();
    const Integrator &integrator = scene->GetIntegrator();
    const bool deterministic = integrator.Deterministic();
    // Refuse a resolution the machine cannot hold before allocating anything (film.h).
    if (const double need = Film::MemoryNeeded(det.Width(), det.Height()), avail = AvailableMemory(); need > avail) {
        char buf[256];
        std::snprintf(buf, sizeof buf,
                      "detector '%s': %dx%d pixels need about %.3g GB of memory (%.0f bytes per pixel) but only "
                      "%.3g GB are available; lower its 'resolution' (or raise its 'pitch')",
                      det.name.c_str(), det.Width(), det.Height(), need / 1e9, need / det.Width() / det.Height(),
                      avail / 1e9);
        Diagnostics located;
        located.Report(Error(scene->Where(&det), buf));
        located.Print(std::cerr);
        return 1;
    }
    Film film(det.Width(), det.Height(), det.Response());
    bool bar = !o.quiet && isatty(2);
    auto start = std::chrono::steady_clock::now();
    if (bar)
        opt.progress = [&](int done, int total) {
            double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            double frac = double(done) / total;
            int width = 30, filled = int(frac * width);
            // rs counts its own steps (batches of field nodes) and has no sample rate.
            char rate[48] = "";
            if (!deterministic)
                std::snprintf(rate, sizeof rate, "  %.2f Msamples/s",
                              double(done) * det.Width() * det.Height() / std::max(t, 1e-9) * 1e-6);
            std::fprintf(stderr, "\r[%s%s] %3d%% %d/%d %s  %s elapsed  ETA %s%s   ",
                         std::string(filled, '=').c_str(), std::string(width - filled, ' ').c_str(),
                         int(frac * 100), done, total, deterministic ? "steps" : "spp", FormatDuration(t).c_str(),
                         FormatDuration(frac > 0 ? t / frac - t : 0).c_str(), rate);
            std::fflush(stderr);
        };
    opt.warn = [&](const std::string &w) { std::cerr << (bar ? "\r" : "") << "warning: " << w << "\n"; };
    // The stop handlers stay installed until the outputs are written, so that a signal during
    // the writes cannot leave a temporary file behind.
    gAnnounce = !o.quiet;
    std::signal(SIGINT, OnStopSignal);
    std::signal(SIGTERM, OnStopSignal);
    RenderStats st;
    try {
        st = integrator.Render(*scene, film, opt);
    } catch (const Error &e) {
        if (bar) std::cerr << "\n";
        if (e.Loc().Known()) {  // an error about a scene object: file:line:col with its source line
            Diagnostics located;
            located.Report(e);
            located.Print(std::cerr);
        } else {
            std::cerr << "error: " << e.Message() << "\n";
        }
        return 1;
    }
    if (bar) std::fprintf(stderr, "\n");
    if (!st.hasImage) {  // cancelled before anything honest could be written (rs)
        std::cerr << "interrupted: " << integrator.name << " " << st.work << "; no image written\n";
        return StoppedStatus(gSignal ? int(gSignal) : SIGINT);
    }

    Image img = film.Resolve();
    img.metadata["phasor:scene"] = o.scene;
    img.metadata["phasor:integrator"] = integrator.ToString();
    if (deterministic) {
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
    if (const SensorPlaneGeometry *sp = det.SensorPlane()) {  // pixel centres, for `phasor profile`
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.17g", sp->PixelCenter(0, 0).x);
        img.metadata["phasor:x0_m"] = buf;
        std::snprintf(buf, sizeof buf, "%.17g", sp->pitchX);
        img.metadata["phasor:pitch_m"] = buf;
    }
    // The EXR and the PNG are written all or nothing (core/image/output_file.h): if either fails,
    // neither appears (and earlier files of those names are left as they were).
    try {
        OutputFiles files;
        WriteExr(files, exr.string(), img);
        if (img.height == 1) {
            // A one-row image as a PNG would be N×1 pixels: stage `phasor profile`'s line plot of
            // its intensity instead (x in metres from the metadata for sensor planes).
            CliOptions plot;
            plot.quiet = true;
            plot.profile.inputs = {exr.string()};
            plot.profile.plot = png.string();
            plot.profile.labels = {integrator.name};
            plot.profile.title = std::filesystem::path(o.scene).filename().string() + ": intensity";
            if (RunProfile(plot, {&img}, &files) != 0) return 1;
        } else if (det.Response().GetKind() == SensorResponse::Kind::Radiometric)
            WriteFalseColorPng(files, png.string(), img, "intensity");
        else
            WritePng(files, png.string(), img);
        files.Commit();
    } catch (const Error &e) {
        std::cerr << "error: " << e.Message() << "\n";
        return 1;
    }
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    if (!o.quiet) {
        std::cerr << (st.cancelled ? "interrupted: " : "");
        if (deterministic)
            std::cerr << integrator.name << " " << st.work << " in " << FormatDuration(st.seconds) << "\n";
        else
            std::cerr << "rendered " << st.sppReached << " spp"
                      << (st.sppMax > st.sppReached ? " (" + std::to_string(st.sppMax) + " in some pixels)" : "")
                      << " in " << FormatDuration(st.seconds) << " with " << integrator.name << "\n";
        for (const std::string &w : st.counters.Warnings()) std::cerr << "warning: " << w << "\n";
        if (!st.cancelled && std::all_of(img.data.begin(), img.data.end(), [](float v) { return v == 0; }))
            std::cerr << "warning: the image is black: " << scene->DarkImageCause() << "\n";
        if (st.invalidSamples > 0)
            std::cerr << "warning: " << st.invalidSamples
                      << " samples were NaN, negative or beyond the float range of the image (|v| > 3.4e38) "
                         "and were discarded (counted in phasor:invalid_samples)\n";
        std::cerr << "wrote " << exr.string() << " and " << png.string() << "\n";
    }
    if (gSignal) return StoppedStatus(int(gSignal));
    return 0;
}

int Check(const CliOptions &o) {
    Diagnostics diag(o.strict);
    auto scene = Load(o, diag);
    if (!scene) return 1;
    if (!o.quiet) std::cerr << o.scene << ": ok\n";
    return 0;
}

int Format(const CliOptions &o) {
    Diagnostics diag;
    auto text = FormatSceneFile(o.scene, diag);
    diag.Print(std::cerr, Colour());
    if (!text || diag.HasErrors()) return 1;
    std::cout << *text;
    return 0;
}

/// The family a command-line word names: "material", "Material", "materials", or "kernel(s)" for
/// materials. Empty (with an error and a suggestion printed) when it names none.
std::string ResolveFamily(const std::string &word) {
    std::string w = word;
    if (w.size() > 1 && (w.back() == 's' || w.back() == 'S')) {
        bool known = false;  // keep a trailing 's' that belongs to the name
        for (const FamilyInfo &f : AllFamilies()) known |= (w == f.family || w == f.keyword);
        if (!known) w.pop_back();
    }
    if (w == "kernel" || w == "Kernel") w = "material";
    std::vector<std::string> names;
    for (const FamilyInfo &f : AllFamilies()) {
        if (w == f.family || w == f.keyword) return f.family;
        names.push_back(f.family);
    }
    const std::string sug = Suggest(w, names);
    std::cerr << "error: unknown family '" << word << "'"
              << (sug.empty() ? "" : "; did you mean '" + sug + "'?") << " (families:";
    for (const std::string &n : names) std::cerr << " " << n;
    std::cerr << ")\n";
    return {};
}

int List(const CliOptions &o) {
    const std::string family = o.family.empty() ? "" : ResolveFamily(o.family);
    if (!o.family.empty() && family.empty()) return 1;
    for (const FamilyInfo &f : AllFamilies()) {
        if (!family.empty() && family != f.family) continue;
        std::cout << f.family << " (" << f.keyword << "):\n";
        for (const Schema *s : f.schemas) std::cout << "  " << s->name << " — " << s->doc << "\n";
    }
    return 0;
}

int Describe(const CliOptions &o) {
    if (o.markdown) {
        std::cout << "# phasor plug-in reference\n\nGenerated by `phasor describe --markdown` from the plug-ins' "
                     "schemas; do not edit by hand.\n\n";
        for (const FamilyInfo &f : AllFamilies()) {
            std::cout << "## " << f.keyword << "\n\n";
            for (const Schema *s : f.schemas) std::cout << s->Markdown();
        }
        std::cout << "## Render\n\n";
        std::cout << RenderSchema().Markdown();
        return 0;
    }
    if (o.family.empty() && (o.name == "Render" || o.name == "render")) {  // the Render block
        std::cout << RenderSchema().Describe();
        return 0;
    }
    if (o.family.empty()) {  // `describe NAME`: the one plug-in of that name in any family
        std::vector<const Schema *> found;
        std::vector<std::string> all;
        for (const FamilyInfo &f : AllFamilies())
            for (const Schema *x : f.schemas) {
                if (x->name == o.name) found.push_back(x);
                all.push_back(x->name);
            }
        if (found.size() == 1) {
            std::cout << found[0]->Describe();
            return 0;
        }
        if (found.empty()) {
            const std::string sug = Suggest(o.name, all);
            std::cerr << "error: no plug-in named '" << o.name << "'"
                      << (sug.empty() ? "" : "; did you mean '" + sug + "'?") << " (see 'phasor list')\n";
        } else {
            std::cerr << "error: '" << o.name << "' names a plug-in in several families; say which:";
            for (const Schema *x : found) std::cerr << " 'phasor describe " << x->family << " " << o.name << "'";
            std::cerr << "\n";
        }
        return 1;
    }
    const std::string family = ResolveFamily(o.family);
    if (family.empty()) return 1;
    const Schema *s = FindSchema(family, o.name);
    if (!s) {
        std::vector<std::string> names;
        for (const FamilyInfo &f : AllFamilies())
            if (f.family == family)
                for (const Schema *x : f.schemas) names.push_back(x->name);
        std::string sug = Suggest(o.name, names);
        std::cerr << "error: no " << family << " named '" << o.name << "'"
                  << (sug.empty() ? "" : "; did you mean '" + sug + "'?") << "\n";
        return 1;
    }
    std::cout << s->Describe();
    return 0;
}

// Whatever a command prints on stdout (CSV, `format`, `describe`, `list`) is collected and written
// at the end with checked write(2) calls: a full disk or a closed pipe is an error with its
// reason and exit status 1, never a silent truncation.
class StdoutCapture {
  public:
    StdoutCapture() : old_(std::cout.rdbuf(text_.rdbuf())) {}
    ~StdoutCapture() { std::cout.rdbuf(old_); }
    /// Writes the collected text to file descriptor 1; returns `status`, or 1 after an error.
    int Flush(int status) {
        std::cout.rdbuf(old_);
        const std::string text = text_.str();
        text_.str({});
        const char *p = text.data();
        std::size_t left = text.size();
        while (left > 0) {
            const ssize_t n = ::write(1, p, left);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) {
                std::cerr << "error: cannot write to standard output: "
                          << (n < 0 ? std::strerror(errno) : "write failed") << "\n";
                return 1;
            }
            p += n;
            left -= std::size_t(n);
        }
        return status;
    }

  private:
    std::ostringstream text_;
    std::streambuf *old_;
};

int RunCommand(const CliOptions &o) {
    switch (o.command) {
        case Command::Help: std::cout << Usage(); return 0;
        case Command::Version: std::cout << "phasor " << PHASOR_VERSION << "\n"; return 0;
        case Command::Render: return Render(o);
        case Command::Check: return Check(o);
        case Command::Format: return Format(o);
        case Command::List: return List(o);
        case Command::Describe: return Describe(o);
        case Command::Profile: return RunProfile(o);
        case Command::Probe: return RunProbe(o);
    }
    return 1;
}

}  // namespace

int main(int argc, char **argv) {
    // A file-size limit (RLIMIT_FSIZE, `ulimit -f`) then makes write(2) fail with EFBIG, reported
    // as "cannot write 'FILE': File too large", instead of killing the program with SIGXFSZ.
    std::signal(SIGXFSZ, SIG_IGN);
    CliOptions o;
    std::string err;
    if (!ParseCommandLine(argc, argv, o, err)) {
        std::cerr << "error: " << err << "\n" << Usage();
        return 1;
    }
    StdoutCapture out;
    try {
        return out.Flush(RunCommand(o));
    } catch (const Error &e) {
        out.Flush(1);
        std::cerr << (e.Loc().Known() ? e.Loc().ToString() + ": " : "") << "error: " << e.Message() << "\n";
        return 1;
    } catch (const std::exception &e) {
        out.Flush(2);
        std::cerr << "internal error: " << e.what() << "\n";
        return 2;
    }
}
