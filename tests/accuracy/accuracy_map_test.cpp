// SPDX-License-Identifier: Apache-2.0
// The accuracy map (issue 20 §3; docs/accuracy.md): ctest label `accuracy`. Each family of
// tests/accuracy/accuracy_map.h on a grid sized for `make test` (the larger grid is
// bench/accuracy_map_bench.cpp), each cell against its independent reference and tolerance. The map
// is written as CSV and drawn as a heat map (python/phasor_plot.py accuracy-map) into
// $PHASOR_ACCURACY_DIR (default: the build tree's accuracy/). A cell beyond its tolerance fails the
// test that computed it; MeanDirectionFilmsFail shows the map catching a deliberately broken
// approximation (the film evaluated at the mean direction again).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "accuracy/accuracy_map.h"
#include "core/render/lobe_average.h"

namespace phasor::test {
namespace {

AccuracyMap &Map() {
    static AccuracyMap map;
    return map;
}

std::string OutputDir() {
    const char *env = std::getenv("PHASOR_ACCURACY_DIR");
    const std::string dir = env && *env ? env : PHASOR_ACCURACY_DIR;
    std::filesystem::create_directories(dir);
    return dir;
}

/// Adds the cells `add` computes to the map and fails for each beyond its tolerance.
template <typename Add>
void Check(Add &&add) {
    AccuracyMap local;
    add(local);
    for (const AccuracyCell &c : local.cells) {
        EXPECT_TRUE(c.Passes()) << c.family << " " << c.row << " | " << c.column << " | " << c.integrator << ": value "
                                << c.value << ", reference " << c.reference << ", error " << c.error << " > " << c.tolerance;
        Map().Add(c);
    }
    double worst = 0;
    for (const AccuracyCell &c : local.cells) worst = std::max(worst, c.error / c.tolerance);
    std::printf("MEASURED %s: %zu cells, worst error %.3g of its tolerance\n",
                local.cells.empty() ? "" : local.cells.front().family.c_str(), local.cells.size(), worst);
}

const std::vector<std::string> Integrators = {"gr", "solve"};

// Issue 20's acceptance: films 0.3–30 µm, incidence 0–70°, disc and Gaussian sources of 0.05–5°,
// free-standing and on glass, reflection and transmission: grt and sample_solve within 1 %.
TEST(AccuracyMap, Films) {
    Check([](AccuracyMap &m) {
        AddFilmCells(m, FilmGrid({0.3e-6, 1e-6, 3e-6, 10e-6, 30e-6}, {0, 5, 10, 45, 70}, {0.05, 0.5, 2, 5}), Integrators, 0.01);
    });
}

// The rows of issue 20's §2 table (n = 1.33, λ = 600 nm, a one-pixel sensor across the specular
// beam): the reference reproduces the issue's truths (4 significant digits), and grt and sample_solve
// are within 1 % of them; the film at the mean direction (the switch) is printed beside them as the
// "before" of grt.
TEST(AccuracyMap, IssueTable) {
    struct Row {
        double d, theta, radius, nSub;
        const char *source;
        double truth;
    };
    const Row rows[] = {{10e-6, 45, 0.5, 1, "disc", 0.09481},    {10e-6, 45, 2, 1, "disc", 0.06002},
                        {10e-6, 45, 2, 1, "gaussian", 0.06542},  {10e-6, 45, 2, 1.5, "disc", 0.02844},
                        {5e-6, 10, Degrees(0.060), 1, "disc", 0.004215}, {5e-6, 5, 5, 1, "disc", 0.00884},
                        {10e-6, 0, 2, 1, "disc", 0.05740}};
    for (const Row &r : rows) {
        FilmCase c;
        c.thickness = r.d;
        c.thetaDeg = r.theta;
        c.radiusDeg = r.radius;
        c.nSub = r.nSub;
        c.source = r.source;
        const double ref = c.Reference();
        EXPECT_NEAR(ref, r.truth, 6e-4 * r.truth) << "the reference against the issue's truth: " << c.Row() << " " << c.Column();
        const double gr = RenderFilm(c, "gr"), solve = RenderFilm(c, "solve");
        SetLobeAverageDisabledForTesting(true);
        const double before = RenderFilm(c, "gr");
        SetLobeAverageDisabledForTesting(false);
        EXPECT_NEAR(gr, ref, 0.01 * ref) << c.Row() << " " << c.Column();
        EXPECT_NEAR(solve, ref, 0.01 * ref) << c.Row() << " " << c.Column();
        std::printf("MEASURED %s | %s: truth %.6f; grt %+.1e, sample_solve %+.1e (mean direction %+.1f %%)\n",
                    c.Row().c_str(), c.Column().c_str(), ref, gr / ref - 1, solve / ref - 1,
                    100 * (before / ref - 1));
    }
}

// The pixel's size does not matter to a sensor that integrates the source over its directions (D4a):
// a pixel of σ = 0.3 µm reads the same average — given an acceptance that holds its wide angular
// spectrum (σ_θ = 1/(√2·k·σ) = 0.22 rad at 600 nm: with 20° it reads 10 % less, the cone's fraction).
TEST(AccuracyMap, FilmsUnderFinePixels) {
    std::vector<FilmCase> cases;
    for (double d : {3e-6, 30e-6})
        for (double theta : {10.0, 45.0}) {
            FilmCase c;
            c.thickness = d;
            c.thetaDeg = theta;
            c.radiusDeg = 2;
            c.sigma = 0.3e-6;
            c.acceptanceDeg = 90;
            cases.push_back(c);
        }
    Check([&](AccuracyMap &m) { AddFilmCells(m, cases, Integrators, 0.01); });
}

// A 10-pair chitin reflector under a 5° disc (the acceptance's beetle) and a 2° Gaussian.
TEST(AccuracyMap, Stacks) {
    std::vector<StackCase> cases;
    for (double lambda : {450e-9, 530e-9, 620e-9})
        for (double theta : {0.0, 30.0, 60.0})
            for (const char *source : {"disc", "gaussian"}) {
                StackCase c;
                c.lambda = lambda;
                c.thetaDeg = theta;
                c.source = source;
                c.radiusDeg = std::string(source) == "disc" ? 5 : 2;
                cases.push_back(c);
            }
    Check([&](AccuracyMap &m) { AddStackCells(m, cases, Integrators, 0.01); });
}

// Grating orders vs J_j² and the grating equation: h/λ, incidence, order, plane wave or 2° disc.
TEST(AccuracyMap, Gratings) {
    std::vector<GratingCase> cases;
    for (double h : {0.05, 0.1, 0.2, 0.3})
        for (double theta : {0.0, 20.0, 45.0})
            for (int order : {-1, 0, 1, 2})
                for (const char *source : {"plane_wave", "disc"}) {
                    GratingCase c;
                    c.heightOverLambda = h;
                    c.thetaDeg = theta;
                    c.order = order;
                    c.source = source;
                    cases.push_back(c);
                }
    Check([&](AccuracyMap &m) { AddGratingCells(m, cases, Integrators, 0.01); });
}

// A coherent Gaussian beam (w0 = 20 µm: σ ≈ 0.29°) reflected by or through a 20 µm film at 45°: the
// power the sensor collects is P·∫R|A|²d²k within 1e-3 with the waist on the film (issue 20's
// acceptance). 5 mm before the film (ρ = 2.5) each pixel sees a narrow local part of the spectrum,
// and the mean-ray mapping of those parts onto the oblique film leaves 2.6e-3 (docs/accuracy.md):
// that cell has 5e-3.
TEST(AccuracyMap, Beams) {
    Check([](AccuracyMap &m) {
        for (bool t : {false, true})
            for (double before : {0.0, 5e-3}) {
                BeamCase c;
                c.transmission = t;
                c.waistBefore = before;
                if (before > 0) {  // the beam has spread to w ≈ 54 µm: a wider sensor
                    c.pixels = 61;
                    c.pitch = 8e-6;
                }
                const double ref = c.Reference();
                for (const std::string &integrator : Integrators) {
                    const double v = c.Collected(integrator);
                    m.Add({"beams", std::string("film 20 um") + (t ? " T" : " R"), Fmt("waist %g mm before", before * 1e3),
                           integrator, v, ref, std::abs(v - ref) / ref, before > 0 ? 5e-3 : 1e-3});
                }
            }
    });
}

TEST(AccuracyMap, Apertures) {
    Check([](AccuracyMap &m) { AddApertureCells(m, ApertureCases()); });
}

// A deliberately broken approximation — the film's efficiency at the mean direction again
// (SetLobeAverageDisabledForTesting) — must make cells of the map fail.
TEST(AccuracyMap, MeanDirectionFilmsFail) {
    SetLobeAverageDisabledForTesting(true);
    AccuracyMap m;
    AddFilmCells(m, FilmGrid({10e-6, 30e-6}, {10, 45}, {2}), {"gr"}, 0.01);
    SetLobeAverageDisabledForTesting(false);
    std::printf("MEASURED mean-direction films: %d of %zu cells fail\n", m.Failures(), m.cells.size());
    EXPECT_GE(m.Failures(), int(m.cells.size()) / 3) << "the map must catch the mean-direction evaluation";
}

// Outside the proven envelope the render says so: a rule that needs more nodes than the cap of 256
// per axis to meet its bound (a thick film under a wide source) is counted
// (RenderEvent::LobeAverageCapped, printed as a warning by `phasor render`). Prints where the cap
// starts at 45° and 70° and the error of those cells against the reference (unproven there, but 256
// Gauss–Legendre nodes per axis still resolve a few hundred radians of phase; the sensor's
// acceptance is widened where its cone, not the average, would cut a 10° disc).
TEST(AccuracyMap, CappedAveragesAreCounted) {
    auto run = [](double thickness, double radiusDeg, double thetaDeg, double *error) {
        FilmCase c;
        c.thickness = thickness;
        c.radiusDeg = radiusDeg;
        c.thetaDeg = thetaDeg;
        // 40° at 45° keeps the sensor's cone from cutting a 10° disc; at 70° the direct light is 40°
        // off the sensor's axis, so 20° (and discs up to 5°).
        c.acceptanceDeg = thetaDeg < 60 ? 40 : 20;
        auto scene = BuildValidation(ValidationScene("film_source.wscene"), c.Defines(), "gr");
        EXPECT_TRUE(scene);
        if (!scene) return -1LL;
        Film film(1, 1, scene->GetDetector().Response());
        RenderOptions opt;
        opt.spp = 1;
        const RenderStats st = scene->GetIntegrator().Render(*scene, film, opt);
        if (error) {
            const Image img = film.Resolve();
            const double ref = c.Reference();
            *error = std::abs(img.At(0, 0, img.ChannelIndex("intensity")) - ref) / ref;
        }
        return st.counters[RenderEvent::LobeAverageCapped];
    };
    EXPECT_EQ(run(10e-6, 5, 45, nullptr), 0) << "a 10 µm film under a 5° disc is within the proven bound";
    EXPECT_GT(run(3e-3, 10, 45, nullptr), 0) << "a 3 mm film under a 10° disc is not";
    for (double theta : {45.0, 70.0})
        for (double d : {10e-6, 30e-6, 100e-6})
            for (double r : {2.0, 5.0, 10.0}) {
                if (theta > 60 && r > 5) continue;
                double e = 0;
                const long long n = run(d, r, theta, &e);
                std::printf("MEASURED %g um film under a %g deg disc at %g deg: %s, error %.2g relative\n", d * 1e6, r,
                            theta, n > 0 ? "capped" : "within the bound", e);
                if (n > 0) {
                    EXPECT_LT(e, 1e-3) << "capped but still close";
                }
            }
}

// Written last (gtest runs a file's tests in order): the map as CSV and as a heat map.
TEST(AccuracyMap, WriteTheMap) {
    ASSERT_FALSE(Map().cells.empty());
    const std::string dir = OutputDir();
    Map().WriteCsv(dir + "/accuracy_map.csv");
    const int rc = DrawAccuracyMap(dir + "/accuracy_map.csv", dir + "/accuracy_map.png", "phasor accuracy map (make test)");
    if (rc == 3) GTEST_SKIP() << "matplotlib is not installed: the map is " << dir << "/accuracy_map.csv";
    EXPECT_EQ(rc, 0);
    std::printf("MEASURED accuracy map: %zu cells, %d beyond tolerance; %s/accuracy_map.{csv,png}\n", Map().cells.size(),
                Map().Failures(), dir.c_str());
}

}  // namespace
}  // namespace phasor::test
