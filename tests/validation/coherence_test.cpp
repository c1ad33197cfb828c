// SPDX-License-Identifier: Apache-2.0
// Circular aperture (Airy ring) and van Cittert–Zernike: spatial coherence of an incoherent disc
// source seen through two narrow slits (theory §9 "Double-slit validation numbers", D5).
#include <cmath>
#include <cstdio>
#include <string>

#include "support/stats.h"
#include "validation/render_row.h"

namespace phasor {
namespace {

using test::RenderRow;
using test::Row;

TEST(CircularAperture, FirstDarkRingAtTheAiryRadius) {
    // D = 100 µm, z = 50 mm, λ = 1 µm: r₁ = 1.22·λz/D = 610 µm (first zero of J₁: 3.8317/π·λz/D).
    const Row r = RenderRow(test::ValidationScene("circular_aperture.wscene"), {}, "grt");
    ASSERT_FALSE(r.v.empty());
    const double expected = 3.8317059702075125 / Pi * 1e-6 * 0.05 / 100e-6, pitch = 10e-6;
    // The first local minimum on the +x side of the axis.
    std::size_t centre = 0;
    while (centre + 1 < r.x.size() && r.x[centre] < 0) ++centre;
    std::size_t i = centre;
    while (i + 1 < r.v.size() && r.v[i + 1] < r.v[i]) ++i;
    std::printf("Airy: first minimum at %.1f um (expected %.1f um, pitch %.0f um); I_min/I_0 = %.2e\n",
                r.x[i] * 1e6, expected * 1e6, pitch * 1e6, r.v[i] / r.v[centre]);
    EXPECT_NEAR(r.x[i], expected, pitch);
    // The central value: on the axis of a hole of radius a the paraxial field is exact in closed
    // form, I(0) = 4·E·sin²(π·a²/(2λz)) = 0.024623 (Fresnel number a²/λz = 0.05; Fraunhofer
    // (πa²/λz)² = 0.02467). Near the axis the pattern falls as 1 − u²/4, u = k·a·r/z, and the
    // Gaussian pixel at offset x averages r² to x² + 2σ²: 1.5e-3 here.
    const double a = 50e-6, z = 0.05, k = 2 * Pi / 1e-6, sigma = 7.98e-6;
    const double i0 = 4 * std::pow(std::sin(Pi * a * a / (2 * 1e-6 * z)), 2);
    const double expectedCentre = i0 * (1 - 0.25 * Sqr(k * a / z) * (Sqr(r.x[centre]) + 2 * sigma * sigma));
    std::printf("Airy: I at x = %.1f um = %.6f (closed form %.6f, on the axis %.6f)\n", r.x[centre] * 1e6,
                r.v[centre], expectedCentre, i0);
    EXPECT_NEAR(r.v[centre] / expectedCentre, 1, 1e-3);
}

/// V = (P − P₁ − P₂)/(P₁ + P₂) at x = 0 (theory §9) for the given source Defines.
double Visibility(const DefineList &source) {
    auto at0 = [&](const DefineList &extra) {
        DefineList defs = source;
        defs.insert(defs.end(), extra.begin(), extra.end());
        const Row r = RenderRow(test::ValidationScene("double_slit.wscene"), defs, "grt");
        EXPECT_EQ(r.v.size(), 1u);
        return r.v.empty() ? 0.0 : r.v[0];
    };
    const double p = at0({}), p1 = at0({{"slit2", "false"}}), p2 = at0({{"slit1", "false"}});
    return (p - p1 - p2) / (p1 + p2);
}

TEST(VanCittertZernike, FringeVisibilityFollowsTheDiscCoherence) {
    // Narrow slits (b = 10 µm) and one pixel at x = 0; a uniform disc of angular radius α = v/(kd)
    // at 50 mm behind the plate. The visibility normalised by its α → 0 value (the same disc,
    // α = 1 µrad: a spherical wave from 50 mm magnifies the fringes, so a plane wave is not the
    // limit) follows the signed 2J₁(v)/v. The disc is sampled with 64 stratified light samples
    // per GR direction: the cross term's dependence on the source point is what VCZ integrates,
    // and one sample per direction leaves ±0.02 of noise in V at v = 5 (measured).
    for (int d : {100, 200}) {
        const DefineList base = {{"b", "10um"},      {"d", std::to_string(d) + "um"}, {"width", "25um"},
                                 {"spp", "4096"},    {"light_samples", "64"},         {"source", "disc"}};
        DefineList point = base;
        point.push_back({"alpha", "1e-6rad"});
        const double v0 = Visibility(point);
        for (double v : {0.5, 1.5, 2.5, 3.2, 5.0, 6.0}) {
            const double alpha = v / (2 * Pi / 1e-6 * d * 1e-6);
            DefineList defs = base;
            char buf[64];
            std::snprintf(buf, sizeof buf, "%.12grad", alpha);
            defs.push_back({"alpha", buf});
            const double vis = Visibility(defs) / v0, expected = 2 * std::cyl_bessel_j(1.0, v) / v;
            std::printf("d = %d um, v = %.1f: V/V0 = %+.4f, 2J1(v)/v = %+.4f\n", d, v, vis, expected);
            EXPECT_NEAR(vis, expected, 0.02) << "d = " << d << ", v = " << v;
        }
    }
}

TEST(VanCittertZernike, DistantSourcesGiveTheirMutualCoherence) {
    // A distant source is an incoherent sum of plane waves (theory §2.2): at x = 0 each direction
    // θ shifts the cross term's phase by k·d·θ_x, so the visibility is the profile's
    // characteristic function at k·d — 2J₁(v)/v for a uniform disc of angular radius α
    // (v = kαd), exp(−½k²Ωd²) = exp(−v²/8) for the Gaussian profile with Ω = α²/4 (D5). The
    // single-slit envelopes move by zα ≤ 80 µm against their 1 mm width (b = 10 µm): negligible.
    // Normalised by the plane-wave limit (α = 1 µrad). 64 stratified light samples per direction,
    // as for the disc above.
    for (const char *profile : {"disc", "gaussian"}) {
        const DefineList base = {{"b", "10um"},   {"d", "100um"},          {"width", "25um"},  {"spp", "4096"},
                                 {"source", "distant"}, {"profile", profile}, {"light_samples", "64"}};
        DefineList narrow = base;
        narrow.push_back({"alpha", "1e-6rad"});
        const double v0 = Visibility(narrow);
        for (double v : {1.0, 2.5, 4.0}) {
            char buf[64];
            std::snprintf(buf, sizeof buf, "%.12grad", v / (2 * Pi / 1e-6 * 100e-6));
            DefineList defs = base;
            defs.push_back({"alpha", buf});
            const double vis = Visibility(defs) / v0;
            const double expected =
                std::string(profile) == "disc" ? 2 * std::cyl_bessel_j(1.0, v) / v : std::exp(-v * v / 8);
            std::printf("distant %s, v = %.1f: V/V0 = %+.4f, expected %+.4f\n", profile, v, vis, expected);
            EXPECT_NEAR(vis, expected, 0.02) << profile << ", v = " << v;
        }
    }
}

// A kernel-sampled direction leaving the aperture answers a plane wave; when it then hits an
// area source at distance t, grt re-weights it by EvalFrom(t)/Eval (the spherical wave from the
// hit). A wide disc 5 mm behind narrow slits makes kernel sampling carry much of the MIS weight
// with one light sample per vertex, little with sixteen: the two estimates must agree (Welch
// t-test on 8 independent Sobol' scramble replicas each, fixed seeds; support/replicas.h). Without
// the re-weighting the first reads 12 % high (measured: 6.43e-3 vs 5.76e-3). The test's power at
// this cost: the first with its source 10 % too bright (source_gain = 1.1, same spp and seeds) is
// rejected; the standard error of the first is 1.3 %, so 1 % would need ~40× the samples.
// Measured: t = −0.13 (true), 6.6 (10 % too bright; p = 1e-4, 9 dof).
TEST(VanCittertZernike, KernelSampledPathsAreReweightedForTheSourceDistance) {
    const DefineList base = {{"source", "disc"}, {"b", "10um"}, {"width", "25um"}, {"alpha", "2deg"}, {"distance", "5mm"}};
    DefineList many = base;
    many.push_back({"light_samples", "16"});
    const auto b = test::RenderRowReplicas(test::ValidationScene("double_slit.wscene"), many, "grt", 8192, 8, 101);
    ASSERT_EQ(b.size(), 1u);
    for (const bool biased : {false, true}) {
        DefineList one = base;
        one.push_back({"light_samples", "1"});
        one.push_back({"source_gain", biased ? "1.1" : "1"});
        const auto a = test::RenderRowReplicas(test::ValidationScene("double_slit.wscene"), one, "grt", 32768, 8, 1);
        ASSERT_EQ(a.size(), 1u);
        const test::TTestResult t =
            test::WelchTTest(a[0].mean, a[0].varianceOfMean, a[0].dof, b[0].mean, b[0].varianceOfMean, b[0].dof);
        std::printf("disc 5 mm behind the slits%s: light_samples 1: %.5e +- %.1e, 16: %.5e +- %.1e (%s)\n",
                    biased ? ", source 10 % too bright" : "", a[0].mean, a[0].StdError(), b[0].mean, b[0].StdError(),
                    t.ToString().c_str());
        EXPECT_GT(a[0].varianceOfMean, 0);
        if (!biased) {
            EXPECT_GT(t.pValue, 1e-3);
            EXPECT_LT(std::abs(a[0].mean - b[0].mean), 0.05 * b[0].mean);
        } else {
            EXPECT_LT(t.pValue, 1e-3) << "a source 10 % too bright must be rejected";
        }
    }
}

}  // namespace
}  // namespace phasor
