// SPDX-License-Identifier: Apache-2.0
// phasor — Gauss–Legendre quadrature: the one set of rules every integral in the project uses
// (the `rs` propagator, the `aperture` footprint integral, the Rice quadrature of core/numerics/rice.h).
#pragma once

#include <type_traits>

namespace phasor {

/// Largest number of nodes a rule may have.
constexpr int MaxGaussLegendreNodes = 64;

/// The n-point Gauss–Legendre rule on [−1, 1]: nodes x[0] < x[1] < … < x[n−1], exactly
/// antisymmetric (x[n−1−i] = −x[i]), and positive, symmetric weights w[i] (Σ w = 2). Exact for
/// polynomials of degree ≤ 2n − 1 (up to rounding, ~1e-16 per node). The arrays live as long as
/// the program.
struct GaussLegendreRule {
    int n = 0;
    const double *x = nullptr;
    const double *w = nullptr;
};

/// The rule with n nodes, 1 ≤ n ≤ MaxGaussLegendreNodes (clamped to that range). Every rule is
/// computed once, in double precision (Newton's method on the Legendre recurrence, A&S 25.4.29),
/// on the first call; thread-safe.
const GaussLegendreRule &GaussLegendre(int n);

/// Largest phase Φ [rad] of e^{iΦt/2}, t ∈ [−1, 1] (a linear phase that changes by Φ over the
/// interval), that the n-point rule integrates with an error below `tol` relative to the
/// interval's length: the remainder f^{(2n)}·L^{2n+1}(n!)⁴/((2n+1)((2n)!)³) (A&S 25.4.30) with
/// |f^{(2n)}| = (Φ/L)^{2n} solved for Φ.
double GaussLegendreMaxPhase(int n, double tol);

/// ∫_a^b f(x) dx by the composite n-point rule on `panels` equal panels (f returns a double or
/// a complex number).
template <typename F>
auto IntegrateGaussLegendre(F &&f, double a, double b, int n, int panels = 1) {
    const GaussLegendreRule &r = GaussLegendre(n);
    std::decay_t<decltype(f(a))> sum{};
    const double h = (b - a) / panels, half = 0.5 * h;
    for (int p = 0; p < panels; ++p) {
        const double mid = a + (p + 0.5) * h;
        for (int i = 0; i < r.n; ++i) sum += (r.w[i] * half) * f(mid + half * r.x[i]);
    }
    return sum;
}

}  // namespace phasor
