// SPDX-License-Identifier: Apache-2.0
// phasor — layer-stack response (layer_stack.h).
//
// Method: the characteristic-matrix (Abelès) product of the stack, evaluated as the equivalent
// Rouard recursion from the substrate up (theory §4.5):
//   Γ_N = r_{N,N+1};   Γ_{j−1} = (r_{j−1,j} + Γ_j e^{2iδ_j}) / (1 + r_{j−1,j} Γ_j e^{2iδ_j}),
//   δ_j = (2π/λ) n_j d_j cosθ_j,  r = Γ₀,
// with the transmitted amplitude accumulated alongside (multiple reflections inside layer j sum
// to the geometric series 1/(1 + r_{j−1,j} Γ_j e^{2iδ_j})):
//   t = t_{N,N+1} · Π_j t_{j−1,j} e^{iδ_j} / (1 + r_{j−1,j} Γ_j e^{2iδ_j}).
// Every factor has |e^{iδ}| ≤ 1 because Im(n_j cosθ_j) ≥ 0 (RefractedCos), so thick absorbing
// or evanescent layers underflow to an opaque layer instead of overflowing as the 2×2 matrix
// product's e^{−iδ} entries do. The interface coefficients are fresnel.h's, so a stack without
// layers is FresnelAmplitudes itself and the conventions (signs, branches) are shared.
#include "materials/layer_stack.h"

#include <vector>

#include "materials/fresnel.h"

namespace phasor {

StackResponse LayerStackResponse(double lambda, Complex nIncident, Complex cosIncident,
                                 std::span<const Layer> layers, Complex nSubstrate) {
    const std::size_t count = layers.size();
    // Media 0 … count+1 (incident, layers, substrate) and the interfaces between them.
    std::vector<Complex> n(count + 2), cosT(count + 2);
    n[0] = nIncident;
    cosT[0] = cosIncident;
    for (std::size_t j = 0; j < count; ++j) n[j + 1] = layers[j].n;
    n[count + 1] = nSubstrate;
    std::vector<FresnelCoefficients> face(count + 1);  // face[j]: medium j → medium j+1
    for (std::size_t j = 0; j <= count; ++j) {
        face[j] = FresnelAmplitudes(n[j], cosT[j], n[j + 1]);
        cosT[j + 1] = face[j].cosThetaT;  // Snell's invariant carried down the stack
    }

    const double k0 = 2 * Pi / lambda;
    const Complex i(0, 1);
    Complex gs = face[count].rs, gp = face[count].rp;  // Γ below the last layer
    Complex ts = face[count].ts, tp = face[count].tp;
    for (std::size_t j = count; j-- > 0;) {  // layer j+1 (1-based), its top face is face[j]
        const Complex phase = std::exp(i * k0 * n[j + 1] * cosT[j + 1] * layers[j].thickness);  // e^{iδ}
        const Complex round = phase * phase;                                                     // e^{2iδ}
        const Complex ds = 1.0 + face[j].rs * gs * round, dp = 1.0 + face[j].rp * gp * round;
        ts *= face[j].ts * phase / ds;
        tp *= face[j].tp * phase / dp;
        gs = (face[j].rs + gs * round) / ds;
        gp = (face[j].rp + gp * round) / dp;
    }

    StackResponse out;
    out.rs = gs;
    out.rp = gp;
    out.ts = ts;
    out.tp = tp;
    out.cosSubstrate = cosT[count + 1];
    out.Rs = std::norm(gs);
    out.Rp = std::norm(gp);
    out.Ts = FresnelPowerFactorS(n[0], cosT[0], n[count + 1], cosT[count + 1]) * std::norm(ts);
    out.Tp = FresnelPowerFactorP(n[0], cosT[0], n[count + 1], cosT[count + 1]) * std::norm(tp);
    return out;
}

}  // namespace phasor
