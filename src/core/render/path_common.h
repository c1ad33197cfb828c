// SPDX-License-Identifier: Apache-2.0
// phasor — pieces shared by the path-tracing integrators (`ray`, `grt`): multiple importance
// sampling, next-event estimation to one light (LightSampler), emission met by a path (area and
// infinite lights, MIS-weighted against NEE) and Russian roulette. Radiance units throughout
// (camera-normalised; theory §2.4 item 4).
#pragma once

#include "core/render/pixel_integrator.h"
#include "core/render/scene.h"

namespace phasor::path {

/// Power heuristic with β = 2 (Veach 1997); f = ∞ marks a delta strategy.
inline double PowerHeuristic(double f, double g) {
    if (std::isinf(f)) return 1;
    double f2 = f * f, g2 = g * g;
    return f2 + g2 > 0 ? f2 / (f2 + g2) : 0;
}

/// The MIS state of a path: whether the last scattering was a (near-)delta lobe or the detector
/// (then emission found by the path is counted in full), else the kernel's solid-angle pdf of the
/// last direction and the vertex it was sampled at.
struct MisState {
    bool deltaBounce = true;
    double prevPdf = 0;
    LightSampleContext prevCtx;
};

/// What SampleDirectLight picked (for integrators that re-evaluate the connection, sample_solve).
struct DirectLightInfo {
    const Light *light = nullptr;
    Vec3 wi;                  // unit direction from the vertex towards the light sample
    double dist = Infinity;   // distance to it (Infinity for lights at infinity)
};

/// Next-event estimation at a surface vertex (pbrt-style): one light chosen by `lights` (the
/// integrator's `light_sampler`: by reach at si, by power or uniformly) with uLight, sampled with uPos; the kernel k
/// prepared at si answers for its continuous lobes (near-delta lobes have no density). Delta lights get f·|cosθ|·E; area and infinite lights are
/// MIS-weighted (power heuristic) against kernel sampling. The shadow ray crosses straight-through
/// surfaces with their transmittance (Scene::Transmittance; their kernels prepared in `scratch` in
/// the regime `rayOptics`). Returns the contribution without the path throughput; counts the
/// shadow rays in stats; fills `info` (if given) with the light sample.
inline SampledSpectrum SampleDirectLight(const Scene &scene, const SurfaceInteraction &si, const PreparedKernel &k,
                                         const LightSampler &lights, double uLight, const Vec2 &uPos,
                                         const SampledWavelengths &wl, PathStats &stats, ScratchBuffer &scratch,
                                         bool rayOptics, DirectLightInfo *info = nullptr) {
    double selectPdf = 0;
    const LightSampleContext ctx{si.p, si.n};
    const Light *light = lights.Sample(uLight, ctx, &selectPdf);
    if (!light || !(selectPdf > 0)) return SampledSpectrum(0.0);
    auto ls = light->SampleLi(ctx, uPos, wl);
    if (!ls || !(ls->pdf > 0) || (ls->L.IsZero() && !ls->beam)) return SampledSpectrum(0.0);
    if (info) *info = DirectLightInfo{light, ls->wi, ls->dist};
    const Vec3 wo = si.shading.ToLocal(ls->wi);
    // A footprint-aware kernel integrates a Gaussian beam's own field over the GR's footprint and
    // answers per unit on-axis irradiance (IncidentWave); every other kernel sees the local
    // irradiance at the hit.
    const bool beamField = ls->beam && (k.Capabilities() & CapFootprintAware);
    const IncidentWave wave{ls->dist, beamField ? &*ls->beam : nullptr};
    const SampledSpectrum &incident = beamField ? ls->beamAxisIrradiance : ls->L;
    // A delta light needs no density; for the others the kernel's value and density together.
    const KernelValue v = ls->delta ? KernelValue{k.EvalFrom(wo, wave), 0} : k.EvalPdf(wo, wave);
    const SampledSpectrum f = v.f * std::abs(wo.z);
    if (f.IsZero() || incident.IsZero()) return SampledSpectrum(0.0);
    const bool far = std::isinf(ls->dist);
    double tMax = 0;
    const Ray shadow = scene.ShadowRay(si, far ? ls->wi : si.p + ls->wi * ls->dist, far, &tMax);
    const SampledSpectrum tr = scene.Transmittance(shadow, tMax, wl, rayOptics, scratch, stats.rays);
    if (tr.IsZero()) return SampledSpectrum(0.0);
    if (ls->delta) return f * incident * tr / selectPdf;
    const double pl = ls->pdf * selectPdf;
    return f * incident * tr * (PowerHeuristic(pl, v.pdf) / pl);
}

/// Radiance emitted by the area light at si towards the path (direction of travel rayDir),
/// MIS-weighted against NEE (which picks lights by `lights`) unless the path arrived through a
/// delta lobe.
inline SampledSpectrum HitEmission(const LightSampler &lights, const SurfaceInteraction &si, const Vec3 &rayDir,
                                   const SampledWavelengths &wl, const MisState &mis) {
    if (!si.areaLight) return SampledSpectrum(0.0);
    const SampledSpectrum le = si.areaLight->L(si.p, si.n, -rayDir, wl);
    if (le.IsZero() || mis.deltaBounce) return le;
    const double lightPdf = si.areaLight->PdfLi(mis.prevCtx, rayDir, si.p, si.n) * lights.Pmf(si.areaLight, mis.prevCtx);
    return le * PowerHeuristic(mis.prevPdf, lightPdf);
}

/// Radiance of the infinite lights along an escaping direction d, MIS-weighted against NEE unless
/// the path arrived through a delta lobe. With skipClosedForm, the lights measured in closed form
/// are left out (`grt` has measured them already after a near-delta lobe).
inline SampledSpectrum EscapedEmission(const Scene &scene, const LightSampler &lights, const Vec3 &d,
                                       const SampledWavelengths &wl, const MisState &mis, bool skipClosedForm = false) {
    SampledSpectrum sum(0.0);
    for (const Light *l : scene.InfiniteLights()) {
        if (skipClosedForm && l->MeasuredInClosedForm()) continue;
        const SampledSpectrum le = l->Le(d, wl);
        if (le.IsZero()) continue;
        if (mis.deltaBounce)
            sum += le;
        else {
            const double lightPdf = l->PdfLi(mis.prevCtx, d, Vec3(), Vec3()) * lights.Pmf(l, mis.prevCtx);
            sum += le * PowerHeuristic(mis.prevPdf, lightPdf);
        }
    }
    return sum;
}

/// Russian roulette on the throughput: survive with probability max(0.05, max_λ beta) when that
/// is below 1 (and rescale). Returns false if the path ends.
inline bool RussianRoulette(SampledSpectrum &beta, double u) {
    const double m = beta.Max();
    if (!(m > 0)) return false;
    if (m < 1) {
        const double survive = std::max(0.05, m);
        if (u >= survive) return false;
        beta /= survive;
    }
    return true;
}

}  // namespace phasor::path
