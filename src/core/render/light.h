// SPDX-License-Identifier: Apache-2.0
// phasor — light sources (docs/generalized_rays.md §4). Radiometric conventions: emitted quantities are
// spectral (per metre of wavelength); a line spectrum carries its integrated strength (D10).
#pragma once

#include <optional>
#include <string>

#include "core/render/genray.h"
#include "core/math.h"
#include "core/render/shape.h"
#include "core/spectrum/spectrum.h"

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
    /// Gaussian-beam lights: the beam's geometry and its irradiance on the axis at the receiver's
    /// axial position (per wavelength, normal to the axis), for footprint-aware kernels, which
    /// integrate the beam's field over their footprint (IncidentWave). L stays the local
    /// irradiance at the receiver, which is what every other kernel needs.
    std::optional<GaussianBeamGeometry> beam = std::nullopt;
    SampledSpectrum beamAxisIrradiance{0.0};
};

/// Coherence description of the light arriving at a point (theory §0 D5), for sample-solve:
/// Ω = omega·I is the angular covariance [rad²] of the arrival directions about wi (never a
/// solid angle; a uniform disc of angular radius α has omega = α²/4). The mutual coherence between
/// transverse points separated by v is μ(v) = exp(−½k²·omega·|v|²).
struct LightCoherence {
    Vec3 wi;            // unit mean direction towards the light
    double omega = 0;   // [rad²]; 0 = fully (spatially) coherent
};

/// A coherent monochromatic field for the forward `rs` integrator (theory §6.2): a plane wave of
/// irradiance `strength` [W/m², normal to `dir`] travelling along `dir`, a spherical wave from a
/// point at `pos` of intensity `strength` [W/sr] (isotropic within `Falloff`-free point lights), or
/// a TEM₀₀ Gaussian beam of power `strength` [W] with its waist (β_s² = `beta2`) centred at `pos`.
/// Amplitude convention: |U|² = irradiance normal to the local direction of travel.
struct CoherentWave {
    enum class Kind { Plane, Spherical, GaussianBeam } kind = Kind::Plane;
    Vec3 dir{0, 0, -1};   // plane, beam: unit direction of travel (the beam's axis)
    Vec3 pos;             // spherical: source position; beam: centre of the waist [m]
    double strength = 0;  // plane: irradiance E [W/m²]; spherical: intensity I [W/sr]; beam: power P [W]
    double lambda = 0;    // vacuum wavelength of the line [m]
    double beta2 = 0;     // beam: β_s² of the waist [m²] (GaussianBeamGeometry; |U|² = P·|ψ|²)
};

/// Cross-section π r² of the scene's bounding sphere [m²]: the area through which a light at
/// infinity sends power into the scene (for relative power estimates).
double SceneCrossSection(const Bounds3 &sceneBounds);

/// Upper bound of every light's strength parameter, in SI units (area `radiance` W/m²/sr, point
/// and spot `intensity` W/sr, plane-wave, distant and directional `irradiance` W/m², Gaussian-beam
/// `power` W): 1e30 — above the brightest real sources (the Sun's 3.8e26 W; petawatt lasers,
/// ~1e27 W/m² focused) and far enough below double's 1.8e308 that no product the renderer forms
/// (geometry, 1/pdf, 1/reference_irradiance with reference_irradiance ≥ 1e-30 W/m²) overflows.
/// Results beyond the float image's range (3.4e38) are still caught, and counted, by the film.
inline constexpr double MaxLightStrength = 1e30;

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

    // ---- Generalized rays (theory §2.4, §0 D4a, D5, D14) ------------------------------------
    /// True for sources that GRs measure in closed form instead of hitting them: delta position or
    /// direction (point, spot, plane wave, directional, Gaussian beam) and distant sources. The
    /// `grt` integrator measures these right after a detector or a near-delta lobe (and never
    /// again on escape); continuous lobes still reach them through SampleLi / Le.
    virtual bool MeasuredInClosedForm() const { return false; }
    /// Eq. 24 in radiance units (k²·M) for the *physical* GR g (g.d = direction of light flow,
    /// ρ > 0 diverging along it), per carried wavelength; nullopt if nothing reaches g.
    virtual std::optional<GrMeasurement> MeasureGR(const SpectralGenRay &g,
                                                   const SampledWavelengths &wl) const;
    /// D4a: the source integrated over all directions of a GR at its waist (g.o, footprint; g.d is
    /// not used — the caller decides which arrival directions count).
    virtual std::optional<GrIncidence> IncidenceOnGR(const SpectralGenRay &g,
                                                     const SampledWavelengths &wl) const;
    /// The field for `rs`: set by monochromatic (line-spectrum) plane waves and isotropic point
    /// lights; nullopt for everything else (the integrator reports which light it cannot handle).
    virtual std::optional<CoherentWave> CoherentField() const { return std::nullopt; }
    /// Coherence description at p (theory §0 D5). Default: fully coherent light from nowhere.
    virtual LightCoherence Coherence(const Vec3 &p) const;

    /// Called once with the scene bounds before rendering.
    virtual void Preprocess(const Bounds3 &sceneBounds) { (void)sceneBounds; }
    virtual std::string ToString() const = 0;

    std::string name;
};

}  // namespace phasor
