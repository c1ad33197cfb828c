// SPDX-License-Identifier: Apache-2.0
#include "core/numerics/rice.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/math.h"
#include "core/numerics/bessel.h"
#include "core/numerics/gauss_legendre.h"

namespace phasor {

double RiceCdfSeries(double t, double c, double *bound) {
    if (bound) *bound = 0;
    if (!(c > 0)) return 0;
    const double mu = 0.5 * t * t, x = 0.5 * c * c;
    const double u1 = -std::expm1(-x);  // P(N_x ≥ 1)
    // Tiny arguments: the first terms, with relative remainders ≤ μ² and ≤ μx/2 (≤ 1e-17 here).
    if (mu < 1e-20) return std::exp(-mu) * (u1 + mu * std::max(0.0, u1 - x * std::exp(-x)));
    if (x < 1e-20) return std::exp(-mu) * u1;

    const double m = std::max(mu, x);
    const int J = static_cast<int>(std::ceil(m + 8 * std::sqrt(m) + 16));
    // Unnormalised sequences started at 1: pm ∝ p_j(μ) (from j = J), px ∝ p_j(x) (from J + 1),
    // u ∝ Σ_{i=j}^{J+1} p_i(x); sum ∝ Σ_j p_j(μ)·P(N_x ≥ j + 1), sumPm ∝ Σ_j p_j(μ). The constants
    // follow from the sequences' own totals (Σ_j p_j = 1) at the end, so no exp, log or ln j! is
    // needed and nothing loses accuracy to a large exponent. Rescaled by 2^−332 before a product
    // could overflow (the ratios of consecutive terms are at most ~1e23 here).
    constexpr double Big = 0x1p332, Small = 0x1p-332;
    const double invMu = 1 / mu, invX = 1 / x;
    double pm = 1, px = 1, u = 1, sum = 0, sumPm = 0;
    int rescaledM = 0, rescaledX = 0;  // how often pm and u were multiplied by 2^−332
    for (int j = J;; --j) {
        sum += pm * u;  // p_j(μ)·P(N_x ≥ j + 1)
        sumPm += pm;
        if (j == 0) break;
        pm *= j * invMu;       // p_{j−1}(μ)
        px *= (j + 1) * invX;  // p_j(x)
        u += px;               // P(N_x ≥ j)
        if (pm > Big) pm *= Small, sumPm *= Small, sum *= Small, ++rescaledM;
        if (u > Big) u *= Small, px *= Small, sum *= Small, ++rescaledX;
    }
    const double u0 = u + px * invX;  // + p_0(x): Σ_{i=0}^{J+1} p_i(x)
    // Σ_{j≤J} p_j(μ) = 1 − P(N_μ > J) and Σ_{i≤J+1} p_i(x) = 1 − P(N_x ≥ J + 2), both ≥ 1 − 1e-17.
    const double result = sum / (sumPm * u0);
    if (bound) {
        // Dropped: ≤ P(N_x ≥ J + 2) ≤ p_{J+1}(x)·r/(1 − r), r = x/(J + 2) (< 1 as J ≥ x + 16), in the
        // sum, and the normalisations' relative P(N_x ≥ J + 2) and P(N_μ > J) ≤ p_{J+1}(μ)/(1 − μ/(J + 2)).
        // p_{J+1}(x) and p_{J+1}(μ): the start values 1 in the final scale, over the totals.
        const double pxTop = std::ldexp(1 / u0, -332 * rescaledX);
        const double pmTop = std::ldexp(mu / (J + 1) / sumPm, -332 * rescaledM);
        const double rx = x / (J + 2), rm = mu / (J + 2);
        const double tailX = pxTop * rx / (1 - rx), tailM = pmTop / (1 - rm);
        *bound = tailX + result * (tailX + tailM);
    }
    return result;
}

double RiceCdfBessel(double t, double c, double *bound) {
    if (bound) *bound = 0;
    if (!(c > 0) || !(t > 0)) return RiceCdfSeries(t, c, bound);
    const double z = t * c, zeta = std::min(t, c) / std::max(t, c);
    const int N = static_cast<int>(std::ceil(9 * std::sqrt(z) + 16));
    if (N > RiceBesselMaxTerms) return RiceCdfQuadrature(t, c);
    // Miller: r_{k−1} = r_{k+1} + (2k/z)·r_k from r_{N+1} = 0, r_N = 1 gives r_k ∝ I_k(z); every
    // term positive. Normalised by e^z = I_0(z) + 2Σ_{k≥1} I_k(z) (DLMF 10.35.5 at θ = 0). The sums
    // are taken on the way down, Σ_{k≥1} ζ^k r_k by Horner (h ← r_k + ζ·h), so no term is stored.
    const double twoOverZ = 2 / z;
    constexpr double Big = 0x1p332, Small = 0x1p-332;
    double above = 0, rk = 1, twice = 0, horner = 0;  // r_{k+1}, r_k; 2Σ_{i≥k} r_i; Σ_{i≥k} ζ^{i−k} r_i
    for (int k = N; k >= 1; --k) {
        twice += 2 * rk;
        horner = rk + zeta * horner;
        const double below = above + (k * twoOverZ) * rk;  // r_{k−1}
        above = rk;
        rk = below;
        if (rk > Big) rk *= Small, above *= Small, twice *= Small, horner *= Small;
    }
    const double r0 = rk, norm = r0 + twice, sum = zeta * horner;  // sum = Σ_{k≥1} ζ^k r_k
    const double front = std::exp(-0.5 * (c - t) * (c - t)) / norm;
    double result;
    if (c < t)
        result = front * sum;  // e^{−(c−t)²/2}·Σ_{k≥1} (c/t)^k·I_k(z)e^{−z}
    else
        result = 1 - front * (r0 + sum);  // 1 − Q₁(t, c), Q₁ = e^{−(c−t)²/2}·Σ_{k≥0} (t/c)^k·I_k(z)e^{−z}
    if (bound) {
        // e^{−z}I_k(z) = P(D = k) for D = N_a − N_b, a = b = z/2 independent Poisson counts (the
        // Skellam law), so the tails beyond N are below the Chernoff bound P(D ≥ n) ≤
        // exp(z(√(1 + s²) − 1) − n·asinh s), s = n/z, at n = N + 1: the sum's (times ζ^{N+1}), and
        // the normalisation's and Miller's start error (≤ (I_{N+1}/I_0)·(K_0/K_{N+1}) ≤ I_{N+1}/I_0),
        // relative errors of every term of ≤ 2·Ch/I_0e and Ch/I_0e. Returned as an absolute bound.
        const double s = (N + 1) / z;
        const double ch = std::exp(z * (std::sqrt(1 + s * s) - 1) - (N + 1) * std::asinh(s));
        const double i0e = r0 / norm, e = std::exp(-0.5 * (c - t) * (c - t));
        const double sumTail = e * std::pow(zeta, N + 1) * ch;
        *bound = sumTail + 3 * ch / i0e * (c < t ? result : 1 - result);
    }
    return result;
}

double RiceCdfQuadrature(double t, double c) {
    if (!(c > 0)) return 0;
    // Rice density of ρ = |X|: ρ·exp(−(ρ−t)²/2)·I₀e(ρt), which is negligible (< e^{-60})
    // outside [t − 11, t + 11].
    auto density = [&](double r) { return r * std::exp(-0.5 * (r - t) * (r - t)) * BesselI0Scaled(r * t); };
    constexpr double Reach = 11;
    const double lo = std::max(0.0, t - Reach), hi = t + Reach;
    if (c >= hi) return 1;
    if (c <= lo) {
        // A disc far out in the tail: negligible unless the disc is small, where [0, c] is smooth
        // and short enough to integrate directly (keeps relative accuracy for tiny sources).
        return c < 2 ? IntegrateGaussLegendre(density, 0.0, c, 8, 8) : 0.0;
    }
    // Integrate the shorter side for accuracy near 0 and 1: composite 8-point Gauss–Legendre on 24 panels.
    if (c - lo <= hi - c) return std::min(1.0, IntegrateGaussLegendre(density, lo, c, 8, 24));
    return std::max(0.0, 1 - IntegrateGaussLegendre(density, c, hi, 8, 24));
}

double RiceCdfAsymptotic(double t, double c) {
    constexpr int K = 6, Nodes = 32;
    static const std::array<double, K> coef = [] {  // c_k = ((2k − 1)!!)²/(k!·8^k)
        std::array<double, K> a{};
        a[0] = 1;
        for (std::size_t k = 0; k + 1 < K; ++k) a[k + 1] = a[k] * Sqr(2.0 * double(k) + 1) / (8.0 * double(k + 1));
        return a;
    }();
    const double a = c - t;
    const bool outside = a >= 0;  // integrate the mass beyond the rim: 1 − P
    const double mid = outside ? a + 6 : a - 6;
    const GaussLegendreRule &g = GaussLegendre(Nodes);
    double sum = 0;
    for (int i = 0; i < Nodes; ++i) {
        const double y = mid + 6 * g.x[i], inv = 1 / (t * (t + y));
        double e = coef[K - 1];
        for (int k = K - 2; k >= 0; --k) e = coef[std::size_t(k)] + inv * e;  // E(t(t + y))
        sum += g.w[i] * std::exp(-0.5 * y * y) * std::sqrt(1 + y / t) * e;
    }
    sum *= 6 / std::sqrt(2 * Pi);
    return outside ? 1 - sum : sum;
}

double RiceCdf(double t, double c) {
    if (!(c > 0)) return 0;
    if (c - t >= RiceReach) return 1;  // e^{−11²/2} < 6e-27
    if (t - c >= RiceReach) return 0;
    // Marcum's series is the cheaper one, except for a small disc about a near mean (c < 2, t ≤ c)
    // where it would subtract from 1 a Q close to 1.
    if (c < 2 && t <= c) return std::min(1.0, RiceCdfSeries(t, c));
    if (t >= RiceAsymptoticMinT) return std::clamp(RiceCdfAsymptotic(t, c), 0.0, 1.0);
    return std::clamp(RiceCdfBessel(t, c), 0.0, 1.0);
}

}  // namespace phasor
