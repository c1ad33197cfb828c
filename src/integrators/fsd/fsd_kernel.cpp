// SPDX-License-Identifier: Apache-2.0
// phasor — an FSD event as a scattering vertex (fsd_kernel.h).
#include "integrators/fsd/fsd_kernel.h"

#include <algorithm>
#include <cmath>

#include "materials/aperture_integral.h"

namespace phasor::fsd {

namespace {

ScatterQuery EventQuery(const SampledWavelengths &wl) {
    ScatterQuery q;
    q.wi = Vec3(0, 0, -1);  // the GR arrives along d = +z of the event frame
    q.wl = &wl;
    q.rayOptics = false;
    return q;
}

// The GR at the event plane.
SpectralGenRay AtEvent(const SpectralGenRay &g, const Event &ev) {
    SpectralGenRay h = g;
    h.Propagate(ev.t);
    h.o = ev.p;
    return h;
}

}  // namespace

EventKernel::EventKernel(Event ev, const SpectralGenRay &g, const SampledWavelengths &wl, const Settings &s)
    : PreparedKernel(EventQuery(wl)), ev_(std::move(ev)), gr_(AtEvent(g, ev_)), lobe_(ev_, gr_, wl, s) {
    caps_ = CapContinuous | CapFootprintAware;
    continuous_.Add(0);
    const Vec3 d = ev_.frame.n;
    const double skip = LeaveDistance(ev_);
    si_.p = ev_.p + d * skip;
    si_.n = d;
    si_.shading = ev_.frame;
    si_.t = ev_.t + skip;
}

double LeaveDistance(const Event &ev) {
    const double mag = std::max({std::abs(ev.p.x), std::abs(ev.p.y), std::abs(ev.p.z)});
    return ev.beyond + 1e-6 * ev.halfWidth + 1e-7 * mag;
}

SampledSpectrum EventKernel::EvalContinuousFrom(const Vec3 &wo, const IncidentWave &w) const {
    if (!(wo.z > 0)) return SampledSpectrum(0.0);
    const Vec3 woWorld = ev_.frame.ToWorld(wo);
    if (w.beam || !std::isfinite(w.dist)) return lobe_.Eval(woWorld, w);  // a beam is placed in world space
    // The source at w.dist from p_v along wo: seen from p it lies at v = wo·dist + d·skip. The
    // caller multiplies by wo.z and the irradiance at p_v (∝ 1/dist² for a point source).
    const double skip = Dot(si_.p - ev_.p, ev_.frame.n);
    const Vec3 v = woWorld * w.dist + ev_.frame.n * skip;
    const double r = Length(v);
    const Vec3 wp = v / r;
    const double cosP = Dot(wp, ev_.frame.n);
    return lobe_.Eval(wp, IncidentWave{r}) * (cosP / wo.z * (w.dist * w.dist) / (r * r));
}

double EventKernel::PdfContinuous(const Vec3 &wo) const {
    if (!(wo.z > 0)) return 0;
    return lobe_.Pdf(ev_.frame.ToWorld(wo));
}

std::optional<ScatterSample> EventKernel::SampleLobes(double u0, const Vec2 &u) const {
    const std::optional<LobeSample> ls = lobe_.Sample(u0, u);
    if (!ls) return std::nullopt;
    ScatterSample s;
    s.wo = ev_.frame.ToLocal(ls->wo);
    if (!(s.wo.z > 0)) return std::nullopt;
    s.weight = ls->weight;
    s.pdf = ls->pdf;
    s.lobe = 0;
    // The GR leaving an event is spread-free (theory §9 item 5): its spread is inside the lobe.
    s.flags = ScatterTransmission | ScatterDiffuse | ScatterSpreadFree;
    s.eta = 1;
    return s;
}

std::optional<LobeResponse> EventKernel::EvalLobe(int lobe, const Vec3 &wo) const {
    if (lobe != 0) return std::nullopt;
    const SampledSpectrum v = EvalContinuous(wo) * std::abs(wo.z);
    LobeResponse r;
    r.hasJones = true;
    for (int i = 0; i < q_.wl->Count(); ++i) {
        r.jones[i] = Jones::Identity() * Complex(std::sqrt(std::max(0.0, v[i])), 0);
        r.mueller[i] = Mueller::Identity() * std::max(0.0, v[i]);
    }
    return r;
}

SampledSpectrum Transmission(const Event &ev, const SpectralGenRay &g, const SampledWavelengths &wl,
                             const Settings &s, const Vec3 &wo, const IncidentWave &w) {
    const Lobe masked(ev, g, wl, s);
    // The unobstructed GR's |A|² in closed form (theory §2.4): the Gaussian integral of the
    // aperture integrand's quadratic form over the whole plane, ∫exp(−xᵀMx + i bᵀx) d²x =
    // π/√det M · exp(−bᵀM⁻¹b/4) — exact for the GR on its own axis (no oblique cut, no beam
    // evolution), and free of the quadrature the masked lobe needs. A beam goes through the box.
    std::optional<Lobe> openBox;
    if (w.beam) {
        Event free = ev;
        free.edges.clear();
        free.mask = DecomposeUnion({}, 2 * ev.halfWidth, ev.halfWidth);
        free.coveredMass.clear();
        free.coveredFraction = 0;
        openBox.emplace(free, g, wl, s);
    }
    const Frame &f = ev.frame;
    SampledSpectrum r(0.0);
    for (int i = 0; i < std::min(wl.Count(), g.count); ++i) {
        double a0;
        if (openBox) {
            a0 = std::norm(openBox->Amplitude(i, -wo, w));
        } else {
            const PlateGaussian pg = MakePlateGaussian(f.n, -wo, f.s, f.t, f.n, g.k[i], g.beta2[i], g.rho[i], w.dist, s.window);
            const Complex det = pg.axx * pg.ayy - pg.axy * pg.axy;
            const Complex q = (pg.bx * pg.bx * pg.ayy - 2.0 * pg.bx * pg.by * pg.axy + pg.by * pg.by * pg.axx) / det;
            a0 = Pi / (g.beta2[i] * std::abs(det)) * std::exp(-0.5 * q.real());  // |(πβ²)^{−1/2}·π/√det·e^{−q/4}|²
        }
        if (a0 > 0) r[i] = std::norm(masked.Amplitude(i, -wo, w)) / a0;
    }
    return r;
}

}  // namespace phasor::fsd
