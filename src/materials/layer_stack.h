// SPDX-License-Identifier: Apache-2.0
// phasor — reflection and transmission of a planar stack of homogeneous layers (thin films,
// multilayer reflectors; theory §4.4–4.5), per polarisation, for complex indices.
//
// Geometry: incident medium (index n₀, half-space) | layer 1 | … | layer N | substrate (half-space).
// Every layer is parallel and homogeneous; thickness is the geometric thickness along the normal.
// The result is the coherent (fully coherent, plane-wave) response: the thin-film regime where the
// layers are thinner than the light's coherence length. A stack with no layers is a bare
// interface and returns exactly fresnel.h's FresnelAmplitudes(n₀, cosθ₀, n_substrate).
#pragma once

#include <span>

#include "core/math.h"

namespace phasor {

/// One layer: complex index n + iκ (κ ≥ 0) at the wavelength of the query, thickness [m] ≥ 0.
struct Layer {
    Complex n;
    double thickness = 0;
};

/// Amplitude and power response of a stack. r and t are electric-field amplitude ratios in the
/// (s, p) basis of core/polarization.h (outgoing over incident, at the top and bottom surfaces
/// of the stack), with the sign conventions of fresnel.h's FresnelAmplitudes, so that
/// Jones::Diagonal(rs, rp) is the stack's reflection Jones matrix. R = |r|²; T = |t|² times the
/// power factor of fresnel.h (FresnelPowerFactorS/P) between the incident medium and the
/// substrate, so for lossless media R + T = 1 per polarisation and 1 − R − T is what the layers
/// absorb. T is 0 when the wave in the substrate is evanescent (total internal reflection).
struct StackResponse {
    Complex rs, rp, ts, tp;
    double Rs = 0, Rp = 0, Ts = 0, Tp = 0;
    Complex cosSubstrate;  // cosθ in the substrate (RefractedCos's branch)
    double R() const { return 0.5 * (Rs + Rp); }  // unpolarised
    double T() const { return 0.5 * (Ts + Tp); }
};

/// The response of `layers` (listed from the incident side down) between an incident medium of
/// index nIncident and a substrate of index nSubstrate, at vacuum wavelength lambda [m], for a
/// plane wave with cosθ = cosIncident in the incident medium (complex allowed, e.g. inside an
/// absorbing medium; for a real incident medium cosθ ∈ (0, 1]). Any number of layers; thick
/// absorbing or evanescent layers are stable (see layer_stack.cpp).
StackResponse LayerStackResponse(double lambda, Complex nIncident, Complex cosIncident,
                                 std::span<const Layer> layers, Complex nSubstrate);

}  // namespace phasor
