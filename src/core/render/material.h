// SPDX-License-Identifier: Apache-2.0
// phasor — the diffraction-kernel (material) interface (docs/kernels.md).
//
// Frame: every direction is in the local shading frame (z = shading normal, pointing to the
// side the shape calls "outside"); wi and wo both point *away* from the surface. wi is the
// direction the tracer came from (towards the camera in a backward tracer).
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/polarization.h"
#include "core/spectrum/spectrum.h"
#include "core/render/texture.h"

namespace phasor {

struct SpectralGenRay;
struct SurfaceInteraction;
struct GaussianBeamGeometry;
class Shape;
class ApertureMask;
class SmoothSurface;
struct Coating;

/// Lobe flags returned by Sample() and ListNearDelta().
enum ScatterFlags : unsigned {
    ScatterReflection = 1u << 0,
    ScatterTransmission = 1u << 1,
    ScatterDiffuse = 1u << 2,     // a continuous lobe with a finite pdf
    /// A near-delta lobe (smooth reflection/refraction, grating order): in the ray-optics limit a
    /// Dirac delta; for a generalized ray its true angular width is the ray's own spread σ_k/k.
    /// Listed by Material::ListNearDelta; never part of Eval (see LobeMask).
    ScatterNearDelta = 1u << 3,
    ScatterDispersive = 1u << 4,  // direction depends on wavelength (collapse to the hero)
    /// Footprint-aware kernels (theory §9 item 5): the lobe already holds the GR's angular spread,
    /// so the outgoing GR is spread-free — later vertices treat it as a classical ray.
    ScatterSpreadFree = 1u << 5,
};

/// Which lobes a query is about — the one rule for what Sample, Eval and Pdf contain, enforced in
/// Material's non-virtual wrappers (so no kernel can get it wrong):
///   * Eval and Pdf report continuous lobes only, and only when the mask has LobeContinuous.
///     Near-delta lobes have no density in Eval, not even for a generalized ray: integrators
///     measure delta and small sources through them in closed form from ListNearDelta (D14).
///   * Sample returns nullopt for a lobe outside the mask. Since Sample picks lobe j with
///     probability p_j and weights it by 1/p_j, the masked estimator is an unbiased estimate of
///     the masked part alone (e.g. LobeContinuous: the continuous lobes' ∫ f·|cosθ| dω).
enum LobeMask : unsigned {
    LobeContinuous = 1u << 0,
    LobeNearDelta = 1u << 1,
    LobeAll = LobeContinuous | LobeNearDelta,
};

/// What a kernel can do for a query (Material::Capabilities). May depend on the query: the
/// `aperture` is a straight near-delta transmission in the ray-optics limit and a footprint-aware
/// continuous lobe for a generalized ray.
enum KernelCaps : unsigned {
    /// Has a continuous lobe: Eval/Pdf can be non-zero, so light sampling (NEE) is useful.
    CapContinuous = 1u << 0,
    /// Has near-delta lobes, listed by ListNearDelta.
    CapNearDelta = 1u << 1,
    /// Footprint-aware (theory §9): reads the whole incident GR (ScatterQuery::gr, ::si),
    /// answers EvalFrom per incident wave and returns spread-free samples.
    CapFootprintAware = 1u << 2,
};

/// What a kernel is asked about (docs/kernels.md, "The interface").
struct ScatterQuery {
    Vec3 wi;                               // local, unit, pointing away from the surface
    const SampledWavelengths *wl = nullptr;
    double etaOutside = 1;                 // real index of the medium on the +z side (the air)
    /// Ray-optics limit requested (the `ray` integrator, spread-free GRs): near-delta lobes are
    /// true deltas and wave effects collapse to their geometric limit.
    bool rayOptics = true;
    /// The lobes Sample, Eval and Pdf are about (LobeMask). `grt`'s NEE asks for LobeContinuous.
    unsigned lobes = LobeAll;
    TextureEvalContext tex;                // where textures are evaluated (uv, p, dp/du, β …)
    /// The incident generalized ray and the hit, for kernels that depend on the GR's footprint:
    /// `gr` is the traced GR at the hit point in world space (gr->d points into the surface,
    /// per-wavelength k, β², ρ; traced convention, ρ > 0 diverging along d), `si` the interaction
    /// (world shading frame, shape and its to_world). Both null for classical rays.
    const SpectralGenRay *gr = nullptr;
    const SurfaceInteraction *si = nullptr;

    /// The incident GR's footprint at carried wavelength i (theory §1.2): β² [m²] and ρ; 0 for a
    /// classical ray. The one accessor for footprints (they are per wavelength: β ∝ λ at a camera).
    double Beta2(int i) const;
    double Rho(int i) const;
};

/// The wave a light sample sends to a receiver, as footprint-aware kernels need it (EvalFrom):
/// over the GR's footprint the incident field is not a plane wave.
///   * `dist`: the wavefront radius at the receiver [m] — a spherical wave from a source at that
///     distance (point and area lights); Infinity for a plane wave.
///   * `beam`: a coherent TEM₀₀ Gaussian beam (core/render/genray.h). Its amplitude varies across the
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
    /// Which lobe: for a near-delta lobe the id ListNearDelta gives it; continuous lobes have ids
    /// of their own (one meaning per kernel, documented in its file; EvalLobe takes it back).
    int lobe = 0;
    unsigned flags = 0;
    double eta = 1;           // relative index η_t/η_i crossed at the hero wavelength (1 for reflection)
};

/// One near-delta lobe of a kernel for a query (Material::ListNearDelta). Per carried wavelength
/// i < wl->Count(): the outgoing direction, the weight and the indices, obeying the vector grating
/// equation in the local tangent plane (z = normal; k = 2π/λ):
///     nOut[i]·wo[i].xy = −nIn[i]·wi.xy + shift·λ_i/(2π)
/// with wo[i] on wi's side for reflection and on the far side for transmission. `shift` is the
/// tangential wave-vector the lobe adds [rad/m]: 0 for a mirror or Snell's law, j·2π/Λ·ĝ for
/// grating order j. Evanescent lobes are not listed; a lobe evanescent at some companion
/// wavelength has weight 0 there.
struct NearDeltaLobe {
    int id = 0;         // stable per kernel; Sample returns the same id in ScatterSample::lobe
    unsigned flags = 0; // ScatterNearDelta | ScatterReflection or ScatterTransmission [| ScatterDispersive]
    std::array<Vec3, NumWavelengths> wo{};  // local, unit, per wavelength (wo[0]: the hero)
    /// a_j(λ): the radiance throughput of the lobe, as ScatterSample::weight·pdf (so including
    /// the (η_i/η_t)² radiance factor on refraction). Σ_j a_j ≤ 1 for a passive surface.
    SampledSpectrum weight;
    std::array<double, NumWavelengths> nIn{}, nOut{};  // absolute real indices of wi's and wo's media
    Vec2 shift;          // tangential wave-vector shift [rad/m], local x, y
    double prob = 0;     // the probability with which Sample picks this lobe for this query
    double Eta(int i) const { return nOut[i] / nIn[i]; }  // relative index crossed
};
/// The near-delta lobes of one query: a fixed-capacity list (a grating lists ≤ 2·max_order+1
/// orders per side); kernels Add() lobes, integrators iterate.
struct NearDeltaLobes {
    static constexpr int Capacity = 64;
    std::array<NearDeltaLobe, Capacity> lobe;
    int count = 0;
    /// Appends a lobe; throws phasor::Error past Capacity (a kernel bug, not user input).
    NearDeltaLobe &Add();
    const NearDeltaLobe *begin() const { return lobe.data(); }
    const NearDeltaLobe *end() const { return lobe.data() + count; }
};

/// The ids of a query's continuous lobes (Material::ContinuousLobes); fixed capacity.
struct ContinuousLobeIds {
    static constexpr int Capacity = 8;
    std::array<int, Capacity> id{};
    int count = 0;
    /// Appends an id; throws phasor::Error past Capacity (a kernel bug, not user input).
    void Add(int lobeId);
    const int *begin() const { return id.data(); }
    const int *end() const { return id.data() + count; }
};

/// The s axis of the polarisation frame in which EvalLobe states a lobe's response (local, unit):
/// normalise(wi × wo) — the normal of the plane through the two directions, which for an interface
/// lobe (reflection, refraction, an in-plane grating order) is ±normalise(n̂ × k̂), the ŝ of
/// core/polarization.h — or, where wi ∥ wo (normal incidence, straight transmission, back-scatter),
/// normalise(ẑ × wi), else ŷ (so that the local x axis is p's reference at normal incidence). The
/// sign of ŝ does not matter for the (s, p) responses kernels give (a diagonal Jones matrix is the
/// same in the basis (−ŝ, −p̂)).
Vec3 LobeSAxis(const Vec3 &wi, const Vec3 &wo);

/// Coherence-dependent terms of one lobe's response (read by `sample_solve`, which defines how
/// they are weighted). Bare interfaces have none: coherent == incoherent, shear 0.
struct LobeCoherence {
    /// Response when the waves that interfere in this lobe (a film's reflections from its two
    /// faces, a grating's neighbouring periods) are mutually incoherent; equal to the coherent
    /// response (LobeResponse::mueller) when the lobe involves no interference.
    std::array<Mueller, NumWavelengths> incoherent{};
    /// Lateral shear between the two interfering waves at the surface [m], local tangent plane
    /// (a film of thickness d at refraction angle θ_t: 2·d·tanθ_t along the plane of incidence).
    std::array<Vec2, NumWavelengths> shear{};
    bool any = false;  // false: no coherence-dependent term (incoherent == mueller, shear 0)
};

/// The response of one given lobe towards one given direction (Material::EvalLobe), per carried
/// wavelength, in the s/p frame of LobeSAxis(wi, wo) — for interface lobes the plane of incidence
/// (core/polarization.h: s = the normal × propagation direction, p completing a right-handed frame
/// with the propagation direction; for normal incidence the local x axis is p's reference). The
/// kernel's convention is the backward tracer's: the wave arrives along −wi and leaves along wo
/// (time reversal, theory §1.6); `sample_solve` applies the reciprocal matrix to light arriving along −wo.
///   * `mueller[i]`: the Mueller matrix; its M00 is the unpolarised value: for a near-delta lobe its
///     weight a_j(λ_i) (ListNearDelta), for a continuous lobe f(wi→wo)·|cosθo| per unit solid angle.
///   * `jones[i]`: the Jones matrix whose Mueller matrix is `mueller[i]`, when the lobe is
///     deterministic (`hasJones`); depolarising lobes (diffuse) have none.
struct LobeResponse {
    std::array<Mueller, NumWavelengths> mueller{};
    std::array<Jones, NumWavelengths> jones{};
    bool hasJones = false;
    LobeCoherence coherence;
};

class Material {
  public:
    virtual ~Material() = default;

    // --- What integrators call (non-virtual: the lobe mask is enforced here, once) ----------

    /// Picks one term of the scattering mixture with probability p_j (u0) and a direction in it
    /// (u). Returns nullopt if the path is absorbed / no valid direction, or the picked lobe is
    /// outside q.lobes (LobeMask).
    std::optional<ScatterSample> Sample(const ScatterQuery &q, double u0, const Vec2 &u) const;
    /// Scattered density towards wo per unit solid angle per unit incident irradiance [1/sr]
    /// (no cosine) of the continuous lobes; 0 unless q.lobes has LobeContinuous.
    SampledSpectrum Eval(const ScatterQuery &q, const Vec3 &wo) const;
    /// Like Eval, for the wave `w` arriving along −wo: a spherical wave from a source at distance
    /// w.dist [m] (its curvature over the GR's footprint matters to footprint-aware kernels;
    /// Infinity gives Eval) or a Gaussian beam (w.beam; the value is then per unit on-axis
    /// irradiance, see IncidentWave). Kernels that are not footprint-aware ignore w.
    SampledSpectrum EvalFrom(const ScatterQuery &q, const Vec3 &wo, const IncidentWave &w) const;
    /// Solid-angle density with which Sample() produces wo (continuous lobes, including their
    /// selection probability); 0 unless q.lobes has LobeContinuous.
    double Pdf(const ScatterQuery &q, const Vec3 &wo) const;
    /// True if the query has no continuous lobe (no point in light sampling).
    bool IsDeltaOnly(const ScatterQuery &q) const { return !(Capabilities(q) & CapContinuous); }
    /// Footprint-awareness for a generalized-ray query (scene checks ask without a query).
    bool IsFootprintAware() const;

    // --- What a kernel implements -------------------------------------------------------------

    /// KernelCaps for the query.
    virtual unsigned Capabilities(const ScatterQuery &q) const = 0;
    /// Lists every near-delta lobe for the query into `out` (which arrives empty), in the order of
    /// their ids. Kernels without near-delta lobes list none.
    virtual void ListNearDelta(const ScatterQuery &q, NearDeltaLobes &out) const {
        (void)q;
        (void)out;
    }
    /// The response (Jones / Mueller, coherence terms) of lobe `lobe` (an id Sample or
    /// ListNearDelta gave for this query) towards wo; nullopt if the lobe does not reach wo (for a
    /// near-delta lobe: wo is not its direction at the hero wavelength, to 1e-9). See LobeResponse.
    virtual std::optional<LobeResponse> EvalLobe(const ScatterQuery &q, int lobe, const Vec3 &wo) const = 0;
    /// The ids of the continuous lobes for the query: those Sample returns with a finite pdf. Their
    /// EvalLobe responses add up to Eval·|cosθo| at every wo (checked by the contract suite), so a
    /// polarised integrator can weight a sampled direction by all of them, as Eval does. Kernels
    /// without continuous lobes list none.
    virtual void ContinuousLobes(const ScatterQuery &q, ContinuousLobeIds &out) const {
        (void)q;
        (void)out;
    }
    /// Σ over ContinuousLobes of EvalLobe towards wo (the Mueller sum; a Jones matrix only when
    /// exactly one lobe answers; no coherence terms); nullopt if none answers.
    std::optional<LobeResponse> EvalContinuousLobes(const ScatterQuery &q, const Vec3 &wo) const;
    /// True if some lobe's EvalLobe may report coherence terms (LobeCoherence::any: a coated
    /// surface, thin_film, multilayer); false promises that none does (checked by the contract
    /// suite), which lets a polarised integrator skip evaluating lobes whose response cannot matter.
    virtual bool HasCoherenceTerms() const { return false; }
    /// The kernel's reference direction in the tangent plane at `tex`, as an angle [rad]
    /// counter-clockwise from the shading frame's x axis (dp/du) — a grating's grating vector — or
    /// nullopt for a kernel without one (isotropic). `phasor probe` measures azimuths from it.
    virtual std::optional<double> ReferenceAngle(const TextureEvalContext &tex) const {
        (void)tex;
        return std::nullopt;
    }
    /// True if f(wi→wo) = f(wo→wi) (checked by the contract suite).
    virtual bool IsReciprocal() const { return true; }
    /// For a non-reciprocal kernel, the sense in which it conserves energy (the contract suite
    /// checks that one; EnergySenseOf). false (default): per query — what Sample can return for one
    /// wi carries at most the incident energy (the backward walk's albedo ≤ 1; the `aperture`).
    /// true: per physical incident direction — light arriving from a direction d (a lobe's wo)
    /// leaves into all the wi whose listed lobes point back at d, and into every wi with
    /// f(wi → d)·|cosθ_i|, with at most its energy (a grating's orders of a plane wave, a rough
    /// surface's glint and halo of the sun carry F); the lobes of one query may then sum to more
    /// than 1. Reciprocal kernels satisfy both. Composite kernels: CombinedEnergySense.
    virtual bool ConservesEnergyPerIncidentDirection() const { return false; }
    /// Called by the scene builder for every shape that uses this kernel; throws phasor::Error
    /// (e.g. a planar kernel on a non-planar shape).
    virtual void CheckShape(const Shape &shape) const { (void)shape; }
    /// Aperture kernels: the plate's openings in plate coordinates (core/render/aperture.h); nullptr for
    /// every other kernel. The forward `rs` integrator reads them.
    virtual const ApertureMask *Openings() const { return nullptr; }
    /// Smooth kernels (conductor, dielectric, thin_film, multilayer): their plane-wave optics, a
    /// coating over a substrate (materials/smooth_surface.h) — what `grating` and `harvey_shack`
    /// multiply their lobes by when they name this kernel as `substrate`; nullptr otherwise.
    virtual const SmoothSurface *Surface() const { return nullptr; }
    /// Coating definitions (thin_film, multilayer): their layers, which `coating = @name` puts on
    /// another kernel's substrate; nullptr for kernels that cannot serve as a coating.
    virtual std::shared_ptr<const Coating> AsCoating() const { return nullptr; }
    virtual std::string ToString() const = 0;

  protected:
    /// Sample over all lobes (the wrapper applies the mask). The default serves kernels whose lobes
    /// are all listed: it picks one of ListNearDelta's lobes with its `prob` (SampleListedLobe).
    virtual std::optional<ScatterSample> SampleLobes(const ScatterQuery &q, double u0, const Vec2 &u) const;
    /// The continuous lobes' value [1/sr] (Eval without the mask); 0 for delta-only kernels.
    virtual SampledSpectrum EvalContinuous(const ScatterQuery &q, const Vec3 &wo) const {
        (void)q;
        (void)wo;
        return SampledSpectrum(0.0);
    }
    /// Footprint-aware kernels: the continuous lobes' value for the incident wave w.
    virtual SampledSpectrum EvalContinuousFrom(const ScatterQuery &q, const Vec3 &wo, const IncidentWave &w) const {
        (void)w;
        return EvalContinuous(q, wo);
    }
    /// The continuous lobes' density [1/sr] (Pdf without the mask).
    virtual double PdfContinuous(const ScatterQuery &q, const Vec3 &wo) const {
        (void)q;
        (void)wo;
        return 0;
    }
};

/// In which sense a kernel conserves energy: the two declarations IsReciprocal and
/// ConservesEnergyPerIncidentDirection as one value (the contract suite checks the declared sense).
enum class EnergySense {
    Reciprocal,            // f(wi→wo) = f(wo→wi): both senses below hold
    PerQuery,              // not reciprocal; what one query's lobes carry is ≤ 1 (its albedo)
    PerIncidentDirection,  // not reciprocal; the light arriving from one direction leaves with ≤ 1
};
EnergySense EnergySenseOf(const Material &m);
/// The sense of a kernel that answers every query with its children's answers to that query — a
/// weighted sum (`mix`, weights that depend on the hit, not on the directions) or one child per
/// side (`two_sided`): reciprocal if every child is; per incident direction if every child is
/// reciprocal or per incident direction (the light from d leaves each child with ≤ 1, so their
/// weighted sum or the child of d's side does too); per query likewise. nullopt if one child
/// conserves energy only per query and another only per incident direction: the composite then
/// bounds neither what a query gathers nor what the light from a direction leaves with (one
/// child's per-query lobes may carry up to 1 from a direction where the other's carry F, …), and
/// no single declaration describes it. Composite kernels refuse such children at creation.
std::optional<EnergySense> CombinedEnergySense(std::span<const Material *const> children);
/// "reciprocal", "conserves energy per query", "conserves energy per incident direction".
const char *Describe(EnergySense s);

/// The direction of a near-delta lobe from the vector grating equation (see NearDeltaLobe):
/// nOut·wo.xy = −nIn·wi.xy + shift·λ/(2π), on wi's side (reflection) or the far side. False if
/// the lobe is evanescent (|wo.xy| ≥ 1) at this wavelength.
bool NearDeltaDirection(const Vec3 &wi, double nIn, double nOut, const Vec2 &shift, double lambda,
                        bool transmission, Vec3 *wo);

/// A kernel's SampleLobes for lobes it has listed: picks lobe j with probability `prob` (u0) and
/// returns its hero direction with weight a_j/p_j, pdf p_j, its id, flags and η. Nullopt if no
/// lobe is listed or the pick has p = 0.
std::optional<ScatterSample> SampleListedLobe(const NearDeltaLobes &lobes, double u0);
/// The same for lobes a kernel keeps in its own small array (NearDeltaLobes is 64 lobes large:
/// constructing one per Sample costs more than a smooth surface's optics).
std::optional<ScatterSample> SampleListedLobe(std::span<const NearDeltaLobe> lobes, double u0);

/// True if unit directions a and b agree to `tol` [rad] (EvalLobe's test for a near-delta lobe).
inline bool SameDirection(const Vec3 &a, const Vec3 &b, double tol = 1e-9) { return Length(a - b) <= tol; }

}  // namespace phasor
