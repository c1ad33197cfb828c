// SPDX-License-Identifier: Apache-2.0
// phasor — the diffraction-kernel (material) interface (design.md §4.1).
//
// Frame: every direction is in the local shading frame (z = shading normal, pointing to the
// side the shape calls "outside"); wi and wo both point *away* from the surface. wi is the
// direction the tracer came from (towards the camera in a backward tracer).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/spectrum.h"
#include "core/texture.h"

namespace phasor {

struct SpectralGenRay;
struct SurfaceInteraction;
struct GaussianBeamGeometry;
class Shape;
class ApertureMask;

/// Lobe flags returned by Sample().
enum ScatterFlags : unsigned {
    ScatterReflection = 1u << 0,
    ScatterTransmission = 1u << 1,
    ScatterDiffuse = 1u << 2,     // a continuous lobe with a finite pdf
    /// A near-delta lobe (smooth reflection/refraction, grating order): in the ray-optics limit a
    /// Dirac delta; for a generalized ray its true angular width is the ray's own spread σ_k/k.
    ScatterNearDelta = 1u << 3,
    ScatterDispersive = 1u << 4,  // direction depends on wavelength (collapse to the hero)
    /// Footprint-aware kernels (theory §9 item 5): the lobe already holds the GR's angular spread,
    /// so the outgoing GR is spread-free — later vertices treat it as a classical ray.
    ScatterSpreadFree = 1u << 5,
};

/// What a kernel is asked about (design.md §4.1).
struct ScatterQuery {
    Vec3 wi;                               // local, unit, pointing away from the surface
    const SampledWavelengths *wl = nullptr;
    double etaOutside = 1;                 // real index of the medium on the +z side (the air)
    /// Ray-optics limit requested (the `ray` integrator): near-delta lobes are true deltas, Eval
    /// returns 0 for them, and wave effects collapse to their geometric limit.
    bool rayOptics = true;
    /// Footprint of the incident generalized ray (theory §1.2): β² [m²] and ρ; zero for a
    /// classical ray. Near-delta lobes use it to spread Eval over the ray's angular width.
    double beta2 = 0, rho = 0;
    /// With !rayOptics: whether Eval includes the near-delta lobes' GR-spread Gaussians. The `grt`
    /// integrator clears it for next-event estimation, because it measures light through
    /// near-delta lobes by following the sampled lobe (closed forms, theory §0 D14).
    bool evalNearDelta = true;
    TextureEvalContext tex;                // where textures are evaluated (uv, p, dp/du, β …)
    /// Footprint-aware kernels (IsFootprintAware, theory §9) need the whole incident GR and the
    /// hit: `gr` is the traced GR at the hit point in world space (gr->d points into the surface,
    /// per-wavelength k, β², ρ; traced convention, ρ > 0 diverging along d), `si` the interaction
    /// (world shading frame, shape and its to_world). Both null for classical rays.
    const SpectralGenRay *gr = nullptr;
    const SurfaceInteraction *si = nullptr;
};

/// The wave a light sample sends to a receiver, as footprint-aware kernels need it (EvalFrom):
/// over the GR's footprint the incident field is not a plane wave.
///   * `dist`: the wavefront radius at the receiver [m] — a spherical wave from a source at that
///     distance (point and area lights); Infinity for a plane wave.
///   * `beam`: a coherent TEM₀₀ Gaussian beam (core/genray.h). Its amplitude varies across the
///     footprint, so the kernel integrates the beam's own field, normalised to unit amplitude on
///     the beam axis at the receiver's axial position: EvalFrom's value is then per unit
///     *on-axis* irradiance (LightSample::beamAxisIrradiance), not per unit irradiance at the hit
///     point (which underflows when a footprint far wider than the beam is centred off its axis).
/// Only footprint-aware kernels read it; see path::SampleDirectLight for who multiplies by what.
struct IncidentWave {
    double dist = Infinity;
    const GaussianBeamGeometry *beam = nullptr;
};

struct ScatterSample {
    Vec3 wo;                  // local, unit, pointing away from the surface
    /// Throughput factor per wavelength: f·|cosθo|/pdf for continuous lobes, a_j/p_j for
    /// discrete ones (theory §3.1). Includes the (η_i/η_t)² radiance factor on refraction.
    SampledSpectrum weight;
    double pdf = 0;           // solid-angle density for continuous lobes; the discrete lobe's
                              // selection probability for near-delta lobes
    int lobe = 0;             // which term of the mixture (for diagnostics / sample–solve)
    unsigned flags = 0;
    double eta = 1;           // relative index η_t/η_i crossed (1 for reflection)
};

class Material {
  public:
    virtual ~Material() = default;

    /// Picks one term of the scattering mixture with probability p_j (u0) and a direction in it
    /// (u). Returns nullopt if the path is absorbed / no valid direction.
    virtual std::optional<ScatterSample> Sample(const ScatterQuery &q, double u0, const Vec2 &u) const = 0;
    /// Scattered density towards wo per unit solid angle per unit incident irradiance [1/sr]
    /// (no cosine); continuous lobes only in the ray-optics limit, near-delta lobes contribute
    /// their GR-spread Gaussian when !q.rayOptics.
    virtual SampledSpectrum Eval(const ScatterQuery &q, const Vec3 &wo) const = 0;
    /// Solid-angle density with which Sample() produces wo (continuous lobes only).
    virtual double Pdf(const ScatterQuery &q, const Vec3 &wo) const = 0;
    /// True if every lobe is a near-delta lobe (no point in light sampling in the ray limit).
    virtual bool IsDeltaOnly() const = 0;
    /// True if f(wi→wo) = f(wo→wi) (checked by the contract suite).
    virtual bool IsReciprocal() const { return true; }
    /// Footprint-aware kernels (theory §9) use the incident GR's wave function (ScatterQuery::gr)
    /// and return spread-free samples; with !q.rayOptics they need q.gr and q.si.
    virtual bool IsFootprintAware() const { return false; }
    /// Like Eval, for the wave `w` arriving along −wo: a spherical wave from a source at distance
    /// w.dist [m] (its curvature over the GR's footprint matters to footprint-aware kernels;
    /// Infinity gives Eval) or a Gaussian beam (w.beam; the value is then per unit on-axis
    /// irradiance, see IncidentWave). Kernels that are not footprint-aware ignore w.
    virtual SampledSpectrum EvalFrom(const ScatterQuery &q, const Vec3 &wo, const IncidentWave &w) const {
        (void)w;
        return Eval(q, wo);
    }
    /// Called by the scene builder for every shape that uses this kernel; throws phasor::Error
    /// (e.g. a planar kernel on a non-planar shape).
    virtual void CheckShape(const Shape &shape) const { (void)shape; }
    /// Aperture kernels: the plate's openings in plate coordinates (core/aperture.h); nullptr for
    /// every other kernel. The forward `rs` integrator reads them.
    virtual const ApertureMask *Openings() const { return nullptr; }
    virtual std::string ToString() const = 0;
};

}  // namespace phasor
