// SPDX-License-Identifier: Apache-2.0
// phasor — the shared generalized-ray path sampler (gr_path.h): the helpers of its estimate.
#include "integrators/gr_path.h"

#include "core/render/lobe_average.h"
#include "core/render/registry.h"

namespace phasor::grpath {

std::vector<ParamSpec> PathParams() {
    return {P::Integer("max_depth", "maximum number of scattering events (-1: unlimited, Russian roulette ends paths)")
                .Default(Value::Integer(16))
                .Min(-1),
            P::Integer("rr_depth", "bounces before Russian roulette starts (never before the first measurement)")
                .Default(Value::Integer(3))
                .Min(0),
            P::Integer("light_samples",
                       "next-event estimates per vertex (stratified when a square); more of them "
                       "reduce the noise from extended sources, e.g. through apertures")
                .Default(Value::Integer(1))
                .Min(1)
                .Max(4096)};
}

void GrPathSampler::CheckDetector(const Scene &scene, const std::string &integrator) {
    const Detector &det = scene.GetDetector();
    if (!det.SupportsGR())
        throw Error("integrator '" + integrator +
                    "' needs a detector that generates generalized rays (perspective, thin_lens, virtual_plane); "
                    "detector '" +
                    det.name + "' does not");
}

bool GrPathSampler::HasDeltaLights(const Scene &scene) {
    for (const Light *l : scene.Lights())
        if (l->IsDelta()) return true;
    return false;
}

bool GrPathSampler::HasHittableEmitters(const Scene &scene) {
    for (const Light *l : scene.Lights())
        if (!l->IsDelta()) return true;
    return false;
}

bool GrPathSampler::HasClosedFormLights(const Scene &scene) {
    for (const Light *l : scene.Lights())
        if (l->MeasuredInClosedForm()) return true;
    return false;
}

bool GrPathSampler::DropCompanions(SampledSpectrum &T, const SampledWavelengths &wl) {
    // T[i > 0] = 0 and T[0]·N: what SampledWavelengths::TerminateSecondary's pdf[0]/N does to
    // everything the film receives, applied to the rest of the path only.
    if (wl.Count() < 2) return false;
    for (int i = 1; i < NumWavelengths; ++i) T[i] = 0;
    T[0] *= wl.Count();
    return true;
}

std::optional<GrMeasurement> GrPathSampler::MeasureOne(const Scene &scene, const Light &light, const SpectralGenRay &g,
                                                       const SurfaceInteraction *si, const SampledWavelengths &wl,
                                                       PathStats &stats) {
    auto m = light.MeasureGR(g.TimeReversed(), wl);
    if (!m || m->value.IsZero()) return std::nullopt;
    ++stats.rays;
    bool blocked;
    if (si)
        blocked = std::isinf(m->dist) ? scene.OccludedDirection(*si, m->wi) : scene.Occluded(*si, si->p + m->wi * m->dist);
    else
        blocked = scene.GetAccel().Occluded(Ray{g.o, m->wi}, 0, m->dist * (1 - 1e-7));
    if (blocked) return std::nullopt;
    return m;
}

SampledSpectrum GrPathSampler::MeasureClosedForm(const Scene &scene, const SpectralGenRay &g,
                                                 const SurfaceInteraction *si, const SampledWavelengths &wl,
                                                 PathStats &stats) {
    SampledSpectrum sum(0.0);
    for (const Light *light : scene.Lights()) {
        if (!light->MeasuredInClosedForm()) continue;
        if (auto m = MeasureOne(scene, *light, g, si, wl, stats)) sum += m->value;
    }
    return sum;
}

SpectralGenRay GrPathSampler::AlongLobe(const SpectralGenRay &g, const SurfaceInteraction &si,
                                        const NearDeltaLobe &lobe, int i) {
    SpectralGenRay out = g;
    const Vec3 wo = si.shading.ToWorld(lobe.wo[i]);
    out.Redirect(wo, lobe.Eta(i));
    out.o = si.SpawnOrigin(wo);
    return out;
}

bool GrPathSampler::UniformLobe(const NearDeltaLobe &lobe, const SampledWavelengths &wl) {
    bool uniform = true;
    for (int i = 1; i < wl.Count(); ++i)
        uniform = uniform && lobe.wo[i] == lobe.wo[0] && lobe.Eta(i) == lobe.Eta(0);
    return uniform;
}

SampledSpectrum GrPathSampler::MeasureThroughLobe(const Scene &scene, const SpectralGenRay &g,
                                                  const SurfaceInteraction &si, const ScatterQuery &q,
                                                  const NearDeltaLobe &lobe, const SampledWavelengths &wl,
                                                  PathStats &stats) {
    // A lobe whose direction or index differs between the carried wavelengths (dispersive) is
    // measured per wavelength along that wavelength's own direction.
    if (lobe.weight.IsZero()) return SampledSpectrum(0.0);
    const bool uniform = UniformLobe(lobe, wl);
    SampledSpectrum v(0.0);
    for (int i = 0; i < (uniform ? 1 : wl.Count()); ++i) {
        if (!uniform && !(lobe.weight[i] > 0)) continue;
        const SpectralGenRay out = AlongLobe(g, si, lobe, i);
        for (const Light *light : scene.Lights()) {
            if (!light->MeasuredInClosedForm()) continue;
            auto m = MeasureOne(scene, *light, out, &si, wl, stats);
            if (!m) continue;
            const SampledSpectrum a = ThroughLobeWeight(si, q, g, lobe, *m, uniform ? -1 : i);
            if (uniform) v += a * m->value;
            else v[i] += a[i] * m->value[i];
        }
    }
    return v;
}

SampledSpectrum GrPathSampler::ThroughLobeWeight(const SurfaceInteraction &si, const ScatterQuery &q,
                                                 const SpectralGenRay &g, const NearDeltaLobe &lobe,
                                                 const GrMeasurement &m, int wavelength) {
    return AverageLobeWeight(*si.material, q, lobe, MeasurementEnsemble(si.shading, g, lobe, m.wi, m.profile),
                             LobeTransfer::Radiance, wavelength);
}

void GrPathSampler::FootprintSample::Remember(const ScatterQuery &query, const SurfaceInteraction &hit,
                                              const SpectralGenRay &g, const Material &m, const ScatterSample &bs) {
    active = true;
    q = query;
    si = hit;
    gr = g;
    q.si = &si;
    q.gr = &gr;
    mat = &m;
    wo = bs.wo;
    f = bs.weight * (bs.pdf / std::max(std::abs(bs.wo.z), 1e-300));
}

SampledSpectrum GrPathSampler::FootprintSample::Correction(double dist) const {
    const SampledSpectrum g = mat->EvalFrom(q, wo, IncidentWave{dist});  // q.lobes = LobeAll
    SampledSpectrum r(0.0);
    for (int i = 0; i < NumWavelengths; ++i) r[i] = f[i] > 0 ? g[i] / f[i] : 0;
    return r;
}

}  // namespace phasor::grpath
