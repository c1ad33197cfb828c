// SPDX-License-Identifier: Apache-2.0
// phasor — the shared generalized-ray path sampler (gr_path.h): the helpers of its estimate.
#include "integrators/gr_path.h"

#include "core/render/lobe_average.h"
#include <cstdio>

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
                .Max(4096),
            LightSamplerParam()};
}

IntegratorSupport PathSupport() {
    IntegratorSupport s;
    s.lights = {LightReach::ClosedForm, LightReach::ClosedForm, LightReach::ClosedForm, LightReach::HitAndSampled};
    s.detector = DetectorNeed::GeneralizedRays;
    s.kernels = {KernelReach::Full, KernelReach::Full, KernelReach::Full};
    return s;
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
                                                       const SpectralGenRay &reversed, const SurfaceInteraction *si,
                                                       const SampledWavelengths &wl, ScratchBuffer &scratch,
                                                       PathStats &stats) {
    auto m = light.MeasureGR(reversed, wl);
    if (!m || m->value.IsZero()) return std::nullopt;
    m->value *= Transmitted(scene, *m, g, si, wl, scratch, stats);
    if (m->value.IsZero()) return std::nullopt;
    return m;
}

SampledSpectrum GrPathSampler::Transmitted(const Scene &scene, const GrMeasurement &m, const SpectralGenRay &g,
                                           const SurfaceInteraction *si, const SampledWavelengths &wl,
                                           ScratchBuffer &scratch, PathStats &stats) {
    double tMax = m.dist * (1 - 1e-7);
    const bool far = std::isinf(m.dist);
    const Ray r = si ? scene.ShadowRay(*si, far ? m.wi : si->p + m.wi * m.dist, far, &tMax) : Ray{g.o, m.wi};
    return scene.Transmittance(r, tMax, wl, false, scratch, stats.rays,
                               [&](const SurfaceInteraction &at, const PreparedKernel &k, const NearDeltaLobe &l, double t) {
                                   // The GR aimed at the source, its footprint carried to the crossing.
                                   SpectralGenRay h = g;
                                   h.Redirect(m.wi, 1);
                                   h.Propagate(t);
                                   h.o = at.p;
                                   return ThroughLobeWeight(at, k, h, l, m, -1);
                               });
}

std::vector<ParamSpec> PathAndFsdParams() {
    std::vector<ParamSpec> p = PathParams();
    for (ParamSpec &f : fsd::Params()) p.push_back(std::move(f));
    return p;
}

GrPathSampler::GrPathSampler(const ParamDict &d)
    : GrPathSampler(d.GetInt("max_depth"), d.GetInt("rr_depth"), d.GetInt("light_samples"),
                    fsd::SettingsFromParams(d), LightSelectionFromName(d.GetString("light_sampler"))) {}

void GrPathSampler::NoteFsd(const Scene &scene, Diagnostics &diag) const {
    if (fsd_.enabled) return;
    const Bounds3 b = scene.Bounds();
    const double size = b.Empty() ? 0 : Length(b.Diagonal()), lambda = scene.Wavelengths().LambdaMax();
    if (!(size > 0) || !(lambda >= 1e-3 * size) || !FsdOccluders(scene).Any()) return;
    char msg[320];
    std::snprintf(msg, sizeof msg,
                  "free-space diffraction at edges is off (fsd = false): the scene is only %.3g wavelengths "
                  "across (lambda up to %.3g m), so the edges of opaque geometry shadow sharply where light "
                  "would bend around them; set fsd = true on the integrator (docs/fsd.md)",
                  size / lambda, lambda);
    diag.Report(Diagnostic{Severity::Note, scene.Where(&scene.GetIntegrator()), msg, {}});
}

std::string GrPathSampler::ParamString() const {
    std::string s = "max_depth = " + std::to_string(maxDepth_) + ", rr_depth = " + std::to_string(rrDepth_) +
                    ", light_samples = " + std::to_string(lightSamples_) + ", fsd = " + (fsd_.enabled ? "true" : "false");
    if (lights_ != LightSelection::Exhaustive) s += std::string(", light_sampler = ") + LightSelectionName(lights_);
    if (fsd_.enabled)
        s += fsd_.radius > 0 ? ", fsd_radius = " + std::to_string(fsd_.radius) + " m"
                             : ", fsd_window = " + std::to_string(fsd_.window);
    return s;
}

void GrPathSampler::ReversedAlongLobe(SpectralGenRay &rev, const SpectralGenRay &g, const SurfaceInteraction &si,
                                      const std::array<Vec3, 2> &origins, const NearDeltaLobe &lobe, int i,
                                      double &revEta) {
    // SpectralGenRay::Redirect's direction and wavenumbers, the spawn origin, TimeReversed's
    // direction (ρ was negated already).
    const Vec3 wo = si.shading.ToWorld(lobe.wo[i]);
    const double eta = lobe.Eta(i);
    rev.d = -wo;
    if (!(eta == revEta)) {  // (the same η gives the same products)
        for (int s = 0; s < g.count; ++s) rev.k[std::size_t(s)] = g.k[std::size_t(s)] * eta;
        revEta = eta;
    }
    rev.o = origins[Dot(wo, si.n) >= 0 ? 0 : 1];  // si.SpawnOrigin(wo)
}

bool GrPathSampler::UniformLobe(const NearDeltaLobe &lobe, const SampledWavelengths &wl) {
    bool uniform = true;
    for (int i = 1; i < wl.Count(); ++i)
        uniform = uniform && lobe.wo[i] == lobe.wo[0] && lobe.Eta(i) == lobe.Eta(0);
    return uniform;
}

SampledSpectrum GrPathSampler::ThroughLobeWeight(const SurfaceInteraction &si, const PreparedKernel &k,
                                                 const SpectralGenRay &g, const NearDeltaLobe &lobe,
                                                 const GrMeasurement &m, int wavelength) {
    return AverageLobeWeight(*si.material, k, lobe, MeasurementEnsemble(si.shading, g, lobe, m.wi, m.profile),
                             LobeTransfer::Radiance, wavelength);
}

}  // namespace phasor::grpath
