// SPDX-License-Identifier: Apache-2.0
// phasor — the command-line program: render, check, format, list, describe, profile.
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
#include <sstream>

#include "app/cli.h"
#include "app/profile.h"
#include "core/image_io.h"
#include "core/registry.h"
#include "core/scene.h"
#include "parser/parser.h"

using namespace phasor;

namespace {

std::atomic<bool> gCancel{false};

extern "C" void OnSigint(int) {
    gCancel.store(true);
    std::signal(SIGINT, SIG_DFL);  // a second Ctrl-C ends the program at once
}

const char *kUsage =
    "usage: phasor <command> [options]\n"
    "\n"
    "commands:\n"
    "  render SCENE [-o FILE] [--spp N] [--threads N] [--seed S] [--integrator NAME]\n"
    "               [--sampler sobol|independent] [-D name=value ...] [--strict] [--quiet]\n"
    "                      render SCENE to FILE (.exr; a .png is written beside it)\n"
    "  check SCENE [-D name=value ...] [--strict]\n"
    "                      load and validate only; exit status 0 if the scene is valid\n"
    "  format SCENE        print SCENE in canonical form\n"
    "  list [FAMILY]       list plug-ins (families: spectrum texture material shape light\n"
    "                      detector integrator)\n"
    "  describe [FAMILY] NAME print a plug-in's parameters (FAMILY only if NAME is in several)\n"
    "  describe --markdown    print every plug-in's parameters as Markdown (docs/plugins.md)\n"
    "  profile IMAGE.exr [IMAGE.exr ...] [--row N] [--channel NAME] [--csv FILE|-] [--plot FILE.png]\n"
    "          [--label NAME ...] [--x0 M --pitch M] [--diff-scale N] [--title TEXT]\n"
    "                      one row (default: the middle one) of a channel (default: intensity) of\n"
    "                      each image as CSV (stdout unless --csv/--plot) and/or a line plot; with\n"
    "                      two images also |a - b| and max |a - b| / max(b)\n"
    "  --version, --help\n";

bool Colour() { return isatty(2) && !std::getenv("NO_COLOR"); }

// Parses and builds; prints diagnostics. Returns nullptr on error.
std::unique_ptr<Scene> Load(const CliOptions &o, Diagnostics &diag) {
    auto desc = ParseSceneFile(o.scene, o.defines, diag);
    std::unique_ptr<Scene> scene;
    if (desc && !diag.HasErrors()) scene = Scene::Build(*desc, diag, o.integrator);
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
            double rate = double(done) * det.Width() * det.Height() / std::max(t, 1e-9);
            std::fprintf(stderr, "\r[%s%s] %3d%% %d/%d spp  %s elapsed  ETA %s  %.2f Msamples/s   ",
                         std::string(filled, '=').c_str(), std::string(width - filled, ' ').c_str(),
                         int(frac * 100), done, total, FormatDuration(t).c_str(),
                         FormatDuration(frac > 0 ? t / frac - t : 0).c_str(), rate * 1e-6);
            std::fflush(stderr);
        };
    opt.warn = [&](const std::string &w) { std::cerr << (bar ? "\r" : "") << "warning: " << w << "\n"; };
    std::signal(SIGINT, OnSigint);
    RenderStats st;
    try {
        st = scene->GetIntegrator().Render(*scene, film, opt);
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
    std::signal(SIGINT, SIG_DFL);
    if (bar) std::fprintf(stderr, "\n");

    Image img = film.Resolve();
    img.metadata["phasor:scene"] = o.scene;
    img.metadata["phasor:integrator"] = scene->GetIntegrator().ToString();
    img.metadata["phasor:spp_requested"] = std::to_string(opt.spp);
    img.metadata["phasor:spp_reached"] = std::to_string(st.sppReached);
    img.metadata["phasor:seed"] = std::to_string(opt.seed);
    img.metadata["phasor:sampler"] = opt.sampler;
    img.metadata["phasor:render_seconds"] = std::to_string(st.seconds);
    img.metadata["phasor:cancelled"] = st.cancelled ? "true" : "false";
    if (const SensorPlaneGeometry *sp = det.SensorPlane()) {  // pixel centres, for `phasor profile`
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.17g", sp->PixelCenter(0, 0).x);
        img.metadata["phasor:x0_m"] = buf;
        std::snprintf(buf, sizeof buf, "%.17g", sp->pitchX);
        img.metadata["phasor:pitch_m"] = buf;
    }
    try {
        WriteExr(exr.string(), img);
        if (img.height == 1) {
            // A one-row image as a PNG would be N×1 pixels: write `phasor profile`'s line plot of
            // its intensity instead (x in metres from the EXR's metadata for sensor planes).
            CliOptions plot;
            plot.quiet = true;
            plot.profile.inputs = {exr.string()};
            plot.profile.plot = png.string();
            plot.profile.labels = {scene->GetIntegrator().name};
            plot.profile.title = std::filesystem::path(o.scene).filename().string() + ": intensity";
            if (RunProfile(plot) != 0) return 1;
        } else if (det.Response().GetKind() == SensorResponse::Kind::Radiometric)
            WriteFalseColorPng(png.string(), img, "intensity");
        else
            WritePng(png.string(), img);
    } catch (const Error &e) {
        std::cerr << "error: " << e.Message() << "\n";
        return 1;
    }
    if (!o.quiet) {
        std::cerr << (st.cancelled ? "interrupted: " : "") << "rendered " << st.sppReached << " spp in "
                  << FormatDuration(st.seconds) << " with " << scene->GetIntegrator().name << "\n";
        if (st.footprintAfterSpreadFree > 0)
            std::cerr << "warning: " << st.footprintAfterSpreadFree
                      << " path vertices met an aperture after another aperture; it acted geometrically "
                         "(only the first footprint-aware kernel on a path diffracts)\n";
        if (st.specularAfterSpreadFree > 0)
            std::cerr << "warning: " << st.specularAfterSpreadFree
                      << " path vertices scattered specularly after an aperture; delta lights (plane "
                         "waves, point, spot, directional, laser beams) are not reached through such a "
                         "surface, so their light behind it is missing (theory §9 item 5)\n";
        if (!st.cancelled && std::all_of(img.data.begin(), img.data.end(), [](float v) { return v == 0; }))
            std::cerr << "warning: the image is black: " << scene->DarkImageCause() << "\n";
        if (st.invalidSamples > 0)
            std::cerr << "warning: " << st.invalidSamples << " samples were NaN/Inf/negative and were discarded\n";
        std::cerr << "wrote " << exr.string() << " and " << png.string() << "\n";
    }
    return st.cancelled ? 130 : 0;
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

}  // namespace

int main(int argc, char **argv) {
    CliOptions o;
    std::string err;
    if (!ParseCommandLine(argc, argv, o, err)) {
        std::cerr << "error: " << err << "\n" << kUsage;
        return 1;
    }
    try {
        switch (o.command) {
            case Command::Help: std::cout << kUsage; return 0;
            case Command::Version: std::cout << "phasor " << PHASOR_VERSION << "\n"; return 0;
            case Command::Render: return Render(o);
            case Command::Check: return Check(o);
            case Command::Format: return Format(o);
            case Command::List: return List(o);
            case Command::Describe: return Describe(o);
            case Command::Profile: return RunProfile(o);
        }
    } catch (const Error &e) {
        std::cerr << (e.Loc().Known() ? e.Loc().ToString() + ": " : "") << "error: " << e.Message() << "\n";
        return 1;
    } catch (const std::exception &e) {
        std::cerr << "internal error: " << e.what() << "\n";
        return 2;
    }
    return 1;
}
