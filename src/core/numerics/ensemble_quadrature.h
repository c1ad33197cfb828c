// SPDX-License-Identifier: Apache-2.0
// phasor — quadrature over an angular ensemble (theory §0 D15): the rules with which a lobe's
// efficiency is averaged over a generalized ray's angular spectrum, a light's angular profile, or
// their product.
//
// The ensemble lives in a plane of 2-D coordinates (x, y) — in practice the direction cosines
// transverse to a source's central direction — as the product of
//   * a profile: a point (Delta), a uniform disc of radius r (a `distant` disc, sin α), or an
//     isotropic Gaussian of per-axis variance Ω (a `distant` Gaussian, a beam's local spectrum);
//   * optionally a window: an isotropic Gaussian N((x, y); c, s²·I) (a generalized ray's angular
//     spectrum, σ_k²/k², seen in these coordinates).
// EnsembleRule builds nodes p_k and weights w_k with Σ_k w_k·g(p_k) ≈ ∫ g(p)·q(p) d²p, q the
// product density (a constant factor of q does not matter: callers normalise). Each node also
// carries q(p_k), so a caller whose exact density e differs smoothly from this q (a window that
// is a Gaussian in another frame, Jacobians) uses w_k·e(p_k)/q(p_k).
//
// Node counts follow the oscillation of g. The caller bounds, per axis, the rate at which g
// varies over a box: |∂^m g/∂x^m| ≤ R_x^m·sup|g| (a band-limited model of the lobe's efficiency:
// its phase changes by at most R_x rad per unit of x — Bernstein's inequality for a function of
// exponential type R_x). With that bound the remainders of the rules are proven:
//   * Gauss–Hermite (a Gaussian factor not clipped by a disc), A&S 25.4.46:
//       |E| ≤ √π·n!/(2ⁿ(2n)!)·(√2σR)^{2n}·sup|g|, relative to the Gaussian's mass;
//   * Gauss–Legendre over an interval of length L (disc chords), A&S 25.4.30:
//       |E| ≤ L^{2n+1}(n!)⁴/((2n+1)((2n)!)³)·R^{2n}·sup|g| (GaussLegendreMaxPhase);
//     the outer axis of a disc is mapped by x = mid − h·cos t, which removes the square-root
//     ends of its chords (the integrand in t is analytic; its rate is h·R plus 2 for the chord);
//   * a Gaussian window clipped by a disc's edge (axes along (u) and across (v) its centre; the disc
//     within ±6s of the centre, for a centre outside the disc the 6s inside the edge, where its tail
//     lies), in this order:
//       - 4 or 6 nodes from the moments of the window on the disc (computed across each chord in
//         closed form or, for chords shorter than s, by a series; along u by Gauss–Legendre), exact
//         for every polynomial in (u, v) of degree 3 (4 nodes) or of degree 5 but v⁴, u·v⁴, u³v²
//         (6 nodes), taken where g's Taylor remainder — from the directional rates below and the
//         measure's and the rule's fourth or sixth moments (Minkowski) — is within tol: proven for
//         the moments as computed (≤ 4e-6 relative), and what a slowly varying g (s·R ≲ 0.2) takes;
//       - for a disc of at least 10s, polar coordinates about its centre (no chord is clipped there;
//         at most MaxMeasureNodes = 20 nodes per axis, beyond which the chord rules below are used and
//         the rule reports itself capped — their model does not hold there):
//         Gauss rules of the Rice density radially and of the von Mises law along each circle, from
//         discretisations (Stieltjes, Golub–Welsch); along a circle of radius ρ the m-th derivative
//         bound is the Touchard polynomial T_m(ρR) (Faà di Bruno), radially g's rates plus the law's
//         change with ρ (a model, checked against brute force);
//       - else Gauss–Legendre in u, the Gaussian counted as a rate of 2.5/s plus the tail's log-slope
//         (d − r)/s² (a model, checked by the tests against brute force; for r ≫ s it under-resolves
//         the average across a clipped chord near the tip, which the polar rules replace); across,
//         Gauss–Hermite on every chord that spans ±6s (the Gaussian exactly, g's rate only), the
//         truncated normal's Gauss rule on the clipped chords near the edge's tip.
// Over the two axes the error of an average (Σ w g/Σ w) is then at most 3·tol·sup|g| (each axis's
// bound relative to the ensemble's mass; a disc's outer axis carries the chord's Jacobian, ≤ 2·tol).
// Every rule has at most MaxEnsembleNodesPerAxis nodes per axis (composite Gauss–Legendre panels
// beyond 16 nodes; the tolerance is then per unit length, as above). Analyticity beyond the band
// limit is assumed: an efficiency with a kink inside the ensemble (a critical angle, a grating
// order appearing) converges algebraically, not as bounded.
#pragma once

#include <utility>
#include <vector>

#include "core/math.h"

namespace phasor {

/// The n-point Gauss–Hermite rule for ∫ f(t)·e^{−t²} dt (Σ w = √π), nodes ascending and exactly
/// antisymmetric. 1 ≤ n ≤ MaxGaussHermiteNodes (clamped); computed once (Newton's method on the
/// normalised Hermite recurrence), thread-safe.
constexpr int MaxGaussHermiteNodes = 64;
struct GaussHermiteRule {
    int n = 0;
    const double *x = nullptr;
    const double *w = nullptr;
};
const GaussHermiteRule &GaussHermite(int n);

/// The fewest Gauss–Hermite nodes whose remainder (above) for a function of rate `rateT` [rad per
/// unit of t] is ≤ tol relative to ∫e^{−t²}; MaxGaussHermiteNodes + 1 if none suffices.
int GaussHermiteNodesFor(double rateT, double tol);
/// The fewest Gauss–Legendre nodes (≤ 64) whose remainder for a total phase Φ = rate·L over the
/// interval is ≤ tol·L·sup|g|; 65 if none suffices.
int GaussLegendreNodesFor(double phase, double tol);

/// The Gauss rule for ∫_a^b f(x)·φ(x) dx, φ the standard normal density (a truncated normal): the
/// fewest nodes n ≤ 12 whose remainder for a function of rate `rate` [rad per unit of x] is ≤ tol
/// relative to ∫_a^b φ — rate^{2n}·β_1⋯β_n/(2n)! with β_k the recurrence coefficients of the
/// weight (k for the untruncated normal: Gauss–Hermite's bound) — as (node, weight) pairs, weights
/// summing to ∫_a^b φ, nodes ascending. From a 64-point Gauss–Legendre discretisation of φ on [a, b]
/// (b − a ≤ 12) by the Stieltjes procedure and the Jacobi matrix's eigen-decomposition
/// (Golub–Welsch). False (out empty) if no n ≤ 12 meets the bound, or b − a is not in (0, 12].
bool TruncatedNormalRule(double a, double b, double rate, double tol, std::vector<std::pair<double, double>> &out);

/// Most nodes per axis of an EnsembleRule.
constexpr int MaxEnsembleNodesPerAxis = 256;

/// The ensemble's shape in the (x, y) plane (see the top of the file).
struct EnsembleShape {
    enum class Profile { Delta, Disc, Gaussian };
    Profile profile = Profile::Delta;
    double radius = 0;    // Disc: radius r > 0
    double variance = 0;  // Gaussian: per-axis variance Ω > 0
    /// The window N(p; windowCentre, windowVariance·I); windowVariance = Infinity: none.
    Vec2 windowCentre;
    double windowVariance = Infinity;
    bool HasWindow() const { return windowVariance < Infinity; }
};

/// An axis-aligned box [lo, hi] in the (x, y) plane.
struct EnsembleBox {
    Vec2 lo, hi;
};

struct EnsembleNode {
    Vec2 p;
    double w = 0;  // quadrature weight, density q included
    double q = 0;  // the density q(p) the rule integrates against
};

/// How the rule was built (for tests and cost statistics).
struct EnsembleRuleInfo {
    int nx = 1, ny = 1;      // nodes per axis (outer x, inner y)
    bool overlap = true;     // false: the window lies outside the disc (the ensemble is empty; one node)
    bool capped = false;     // the bound does not hold: an axis needed more than MaxEnsembleNodesPerAxis nodes,
                             // or a window at the edge of a disc ≥ 10s needed more than 20 polar nodes per axis
};

/// Builds the rule for `shape` into `out` (cleared first). `rates(box)` returns upper bounds
/// (R_x, R_y) [rad per unit of x, y] on the rate of the integrand over the box (see the top of the
/// file); it is called at most twice. `tol` is the remainder bound relative to sup|g| (per unit
/// length or Gaussian mass). A Delta profile, or an ensemble so narrow that one node meets the
/// bound, gives one node at the ensemble's mean.
/// Optionally `rates.Bound(box)` returns cheaper, looser bounds (each ≥ what rates(box) returns, or
/// Infinity): a Gaussian ensemble asks it first, and where even its rates need one node per axis the
/// rule is that node without asking rates(box) — the rule rates(box) would give, since node counts
/// never fall as a rate grows.
template <typename Rates>
EnsembleRuleInfo BuildEnsembleRule(const EnsembleShape &shape, Rates &&rates, double tol, std::vector<EnsembleNode> &out);

// ---- implementation detail: the rule builder behind the template ---------------------------------
namespace ensemble_detail {
struct RatesRef {
    void *ctx;
    Vec2 (*call)(void *, const EnsembleBox &);
    Vec2 (*bound)(void *, const EnsembleBox &);  // nullptr: the rates have no cheaper bound
    Vec2 operator()(const EnsembleBox &b) const { return call(ctx, b); }
};
EnsembleRuleInfo Build(const EnsembleShape &shape, const RatesRef &rates, double tol, std::vector<EnsembleNode> &out);
}  // namespace ensemble_detail

template <typename Rates>
EnsembleRuleInfo BuildEnsembleRule(const EnsembleShape &shape, Rates &&rates, double tol, std::vector<EnsembleNode> &out) {
    using R = std::remove_reference_t<Rates>;
    ensemble_detail::RatesRef ref{const_cast<void *>(static_cast<const void *>(&rates)),
                                  [](void *c, const EnsembleBox &b) { return (*static_cast<R *>(c))(b); }, nullptr};
    if constexpr (requires(R &r, const EnsembleBox &b) { r.Bound(b); })
        ref.bound = [](void *c, const EnsembleBox &b) { return static_cast<R *>(c)->Bound(b); };
    return ensemble_detail::Build(shape, ref, tol, out);
}

}  // namespace phasor
