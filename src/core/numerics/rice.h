// SPDX-License-Identifier: Apache-2.0
// phasor — the Rice distribution function P(|X| ≤ c) for X ~ N₂(μ, I), |μ| = t, i.e. 1 − Q₁(t, c)
// with Marcum's Q-function: the mass of a Gaussian inside a disc that does not share its centre.
// `distant` disc sources measured by a generalized ray and the virtual plane's acceptance cone
// (core/render/genray.h, DiscGaussianProbability) call it once per GR and wavelength.
#pragma once

namespace phasor {

/// Largest max(t², c²)/2 of RiceCdfSeries' stated rounding bound (its cost grows as t², c²).
constexpr double RiceSeriesMaxHalfSquare = 2000;

/// How far (in σ) a disc's edge lies beyond the mean, or inside it, where RiceCdf is exactly 0 or 1.
inline constexpr double RiceReach = 11;

/// P(|X| ≤ c), X ~ N₂(μ, I), |μ| = t ≥ 0, c ≥ 0 (dimensionless: offset and radius in units of σ).
///   * c − t ≥ RiceReach (11): 1 (the mass outside is below e^{−(c−t)²/2} < 6e-27, the 2-D normal's mass
///     outside the radius c − t about its mean);
///   * t − c ≥ RiceReach: 0 (the mass inside is below (c²/2)·e^{−(t−c)²/2}: the disc's area times the
///     density at its nearest point, i.e. < 6e-27 of what the same disc holds about the mean
///     (c²/2 for a small disc), so a measurement divided by the disc's area stays accurate);
///   * c < 2 and t ≤ c (a small disc about a near mean, P small): RiceCdfSeries, relative error
///     ≤ 5e-14 there (a proven bound, J ≤ 30);
///   * t ≥ RiceAsymptoticMinT (35): RiceCdfAsymptotic (relative ~1e-13);
///   * else RiceCdfBessel, relative error ≤ 2e-12 (a proven bound).
double RiceCdf(double t, double c);

/// The Poisson-mixture series P(|X| ≤ c) = Σ_{j≥0} p_j(μ)·P(N_x ≥ j + 1), μ = t²/2, x = c²/2,
/// p_j(μ) = e^{−μ}μ^j/j!, N_x ~ Poisson(x) (the non-central χ² with 2 degrees of freedom is a
/// Poisson mixture of central ones, and P(χ²_{2j+2} ≤ c²) = P(N_x ≥ j + 1); equivalently
/// P(N_x > N_μ) for independent counts). All terms are positive; they are summed for
/// j = J … 0, J = ⌈M + 8√M + 16⌉, M = max(μ, x), with the recurrences p_{j−1}(μ) = p_j(μ)·j/μ,
/// p_j(x) = p_{j+1}(x)·(j + 1)/x and P(N_x ≥ j) = P(N_x ≥ j + 1) + p_j(x), started at 1 and
/// normalised at the end by their own totals (Σ_j p_j = 1): no exp, log or ln j! enters, so no
/// large exponent spoils the relative accuracy far in a tail; rescaled by 2^−332 before anything
/// could overflow.
/// Error bound (proven; *bound receives the truncation part): the sum drops ≤ P(N_x ≥ J + 2)
/// ≤ p_{J+1}(x)·r/(1 − r), r = x/(J + 2) < 1, and the normalisations are relatively off by
/// P(N_x ≥ J + 2) and P(N_μ > J) ≤ p_{J+1}(μ)/(1 − μ/(J + 2)); below 1e-15 of the result over the
/// whole range (tested). Rounding: each p is a product of ≤ J + 1 factors of two roundings, each
/// total a sum of positive terms, so to first order the relative error is ≤ 2J·u for p, 3J·u for
/// the tails and totals, 6J·u for the sum and (12J + 4)·u for the result, u = 2^−53: ≤ 3.2e-12 at
/// M = RiceSeriesMaxHalfSquare (J = 2374), ≤ 1.7e-13 for t, c ≤ 10 (measured: ~1e-15, tests/core/
/// numerics/rice_test.cpp). μ or x < 1e-20: the first one or two terms
/// (relative remainder ≤ max(μ², μx) < 1e-17). Cost: J + 1 terms of ~6 flops (J = 17 at t, c ≪ 1,
/// 23 at t, c ~ 1, 123 at t, c ~ 10) against 192 exp and I₀ evaluations for the quadrature.
double RiceCdfSeries(double t, double c, double *bound = nullptr);

/// Largest number of terms RiceCdfBessel sums (beyond it, t·c > 39 000, it takes the quadrature).
constexpr int RiceBesselMaxTerms = 1800;

/// Marcum's series: for c < t, P = e^{−(c−t)²/2}·Σ_{k≥1} (c/t)^k·I_k(tc)e^{−tc}; for c ≥ t,
/// P = 1 − e^{−(c−t)²/2}·Σ_{k≥0} (t/c)^k·I_k(tc)e^{−tc}. The I_k(z)e^{−z}, k ≤ N = ⌈9√z + 16⌉, by
/// Miller's backward recurrence (all terms positive, stable for I_k) normalised with
/// I_0 + 2Σ_{k≥1} I_k = e^z. Error bound (proven; *bound, absolute): e^{−z}I_k(z) is the Skellam
/// law of a difference of two Poisson(z/2) counts, so the neglected tails and Miller's start error
/// are below multiples of its Chernoff bound at N + 1 (< 1e-16 of the result over the range where
/// RiceCdf uses it, tested; the start N keeps it there for every z); rounding: positive sums
/// of ≤ N + 1 terms, ≤ (4N + 8)·u relative, then for c ≥ t the subtraction 1 − Q, which keeps that
/// accuracy where P is not small: c ≥ 2 and c ≥ t give P ≥ P(c, c) = ½(1 − I_0(c²)e^{−c²}) > 0.39,
/// so the relative error is ≤ (4N + 8)·u/0.39 ≤ 2e-12 for N ≤ RiceBesselMaxTerms. The sums are
/// taken during the recurrence (Σ ζ^k r_k by Horner), nothing stored: N + 1 steps of ~6 flops, ~0.8 k
/// instructions at t, c ~ 5 and ~6 k at t, c ~ 50 (RiceCdfSeries: 1.8 k, 31 k; the quadrature ~50 k).
double RiceCdfBessel(double t, double c, double *bound = nullptr);

/// Smallest t for which RiceCdf takes RiceCdfAsymptotic.
constexpr double RiceAsymptoticMinT = 35;

/// For t ≥ RiceAsymptoticMinT and |c − t| < 11: the Rice density in y = ρ − t is
/// φ(y)·√(1 + y/t)·E(t(t + y)), E(x) = I₀(x)e^{−x}√(2πx), and E is smooth and close to 1 where φ
/// lives: E by its first six asymptotic terms Σ_k c_k x^{−k}, c_k = ((2k − 1)!!)²/(k!·8^k), whose
/// remainder is at most twice the first omitted term (Watson's lemma on I₀(x)e^{−x} =
/// (1/π)∫₀² e^{−xs}(s(2 − s))^{−1/2} ds: the binomial series of (1 − s/2)^{−1/2} has positive terms
/// with ratios ≤ 1/2, and s ≥ 1 adds ≤ e^{−x}) — here x ≥ t(t − 23) ≥ 420, so ≤ 2.1e-16 relative;
/// the product integrated by 32-point Gauss–Legendre over the 12 units below a = c − t (P, for
/// c < t) or above it (1 − P, for c ≥ t; P ≥ 0.39 there), beyond which the density is below
/// e^{−72} of its value at a (measured: 4.4e-14 relative for the normal alone over every a; the
/// tests compare with the quadrature and Marcum's series). Cost ~2 k instructions whatever t and c
/// (RiceCdfBessel's ~9√(tc) steps: ~3 k at t, c ~ 40, ~5 k at 60; the quadrature ~50 k).
double RiceCdfAsymptotic(double t, double c);

/// The same by integrating the Rice density ρ·e^{−(ρ−t)²/2}·I₀(ρt) over the shorter side of
/// [max(0, t − 11), t + 11] with a composite 8-point Gauss–Legendre rule on 24 panels (192 density
/// evaluations, each an exp and a scaled I₀); absolute error ~1e-12. The reference of the series'
/// test, and what RiceCdf uses for large arguments.
double RiceCdfQuadrature(double t, double c);

}  // namespace phasor
