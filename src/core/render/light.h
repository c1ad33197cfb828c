// SPDX-License-Identifier: Apache-2.0
// phasor — light sources (docs/generalized_rays.md §4). Radiometric conventions: emitted quantities are
// spectral (per metre of wavelength); a line spectrum carries its integrated strength (D10).
#pragma once

#include <optional>
#include <string>

#include "core/render/genray.h"
#include "core/math.h"
#include "core/geometry/shape.h"
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

/// What kind of emitter a light is: how a path can reach it (pbrt-v4's LightType, plus the sources
/// at infinity of finite extent that generalized rays measure in closed form). The one category
/// integrators and scene checks read (Light::Type(); the scene's category lists, the support
/// declarations of integrator_support.h).
enum class LightType {
    /// At one point (point, spot): never hit; reached by next-event estimation, and measured in
    /// closed form by generalized rays (theory §2.4 item 5).
    DeltaPosition,
    /// One direction at every point, from infinity (directional, plane_wave, gaussian_beam, a
    /// distant source of zero extent): never hit; next-event estimation or closed form (items 1–2).
    DeltaDirection,
    /// At infinity with a finite angular extent (distant): escaping rays see it (Le), next-event
    /// estimation samples it, and generalized rays measure it in closed form after a detector or a
    /// near-delta lobe (item 3, D14).
    Distant,
    /// A surface that emits (area): hit by rays (L) and sampled by next-event estimation;
    /// generalized rays measure it as its radiance where they hit it (item 4).
    Area,
};
inline constexpr int NumLightTypes = 4;
/// "delta position", "delta direction", "distant", "area".
const char *Describe(LightType t);

class CoherentSource;

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

/// cos(max(0, a − b)) and sin(max(0, a − b)) for angles a, b ∈ [0, π] given by their
/// cosines and sines (no inverse trigonometry): Light::Reach's reduced angles.
inline double CosOfReduced(double cosA, double sinA, double cosB, double sinB) {
    return cosA >= cosB ? 1.0 : cosA * cosB + sinA * sinB;
}
inline double SinOfReduced(double cosA, double sinA, double cosB, double sinB) {
    return cosA >= cosB ? 0.0 : sinA * cosB - cosA * sinB;
}

/// The receiver's factor of Light::Reach: |cosθ| between the receiver's normal n and a unit
/// direction w towards (or from) the light, θ first reduced by the half-angle (given by its cosine
/// and sine) in which the light's directions lie about w (pbrt-v4's LightBounds importance):
/// cos(max(0, θ − spread)), but at least 1e-3 — n is the geometric normal, and a kernel weighs by
/// its shading normal's cosine, which need not vanish where the geometric one does (a delta light
/// in the plane of a smooth-shaded facet still lights it). 1 for a point in free space (n = 0).
inline double ReceiverCosine(const Vec3 &n, const Vec3 &w, double cosSpread = 1, double sinSpread = 0) {
    if (n == Vec3()) return 1;
    const double cosI = std::min(1.0, std::abs(Dot(n, w)) / Length(n));
    return std::max(1e-3, CosOfReduced(cosI, std::sqrt(1 - cosI * cosI), cosSpread, sinSpread));
}

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
    /// The light's category; may depend on its parameters (a distant source of zero extent is a
    /// delta direction).
    virtual LightType Type() const = 0;
    /// Delta position or delta direction: never hit by rays.
    bool IsDelta() const { return Type() == LightType::DeltaPosition || Type() == LightType::DeltaDirection; }
    /// At infinity (delta directions and distant sources): shadow rays run to infinity and escaping
    /// rays ask Le.
    bool IsInfinite() const { return Type() == LightType::DeltaDirection || Type() == LightType::Distant; }
    /// The emission spectrum (for wavelength sampling) and a relative power scale [W/m] so that
    /// the sampler can weight lights against each other.
    virtual const Spectrum &EmissionSpectrum() const = 0;
    virtual double PowerScale() const = 0;
    /// How much of this light reaches a receiver at ctx (ctx.n: its geometric normal, either side
    /// facing; zero for a point in free space): an estimate of the irradiance there per unit of the
    /// emission spectrum [the light's strength unit × sr, e.g. W/m² per unit spectrum], with
    /// visibility ignored, that is 0 only where the light sends nothing towards ctx.p, whatever the
    /// receiver's orientation (ReceiverCosine never vanishes) — the
    /// `exhaustive` light sampler's weight (light_sampler.h). NaN (the default): no estimate; the
    /// sampler then weighs every light by power at that point.
    virtual double Reach(const LightSampleContext &ctx) const {
        (void)ctx;
        return std::numeric_limits<double>::quiet_NaN();
    }

    // ---- Generalized rays (theory §2.4, §0 D4a, D5, D14) ------------------------------------
    /// True for sources that GRs measure in closed form instead of hitting them: every type but
    /// Area. The `grt` integrator measures these right after a detector or a near-delta lobe (and
    /// never again on escape); continuous lobes still reach them through SampleLi / Le.
    bool MeasuredInClosedForm() const { return Type() != LightType::Area; }
    /// Eq. 24 in radiance units (k²·M) for the *physical* GR g (g.d = direction of light flow,
    /// ρ > 0 diverging along it), per carried wavelength that g measures (g.Measures; 0 in the others:
    /// MeasurePerWavelength, lights/closed_form.h); nullopt if nothing reaches g.
    virtual std::optional<GrMeasurement> MeasureGR(const SpectralGenRay &g,
                                                   const SampledWavelengths &wl) const;
    /// A test to make before MeasureGR: true only where MeasureGR(g, ·) certainly returns nullopt or
    /// a zero value (a GR facing away from a light at infinity; a `distant` disc beyond the reach of
    /// every measured window, DistantDiscOutOfReach), so a caller may skip what a measurement needs
    /// (the GR along a listed lobe, its copies). False: no claim (the default). Reads only g.
    virtual bool MeasuresNothing(const SpectralGenRay &g) const {
        (void)g;
        return false;
    }
    /// D4a: the source integrated over all directions of a GR at its waist (g.o, footprint; g.d is
    /// not used — the caller decides which arrival directions count).
    virtual std::optional<GrIncidence> IncidenceOnGR(const SpectralGenRay &g,
                                                     const SampledWavelengths &wl) const;
    /// The light's field, for integrators that propagate fields (`rs`, which also needs a line
    /// spectrum): core/render/coherent_source.h. nullptr for lights that are not coherent (area,
    /// distant sources of finite extent) or whose field is not implemented (spot).
    virtual const CoherentSource *Coherent() const { return nullptr; }
    /// Coherence description at p (theory §0 D5). Default: fully coherent light from nowhere.
    virtual LightCoherence Coherence(const Vec3 &p) const;

    /// Called once with the scene bounds before rendering.
    virtual void Preprocess(const Bounds3 &sceneBounds) { (void)sceneBounds; }
    virtual std::string ToString() const = 0;

    std::string name;
};

}  // namespace phasor
