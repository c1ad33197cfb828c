// SPDX-License-Identifier: Apache-2.0
// phasor — the command-line program: render, check, format, list, describe, profile, probe, compare.
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
#include "app/compare.h"
#include "app/distributed.h"
#include "app/plot.h"
#include "app/probe.h"
#include "app/profile.h"
#include "app/render.h"
#include "app/render_common.h"
#include "core/image/image_io.h"
#include "core/render/registry.h"
#include "core/render/scene.h"
#include "parser/parser.h"

using namespace phasor;

namespace {

// The usage text, in two parts around the list of families (from the registry).
const char *kUsageHead =
    "usage: phasor <command> [options]\n"
    "\n"
    "commands:\n"
    "  render SCENE [-o FILE] [--spp N] [--threads N] [--seed S] [--integrator NAME]\n"
    "               [--sampler sobol|independent] [-D name=value ...] [--strict | --permissive]\n"
    "               [--quiet] [--sweep NAME=v1,v2,... ...] [--checkpoint SECONDS]\n"
    "                      render SCENE to FILE (.exr; a .png is written beside it); --sweep: one\n"
    "                      render per value (FILE-NAME=v.exr); --checkpoint: FILE.ckpt every SECONDS\n"
    "  render --resume FILE.ckpt [--spp N] [...]\n"
    "                      continue a checkpointed render (bit for bit); under mpirun/srun the\n"
    "                      ranks share the work (docs/distributed.md)\n"
    "  check SCENE [-D name=value ...] [--strict | --permissive]\n"
    "                      load and validate only; exit status 0 if the scene is valid\n"
    "                      (unknown parameters and -D names that match no Define are errors;\n"
    "                      --permissive makes them warnings, --strict makes every warning an error)\n"
    "  format SCENE        print SCENE in canonical form\n"
    "  list [FAMILY]       list the plug-ins of every family or of FAMILY, one of\n";
const char *kUsageTail =
    "  describe [FAMILY] NAME print a plug-in's parameters (FAMILY only if NAME is in several)\n"
    "  describe --markdown    print every plug-in's parameters as Markdown (docs/plugins.md)\n"
    "  profile IMAGE.exr [IMAGE.exr ...] [--row N | --column N] [--channel NAME] [--csv FILE|-]\n"
    "          [--plot FILE.png] [--label NAME ...] [--x0 M --pitch M] [--diff-scale N] [--title TEXT]\n"
    "                      one row (default: the middle one) or column of a channel (default:\n"
    "                      intensity) of each image as CSV (stdout unless --csv/--plot) and/or a line\n"
    "                      plot (matplotlib); with two images also |a - b| and max |a - b| / max(b)\n"
    "  probe SCENE --material NAME --theta ANGLE [--phi ANGLE] --lambda LENGTH [--uv U V]\n"
    "        [--samples N] [--seed S] [--ray] [--csv FILE|-] [--plot FILE.png] [-D name=value ...]\n"
    "                      one kernel of SCENE lit from (theta, phi) at wavelength lambda (e.g. 30deg,\n"
    "                      550nm): reflectance R and transmittance T (power; continuous lobes by Monte\n"
    "                      Carlo with a standard error), each near-delta lobe's direction and efficiency;\n"
    "                      --ray: the ray-optics limit; --plot: the angular distribution\n"
    "  compare SCENE --integrators A,B[,...]|all [--spp N | --time SECONDS]\n"
    "          [--reference FILE.exr | --reference-integrator NAME [--reference-spp N]]\n"
    "          [--row N | --column N] [-o DIR] [-D name=value ...] [--seed S] [--threads N] [--quiet]\n"
    "                      render SCENE with each integrator (equal spp or equal time) and compare\n"
    "                      them: EXR/PNG each, grid, differences, table, plots, DIR/index.html\n"
    "  --version, --help\n";

std::string Usage() {
    std::string families;
    for (const FamilyInfo &f : AllFamilies()) families += " " + f.family;
    return kUsageHead + std::string("                     ") + families + "\n" + kUsageTail;
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
        if (!dist::Root()) return status;  // one voice under MPI: rank 0's
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
        case Command::Render: return RunRender(o);
        case Command::Check: return Check(o);
        case Command::Format: return Format(o);
        case Command::List: return List(o);
        case Command::Describe: return Describe(o);
        case Command::Profile: return RunProfile(o);
        case Command::Probe: return RunProbe(o);
        case Command::Compare: return RunCompare(o);
    }
    return 1;
}

// The command on this process: under MPI, `render` and `compare` run on every rank together; every
// other command runs on rank 0 alone (the others wait for its status).
int RunOnRank(const CliOptions &o, StdoutCapture &out) {
    const bool together = o.command == Command::Render || o.command == Command::Compare;
    if (!dist::Root() && !together) return dist::Agree(0);
    try {
        const int status = out.Flush(RunCommand(o));
        return together ? status : dist::Agree(status);
    } catch (const Error &e) {
        out.Flush(1);
        std::cerr << (e.Loc().Known() ? e.Loc().ToString() + ": " : "") << "error: " << e.Message() << "\n";
        return together ? 1 : dist::Agree(1);
    } catch (const std::exception &e) {
        out.Flush(2);
        std::cerr << "internal error: " << e.what() << "\n";
        return together ? 2 : dist::Agree(2);
    }
}

}  // namespace

int main(int argc, char **argv) {
    // A file-size limit (RLIMIT_FSIZE, `ulimit -f`) then makes write(2) fail with EFBIG, reported
    // as "cannot write 'FILE': File too large", instead of killing the program with SIGXFSZ.
    std::signal(SIGXFSZ, SIG_IGN);
    // MPI when an MPI launcher started the program (distributed.h); then rank 0 alone prints.
    if (!dist::Start(argc, argv)) return 1;
    struct Finish {
        ~Finish() { dist::Finish(); }
    } finish;
    CliOptions o;
    std::string err;
    if (!ParseCommandLine(argc, argv, o, err)) {  // every rank sees the same arguments
        std::cerr << "error: " << err << "\n" << Usage();
        return 1;
    }
    StdoutCapture out;
    return RunOnRank(o, out);
}
