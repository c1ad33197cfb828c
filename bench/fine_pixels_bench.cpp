// SPDX-License-Identifier: Apache-2.0
// Fine pixels behind an aperture (issue 20 §1, docs/narrow_pixels.md): `grt` against `rs` on
// scenes/validation/fine_pixels.wscene, in one run.
//   1. The issue's table: the 60 µm hole 20 mm before a row 0.21 mm wide of 41, 81, 121 and 201
//      pixels, plane wave and TEM00 beam (w0 = 90 µm): the centre pixel's grt/rs − 1, the row's
//      largest |grt − rs| over its peak, and both times.
//   2. A wider grid than the test's (tests/validation/fine_pixels_cases.h): pitch λ/2 … 20λ ×
//      plane wave / beam × hole / double slit × three positions of a 5-pixel row (on the axis;
//      80 µm off it under 0.2° incidence; 150 µm off it under 0.5°), one CSV line per cell in
//      the accuracy map's columns. Every cell must be within 2e-3 of its peak (exit status 1
//      otherwise).
//
//   bench_fine_pixels [--threads T] [--grid-only | --table-only]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>

#include "support/scene_builder.h"
#include "validation/fine_pixels_cases.h"

using namespace phasor;

namespace {

struct Result {
    std::vector<double> row;
    double seconds = 0;
};

Result Run(const std::string &integrator, const DefineList &defines, int threads) {
    Diagnostics diag;
    const std::string scene = std::string(PHASOR_SOURCE_DIR) + "/scenes/validation/fine_pixels.wscene";
    auto desc = ParseSceneFile(scene, defines, diag);
    std::unique_ptr<Scene> built;
    if (desc) built = Scene::Build(*desc, diag, integrator);
    if (!built) {
        diag.Print(std::cerr);
        std::exit(1);
    }
    const Detector &det = built->GetDetector();
    Film film(det.Width(), det.Height(), det.Response());
    RenderOptions opt;
    opt.spp = built->Settings().options.spp;
    opt.seed = 1;
    opt.threads = threads;
    const auto start = std::chrono::steady_clock::now();
    built->GetIntegrator().Render(*built, film, opt);
    Result r;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const Image img = film.Resolve();
    const int c = img.ChannelIndex("intensity");
    for (int i = 0; i < img.width; ++i) r.row.push_back(img.At(i, img.height / 2, c));
    return r;
}

struct Compared {
    double errOfPeak = 0, centre = 0, grtSeconds = 0, rsSeconds = 0;
};

Compared Compare(const DefineList &defines, int threads) {
    const Result g = Run("grt", defines, threads), r = Run("rs", defines, threads);
    Compared c;
    double peak = 0;
    for (std::size_t i = 0; i < r.row.size(); ++i) {
        c.errOfPeak = std::max(c.errOfPeak, std::abs(g.row[i] - r.row[i]));
        peak = std::max(peak, r.row[i]);
    }
    c.errOfPeak /= peak;
    c.centre = g.row[g.row.size() / 2] / r.row[r.row.size() / 2] - 1;
    c.grtSeconds = g.seconds;
    c.rsSeconds = r.seconds;
    return c;
}

void IssueTable(int threads) {
    std::printf("issue 20 §1: 60 um hole, 633 nm, sensor 0.21 mm wide 20 mm behind (spp 4096)\n");
    std::printf("| pixels (pitch) | source | centre grt/rs - 1 | max|grt-rs| / peak | grt [s] | rs [s] |\n");
    std::printf("|---|---|---|---|---|---|\n");
    for (int n : {41, 81, 121, 201})
        for (const char *source : {"plane", "beam"}) {
            const double pitch = 210.0 / n;  // µm
            char p[32];
            std::snprintf(p, sizeof p, "%.6gum", pitch);
            const Compared c =
                Compare({{"pitch", p}, {"n", std::to_string(n)}, {"source", std::string("\"") + source + "\""}},
                        threads);
            std::printf("| %d (%.2f um) | %s | %+.1e | %.1e | %.2f | %.2f |\n", n, pitch, source, c.centre, c.errOfPeak,
                        c.grtSeconds, c.rsSeconds);
            std::fflush(stdout);
        }
}

bool Grid(int threads) {
    std::printf("\ngrid (5 pixels a row, spp 4096), tolerance 2e-3 of the row's peak\n");
    std::printf("pitch_over_lambda,source,aperture,offset_um,tilt_deg,max_err_of_peak,centre_rel,grt_s,rs_s\n");
    bool ok = true;
    for (double p : {0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 5.0, 7.0, 10.0, 14.0, 20.0})
        for (const char *source : {"plane", "beam"})
            for (const char *aperture : {"disc", "slits"})
                for (const auto &[offset, tilt] : {std::pair{0.0, 0.0}, {80.0, 0.2}, {-150.0, 0.5}}) {
                    const test::FinePixelCase cell{p, source, aperture, offset, tilt, 5};
                    const Compared c = Compare(test::FinePixelDefines(cell), threads);
                    ok = ok && c.errOfPeak <= 2e-3;
                    std::printf("%g,%s,%s,%g,%g,%.2e,%+.2e,%.3f,%.3f%s\n", p, source, aperture, offset, tilt,
                                c.errOfPeak, c.centre, c.grtSeconds, c.rsSeconds, c.errOfPeak <= 2e-3 ? "" : ",FAIL");
                    std::fflush(stdout);
                }
    return ok;
}

}  // namespace

int main(int argc, char **argv) {
    int threads = 0;
    bool table = true, grid = true;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--grid-only")) table = false;
        else if (!std::strcmp(argv[i], "--table-only")) grid = false;
        else {
            std::fprintf(stderr, "usage: bench_fine_pixels [--threads T] [--grid-only | --table-only]\n");
            return 2;
        }
    }
    if (table) IssueTable(threads);
    if (grid && !Grid(threads)) {
        std::printf("some cells are beyond 2e-3 of their peak\n");
        return 1;
    }
    return 0;
}
