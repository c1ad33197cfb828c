// SPDX-License-Identifier: Apache-2.0
// phasor — the built scene: shapes with their kernels, lights, detector, integrator and render
// settings, plus the Embree accelerator and the wavelength sampler.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/accel.h"
#include "core/render/detector.h"
#include "core/render/integrator.h"
#include "core/render/light.h"
#include "core/render/light_sampler.h"
#include "core/render/material.h"
#include "core/render/registry.h"
#include "core/render/texture.h"
#include "core/scratch_buffer.h"
#include "core/spectrum/spectrum.h"

namespace phasor {

/// The fraction of a shadow ray's segment left out at the far end, where the light is (pbrt's
/// ShadowEpsilon): Embree intersects triangles in single precision, so a shadow ray that stopped
/// 1e-7 of the way short of a point sampled on a mesh lamp still hit the lamp's own triangles for a
/// third of the samples (tests/integrators/area_light_floor_test.cpp). An occluder closer to the
/// lamp than 1e-4 of the distance does not shadow it.
inline constexpr double ShadowEpsilon = 1e-4;

/// Settings of the `Render` block (all optional; the CLI may override them).
struct RenderSettings {
    /// The block's spp, seed and sampler: the defaults of a render's RenderOptions (the program
    /// applies --spp, --seed, --sampler on top; threads, cancellation and callbacks are unset here).
    RenderOptions options;
    std::string output;  // "" → derived from the scene file name
    FileLoc loc;
};

/// The schema of the `Render` block (documented with the plug-ins: `phasor describe Render`).
const Schema &RenderSchema();

class Scene {
  public:
    /// Builds a scene from a description: creates every entity through the registry, checks the
    /// whole thing (exactly one detector unless `Render.detector` picks one, …). Returns nullptr
    /// after reporting errors to `diag`. `integratorOverride` picks an integrator by @name or by
    /// plug-in type (created with default parameters when the scene has none of that type).
    static std::unique_ptr<Scene> Build(const SceneDesc &desc, Diagnostics &diag,
                                        const std::string &integratorOverride = "");
    ~Scene();

    const Accel &GetAccel() const { return *accel_; }
    const std::vector<const Light *> &Lights() const { return lights_; }
    const std::vector<std::shared_ptr<Shape>> &Shapes() const { return shapes_; }
    /// Where a plug-in object (light, shape, detector, …) was defined, for errors found at render
    /// time; unknown for objects the scene did not create from a description.
    FileLoc Where(const void *object) const;
    const std::vector<const Light *> &InfiniteLights() const { return infiniteLights_; }
    /// The lights by how integrators reach them, each in the order of Lights() (computed once by
    /// Build): delta lights (Light::IsDelta: a path cannot hit them; light sampling or a closed form
    /// reaches them), the others (a path may hit or escape to them: area and wide infinite lights),
    /// and those `grt` measures in closed form (Light::MeasuredInClosedForm).
    const std::vector<const Light *> &DeltaLights() const { return deltaLights_; }
    const std::vector<const Light *> &HittableEmitters() const { return hittableEmitters_; }
    const std::vector<const Light *> &ClosedFormLights() const { return closedFormLights_; }
    /// The lights on shapes (LightType::Area): what a ray can hit at a finite distance.
    const std::vector<const Light *> &AreaLights() const { return areaLights_; }
    /// Next-event estimation's choice among Lights() (an integrator's `light_sampler`).
    const LightSampler &GetLightSampler(LightSelection how) const {
        if (how == LightSelection::Exhaustive) return *exhaustiveLights_;
        return how == LightSelection::Power ? *powerLights_ : *uniformLights_;
    }
    const Detector &GetDetector() const { return *detector_; }
    const Integrator &GetIntegrator() const { return *integrator_; }
    const WavelengthSampler &Wavelengths() const { return *wavelengths_; }
    /// After a render whose image is black: the likely cause and its fix, from cheap checks
    /// (lights' spectra vs the detector's response, aperture plates with no open area, a camera
    /// inside closed geometry, lights reaching a sensor plane only from behind). scene_checks.cpp.
    std::string DarkImageCause() const;
    const RenderSettings &Settings() const { return settings_; }
    /// A sampler by name, seeded: the scene's Sampler block of that name, else a plug-in of the
    /// sampler family of that type; nullptr if neither exists (SamplerNames lists the choices).
    std::unique_ptr<Sampler> NewSampler(const std::string &name, uint64_t seed) const;
    std::vector<std::string> SamplerNames() const;
    RenderSettings &Settings() { return settings_; }
    Bounds3 Bounds() const { return accel_->Bounds(); }

    /// The nearest surface along `ray` before tMax [m]; `precision` as in Accel (HitPrecision):
    /// Double wherever a phase is carried.
    std::optional<SurfaceInteraction> Intersect(const Ray &ray, double tMax = Infinity,
                                                HitPrecision precision = HitPrecision::Double) const {
        if (rayLog_) rayLog_->push_back(ray);
        return accel_->IntersectSurface(ray, 0, tMax, precision);
    }
    /// Benchmarks only: appends every ray the scene is asked to trace (intersection and shadow
    /// rays) to `log`; single-threaded renders only. nullptr stops recording.
    void RecordRays(std::vector<Ray> *log) { rayLog_ = log; }
    /// Shadow rays that cross straight-through surfaces (theory §3.5; pbrt's and Mitsuba's shadow
    /// rays through null interfaces): the fraction of the light that arrives along `ray` (unit d)
    /// from distance tMax [m] (Infinity: a direction), per carried wavelength — 1 with nothing on
    /// the way, 0 when a surface blocks it, else the product over the surfaces crossed of their
    /// straight-through lobes' weights (Material::MayPassStraight, IsStraightThrough; summed when a
    /// kernel lists several). Each crossed surface's kernel is prepared for a classical ray from
    /// −d in the regime `rayOptics` (a GR's path: false, the coherent film; `ray`: true) in
    /// `scratch` (rewound afterwards). `weigh(si, k, lobe, t)` replaces a lobe's weight at its
    /// mean direction (grt's average over the measurement's plane waves, theory §0 D15); t is the
    /// distance along the ray. Counts each ray traced in `rays`. Scenes without such surfaces cost
    /// one occlusion query. At most MaxCrossings surfaces are crossed; a segment
    /// through more is taken as blocked.
    template <class Weigh>
    SampledSpectrum Transmittance(Ray ray, double tMax, const SampledWavelengths &wl, bool rayOptics,
                                  ScratchBuffer &scratch, long long &rays, Weigh &&weigh) const;
    SampledSpectrum Transmittance(const Ray &ray, double tMax, const SampledWavelengths &wl, bool rayOptics,
                                  ScratchBuffer &scratch, long long &rays) const {
        return Transmittance(ray, tMax, wl, rayOptics, scratch, rays,
                             [](const SurfaceInteraction &, const PreparedKernel &, const NearDeltaLobe &l, double) {
                                 return l.Weight();
                             });
    }
    /// The shadow ray from the surface point `from` to the point `to` (stopping ShadowEpsilon of the
    /// way short of it) or, with toDirection, along the direction `to` to infinity.
    Ray ShadowRay(const SurfaceInteraction &from, const Vec3 &to, bool toDirection, double *tMax) const;
    static constexpr int MaxCrossings = 64;

  private:
    Scene() = default;
    /// A sensor plane against the aperture plates: an error if it lies in or crosses a plate's
    /// plane; without `aim`, aims it at the plate all light must pass (or warns). scene_checks.cpp.
    void CheckSensorPlane(Diagnostics &diag);
    std::unique_ptr<BuildContext> ctx_;  // owns every plug-in object
    std::unique_ptr<Accel> accel_;
    std::vector<std::shared_ptr<Shape>> shapes_;
    std::vector<const Light *> lights_, infiniteLights_, deltaLights_, hittableEmitters_, closedFormLights_, areaLights_;
    std::unique_ptr<LightSampler> uniformLights_, powerLights_, exhaustiveLights_;
    std::shared_ptr<Detector> detector_;
    std::shared_ptr<Integrator> integrator_;
    std::unique_ptr<WavelengthSampler> wavelengths_;
    RenderSettings settings_;
    std::unique_ptr<SceneDesc> ownedDesc_;
    std::vector<Ray> *rayLog_ = nullptr;
    bool straightThrough_ = false;
};

template <class Weigh>
SampledSpectrum Scene::Transmittance(Ray ray, double tMax, const SampledWavelengths &wl, bool rayOptics,
                                     ScratchBuffer &scratch, long long &rays, Weigh &&weigh) const {
    ++rays;
    if (rayLog_) rayLog_->push_back(ray);
    if (!straightThrough_) return SampledSpectrum(accel_->Occluded(ray, 0, tMax) ? 0.0 : 1.0);
    SampledSpectrum T(1.0);
    double t = 0;  // distance travelled from the first origin
    const ScratchBuffer::Mark mark = scratch.Save();
    for (int crossed = 0;; ++crossed) {
        const std::optional<SurfaceInteraction> si = accel_->IntersectSurface(ray, 0, tMax);
        if (!si) break;
        const Material *mat = si->material;
        if (crossed == MaxCrossings || !mat || !mat->MayPassStraight()) {
            T = SampledSpectrum(0.0);
            break;
        }
        ScatterQuery q;
        q.wi = si->shading.ToLocal(-ray.d);
        q.wl = &wl;
        q.rayOptics = rayOptics;
        q.tex = TextureEvalContext(*si);
        q.si = &*si;
        const PreparedKernel &k = mat->Prepare(q, scratch);
        SampledSpectrum a(0.0);
        for (const NearDeltaLobe &l : k.ListNearDelta())
            if (IsStraightThrough(l, q.wi, wl.Count())) a += weigh(*si, k, l, t + si->t);
        T *= a;
        if (T.IsZero()) break;
        // On from the far side of the surface.
        const Vec3 o = si->SpawnOrigin(ray.d);
        const double moved = Dot(o - ray.o, ray.d);
        t += moved;
        tMax -= moved;
        ray.o = o;
        ++rays;
        if (rayLog_) rayLog_->push_back(ray);
    }
    scratch.Rewind(mark);
    return T;
}

}  // namespace phasor
