// SPDX-License-Identifier: Apache-2.0
// `grt` vs `rs` on the paper's double slit (scenes/validation/double_slit.wscene, d = 100 µm,
// 4000 µm slits, 48 Gaussian pixels), in one run (issue 5; the paper reports 8.9 s vs 246 s,
// 27.6×). Both solve the same 3-D problem. A strict `rs` (3-D, accuracy 1e-9) is the reference;
// `rs` is then timed at its documented accuracy (the default, 1e-4 of peak) and at 2e-3 (the
// error grt is held to), each with its measured error; `grt` runs with growing stratified
// direction lattices until its row is within 2e-3 of the reference's peak. Times are medians of
// three runs. `rs`'s 2-D mode (slits taken as infinite, ≈1.3e-4 of peak away from the 4000 µm
// slits) is timed too: on this scene it is the cheapest answer of all, a symmetry grt cannot use.
//
//   bench_double_slit [--threads T] [--d <micrometres>]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>

#include "parser/parser.h"
#include "support/scene_builder.h"

using namespace phasor;

namespace {

struct Result {
    std::vector<double> row;
    double seconds = 0;
};

Result Run(const std::string &integrator, const DefineList &defines, int spp, int threads,
           const std::string &rsMode = "", double rsAccuracy = 0, int repeats = 1) {
    Diagnostics diag;
    const std::string scene = std::string(PHASOR_SOURCE_DIR) + "/scenes/validation/double_slit.wscene";
    auto desc = ParseSceneFile(scene, defines, diag);
    if (!desc) {
        diag.Print(std::cerr);
        std::exit(1);
    }
    if (!rsMode.empty())
        for (SceneEntity &e : desc->entities)
            if (e.keyword == "Integrator" && e.type == "rs") {
                e.params.Set("mode", Value::String(rsMode));
                if (rsAccuracy > 0) e.params.Set("accuracy", Value::Number(rsAccuracy));
            }
    auto built = Scene::Build(*desc, diag, integrator);
    if (!built) {
        diag.Print(std::cerr);
        std::exit(1);
    }
    const Detector &det = built->GetDetector();
    RenderOptions opt;
    opt.spp = spp;
    opt.seed = 1;
    opt.threads = threads;
    Result r;
    std::vector<double> times;
    for (int k = 0; k < repeats; ++k) {
        Film film(det.Width(), det.Height(), det.Response());
        const auto start = std::chrono::steady_clock::now();
        built->GetIntegrator().Render(*built, film, opt);
        times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        if (k == 0) {
            const Image img = film.Resolve();
            const int c = img.ChannelIndex("intensity");
            for (int i = 0; i < img.width; ++i) r.row.push_back(img.At(i, img.height / 2, c));
        }
    }
    std::sort(times.begin(), times.end());
    r.seconds = times[times.size() / 2];
    return r;
}

double ErrorOfPeak(const std::vector<double> &a, const std::vector<double> &ref) {
    double m = 0, peak = 0;
    for (std::size_t i = 0; i < ref.size(); ++i) {
        m = std::max(m, std::abs(a[i] - ref[i]));
        peak = std::max(peak, ref[i]);
    }
    return m / peak;
}

}  // namespace

int main(int argc, char **argv) {
    int threads = 0;
    std::string d = "100";
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--d") && i + 1 < argc) d = argv[++i];
        else {
            std::fprintf(stderr, "usage: bench_double_slit [--threads T] [--d <micrometres>]\n");
            return 2;
        }
    }
    const DefineList defines = {{"d", d + "um"}};
    std::printf("double slit d = %s um, 48 Gaussian pixels, lambda = 1 um, z = 10 mm, 4000 um slits\n", d.c_str());
    const Result ref = Run("rs", defines, 1, threads, "3d", 1e-9);
    std::printf("  rs 3-D, accuracy 1e-9 (reference)         %9.3f s\n", ref.seconds);
    const Result rs3 = Run("rs", defines, 1, threads, "3d", 1e-4, 3);
    const double eRs3 = ErrorOfPeak(rs3.row, ref.row);
    std::printf("  rs 3-D, accuracy 1e-4 (documented)        %9.3f s   error %.2e of peak\n", rs3.seconds, eRs3);
    const Result rsLoose = Run("rs", defines, 1, threads, "3d", 2e-3, 3);
    const double eLoose = ErrorOfPeak(rsLoose.row, ref.row);
    std::printf("  rs 3-D, accuracy 2e-3                     %9.3f s   error %.2e of peak\n", rsLoose.seconds, eLoose);
    const Result rs2 = Run("rs", defines, 1, threads, "2d", 1e-4, 3);
    std::printf("  rs 2-D (infinite slits), accuracy 1e-4    %9.4f s   error %.2e of peak\n", rs2.seconds,
                ErrorOfPeak(rs2.row, ref.row));
    double tGrt = 0, eGrt = 0;
    int nGrt = 0;
    for (int n : {8, 16, 24, 32, 48, 64}) {
        const Result g = Run("grt", defines, n * n, threads, "", 0, 3);
        const double e = ErrorOfPeak(g.row, ref.row);
        std::printf("  grt %2dx%-2d lattice                        %9.3f s   error %.2e of peak\n", n, n, g.seconds, e);
        if (e <= 2e-3 && nGrt == 0) {
            tGrt = g.seconds;
            eGrt = e;
            nGrt = n;
        }
    }
    if (nGrt == 0) {
        std::printf("  grt did not reach 2e-3 of peak\n");
        return 1;
    }
    if (eRs3 > 1e-4 || eLoose > 2e-3) {
        std::printf("  rs missed its accuracy target\n");
        return 1;
    }
    std::printf("grt %dx%d (%.1e) %.3f s vs rs 3-D: at its documented 1e-4 %.3f s -> rs/grt = %.0fx (goal >= 100x); "
                "at the same 2e-3 %.3f s -> %.0fx (paper: 27.6x); rs 2-D is %.1fx faster than grt\n",
                nGrt, nGrt, eGrt, tGrt, rs3.seconds, rs3.seconds / tGrt, rsLoose.seconds, rsLoose.seconds / tGrt,
                tGrt / std::max(rs2.seconds, 1e-9));
    return 0;
}
