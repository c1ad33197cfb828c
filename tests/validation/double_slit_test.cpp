// SPDX-License-Identifier: Apache-2.0
// The paper's double-slit validation (supplement §S5.2, Figs. S5–S6; theory §6, §9) on
// scenes/validation/double_slit.wscene: generalized rays (`grt`, 64×64 direction lattice per
// pixel) against the forward Rayleigh–Sommerfeld integrator (`rs`), `rs` against an independent
// 2-D RS computed here (Hankel form, theory §6.2), and the analytic checks of theory §6.7/§9
// (contrast, energy, scale invariance, single slit, Airy ring, van Cittert–Zernike).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>

#include "validation/render_row.h"

namespace phasor {
namespace {

using test::MaxDiffOfPeak;
using test::RenderRow;
using test::Row;
const std::string kScene = test::ValidationScene("double_slit.wscene");

/// Independent 2-D Rayleigh–Sommerfeld (theory §6.2, Hankel form) for slits [lo_j, hi_j] (infinite
/// along y) lit by a unit plane wave tilted by `tilt` in the x–z plane, integrated against
/// Gaussian pixels of std sigma: U(x) = (ikz/2)∫U₀(x')H₁⁽¹⁾(kR)/R dx', H₁ by its asymptotic series
/// (kR ≥ 6·10⁴ here: three terms are exact to 1e-14), composite Simpson over the slits (λ/8 steps),
/// the pixel integral by the trapezoid rule on a λ/2 grid (spectrally accurate under a Gaussian).
std::vector<double> Hankel2D(const std::vector<std::pair<double, double>> &slits, double lambda, double z,
                             double tilt, double sigma, const std::vector<double> &centres) {
    const double k = 2 * Pi / lambda;
    auto h1 = [](double x) {  // H₁⁽¹⁾(x) ~ √(2/πx) e^{i(x−3π/4)} (1 + 3i/(8x) + 15/(128x²) …)
        const std::complex<double> i(0, 1);
        const std::complex<double> series = 1.0 + 3.0 * i / (8 * x) + 15.0 / (128 * x * x) - 315.0 * i / (3072 * x * x * x);
        return std::sqrt(2 / (Pi * x)) * std::exp(i * (x - 0.75 * Pi)) * series;
    };
    auto field = [&](double x) {
        std::complex<double> u = 0;
        for (auto [lo, hi] : slits) {
            int n = 2 * int(std::ceil((hi - lo) / (lambda / 8) / 2));
            const double h = (hi - lo) / n;
            for (int j = 0; j <= n; ++j) {
                const double xp = lo + j * h, r = std::hypot(x - xp, z);
                const double w = (j == 0 || j == n) ? 1 : (j % 2 ? 4 : 2);
                u += w * h / 3 * std::exp(std::complex<double>(0, k * std::sin(tilt) * xp)) * h1(k * r) / r;
            }
        }
        return std::complex<double>(0, k * z / 2) * u;
    };
    std::vector<double> out;
    const double dx = lambda / 2;
    for (double xc : centres) {
        double acc = 0;
        const int n = int(std::ceil(7 * sigma / dx));
        for (int j = -n; j <= n; ++j) {
            const double x = xc + j * dx;
            acc += std::norm(field(x)) * std::exp(-0.5 * (j * dx) * (j * dx) / (sigma * sigma));
        }
        out.push_back(acc * dx / (std::sqrt(2 * Pi) * sigma));
    }
    return out;
}

// ---- grt vs rs vs the independent reference, d = 50 … 800 µm ---------------------------------

TEST(DoubleSlit, GrtMatchesRsAndRsMatchesAnIndependentReference) {
    for (int d : {50, 100, 200, 400, 800}) {
        const DefineList defs = {{"d", std::to_string(d) + "um"}};
        const Row grt = RenderRow(kScene, defs, "grt"), rs = RenderRow(kScene, defs, "rs");
        ASSERT_EQ(grt.v.size(), 48u);
        const double e = MaxDiffOfPeak(grt, rs);
        const double dd = d * 1e-6, b = 40e-6;
        const std::vector<double> ref =
            Hankel2D({{-dd / 2 - b / 2, -dd / 2 + b / 2}, {dd / 2 - b / 2, dd / 2 + b / 2}}, 1e-6, 1e-2, 0, 7.98e-6, rs.x);
        Row refRow{rs.x, ref, 0};
        const double eRef = MaxDiffOfPeak(rs, refRow);
        std::printf("d = %3d um: max|grt-rs| = %.2e of peak (grt %.2f s, 64x64 lattice), |rs-ref| = %.2e (rs %.3f s)\n",
                    d, e, grt.seconds, eRef, rs.seconds);
        EXPECT_LE(e, 2e-3) << "d = " << d;
        EXPECT_LE(eRef, 1e-3) << "d = " << d;
    }
}

// ---- time reversal and obliquity (D3): tilted waves, an asymmetric pair, a point source -------

TEST(DoubleSlit, ObliqueIncidenceOnAnAsymmetricPair) {
    for (int tilt : {1, 3, 5}) {
        // A 2.4 mm row keeps the pattern (shifted by z·tanθ ≤ 0.87 mm) on the sensor.
        const DefineList defs = {{"tilt", std::to_string(tilt) + "deg"}, {"b2", "25um"}, {"width", "2400um"}};
        const Row grt = RenderRow(kScene, defs, "grt"), rs = RenderRow(kScene, defs, "rs");
        const double e = MaxDiffOfPeak(grt, rs);
        Row ref{rs.x, Hankel2D({{-70e-6, -30e-6}, {37.5e-6, 62.5e-6}}, 1e-6, 1e-2, Radians(tilt), 7.98e-6, rs.x), 0};
        // Hankel2D gives |U|² for a unit-amplitude wave; the sensor reports flux, and a plane wave of
        // unit irradiance (normal to itself) puts cosθ per unit area through the plate (D4).
        for (double &v : ref.v) v *= std::cos(Radians(tilt));
        const double eRef = MaxDiffOfPeak(rs, ref);
        std::printf("tilt = %d deg, b = 40/25 um: max|grt-rs| = %.2e of peak, |rs-ref| = %.2e\n", tilt, e, eRef);
        EXPECT_LE(e, 2e-3) << "tilt = " << tilt;
        EXPECT_LE(eRef, 1e-3) << "tilt = " << tilt;
    }
}

TEST(DoubleSlit, PointSourceBehindTheSlits) {
    // Short slits keep the 3-D RS integral cheap; the spherical wave's curvature over the GR's
    // footprint (k·(300 µm)²/2R ≈ 5.7 rad at R = 50 mm) is essential here.
    const DefineList defs = {{"source", "point"}, {"length", "400um"}, {"width", "600um"}};
    const Row grt = RenderRow(kScene, defs, "grt"), rs = RenderRow(kScene, defs, "rs");
    const double e = MaxDiffOfPeak(grt, rs);
    std::printf("point source at 50 mm: max|grt-rs| = %.2e of peak (rs %.2f s)\n", e, rs.seconds);
    EXPECT_LE(e, 2e-3);
}

TEST(DoubleSlit, SpotLightBehindTheSlitsActsAsItsPointSource) {
    // A spot light aimed at the plate with every opening inside its cone is the point source of
    // the same intensity (its falloff is 1 there): grt with the spot against rs with the point.
    // The spot's falloff is evaluated where each GR's mean ray meets the plate (not across its
    // footprint), so a cone edge crossing the openings is not covered by this check.
    const DefineList common = {{"length", "400um"}, {"width", "600um"}};
    DefineList spot = common, point = common;
    spot.push_back({"source", "spot"});
    point.push_back({"source", "point"});
    const Row grt = RenderRow(kScene, spot, "grt"), rs = RenderRow(kScene, point, "rs");
    const double e = MaxDiffOfPeak(grt, rs);
    std::printf("spot light at 50 mm: max|grt(spot)-rs(point)| = %.2e of peak\n", e);
    EXPECT_LE(e, 2e-3);
}

// ---- contrast of the interference term (theory §9) --------------------------------------------

/// C = √(∫(P − P₁ − P₂)² / ∫P²) over the row.
double Contrast(const Row &p, const Row &p1, const Row &p2) {
    double num = 0, den = 0;
    for (std::size_t i = 0; i < p.v.size(); ++i) {
        const double c = p.v[i] - p1.v[i] - p2.v[i];
        num += c * c;
        den += p.v[i] * p.v[i];
    }
    return std::sqrt(num / den);
}

TEST(DoubleSlit, ContrastFollowsTheGaussianPixelDecoherence) {
    const std::pair<int, double> expected[] = {{50, 0.522}, {100, 0.497}, {200, 0.275}, {400, 0.035}, {800, 0.0}};
    for (auto [d, c] : expected) {
        const std::string dd = std::to_string(d) + "um";
        const DefineList both = {{"d", dd}, {"pitch", "2.5um"}};
        const DefineList one = {{"d", dd}, {"pitch", "2.5um"}, {"slit2", "false"}};
        const DefineList two = {{"d", dd}, {"pitch", "2.5um"}, {"slit1", "false"}};
        const Row p = RenderRow(kScene, both, "rs"), p1 = RenderRow(kScene, one, "rs"), p2 = RenderRow(kScene, two, "rs");
        const double cr = Contrast(p, p1, p2);
        std::printf("d = %3d um: C = %.3f (rs, pitch 2.5 um; theory %.3f)\n", d, cr, c);
        EXPECT_NEAR(cr, c, 0.02) << "d = " << d;
    }
    // The same from generalized rays at two spacings (a 32×32 lattice is ample for C).
    for (auto [d, c] : {expected[1], expected[2]}) {
        const std::string dd = std::to_string(d) + "um";
        const DefineList base = {{"d", dd}, {"pitch", "2.5um"}, {"width", "800um"}};
        DefineList one = base, two = base;
        one.push_back({"slit2", "false"});
        two.push_back({"slit1", "false"});
        const double cg = Contrast(RenderRow(kScene, base, "grt", 1024), RenderRow(kScene, one, "grt", 1024),
                                   RenderRow(kScene, two, "grt", 1024));
        std::printf("d = %3d um: C = %.3f (grt, pitch 2.5 um, |x| < 400 um)\n", d, cg);
        EXPECT_NEAR(cg, c, 0.02) << "d = " << d;
    }
}

// ---- energy (Parseval), real scale ------------------------------------------------------------

TEST(DoubleSlit, EnergyThroughTheSlitsIsRecovered) {
    // An 8 mm sensor (≥ 6 mm; a 6 mm one holds 99.0 % of the power), pitch 10 µm ≤ 1.5σ_pix:
    // Σ pixel·pitch = power per unit slit length / E = 2b (theory §6.7, §9).
    const DefineList defs = {{"width", "8000um"}, {"pitch", "10um"}};
    for (const char *integrator : {"grt", "rs"}) {
        const Row r = RenderRow(kScene, defs, integrator, 1024);
        double sum = 0;
        for (double v : r.v) sum += v * 10e-6;
        std::printf("%s: sum pixel*pitch = %.5g um (2b = 80 um)\n", integrator, sum * 1e6);
        EXPECT_NEAR(sum / 80e-6, 1, 0.01) << integrator;
    }
}

TEST(DoubleSlit, RealScaleGivesTheSameProfile) {
    const double s = 0.633;
    auto um = [&](double v) { return std::to_string(v * s) + "um"; };
    const DefineList scaled = {{"lambda", um(1)},     {"d", um(100)},   {"b", um(40)},       {"length", um(4000)},
                               {"z", um(10000)},      {"pitch", um(25)}, {"width", um(1200)}, {"sigma_pix", um(7.98)}};
    const Row unit = RenderRow(kScene, {}, "grt"), real = RenderRow(kScene, scaled, "grt");
    ASSERT_EQ(real.x.size(), unit.x.size());
    EXPECT_NEAR(real.x[0], s * unit.x[0], 1e-12);  // the scaled scene really is scaled
    const double e = MaxDiffOfPeak(real, unit);
    std::printf("lambda = 0.633 um, all lengths x0.633: max diff = %.2e of peak\n", e);
    EXPECT_LE(e, 1e-3);
}

// ---- single slit, circular aperture -----------------------------------------------------------

TEST(SingleSlit, MatchesFraunhoferAtFresnelNumber004) {
    // Slit 1 alone, centred (d = 0): I(x) = (b²/λz)·sinc²(kbx/2z) (theory §6.7).
    const Row r = RenderRow(kScene, {{"d", "0um"}, {"slit2", "false"}}, "grt");
    const double b = 40e-6, z = 1e-2, lambda = 1e-6, k = 2 * Pi / lambda, peak = b * b / (lambda * z);
    double e = 0;
    for (std::size_t i = 0; i < r.v.size(); ++i) {
        const double u = k * b * r.x[i] / (2 * z), s = u == 0 ? 1 : std::sin(u) / u;
        e = std::max(e, std::abs(r.v[i] - peak * s * s));
    }
    std::printf("single slit vs Fraunhofer: max diff = %.2e of peak (peak %.4f, expected %.2f)\n", e / peak,
                r.Peak(), peak);
    EXPECT_LE(e / peak, 0.03);
}

}  // namespace
}  // namespace phasor
