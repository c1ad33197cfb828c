// SPDX-License-Identifier: Apache-2.0
// Energy bookkeeping for kernel tests, in both senses of Material::ConservesEnergyPerIncidentDirection
// (core/render/material.h): what one query gathers (the backward albedo a camera at wi sees) and
// what the light arriving from one direction d leaves with (per incident direction: the listed lobes
// of the queries that point back at d, and ∫ f(w → d)·|cosθ_w| dω_w over the continuous lobes).
// The quadratures are deterministic (Gauss–Legendre over the projected disc of directions), written
// without the kernels' own sampling formulas.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/numerics/gauss_legendre.h"
#include "core/render/material.h"

namespace phasor::test {

/// ∫ g(w) d²u over the unit disc of a direction's tangential part u = (w.x, w.y), w on the side
/// `sign` (±1) of the surface (d²u = |cosθ_w| dω_w), for a g (returning a SampledSpectrum) that
/// peaks at u = centre: Gauss–Legendre in polar coordinates about `centre`, the radius on panels
/// doubling from `core` (resolving a peaked lobe of width ≳ core) with a cos-map at each panel (so
/// the square-root ends of the visible arc at ρ = 1 ∓ |centre| cost nothing), the azimuth over the
/// part of each ring inside the unit disc (found by bisection on the ring). Smooth integrands: ~1e-7.
template <typename G>
SampledSpectrum IntegrateProjectedDisc(const Vec2 &centre, double sign, double core, G &&g) {
    const double s = std::hypot(centre.x, centre.y);
    const double phiI = s > 0 ? std::atan2(-centre.y, -centre.x) : 0;  // towards the disc's centre
    std::vector<double> edges = {0};
    for (double r = core; r < 1 + s; r *= 2) edges.push_back(r);
    if (s < 1 && s > 0) edges.push_back(1 - s);
    edges.push_back(1 + s);
    std::sort(edges.begin(), edges.end());
    const GaussLegendreRule &gr = GaussLegendre(16), &gp = GaussLegendre(32);
    SampledSpectrum total(0.0);
    for (std::size_t e = 0; e + 1 < edges.size(); ++e) {
        const double a = edges[e], b = edges[e + 1];
        if (b <= a) continue;
        for (int i = 0; i < gr.n; ++i) {
            const double tau = 0.5 * Pi * (1 + gr.x[i]), dtau = 0.5 * Pi * gr.w[i];
            const double rho = a + 0.5 * (b - a) * (1 - std::cos(tau)), drho = 0.5 * (b - a) * std::sin(tau) * dtau;
            // The half-arc inside the disc about the direction to its centre: |centre + ρ e^{iφ}| < 1.
            auto visible = [&](double dphi) {
                const double phi = phiI + dphi;
                return (centre.x + rho * std::cos(phi)) * (centre.x + rho * std::cos(phi)) +
                           (centre.y + rho * std::sin(phi)) * (centre.y + rho * std::sin(phi)) <
                       1;
            };
            double h;
            if (visible(Pi)) h = Pi;
            else if (!visible(0)) continue;
            else {
                double lo = 0, hi = Pi;
                for (int it = 0; it < 60; ++it) (visible(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
                h = 0.5 * (lo + hi);
            }
            SampledSpectrum ring(0.0);
            for (int j = 0; j < gp.n; ++j) {
                const double phi = phiI + h * gp.x[j];
                const double ux = centre.x + rho * std::cos(phi), uy = centre.y + rho * std::sin(phi);
                ring += g(Vec3(ux, uy, sign * SafeSqrt(1 - ux * ux - uy * uy))) * (h * gp.w[j]);
            }
            total += ring * (rho * drho);
        }
    }
    return total;
}

/// What a camera at wi gathers through the continuous lobes of the kernel k prepared there, on its
/// own side: ∫ Eval(wo)·|cosθo| dωo over wi's hemisphere (the backward integral Sample estimates),
/// per carried wavelength; `core` as for IntegrateProjectedDisc (the lobe is assumed to peak at the
/// mirror direction).
inline SampledSpectrum ContinuousAlbedo(const PreparedKernel &k, double core) {
    const Vec3 &wi = k.Query().wi;
    return IntegrateProjectedDisc(Vec2(-wi.x, -wi.y), wi.z > 0 ? 1 : -1, core,
                                  [&](const Vec3 &wo) { return k.Eval(wo); });
}

/// What the continuous lobes send out of the light arriving from d: ∫ Eval(q(w), d)·|cosθ_w| dω_w
/// over the directions w on d's side (q(w) = q with wi = w, the kernel prepared there), per carried
/// wavelength.
inline SampledSpectrum ContinuousFrom(const Material &m, const ScatterQuery &q, const Vec3 &d, double core) {
    ScatterQuery qw = q;
    ScratchBuffer atW;
    return IntegrateProjectedDisc(Vec2(-d.x, -d.y), d.z > 0 ? 1 : -1, core, [&](const Vec3 &w) {
        qw.wi = w;
        atW.Reset();
        return m.Prepare(qw, atW).Eval(d);
    });
}

/// The energy of the light arriving from d = q.wi that leaves through listed near-delta lobes, at
/// wavelength slot j, for a kernel that lists per query what arrives *at* wi
/// (Material::ConservesEnergyPerIncidentDirection): the light from d goes into every direction o
/// that some lobe of q reaches at λ_j (the outgoing candidates), and of each query at o the lobes
/// that point back at d at λ_j carry it (their radiance factor (n_in/n_out)² undone). For a
/// reciprocal kernel the same as the listed lobes' energy of q.
struct ListedForward {
    double energy = 0;
    int outgoing = 0;  // the number of outgoing candidates
};
inline ListedForward ListedEnergyFrom(const Material &m, const ScatterQuery &q, int j) {
    ScratchBuffer scratch;
    std::vector<Vec3> outs;
    for (const NearDeltaLobe &l : m.Prepare(q, scratch).ListNearDelta())
        if (l.Weight()[j] > 0 &&
            std::none_of(outs.begin(), outs.end(), [&](const Vec3 &o) { return SameDirection(o, l.wo[j]); }))
            outs.push_back(l.wo[j]);
    ListedForward f;
    f.outgoing = int(outs.size());
    for (const Vec3 &o : outs) {
        ScatterQuery back = q;
        back.wi = o;
        for (const NearDeltaLobe &l : m.Prepare(back, scratch).ListNearDelta())
            if (l.Weight()[j] > 0 && SameDirection(l.wo[j], q.wi)) f.energy += l.Weight()[j] * l.Eta(j) * l.Eta(j);
    }
    return f;
}

}  // namespace phasor::test
