// SPDX-License-Identifier: Apache-2.0
// phasor — dispersion formulas for real refractive indices n(λ): Sellmeier's and Cauchy's.
// One implementation for the named glasses and liquids (named_ior.h) and the `sellmeier` and
// `cauchy` spectrum plug-ins (src/spectra/). All arguments are SI: λ the vacuum wavelength [m],
// Sellmeier's C_j [m²], Cauchy's B [m²] and C [m⁴].
//
// A fit is valid on the band it was made on; outside [lo, hi] the formula is evaluated at the
// nearer end (a constant continuation), so that the poles of a Sellmeier formula (its resonances
// λ_j = √C_j) and Cauchy's 1/λ⁴ growth never reach a renderer.
#pragma once

#include <cmath>
#include <span>

#include "core/math.h"

namespace phasor::dispersion {

/// Sellmeier (1871): n² = 1 + Σ_j B_j λ²/(λ² − C_j), λ clamped to [lo, hi]. Returns 0 (no index)
/// where n² ≤ 0 or is not finite, i.e. between a resonance and the band where the fit holds.
inline double Sellmeier(double lambda, std::span<const double> b, std::span<const double> c, double lo, double hi) {
    const double l2 = Sqr(Clamp(lambda, lo, hi));
    double n2 = 1;
    for (std::size_t j = 0; j < b.size(); ++j) n2 += b[j] * l2 / (l2 - c[j]);
    return n2 > 0 && std::isfinite(n2) ? std::sqrt(n2) : 0.0;
}

/// Cauchy (1836): n = A + B/λ² + C/λ⁴, λ clamped to [lo, hi].
inline double Cauchy(double lambda, double a, double b, double c, double lo, double hi) {
    const double x = 1 / Sqr(Clamp(lambda, lo, hi));  // 1/λ²
    return a + (b + c * x) * x;
}

}  // namespace phasor::dispersion
