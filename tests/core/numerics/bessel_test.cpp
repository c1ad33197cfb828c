// SPDX-License-Identifier: Apache-2.0
// Cylinder functions (core/numerics/bessel.h): Hankel functions against known values, the
// standard library, their Wronskian and large-argument behaviour; the scaled I₀.
#include <gtest/gtest.h>

#include <cmath>

#include "core/numerics/bessel.h"

namespace phasor {
namespace {

TEST(Hankel, MatchesKnownValues) {
    // H₀⁽¹⁾(x), H₁⁽¹⁾(x) to 20 digits (mpmath); x = 25 and 100 use the asymptotic series.
    struct Known {
        double x;
        Complex h0, h1;
    };
    const Known known[] = {
        {1, {0.76519768655796655145, 0.088256964215676957983}, {0.44005058574493351596, -0.78121282130028871655}},
        {10, {-0.2459357644513483352, 0.055671167283599391424}, {0.04347274616886143667, 0.24901542420695388392}},
        {25, {0.096266783275958116174, -0.12724943226800613783}, {-0.12535024958028990465, -0.098829964783237410053}},
        {100, {0.019985850304223122424, -0.077244313365083152254}, {-0.077145352014112158033, -0.020372312002759793305}},
    };
    for (const Known &k : known) {
        Complex h0, h1;
        Hankel01(k.x, &h0, &h1);
        EXPECT_LT(std::abs(h0 - k.h0), 1e-14 * std::abs(k.h0)) << k.x;
        EXPECT_LT(std::abs(h1 - k.h1), 1e-14 * std::abs(k.h1)) << k.x;
    }
}

TEST(Hankel, MatchesStdBessel) {
    // Both sides of the switch to the asymptotic series (x = 25) and far beyond it.
    for (double x : {0.5, 7.0, 24.9, 25.0, 31.7, 100.0, 1234.5, 62831.9}) {
        Complex h0, h1;
        Hankel01(x, &h0, &h1);
        const Complex r0(std::cyl_bessel_j(0.0, x), std::cyl_neumann(0.0, x));
        const Complex r1(std::cyl_bessel_j(1.0, x), std::cyl_neumann(1.0, x));
        EXPECT_LT(std::abs(h0 - r0), 1e-12 * std::abs(r0)) << x;
        EXPECT_LT(std::abs(h1 - r1), 1e-12 * std::abs(r1)) << x;
    }
}

TEST(Hankel, ObeysTheWronskianAndTheAsymptoticAmplitude) {
    // J₁Y₀ − J₀Y₁ = 2/(πx) (DLMF 10.5.2), i.e. Im(conj(H₀)·H₁) = −2/(πx), at any x — a check of
    // the asymptotic branch independent of std::cyl_neumann. And |H_ν|²·πx/2 = |P_ν|² → 1 with
    // |P_ν|² − 1 = O(1/x²) (DLMF 10.17.5: P = 1 + i·a₁/x − a₂/x² …, |a₁|² − 2a₂ = O(1)).
    for (double x : {0.3, 3.0, 24.99, 25.0, 80.0, 1e3, 1e5, 1e7}) {
        Complex h0, h1;
        Hankel01(x, &h0, &h1);
        const double wronskian = -2 / (Pi * x);
        EXPECT_NEAR(std::imag(std::conj(h0) * h1) / wronskian, 1.0, 1e-13) << x;
        if (x >= HankelAsymptoticMin) {
            EXPECT_NEAR(std::norm(h0) * Pi * x / 2, 1.0, 1.0 / (x * x)) << x;
            EXPECT_NEAR(std::norm(h1) * Pi * x / 2, 1.0, 1.0 / (x * x)) << x;
        }
    }
}

TEST(BesselI0Scaled, MatchesStdAndIsContinuousAtTheAsymptoticSwitch) {
    // I₀(0) = 1; I₀(1)e^{−1} = 0.46575960759364043 (A&S Table 9.8); against std::cyl_bessel_i
    // over 0–700 (fine steps up to 30, across the switch at 22) to 1e-14 relative (measured
    // 3.3e-15: a few ulps of the ~50-term sums).
    EXPECT_EQ(BesselI0Scaled(0), 1.0);
    EXPECT_NEAR(BesselI0Scaled(1), 0.46575960759364043, 1e-15);
    double worst = 0;
    for (double x = 0; x < 700; x += x < 30 ? 0.0137 : 0.91) {
        const double ref = std::cyl_bessel_i(0.0, x) * std::exp(-x);
        worst = std::max(worst, std::abs(BesselI0Scaled(x) - ref) / ref);
    }
    EXPECT_LT(worst, 1e-14);
    const double below = BesselI0Scaled(std::nextafter(22.0, 0.0)), above = BesselI0Scaled(22);
    EXPECT_NEAR(above / below, 1.0, 1e-14);
    // Far out: √(2πx)·I₀(x)e^{−x} = 1 + 1/(8x) + 4.5/(8x)² + … (the last term is 7e-10 at 1e4).
    EXPECT_NEAR(BesselI0Scaled(1e4) * std::sqrt(2 * Pi * 1e4), 1 + 1 / 8e4, 1e-9);
}

TEST(BesselJSequence, MatchesStdCylBesselJ) {
    // Every order 0…30 against std::cyl_bessel_j over small, moderate and large arguments (the
    // grating's m = k·h·cosθ_i spans ~0–20; far larger x only costs time). Tolerance: the
    // backward recurrence and the normalisation sum each lose a few ulps per O(x) terms, so
    // 2e-15 absolute on values ≤ 1 plus 1e-12 relative for the tiny high orders.
    constexpr int N = 30;
    double j[N + 1];
    for (double x : {0.0, 1e-12, 3e-9, 1e-8, 2e-6, 0.01, 0.3, 1.0, 2.404825557695773, 5.5, 12.7, 29.9, 31.3, 77.0,
                     250.0}) {
        BesselJSequence(x, N, j);
        for (int n = 0; n <= N; ++n) {
            const double ref = std::cyl_bessel_j(double(n), x);
            EXPECT_NEAR(j[n], ref, 2e-15 * std::max(1.0, std::sqrt(x)) + 1e-12 * std::abs(ref))
                << "n = " << n << ", x = " << x;
        }
    }
    // A deliberately shorter start (as if the margin were dropped) would fail here: the check
    // is sensitive to the top orders, J_30(31.3) ≈ 0.12 and J_30(5.5) ≈ 4e-18.
    BesselJSequence(5.5, N, j);
    EXPECT_NEAR(j[N] / std::cyl_bessel_j(double(N), 5.5), 1.0, 1e-12);
}

TEST(BesselJSequence, FewOrdersAreAsAccurateAsMany) {
    // nMax below x (a grating with a small max_order): the normalisation still sums every order
    // that matters. Starting at max(nMax, x) + 6 + √(24x) instead gave 3e-12 at x = 1.9, nMax = 0
    // (x ≤ 2 now takes the series path; the shortened start still fails at x = 3).
    double j[8];
    for (int nMax = 0; nMax <= 7; ++nMax)
        for (double x : {0.1, 0.5, 1.0, 1.9, 3.0, 5.0, 8.0, 12.0, 20.0, 40.0}) {
            BesselJSequence(x, nMax, j);
            for (int n = 0; n <= nMax; ++n)
                EXPECT_NEAR(j[n], std::cyl_bessel_j(double(n), x), 2e-15 * std::max(1.0, std::sqrt(x)))
                    << "n = " << n << ", nMax = " << nMax << ", x = " << x;
        }
}

TEST(BesselJSequence, SmallArgumentSeriesPathMatchesStd) {
    // x ≤ 2 with nMax ≤ 24 takes the series of the top two orders and the recurrence down (a
    // grating's m ≈ 1): every order of every nMax, from x = 1e-8 (where J_24 ≈ 1e-223) to the
    // switch at 2 and just past it (the Miller path). The recurrence adds about an ulp per step:
    // 4e-15 absolute; the relative term is std::cyl_bessel_j's own error at tiny values (~1e-13).
    // Nothing is written past out[nMax] (a sentinel).
    constexpr double Sentinel = 12345.0;
    double j[26];
    for (int nMax = 0; nMax <= 24; ++nMax)
        for (double x : {1e-8, 3e-6, 1e-3, 0.05, 0.37, 0.99, 1.1377, 1.5, 1.999, 2.0, 2.0000001}) {
            j[nMax + 1] = Sentinel;
            BesselJSequence(x, nMax, j);
            EXPECT_EQ(j[nMax + 1], Sentinel) << "nMax = " << nMax << ", x = " << x;
            for (int n = 0; n <= nMax; ++n) {
                const double ref = std::cyl_bessel_j(double(n), x);
                EXPECT_NEAR(j[n], ref, 4e-15 + 1e-12 * std::abs(ref)) << "n = " << n << ", nMax = " << nMax << ", x = " << x;
            }
        }
}

TEST(BesselJSequence, SumOfSquaresIsOne) {
    // Σ_{n∈ℤ} J_n(x)² = J_0² + 2Σ_{n≥1} J_n² = 1 (DLMF 10.23.3) once nMax ≫ x.
    constexpr int N = 60;
    double j[N + 1];
    for (double x : {0.0, 0.5, 3.0, 17.0, 40.0}) {
        BesselJSequence(x, N, j);
        double s = j[0] * j[0];
        for (int n = 1; n <= N; ++n) s += 2 * j[n] * j[n];
        EXPECT_NEAR(s, 1.0, 1e-13) << x;
    }
}

}  // namespace
}  // namespace phasor
