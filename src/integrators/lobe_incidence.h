// SPDX-License-Identifier: Apache-2.0
// phasor — theory §0 D4a extended through listed near-delta lobes (issue 12, "a screen behind a
// mirror, film or grating"), for detectors that integrate closed-form sources analytically over
// their directions (`virtual_plane`).
//
// A sensor-plane GR facing a plane wave directly is integrated in closed form (D4a). Facing the
// same wave through a mirror, a thin film or a grating, the sampled directions would have to land
// inside the GR's ~1e-3 rad lobe by chance (a screen behind a mirror read 0 at 64 spp). Here every
// listed lobe of every *planar* shape with a near-delta kernel is integrated analytically instead:
// for a light, a shape and a lobe j, Newton's method finds the detector direction u* whose ray
// reaches the shape at p and leaves through lobe j exactly towards the light (towards the
// direction Light::IncidenceOnGR gives at p: fixed for plane waves and distant sources, towards
// the point for point and spot lights, the local wavefront normal of a Gaussian beam). With the
// residual r(u) = ω_j(u) − s(p(u)) (exit direction minus source direction, in the plane ⊥ s, u
// in solid-angle coordinates at the detector) the source's radiance seen by the detector is
// a_j·E_p·δ²(r(u)), so its integral over the detector's directions is
//     E_det = a_j(λ)·E_p(λ) / |det ∂r/∂u|                                      (1)
// arriving from u*, which the detector then weighs like a direct source (cosθ, acceptance; D4a).
// (1) is exact: for a mirror |det| = 1 (a plane wave) or ((R+d)/R)² (a point source at R from the
// mirror, d from the screen: the image source's I/(R+d)²); for a grating order it is the
// anamorphic factor cosθ_det/cosθ_src of flux conservation. The Jacobian is taken by central
// differences (error ~1e-12 relative on planar shapes, where r is smooth).
//
// Scope: planar shapes (Shape::IsPlanar: rectangle, disk), where the solution for a lobe is
// unique, so every pixel sample finds the same one and the estimate stays unbiased; footprint-
// aware kernels (the aperture) are excluded (they integrate their own lobes). A dispersive lobe is
// solved per carried wavelength. Only the first vertex is covered: light reaching the sensor
// through two near-delta vertices is still found by the sampled path (D14 at its second vertex).
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "core/render/detector.h"
#include "core/render/pixel_integrator.h"
#include "core/render/scene.h"

namespace phasor {

class LobeIncidence {
  public:
    /// Collects the scene's planar shapes whose kernel lists near-delta lobes for a generalized ray.
    explicit LobeIncidence(const Scene &scene);

    /// True if no shape qualifies (nothing to integrate).
    bool Empty() const { return shapes_.empty(); }
    /// True if `shape` is integrated here: the sampled path must not measure closed-form sources
    /// through its listed lobes at the first vertex again (D14), or they would count twice.
    bool Covers(const Shape *shape) const;

    /// One term of Integrate, for integrators that re-evaluate it (sample_solve): the value, the
    /// light, the surface point p with the GR the detector sends there, the lobe and the carried
    /// wavelength it was solved for (−1: one solve for every wavelength).
    struct Contribution {
        SampledSpectrum value;             // what Integrate adds for this light and lobe
        const Light *light = nullptr;      // the scene's light
        bool ensemble = true;              // false if `mode` replaced the light for this measurement
        const SurfaceInteraction *si = nullptr;
        const SpectralGenRay *gr = nullptr;  // the detector's GR placed at p (tracing direction into the surface)
        int lobe = 0;
        Vec3 woLocal;                      // the lobe's direction at p towards the light (local)
        int wavelength = -1;
        Vec3 travel;                       // world direction in which the light arrives at p
        double dist = Infinity;            // p to the light (Infinity for lights at infinity)
        AngularProfile profile;            // the light's angular profile at p (GrIncidence::profile)
    };
    using Report = std::function<void(const Contribution &)>;
    /// Replaces a light by the one to measure from p (sample_solve's coherent modes).
    using ModeOf = std::function<const Light *(const Light *, const Vec3 &)>;

    /// The pixel value (the detector's IntegrateIncidence units) of every closed-form light seen
    /// from the sample's origin through one listed lobe of a covered shape, each unoccluded
    /// (detector → p → light). `g` is the sample's GR at its origin (footprint per wavelength).
    /// The kernels met are prepared in `scratch` and dropped again before the call returns.
    /// `report` (if given) receives every term; `mode` (if given) picks the light measured for each
    /// closed-form light.
    SampledSpectrum Integrate(const Scene &scene, const DetectorGrSample &ds, const SpectralGenRay &g,
                              const SampledWavelengths &wl, ScratchBuffer &scratch, PathStats &stats,
                              const Report *report = nullptr, const ModeOf *mode = nullptr) const;

  private:
    std::vector<const Shape *> shapes_;
};

}  // namespace phasor
