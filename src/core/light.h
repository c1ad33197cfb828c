// SPDX-License-Identifier: Apache-2.0
// phasor — light sources (design.md §3 "lights"). Radiometric conventions: emitted quantities are
// spectral (per metre of wavelength); a line spectrum carries its integrated strength (D10).
#pragma once

#include <optional>
#include <string>

#include "core/math.h"
#include "core/shape.h"
#include "core/spectrum.h"

namespace phasor {

/// The receiving point for light sampling.
struct LightSampleContext {
    Vec3 p;
    Vec3 n;  // geometric normal at p (zero for points in free space)
};

struct LightSample {
    /// Incident quantity at the receiver along -wi: radiance for area/environment lights,
    /// irradiance (normal to wi) for delta lights. Not divided by pdf.
    SampledSpectrum L;
    Vec3 wi;          // unit direction from the receiver towards the light
    double dist = 0;  // distance to the sampled point (Infinity for directional lights)
    double pdf = 0;   // solid-angle density; 1 for delta lights
    bool delta = false;
};

class Light {
  public:
    virtual ~Light() = default;

    /// Samples incident light at ctx (next-event estimation). nullopt if nothing is emitted
    /// towards ctx or the sample failed.
    virtual std::optional<LightSample> SampleLi(const LightSampleContext &ctx, const Vec2 &u,
                                                const SampledWavelengths &wl) const = 0;
    /// Solid-angle density that SampleLi would pick direction wi arriving from light point pLight
    /// with normal nLight (area lights; 0 for delta lights).
    virtual double PdfLi(const LightSampleContext &ctx, const Vec3 &wi, const Vec3 &pLight,
                         const Vec3 &nLight) const = 0;
    /// Area lights: radiance leaving surface point (p, n) in direction w.
    virtual SampledSpectrum L(const Vec3 &p, const Vec3 &n, const Vec3 &w,
                              const SampledWavelengths &wl) const;
    /// Lights at infinity with finite extent: radiance arriving along a ray that escapes the
    /// scene in direction d (d points away from the scene).
    virtual SampledSpectrum Le(const Vec3 &d, const SampledWavelengths &wl) const;
    /// True for delta-position or delta-direction lights (never hit by rays).
    virtual bool IsDelta() const = 0;
    /// True for lights at infinity (directional, environment).
    virtual bool IsInfinite() const { return false; }
    /// The emission spectrum (for wavelength sampling) and a relative power scale [W/m] so that
    /// the sampler can weight lights against each other.
    virtual const Spectrum &EmissionSpectrum() const = 0;
    virtual double PowerScale() const = 0;
    /// Called once with the scene bounds before rendering.
    virtual void Preprocess(const Bounds3 &sceneBounds) { (void)sceneBounds; }
    virtual std::string ToString() const = 0;

    std::string name;
};

}  // namespace phasor
