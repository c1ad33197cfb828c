// SPDX-License-Identifier: Apache-2.0
// Closed-form references for free-space diffraction tests: Fresnel's integrals and the knife edge
// (Born & Wolf, "Principles of Optics", §8.7; Goodman, "Introduction to Fourier Optics", §4.5).
#pragma once

#include <cmath>

#include "core/math.h"
#include "core/numerics/faddeeva.h"

namespace phasor::test {

/// C(w) + i·S(w) = ∫₀ʷ e^{iπt²/2} dt, from the error function: ((1+i)/2)·erf(√π(1−i)w/2), with
/// erf(z) = 1 − e^{−z²}·w(iz) (iz in the upper half-plane for w ≥ 0; C and S are odd).
inline Complex Fresnel(double w) {
    if (w < 0) return -Fresnel(-w);
    const double a = 0.5 * std::sqrt(Pi) * w;
    const Complex z(a, -a), iz(a, a);
    const Complex erf = 1.0 - std::exp(-z * z) * FaddeevaW(iz);
    return Complex(0.5, 0.5) * erf;
}

/// Intensity behind a straight edge (the screen covers x < 0) at distance z, relative to the
/// unobstructed plane wave: ½[(½ + C(w))² + (½ + S(w))²], w = x·√(2/(λz)).
inline double KnifeEdgeIntensity(double x, double lambda, double z) {
    const Complex cs = Fresnel(x * std::sqrt(2 / (lambda * z)));
    return 0.5 * (std::pow(0.5 + cs.real(), 2) + std::pow(0.5 + cs.imag(), 2));
}

}  // namespace phasor::test
