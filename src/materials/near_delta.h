// SPDX-License-Identifier: Apache-2.0
// phasor — the angular spread of near-delta lobes for generalized rays (design.md §4.1, theory
// §1.2, §1.6): a smooth reflection/refraction keeps the GR's β and ρ and only turns its mean
// direction (supplement S6.4), so the outgoing lobe is the GR's own angular Gaussian about the
// lobe direction, with per-axis variance σ_k²/k² = (1+ρ²)/(2β²k²) in the outgoing medium.
#pragma once

#include "core/material.h"

namespace phasor {

/// True if Eval should report near-delta lobes as GR-spread Gaussians for this query.
inline bool SpreadNearDelta(const ScatterQuery &q) { return !q.rayOptics && q.evalNearDelta && q.beta2 > 0; }

/// Per-axis angular variance [rad²] of a GR with the query's footprint in a medium of index eta at
/// vacuum wavelength lambda.
inline double NearDeltaAngularVariance(const ScatterQuery &q, double eta, double lambda) {
    const double k = 2 * Pi * eta / lambda;
    return 0.5 * (1 + q.rho * q.rho) / (q.beta2 * k * k);
}

/// Solid-angle density [1/sr] of a near-delta lobe about the unit direction wc: the isotropic
/// Gaussian N₂(u⊥; 0, var·I) in the direction cosines u⊥ of wo transverse to wc (d²u⊥ = cos dω about
/// wc, so it is normalised up to the e^{−1/(2var)} tail), zero in wc's opposite hemisphere.
inline double NearDeltaDensity(const Vec3 &wo, const Vec3 &wc, double var) {
    const double c = Dot(wo, wc);
    if (c <= 0) return 0;
    const double sin2 = std::max(0.0, 1 - c * c);
    return c * std::exp(-0.5 * sin2 / var) / (2 * Pi * var);
}

}  // namespace phasor
