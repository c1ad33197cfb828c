// SPDX-License-Identifier: Apache-2.0
// Gauss–Legendre rules (core/numerics/gauss_legendre.h): exactness to degree 2n − 1, the A&S
// 25.4.30 remainder at degree 2n, symmetry, tabulated values, and the linear-phase bound.
#include <gtest/gtest.h>

#include <cmath>

#include "core/math.h"
#include "core/numerics/gauss_legendre.h"

namespace phasor {
namespace {

// ∫_{−1}^{1} x^k dx.
double MonomialIntegral(int k) { return k % 2 ? 0.0 : 2.0 / (k + 1); }

double RuleOnMonomial(const GaussLegendreRule &r, int k) {
    double s = 0;
    for (int i = 0; i < r.n; ++i) s += r.w[i] * std::pow(r.x[i], k);
    return s;
}

TEST(GaussLegendre, IsExactForPolynomialsOfDegreeUpTo2nMinus1) {
    // Every monomial x^k, k ≤ 2n − 1, for every rule. The values are ≤ 2 and the sum has n
    // terms of magnitude ≤ w_i, so rounding alone allows ~n·1e-16: 1e-14 is a margin of ~2 at
    // n = 64, and ~1e3 below the error at degree 2n for the rules checked there.
    for (int n = 1; n <= MaxGaussLegendreNodes; ++n) {
        const GaussLegendreRule &r = GaussLegendre(n);
        ASSERT_EQ(r.n, n);
        for (int k = 0; k <= 2 * n - 1; ++k)
            EXPECT_NEAR(RuleOnMonomial(r, k), MonomialIntegral(k), 1e-14) << "n = " << n << ", x^" << k;
    }
}

TEST(GaussLegendre, MissesDegree2nByTheTheoreticalRemainder) {
    // A&S 25.4.30: ∫f − Σ w f(x_i) = 2^{2n+1}(n!)⁴/((2n+1)((2n)!)³)·f^{(2n)}(ξ), and for x^{2n}
    // f^{(2n)} = (2n)! exactly. Down to n = 12 the remainder (~1e-7) dwarfs rounding (1e-15), so
    // 1e-6 relative checks the rules are the Gauss rules, not merely exact to some lower degree.
    for (int n = 1; n <= 12; ++n) {
        const double logRem = (2 * n + 1) * std::log(2.0) + 4 * std::lgamma(n + 1.0) -
                              std::log(2 * n + 1.0) - 2 * std::lgamma(2 * n + 1.0);
        const double err = MonomialIntegral(2 * n) - RuleOnMonomial(GaussLegendre(n), 2 * n);
        EXPECT_NEAR(err / std::exp(logRem), 1.0, 1e-6) << "n = " << n;
    }
}

TEST(GaussLegendre, NodesAreSortedSymmetricAndWeightsSumToTwo) {
    for (int n = 1; n <= MaxGaussLegendreNodes; ++n) {
        const GaussLegendreRule &r = GaussLegendre(n);
        double sum = 0;
        for (int i = 0; i < n; ++i) {
            sum += r.w[i];
            EXPECT_GT(r.w[i], 0) << n;
            if (i > 0) {
                EXPECT_LT(r.x[i - 1], r.x[i]) << n;
            }
            if (2 * i + 1 == n) {
                EXPECT_LT(std::abs(r.x[i]), 1e-16) << n;  // the middle node of an odd rule
            } else {
                EXPECT_EQ(r.x[n - 1 - i], -r.x[i]) << n;  // exactly mirrored
            }
            EXPECT_EQ(r.w[n - 1 - i], r.w[i]) << n;
        }
        EXPECT_NEAR(sum, 2.0, 1e-14) << n;
    }
}

TEST(GaussLegendre, MatchesTabulatedEightPointRule) {
    // Abramowitz & Stegun Table 25.4 (n = 8), to the 16 digits printed there: agreement within
    // 2e-16 (one unit of the last printed digit plus the table's rounding).
    const double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
    const double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
    const GaussLegendreRule &r = GaussLegendre(8);
    for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(r.x[4 + i], x[i], 2e-16);
        EXPECT_NEAR(r.w[4 + i], w[i], 2e-16);
    }
}

TEST(GaussLegendre, OutOfRangeCountsAreClamped) {
    EXPECT_EQ(GaussLegendre(0).n, 1);
    EXPECT_EQ(GaussLegendre(MaxGaussLegendreNodes + 5).n, MaxGaussLegendreNodes);
    EXPECT_EQ(&GaussLegendre(7), &GaussLegendre(7));  // computed once, same storage
}

TEST(GaussLegendre, CompositeRuleIntegratesSmoothFunctions) {
    // ∫_0^π sin = 2; 8 nodes on 4 panels: error ~ (π/4)^{16}/16!·… < 1e-15.
    EXPECT_NEAR(IntegrateGaussLegendre([](double t) { return std::sin(t); }, 0.0, Pi, 8, 4), 2.0, 1e-14);
    // Complex integrands: ∫_{−1}^{1} e^{3it} dt = 2 sin(3)/3.
    const Complex z = IntegrateGaussLegendre([](double t) { return std::polar(1.0, 3 * t); }, -1.0, 1.0, 12);
    EXPECT_NEAR(z.real(), 2 * std::sin(3.0) / 3, 1e-14);
    EXPECT_NEAR(z.imag(), 0.0, 1e-15);
}

TEST(GaussLegendre, MaxPhaseBoundsTheLinearPhaseError) {
    // At Φ = GaussLegendreMaxPhase(n, tol) the n-point error on e^{iΦt/2} over [−1, 1], relative
    // to the interval's length 2, is below tol: the real and imaginary parts each obey the
    // remainder bound, so |error| ≤ √2·tol. It is also not far below it (> tol/100 for these n:
    // the bound is the remainder's leading term), so the rule spends no nodes for nothing.
    for (int n : {6, 8, 12, 16, 20})
        for (double tol : {1e-6, 1e-10, 1e-13}) {
            const double phi = GaussLegendreMaxPhase(n, tol);
            const Complex exact = 2 * std::sin(phi / 2) / (phi / 2);
            const Complex q = IntegrateGaussLegendre([&](double t) { return std::polar(1.0, phi * t / 2); },
                                                     -1.0, 1.0, n);
            const double rel = std::abs(q - exact) / 2;
            EXPECT_LE(rel, std::sqrt(2.0) * tol) << "n = " << n << ", tol = " << tol;
            EXPECT_GE(rel, 0.01 * tol) << "n = " << n << ", tol = " << tol;
        }
}

}  // namespace
}  // namespace phasor
