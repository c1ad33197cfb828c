// SPDX-License-Identifier: Apache-2.0
// phasor — cylinder functions (bessel.h).
#include "core/numerics/bessel.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace phasor {

namespace {

constexpr int HankelTerms = 48;
// BesselJSequence's power-series path: x in [1e-8, SeriesMaxX], nMax ≤ SeriesMaxOrder.
constexpr double SeriesMaxX = 2;
constexpr int SeriesMaxOrder = 24;
// Its factors: 1/n! and 1/(k·(n + k)) (the ratio of consecutive terms over −x²/4). At x ≤ 2 the
// k-th term is at most 1/(k!)² of the first, and the sum at least J₀(2) ≈ 0.22 of it: 13 terms
// reach the 1e-17 cut, 16 are tabulated.
struct BesselSeriesTables {
    std::array<double, SeriesMaxOrder + 1> invFactorial{};
    std::array<std::array<double, 17>, SeriesMaxOrder + 1> coefficient{};
};
constexpr BesselSeriesTables SeriesTables = [] {
    BesselSeriesTables b;
    double f = 1;
    for (int n = 0; n <= SeriesMaxOrder; ++n) {
        if (n > 0) f *= n;
        b.invFactorial[std::size_t(n)] = 1 / f;
        for (std::size_t k = 1; k < b.coefficient[0].size(); ++k)
            b.coefficient[std::size_t(n)][k] = 1 / (double(k) * double(n + int(k)));
    }
    return b;
}();

struct HankelCoefficients {
    std::array<double, HankelTerms> a0, a1;  // a_m(ν) of DLMF 10.17.1 for ν = 0, 1
};

const HankelCoefficients &HankelCoeffs() {
    static const HankelCoefficients c = [] {
        HankelCoefficients h;
        h.a0[0] = h.a1[0] = 1;
        for (int m = 1; m < HankelTerms; ++m) {
            const double odd = (2.0 * m - 1) * (2.0 * m - 1);
            h.a0[m] = h.a0[m - 1] * (0 - odd) / (8.0 * m);
            h.a1[m] = h.a1[m - 1] * (4 - odd) / (8.0 * m);
        }
        return h;
    }();
    return c;
}

}  // namespace

void HankelAsymptoticFactors(double x, Complex *p0, Complex *p1) {
    const HankelCoefficients &c = HankelCoeffs();
    double r0 = 1, i0 = 0, r1 = 1, i1 = 0, xm = 1;
    for (int m = 1; m < HankelTerms; ++m) {
        xm /= x;
        const double t0 = c.a0[m] * xm, t1 = c.a1[m] * xm;
        switch (m & 3) {  // i^m
            case 0: r0 += t0, r1 += t1; break;
            case 1: i0 += t0, i1 += t1; break;
            case 2: r0 -= t0, r1 -= t1; break;
            default: i0 -= t0, i1 -= t1; break;
        }
        if (std::abs(t0) < 1e-17 && std::abs(t1) < 1e-17) break;
    }
    *p0 = Complex(r0, i0);
    *p1 = Complex(r1, i1);
}

void Hankel01(double x, Complex *h0, Complex *h1) {
    if (x >= HankelAsymptoticMin) {
        Complex p0, p1;
        HankelAsymptoticFactors(x, &p0, &p1);
        const double amp = std::sqrt(2 / (Pi * x));
        *h0 = amp * std::polar(1.0, x - Pi / 4) * p0;
        *h1 = amp * std::polar(1.0, x - 3 * Pi / 4) * p1;
        return;
    }
    *h0 = Complex(std::cyl_bessel_j(0.0, x), std::cyl_neumann(0.0, x));
    *h1 = Complex(std::cyl_bessel_j(1.0, x), std::cyl_neumann(1.0, x));
}

double BesselI0Scaled(double x) {
    x = std::max(0.0, x);
    if (x < 22) {
        // I₀(x) = Σ_k (x²/4)^k/(k!)² (A&S 9.6.12): positive terms, no cancellation; at x = 22 the
        // terms fall below 1e-17 of the sum after ~45 of them.
        const double q = 0.25 * x * x;
        double term = 1, sum = 1;
        for (int k = 1; k < 200 && term > 1e-17 * sum; ++k) {
            term *= q / (double(k) * k);
            sum += term;
        }
        return sum * std::exp(-x);
    }
    // √(2πx)·I₀(x)e^{−x} ~ Σ_k ((2k−1)!!)²/(k!(8x)^k) (A&S 9.7.1), summed until the terms stop
    // falling or drop below 1e-17: the smallest term near k ≈ 2x is ~e^{−2x} < 1e-19 for x ≥ 22.
    const double y = 1 / (8 * x);
    double term = 1, sum = 1;
    for (int k = 1; k < 60; ++k) {
        const double next = term * (2 * k - 1) * (2 * k - 1) * y / k;
        if (next >= term || next < 1e-17 * sum) break;
        term = next;
        sum += term;
    }
    return sum / std::sqrt(2 * Pi * x);
}

void BesselJSequence(double x, int nMax, double *out) {
    if (nMax < 0) return;
    if (!(x >= 1e-8)) {
        // J_n(x) = (x/2)^n/n!·(1 − (x/2)²/(n+1) + …): the next term is below 1e-32 relative.
        const double h = std::max(0.0, x) / 2;
        double t = 1;
        for (int n = 0; n <= nMax; ++n) {
            out[n] = t * (1 - h * h / (n + 1));
            t *= h / (n + 1);
        }
        return;
    }
    if (x <= SeriesMaxX && nMax <= SeriesMaxOrder) {
        // Small x (a grating's m = k₀·h·cosθ ≈ 1): J_top and J_{top−1} from their power series
        // J_n(x) = (x/2)ⁿ/n!·Σ_k (−x²/4)^k/(k!·(n+1)_k) (DLMF 10.2.2), the rest by the recurrence
        // downwards — stable, J being the recessive solution as n grows (DLMF 3.6(ii)); for x ≤ 2
        // below J₀'s first zero (2.405) every J_n(x) > 0, and the terms' magnitudes sum to at most
        // e^{x²/4} ≤ e times the first while the sum is at least J₀(2) ≈ 0.22 of it: at most a
        // factor ~10 of cancellation. The recurrence adds about an ulp per step (≲ 3.5e-15
        // absolute at 24 orders). No normalisation and no division: at x ≈ 1 about 70 % of
        // the instructions of the start at max(nMax + 6, x + 10) + √(24x) below. x ≥ 1e-8 and
        // top ≤ 24 keep (x/2)^top/top! above 1e-241, far from underflow.
        const int top = std::max(nMax, 1);
        const double h = x / 2, q = -h * h;
        double power = 1;  // (x/2)^(top − 1)
        for (int n = 1; n < top; ++n) power *= h;
        // Both series in one loop (their terms fall by q·c[k]); J_{top−1}'s converge the slower.
        const auto &cTop = SeriesTables.coefficient[std::size_t(top)];
        const auto &cBelow = SeriesTables.coefficient[std::size_t(top - 1)];
        double tTop = power * h * SeriesTables.invFactorial[std::size_t(top)], next = tTop;  // J_top
        double tBelow = power * SeriesTables.invFactorial[std::size_t(top - 1)], cur = tBelow;  // J_{top−1}
        for (std::size_t k = 1; k < cBelow.size() && std::abs(tBelow) > 1e-17 * cur; ++k) {
            tTop *= q * cTop[k];
            next += tTop;
            tBelow *= q * cBelow[k];
            cur += tBelow;
        }
        if (top <= nMax) out[top] = next;
        out[top - 1] = cur;
        const double twoOverX = 2 / x;
        for (int n = top - 1; n > 0; --n) {
            const double prev = double(n) * twoOverX * cur - next;  // J_{n−1}
            next = cur;
            cur = prev;
            out[n - 1] = cur;
        }
        return;
    }
    // Start above both nMax and x with a margin d that makes the contamination by the dominant
    // solution Y negligible at n ≤ max(nMax, x): its relative size there is ~J_N/Y_N, which falls
    // like exp(−(2/3)(2d)^{3/2}/√x) past the transition n ≈ x (DLMF 10.19.8), below 1e-16 for
    // d ≳ 0.3·x^{1/3}·… — d = 6 + √(24·x) covers it with room (x = 250 needs d ≈ 46, this gives
    // 83; x = 1 gets exp(−68)). Above the transition, at n = nMax > x, the contamination is
    // (x/2)^{2d}·(nMax!/N!)², N = nMax + d, smaller still: the margin follows x, not nMax (10
    // orders at x = 3 start at 24, not 34). The normalisation sum J_0 + 2ΣJ_2k needs
    // 4 more above x whatever nMax is (at nMax = 0, x + 6 + √(24x) leaves 1e-12 at x ≈ 2; measured
    // by tests/core/numerics/bessel_test.cpp): start at max(nMax + 6, x + 10) + √(24x).
    const double top = std::max(nMax + 6.0, x + 10);
    int start = int(top + std::sqrt(24 * x));
    start += start & 1;  // even, so the normalisation sum pairs up
    double next = 0, cur = 1e-30, norm = 0;  // J_{n+1}, J_n up to a common factor
    const double twoOverX = 2 / x;            // a multiplication in the loop, not a division
    // One step from J_n to J_{n−1} (n as a double: the same product as with the integer); kept
    // where n − 1 ≤ nMax; everything kept rescaled when it grows large.
    auto step = [&](int n, double dn) {
        const double prev = dn * twoOverX * cur - next;  // J_{n−1}
        next = cur;
        cur = prev;
        if (n - 1 <= nMax) out[n - 1] = cur;
    };
    auto rescale = [&](int from) {
        if (std::abs(cur) > 1e250) {
            cur *= 1e-250;
            next *= 1e-250;
            norm *= 1e-250;
            for (int k = from; k <= nMax; ++k) out[k] *= 1e-250;
        }
    };
    // In pairs from the even start: J_{n−1} (odd), then J_{n−2} (even: the normalisation's terms).
    double dn = start;
    for (int n = start; n > 0; n -= 2, dn -= 2) {
        step(n, dn);
        rescale(n - 1);
        step(n - 1, dn - 1);
        if (n - 2 > 0) norm += 2 * cur;
        rescale(n - 2);
    }
    norm += cur;  // + J_0
    for (int k = 0; k <= nMax; ++k) out[k] /= norm;
}

}  // namespace phasor
