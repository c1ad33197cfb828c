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

/// The incoherent response of a stack (the ray-optics limit, theory §0 D8, §4.4–4.5: "a film's
/// incoherent sum"): inside every layer in which the wave propagates, the multiply reflected waves are
/// summed in power instead of in amplitude — what a stack of layers thicker than the light's
/// coherence length (or laterally sheared past its coherence width) reflects, and what a ray
/// tracer bouncing rays inside each slab computes. Layers in which the wave does not propagate
/// (LayerPropagates false: evanescent beyond a critical angle, or metallic) have no propagation
/// phase that could decorrelate, so each run of them is kept coherent together with its two
/// faces and acts as one effective interface (mixed coherent/incoherent stacks: Katsidis &
/// Siapkas, Appl. Opt. 41, 3978 (2002); Centurioni, Appl. Opt. 44, 7532 (2005)); so does a layer of
/// zero thickness (it is no layer). Without layers, or when no layer propagates, it equals
/// LayerStackResponse's R and T.
///
/// Rs, Rp, Ts, Tp as in StackResponse (T with the power factor between the incident medium and
/// the substrate, so a lossless stack has R + T = 1 per polarisation). Rsp and Tsp are the s–p
/// cross sums Σ a_s·conj(a_p) over the summed waves (Tsp including √(P_s·P_p) of the power
/// factors): with Rs, Rp they give the Mueller matrix of the incoherent sum,
/// Mueller::FromDiagonalSums(Rs, Rp, Rsp), which depolarises partially.
struct IncoherentStackResponse {
    double Rs = 0, Rp = 0, Ts = 0, Tp = 0;
    Complex Rsp, Tsp;
    double R() const { return 0.5 * (Rs + Rp); }  // unpolarised
    double T() const { return 0.5 * (Ts + Tp); }
};
IncoherentStackResponse LayerStackIncoherent(double lambda, Complex nIncident, Complex cosIncident,
                                             std::span<const Layer> layers, Complex nSubstrate);

/// True if a wave with normal wave-vector component q = n·cosθ (in units of k₀) propagates
/// rather than decays: Re q > Im q. Lossless media beyond the critical angle (q imaginary) and
/// metals (n ≪ κ) do not; glasses and weakly absorbing films such as Cu₂O do.
inline bool LayerPropagates(Complex q) { return q.real() > q.imag(); }

/// Lateral shear [m] between the wave reflected at the top face of the stack and the one that
/// crosses every layer down to the substrate face and back: Σ_j 2·d_j·tanθ_j over the layers in
/// which the wave propagates (theory §4.4: 2·d·tanθ_t for one film), with tanθ_j the ray
/// direction of the propagating wave, n₀sinθ₀/Re(n_j cosθ_j). Evanescent and metallic layers
/// (LayerPropagates false) add nothing. 0 at normal incidence. The deeper wave exits displaced
/// along the incident wave's tangential direction of travel.
double LayerStackShear(Complex nIncident, Complex cosIncident, std::span<const Layer> layers);

}  // namespace phasor
