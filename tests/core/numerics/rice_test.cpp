// SPDX-License-Identifier: Apache-2.0
// The Rice distribution function (core/numerics/rice.h): the Poisson-mixture and Marcum (Bessel)
// series against the Gauss–Legendre quadrature of the Rice density they replaced and against each
// other, over the whole range they are used in; against closed forms (a centred disc, a disc whose
// rim passes through the mean) and a fine quadrature to relative accuracy, deep in the tails too;
// their truncation bounds; RiceCdf's switches.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/math.h"
#include "core/numerics/bessel.h"
#include "core/numerics/gauss_legendre.h"
#include "core/numerics/rice.h"

namespace phasor {
namespace {

// Every (t, c) of a grid over the series' domain (max(t, c) ≤ √(2·RiceSeriesMaxHalfSquare) ≈ 63.2,
// dense below 3 where `distant` sources measured by wide GRs live) with c − t < 11.
template <typename F>
void ForGrid(F &&f) {
    const double top = std::sqrt(2 * RiceSeriesMaxHalfSquare);
    for (double t = 0; t <= top; t += t < 3 ? 0.037 : 0.61)
        for (double c = 1e-3; c <= top; c += c < 3 ? 0.029 : 0.53)
            if (c - t < 11) f(t, c);
}

TEST(Rice, SeriesAgreesWithTheQuadratureOverItsWholeRange) {
    // The quadrature is accurate to ~1e-12 absolute; where it is in the tail beyond t − 11 it
    // integrates only [t − 11, c] and loses the relative accuracy the series keep (tested below
    // against closed forms), so this comparison is absolute.
    double worstSeries = 0, worstBessel = 0, worstT = 0, worstC = 0;
    int n = 0;
    ForGrid([&](double t, double c) {
        const double q = RiceCdfQuadrature(t, c);
        const double d = std::fabs(RiceCdfSeries(t, c) - q);
        if (d > worstSeries) worstSeries = d, worstT = t, worstC = c;
        worstBessel = std::max(worstBessel, std::fabs(RiceCdfBessel(t, c) - q));
        ++n;
    });
    EXPECT_GT(n, 10000);
    EXPECT_LT(worstSeries, 1e-12) << "at t = " << worstT << ", c = " << worstC;
    EXPECT_LT(worstBessel, 1e-12);
    // Marcum's series beyond the Poisson series' range, up to where it hands over (t·c ≈ 39 000).
    double worst = 0;
    for (double t = 60; t < 197; t += 3.7)
        for (double c = t - 10.9; c < t + 11; c += 0.87) worst = std::max(worst, std::fabs(RiceCdfBessel(t, c) - RiceCdfQuadrature(t, c)));
    EXPECT_LT(worst, 1e-12);
}

TEST(Rice, TheTwoSeriesAgreeToRelativeAccuracy) {
    // Independent algorithms (Poisson mixture vs Miller-recurrence Bessel functions), relative to
    // each other, where P is not tiny or is a positive sum in both.
    double worst = 0;
    ForGrid([&](double t, double c) {
        // Where RiceCdf uses them: Marcum's 1 − Q is relative only where P is not small, and a disc
        // 11σ beyond the mean is 0 (there both underflow near 1e-290 in different places).
        if (t < 1e-3 || (c >= t && c < 2) || t - c >= 11) return;
        const double a = RiceCdfSeries(t, c), b = RiceCdfBessel(t, c);
        if (a > 1e-290) worst = std::max(worst, std::fabs(a - b) / a);
    });
    EXPECT_LT(worst, 1e-12);
}

TEST(Rice, SeriesKeepsRelativeAccuracyFarInTheTail) {
    // A small disc far from the mean (c < 2 ≤ t − 11), values down to 1e-208: against the Rice
    // density integrated over [0, c] by 400 panels of the 16-point rule (RiceCdfQuadrature's 64
    // nodes there are off by up to 7e-11 at t = 30, c = 1.9, where the density grows like e^{30ρ}).
    for (double t : {13.0, 20.0, 30.0})
        for (double c : {1e-4, 0.01, 0.3, 1.0, 1.9}) {
            auto density = [&](double r) { return r * std::exp(-0.5 * Sqr(r - t)) * BesselI0Scaled(r * t); };
            const double ref = IntegrateGaussLegendre(density, 0.0, c, 16, 400);
            ASSERT_GT(ref, 1e-300) << t << " " << c;
            EXPECT_NEAR(RiceCdfSeries(t, c) / ref, 1, 1e-13) << "t = " << t << ", c = " << c;
            EXPECT_NEAR(RiceCdfBessel(t, c) / ref, 1, 1e-13) << "t = " << t << ", c = " << c;
        }
}

TEST(Rice, SeriesMatchesClosedFormsToRelativeAccuracy) {
    // A centred disc: 1 − e^{−c²/2}, from c = 1e-9 (5e-19) to 1 − 1e-16.
    for (double c = 1e-9; c < 8.5; c *= 1.7)
        EXPECT_NEAR(RiceCdfSeries(0, c) / -std::expm1(-0.5 * c * c), 1, 2e-14) << c;
    // The rim through the mean, c = t: Q₁(a, a) = ½(1 + e^{−a²}I₀(a²)) (Marcum's
    // identity), so P = ½(1 − I₀e(t²)); I₀e itself is accurate to ~1e-14 relative.
    // (From t = 0.3 on: below, 1 − I₀e(t²) cancels and the reference itself loses digits.)
    for (double t = 0.3; t < 63; t *= 1.3) {
        const double ref = 0.5 * (1 - BesselI0Scaled(t * t));
        EXPECT_NEAR(RiceCdfSeries(t, t) / ref, 1, 1e-13) << t;
        EXPECT_NEAR(RiceCdfBessel(t, t) / ref, 1, 1e-13) << t;
    }
    // Tiny arguments on both sides of the 1e-20 switch to the leading terms.
    for (double t : {1e-12, 1e-10, 1.5e-10, 1e-9})
        for (double c : {1e-12, 1e-10, 1.5e-10, 1e-6, 1.0}) {
            const double mu = 0.5 * t * t, x = 0.5 * c * c;
            // P(N_x > N_μ) = e^{−μ}[(1 − e^{−x}) + μ(1 − e^{−x} − x e^{−x})] + O(μ²)
            const double u1 = -std::expm1(-x), u2 = c < 1e-3 ? x * x / 2 : u1 - x * std::exp(-x);
            EXPECT_NEAR(RiceCdfSeries(t, c) / (std::exp(-mu) * (u1 + mu * u2)), 1, 1e-14) << t << " " << c;
        }
}

TEST(Rice, TruncationBoundsAreNegligibleEverywhere) {
    double worstSeries = 0, worstBessel = 0;
    ForGrid([&](double t, double c) {
        double bound = -1;
        const double p = RiceCdfSeries(t, c, &bound);
        ASSERT_GE(bound, 0);
        if (p > 1e-290) worstSeries = std::max(worstSeries, bound / p);  // (below, the value underflows)
        const double b = RiceCdfBessel(t, c, &bound);
        ASSERT_GE(bound, 0);
        if (b > 1e-290 && t > 0 && t - c < 11 && !(c >= t && c < 2)) worstBessel = std::max(worstBessel, bound / b);
    });
    EXPECT_LT(worstSeries, 1e-15);
    // Marcum's, where RiceCdf uses it.
    EXPECT_LT(worstBessel, 1e-15);
}

TEST(Rice, IsAProbabilityMonotoneInBothArguments) {
    ForGrid([&](double t, double c) {
        const double p = RiceCdf(t, c);
        ASSERT_GE(p, 0);
        ASSERT_LE(p, 1);
        // A larger disc holds more; a farther mean leaves less inside (to the rounding bound).
        ASSERT_GE(RiceCdf(t, c * 1.01) * (1 + 4e-12), p) << t << " " << c;
        ASSERT_LE(RiceCdf(t * 1.01 + 1e-3, c), p * (1 + 4e-12)) << t << " " << c;
    });
}

TEST(Rice, AsymptoticFormAgreesWithMarcumsSeriesAndTheQuadrature) {
    // Against Marcum's series (its proven 2e-12) wherever both apply, relative to P below the rim's
    // mean (c < t: P small, relative accuracy matters) and absolutely above it (P ≥ 0.39); against
    // the quadrature (absolute ~1e-12) beyond the series' terms. Dropping the asymptotic expansion's
    // second term (1/(8x) ≥ 1e-6 here) would miss both by orders of magnitude.
    double worstBessel = 0, worstQuadrature = 0;
    for (double t = RiceAsymptoticMinT; t <= 190; t += 3.7)
        for (double a = -10.9; a < 10.9; a += 0.173) {
            const double c = t + a, p = RiceCdfAsymptotic(t, c), ref = RiceCdfBessel(t, c);
            worstBessel = std::max(worstBessel, std::abs(p - ref) / (a < 0 ? ref : 1.0));
        }
    for (double t : {200.0, 350.0, 700.0, 1500.0})
        for (double a = -10.9; a < 10.9; a += 0.31)
            worstQuadrature = std::max(worstQuadrature, std::abs(RiceCdfAsymptotic(t, t + a) - RiceCdfQuadrature(t, t + a)));
    std::printf("MEASURED RiceCdfAsymptotic: relative to Marcum's series %.2g, absolute to the quadrature %.2g\n",
                worstBessel, worstQuadrature);
    EXPECT_LT(worstBessel, 5e-12);
    EXPECT_LT(worstQuadrature, 5e-12);
    // RiceCdf takes it from t = 35 on, continuously.
    EXPECT_EQ(RiceCdf(35, 38), RiceCdfAsymptotic(35, 38));
    EXPECT_EQ(RiceCdf(34.9, 38), RiceCdfBessel(34.9, 38));
    EXPECT_NEAR(RiceCdf(35, 30) / RiceCdfBessel(35, 30), 1, 5e-12);
}

TEST(Rice, SwitchesOfRiceCdfAreContinuous) {
    // c − t = 11: 1 within e^{−60.5}.
    for (double t : {0.0, 5.0, 40.0, 80.0}) {
        EXPECT_EQ(RiceCdf(t, t + 11), 1);
        EXPECT_NEAR(RiceCdf(t, t + 10.9), 1, 1e-12);
    }
    // t − c ≥ 11: 0, and what is dropped is below (c²/2)·e^{−(t−c)²/2}.
    for (double t : {11.5, 20.0, 40.0})
        for (double c : {1e-3, 0.5, t - 11}) {
            EXPECT_EQ(RiceCdf(t, c), 0);
            EXPECT_LE(RiceCdfSeries(t, c), 0.5 * c * c * std::exp(-0.5 * Sqr(t - c))) << t << " " << c;
        }
    // A small disc about a near mean: the Poisson series; else Marcum's; beyond its terms the quadrature.
    EXPECT_EQ(RiceCdf(0.5, 1.5), RiceCdfSeries(0.5, 1.5));
    EXPECT_EQ(RiceCdf(1.5, 0.5), RiceCdfBessel(1.5, 0.5));
    EXPECT_EQ(RiceCdf(30, 35), RiceCdfBessel(30, 35));
    EXPECT_EQ(RiceCdf(40, 45), RiceCdfAsymptotic(40, 45));
    EXPECT_EQ(RiceCdfBessel(200, 201), RiceCdfQuadrature(200, 201));
    EXPECT_NEAR(RiceCdfBessel(197, 198), RiceCdfQuadrature(197, 198), 1e-12);
    // Beyond it a disc more than 11σ short of the mean holds nothing (< e^{−60.5}).
    EXPECT_EQ(RiceCdf(100, 88.9), 0);
    EXPECT_EQ(RiceCdf(0, 0), 0);
}

}  // namespace
}  // namespace phasor
