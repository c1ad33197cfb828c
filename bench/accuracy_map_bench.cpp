// SPDX-License-Identifier: Apache-2.0
// The accuracy map's larger grid (issue 20 §3; docs/accuracy.md): the families of
// tests/accuracy/accuracy_map.h over more thicknesses, angles, source sizes, pixel sizes, grating
// heights and beam distances than `make test` affords (the ctest `test_accuracy` runs a subset).
// Writes DIR/accuracy_map_large.csv and the heat map DIR/accuracy_map_large.png (python/phasor_plot.py)
// and prints each family's worst cell; exit status 1 if any cell is beyond its tolerance.
//
//   build/bench/bench_accuracy_map [DIR]        (default: ./accuracy; ~15 min of one idle core)
#include <cstdio>
#include <filesystem>

#include "accuracy/accuracy_map.h"

using namespace phasor;
using namespace phasor::test;

namespace {

void Report(const AccuracyMap &m, const std::string &family) {
    int n = 0, bad = 0;
    double worst = 0;
    const AccuracyCell *w = nullptr;
    for (const AccuracyCell &c : m.cells) {
        if (c.family != family) continue;
        ++n;
        bad += !c.Passes();
        if (c.error / c.tolerance >= worst) {
            worst = c.error / c.tolerance;
            w = &c;
        }
    }
    std::printf("%-10s %6d cells, %4d beyond tolerance, worst %.3g of its tolerance", family.c_str(), n, bad, worst);
    if (w) std::printf(" (%s | %s | %s: error %.3g)", w->row.c_str(), w->column.c_str(), w->integrator.c_str(), w->error);
    std::printf("\n");
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char **argv) {
    const std::string dir = argc > 1 ? argv[1] : "accuracy";
    std::filesystem::create_directories(dir);
    const std::vector<std::string> integrators = {"gr", "solve"};
    AccuracyMap map;

    // Films: 0.1–100 µm × 0–70° × sources of 0.01–10° (disc, Gaussian) × free/glass × R/T (beyond
    // 70° the one-pixel sensor's 20° cone starts to see the source itself under a 10° disc).
    AddFilmCells(map,
                 FilmGrid({0.1e-6, 0.3e-6, 1e-6, 3e-6, 10e-6, 30e-6, 100e-6}, {0, 2, 5, 10, 20, 30, 45, 60, 70},
                          {0.01, 0.05, 0.5, 2, 5, 10}),
                 integrators, 0.01);
    Report(map, "films");
    // Pixel size: a sensor integrating the source over its directions reads the same for any σ.
    {
        std::vector<FilmCase> cases;
        for (double sigma : {0.3e-6, 1e-6, 10e-6, 50e-6})
            for (double d : {1e-6, 10e-6, 30e-6})
                for (double theta : {0.0, 10.0, 45.0})
                    for (double r : {0.5, 2.0}) {
                        FilmCase c;
                        c.thickness = d;
                        c.thetaDeg = theta;
                        c.radiusDeg = r;
                        c.sigma = sigma;
                        c.acceptanceDeg = sigma < 1.5e-6 ? 90 : 20;
                        cases.push_back(c);
                    }
        AddFilmCells(map, cases, integrators, 0.01, "pixels");
        Report(map, "pixels");
    }
    // Stacks: the beetle's reflector across the visible, 0–70°, discs and Gaussians of 0.5–10°.
    {
        std::vector<StackCase> cases;
        for (double lambda : {420e-9, 450e-9, 490e-9, 530e-9, 570e-9, 620e-9, 680e-9})
            for (double theta : {0.0, 15.0, 30.0, 45.0, 60.0, 70.0})
                for (const char *source : {"disc", "gaussian"})
                    for (double r : {0.5, 2.0, 5.0, 10.0}) {
                        StackCase c;
                        c.lambda = lambda;
                        c.thetaDeg = theta;
                        c.source = source;
                        c.radiusDeg = r;
                        cases.push_back(c);
                    }
        AddStackCells(map, cases, integrators, 0.01);
        Report(map, "stacks");
    }
    // Gratings: h/λ 0.02–0.5, incidence 0–60°, orders −3…3, a plane wave or a disc of 0.5–5°.
    {
        std::vector<GratingCase> cases;
        for (double h : {0.02, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5})
            for (double theta : {0.0, 10.0, 20.0, 30.0, 45.0, 60.0})
                for (int order = -3; order <= 3; ++order)
                    for (double r : {0.0, 0.5, 2.0, 5.0}) {
                        GratingCase c;
                        c.heightOverLambda = h;
                        c.thetaDeg = theta;
                        c.order = order;
                        c.source = r > 0 ? "disc" : "plane_wave";
                        c.radiusDeg = r;
                        cases.push_back(c);
                    }
        AddGratingCells(map, cases, integrators, 0.01);
        Report(map, "gratings");
    }
    // Beams: a Gaussian beam through or off films of 5–50 µm, its waist 0–10 mm before the film.
    for (double d : {5e-6, 20e-6, 50e-6})
        for (bool t : {false, true})
            for (double before : {0.0, 1e-3, 5e-3, 10e-3}) {
                BeamCase c;
                c.thickness = d;
                c.transmission = t;
                c.waistBefore = before;
                if (before > 0) {  // the beam has spread: a wider sensor
                    c.pixels = before > 5e-3 ? 81 : 61;
                    c.pitch = 8e-6;
                }
                const double ref = c.Reference();
                for (const std::string &integrator : integrators) {
                    const double v = c.Collected(integrator);
                    map.Add({"beams", Fmt("film %g um", d * 1e6) + (t ? " T" : " R"), Fmt("waist %g mm before", before * 1e3),
                             integrator, v, ref, std::abs(v - ref) / ref, before > 0 ? 5e-3 : 1e-3});
                }
            }
    Report(map, "beams");
    AddApertureCells(map, ApertureCases());
    Report(map, "apertures");

    map.WriteCsv(dir + "/accuracy_map_large.csv");
    const int rc = DrawAccuracyMap(dir + "/accuracy_map_large.csv", dir + "/accuracy_map_large.png",
                                   "phasor accuracy map (bench)");
    std::printf("%zu cells, %d beyond tolerance: %s/accuracy_map_large.csv%s\n", map.cells.size(), map.Failures(),
                dir.c_str(), rc == 0 ? " and .png" : " (no heat map: matplotlib missing or failed)");
    return map.Failures() > 0 ? 1 : 0;
}
