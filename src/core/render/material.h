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
#include "core/scratch_buffer.h"
#include "core/polarization.h"
#include "core/spectrum/spectrum.h"
#include "core/render/texture.h"

namespace phasor {

struct SpectralGenRay;
struct SurfaceInteraction;
struct GaussianBeamGeometry;
class Shape;

/// Lobe flags returned by PreparedKernel::Sample and ListNearDelta.
enum ScatterFlags : unsigned {
    ScatterReflection = 1u << 0,
    ScatterTransmission = 1u << 1,
    ScatterDiffuse = 1u << 2,     // a continuous lobe with a finite pdf
    /// A near-delta lobe (smooth reflection/refraction, grating order): in the ray-optics limit a
    /// Dirac delta; for a generalized ray its true angular width is the ray's own spread σ_k/k.
    /// Listed by PreparedKernel::ListNearDelta; never part of Eval (see LobeMask).
    ScatterNearDelta = 1u << 3,
    ScatterDispersive = 1u << 4,  // direction depends on wavelength (collapse to the hero)
    /// Footprint-aware kernels (theory §9 item 5): the lobe already holds the GR's angular spread,
    /// so the outgoing GR is spread-free — later vertices treat it as a classical ray.
    ScatterSpreadFree = 1u << 5,
};

/// Which lobes a question to a prepared kernel is about (the last argument of PreparedKernel's
/// Sample, Eval, EvalFrom, Pdf and EvalPdf; the rule is stated there).
enum LobeMask : unsigned {
    LobeContinuous = 1u << 0,
    LobeNearDelta = 1u << 1,
    LobeAll = LobeContinuous | LobeNearDelta,
};

/// What a kernel can do for a query (PreparedKernel::Capabilities). May depend on the query: the
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
    /// The caller follows a sampled dispersive near-delta lobe at the hero wavelength alone (theory
    /// §0 D10: `grt` drops the companions from the throughput there): Sample may then return such a
    /// lobe's weight at the hero only, the companions 0 (a kernel that defers companion weights,
    /// NearDeltaLobe::DeferWeights, need not compute them). Nothing else changes.
    bool heroAfterDispersive = false;
    TextureEvalContext tex;                // where textures are evaluated (uv, p, dp/du, β …)
    /// The incident generalized ray and the hit, for kernels that depend on the GR's footprint:
    /// `gr` is the traced GR at the hit point in world space (gr->d points into the surface,
    /// per-wavelength k, β², ρ; traced convention, ρ > 0 diverging along d), `si` the interaction
    /// (world shading frame, shape and its to_world). Both null for classical rays. Read while the
    /// kernel is prepared only (Material::Prepare).
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

/// One near-delta lobe of a kernel for a query (PreparedKernel::ListNearDelta). Per carried wavelength
/// i < wl->Count(): the outgoing direction, the weight and the indices, obeying the vector grating
/// equation in the local tangent plane (z = normal; k = 2π/λ):
///     nOut[i]·wo[i].xy = −nIn[i]·wi.xy + shift·λ_i/(2π)
/// with wo[i] on wi's side for reflection and on the far side for transmission. `shift` is the
/// tangential wave-vector the lobe adds [rad/m]: 0 for a mirror or Snell's law, j·2π/Λ·ĝ for
/// grating order j. Evanescent lobes are not listed; a lobe evanescent at some companion
/// wavelength has weight 0 there.
class PreparedKernel;
struct NearDeltaLobe {
    int id = 0;         // stable per kernel; Sample returns the same id in ScatterSample::lobe
    unsigned flags = 0; // ScatterNearDelta | ScatterReflection or ScatterTransmission [| ScatterDispersive]
    /// Local, unit, per wavelength (wo[0]: the hero). A slot where the lobe carries nothing has
    /// some direction of the lobe (a propagating slot its own, an evanescent one the hero's).
    std::array<Vec3, NumWavelengths> wo{};
    std::array<double, NumWavelengths> nIn{}, nOut{};  // absolute real indices of wi's and wo's media
    Vec2 shift;          // tangential wave-vector shift [rad/m], local x, y
    double prob = 0;     // the probability with which Sample picks this lobe for this query
    double Eta(int i) const { return nOut[i] / nIn[i]; }  // relative index crossed

    /// a_j(λ): the radiance throughput of the lobe, as ScatterSample::weight·pdf (so including
    /// the (η_i/η_t)² radiance factor on refraction). Σ_j a_j ≤ 1 for a passive surface. A kernel
    /// may list the companion wavelengths' weights lazily (DeferWeights): the first call computes
    /// them (PreparedKernel::LobeWeightAt of the kernel that listed the lobe, which must still be
    /// alive: read it before that kernel's ScratchBuffer is rewound, also through a copy).
    /// With `slots`, only the slots with their bit set are computed (the others may be pending).
    const SampledSpectrum &Weight(unsigned slots = ~0u) const {
        if (pending_.slots & slots) Complete(pending_.slots & slots);
        return weight_;
    }
    /// Whether the lobe may carry light at carried wavelength slot i (its weight there is not
    /// known to be 0), or at any: without computing a pending weight.
    bool MayCarry(int i) const { return ((pending_.slots >> i) & 1u) || weight_[i] > 0; }
    bool MayCarryAny() const { return pending_.slots || !weight_.IsZero(); }
    /// The slots whose weight is still to be computed (bit i: slot i).
    unsigned PendingSlots() const { return pending_.slots; }
    void SetWeight(const SampledSpectrum &w) {
        weight_ = w;
        pending_ = {};
    }
    void SetWeight(int i, double w) {
        weight_[i] = w;
        pending_.slots &= ~(1u << i);
    }
    /// The weights of `slots` (never the hero's, bit 0: Sample needs it) are left to
    /// kernel.LobeWeightAt(id, kernel.Query().wi, slots) — `id` as set now — asked when Weight()
    /// is first called (a grating lists its hero wavelength's efficiencies and computes the
    /// companions' only for the lobes some light may reach). A kernel that lists a child's lobes
    /// as its own (a mixture, scaled by ScaleWeight) defers their pending slots again to itself.
    void DeferWeights(unsigned slots, const PreparedKernel &kernel);
    /// The computed weights times s (a mixture's share; pending slots are deferred again, above).
    void ScaleWeight(double s) { weight_ *= s; }
    /// A copy with every weight computed and no tie to the kernel that listed it: what to keep
    /// past that kernel's ScratchBuffer (Rewind, Reset).
    NearDeltaLobe Detached() const {
        Weight();
        return *this;
    }

  private:
    struct Pending {
        const PreparedKernel *kernel = nullptr;  // the kernel that listed the lobe
        int id = 0;                              // the lobe's id there
        unsigned slots = 0;                      // bit i: slot i is pending
    };
    void Complete(unsigned slots) const;  // fills these pending slots (material.cpp)
    mutable SampledSpectrum weight_;
    mutable Pending pending_;
};
/// The near-delta lobes a kernel lists while it is prepared (Material::Prepare), in the scratch
/// buffer: room for at most `capacity` lobes, which the kernel knows (a smooth surface 2, a grating
/// 2·(2·max_order + 1)). The prepared kernel keeps Lobes() (PreparedKernel::ListNearDelta).
class LobeList {
  public:
    LobeList(ScratchBuffer &scratch, int capacity)
        : lobe_(scratch.Room<NearDeltaLobe>(std::size_t(capacity))), capacity_(capacity) {}
    /// Appends a lobe (value-initialised); throws phasor::Error past the capacity (a kernel bug).
    NearDeltaLobe &Add();
    int Count() const { return count_; }
    NearDeltaLobe &operator[](int k) { return lobe_[k]; }
    std::span<const NearDeltaLobe> Lobes() const { return {lobe_, std::size_t(count_)}; }

  private:
    NearDeltaLobe *lobe_;
    int capacity_, count_ = 0;
};

/// The ids of a query's continuous lobes (PreparedKernel::ContinuousLobes); fixed capacity.
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

/// The response of one given lobe towards one given direction (PreparedKernel::EvalLobe), per carried
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

/// The continuous lobes' value and density towards one direction (PreparedKernel::EvalPdf).
struct KernelValue {
    SampledSpectrum f;  // [1/sr] as PreparedKernel::Eval / EvalFrom (no cosine)
    double pdf = 0;     // [1/sr] as PreparedKernel::Pdf
};

/// A kernel prepared for one query (Material::Prepare; pbrt-v4's BSDF from GetBSDF, Mitsuba 3's
/// BSDF with its SurfaceInteraction): what depends on the query alone — textures, the smooth
/// surface's optics at θ_i, a grating's orders, a mixture's weight, the plate a generalized ray
/// meets — is evaluated once, the near-delta lobes are listed once, and every question about the
/// query (Sample, Eval, Pdf, EvalPdf, ListNearDelta, EvalLobe, …) is a method of this object. It
/// lives in the ScratchBuffer it was prepared in, until that buffer is reset.
///
/// The query it keeps (Query()) has `gr` and `si` cleared: a kernel reads what it needs of the
/// incident generalized ray and the hit while it is prepared (the integrator moves both on).
///
/// The lobe mask (`lobes`, LobeMask) is the one rule for what Sample, Eval and Pdf contain, enforced
/// here in the non-virtual methods, so no kernel can get it wrong:
///   * Eval and Pdf report continuous lobes only, and only when the mask has LobeContinuous.
///     Near-delta lobes have no density in Eval, not even for a generalized ray: integrators
///     measure delta and small sources through them in closed form from ListNearDelta (D14).
///   * Sample returns nullopt for a lobe outside the mask. Since Sample picks lobe j with
///     probability p_j and weights it by 1/p_j, the masked estimator is an unbiased estimate of
///     the masked part alone (e.g. LobeContinuous: the continuous lobes' ∫ f·|cosθ| dω).
class PreparedKernel {
  public:
    PreparedKernel(const PreparedKernel &) = delete;
    PreparedKernel &operator=(const PreparedKernel &) = delete;

    /// The query, with `gr` and `si` cleared (see above).
    const ScatterQuery &Query() const { return q_; }
    /// KernelCaps for the query.
    unsigned Capabilities() const { return caps_; }
    /// True if the query has no continuous lobe (no point in light sampling).
    bool IsDeltaOnly() const { return !(caps_ & CapContinuous); }
    /// Every near-delta lobe of the query, in the order of their ids (none for a kernel without
    /// near-delta lobes).
    std::span<const NearDeltaLobe> ListNearDelta() const { return lobes_; }
    /// The listed lobe of id `id`, or nullptr.
    const NearDeltaLobe *FindLobe(int id) const;
    /// The ids of the continuous lobes: those Sample returns with a finite pdf. Their EvalLobe
    /// responses add up to Eval·|cosθo| at every wo (checked by the contract suite), so a polarised
    /// integrator can weight a sampled direction by all of them, as Eval does.
    const ContinuousLobeIds &ContinuousLobes() const { return continuous_; }

    /// Picks one term of the scattering mixture with probability p_j (u0) and a direction in it
    /// (u). Returns nullopt if the path is absorbed / no valid direction, or the picked lobe is
    /// outside `lobes` (LobeMask).
    std::optional<ScatterSample> Sample(double u0, const Vec2 &u, unsigned lobes = LobeAll) const;
    /// Scattered density towards wo per unit solid angle per unit incident irradiance [1/sr]
    /// (no cosine) of the continuous lobes; 0 unless `lobes` has LobeContinuous.
    SampledSpectrum Eval(const Vec3 &wo, unsigned lobes = LobeAll) const {
        return (lobes & LobeContinuous) ? EvalContinuous(wo) : SampledSpectrum(0.0);
    }
    /// Like Eval, for the wave `w` arriving along −wo: a spherical wave from a source at distance
    /// w.dist [m] (its curvature over the GR's footprint matters to footprint-aware kernels;
    /// Infinity gives Eval) or a Gaussian beam (w.beam; the value is then per unit on-axis
    /// irradiance, see IncidentWave). Kernels that are not footprint-aware ignore w.
    SampledSpectrum EvalFrom(const Vec3 &wo, const IncidentWave &w, unsigned lobes = LobeAll) const {
        return (lobes & LobeContinuous) ? EvalContinuousFrom(wo, w) : SampledSpectrum(0.0);
    }
    /// Solid-angle density with which Sample() produces wo (continuous lobes, including their
    /// selection probability); 0 unless `lobes` has LobeContinuous.
    double Pdf(const Vec3 &wo, unsigned lobes = LobeAll) const {
        return (lobes & LobeContinuous) ? PdfContinuous(wo) : 0;
    }
    /// EvalFrom and Pdf towards one direction together (what light sampling with MIS needs; a
    /// kernel shares the work of the two where it can). Equal to (EvalFrom(wo, w), Pdf(wo)).
    KernelValue EvalPdf(const Vec3 &wo, const IncidentWave &w = {}, unsigned lobes = LobeAll) const {
        return (lobes & LobeContinuous) ? EvalPdfContinuous(wo, w) : KernelValue{};
    }
    /// The response (Jones / Mueller, coherence terms) of lobe `lobe` (an id Sample or
    /// ListNearDelta gave for this query) towards wo; nullopt if the lobe does not reach wo (for a
    /// near-delta lobe: wo is not its direction at the hero wavelength, to 1e-9). See LobeResponse.
    virtual std::optional<LobeResponse> EvalLobe(int lobe, const Vec3 &wo) const = 0;
    /// Σ over ContinuousLobes of EvalLobe towards wo (the Mueller sum; a Jones matrix only when
    /// exactly one lobe answers; no coherence terms); nullopt if none answers.
    std::optional<LobeResponse> EvalContinuousLobes(const Vec3 &wo) const;
    /// How fast the efficiencies a_j of the near-delta lobes may vary with the direction the light
    /// arrives from (theory §0 D15, core/render/lobe_average.h): a bound B [rad per unit of κ] such
    /// that the m-th derivative of a_j with respect to κ, the tangential wave-vector of the arrival
    /// direction in units of k₀ = 2π/λ (n·sinθ in the light's medium; the Snell invariant), is at
    /// most B^m·sup|a_j| for κ ≤ kappaMax, at every carried wavelength — a band-limited model: a
    /// film's fringes oscillate at 2k₀·d·dq/dκ (q = √(n² − κ²)) per round trip, a grating's
    /// J_j(m)² at 2·dm/dκ. 0 (the default) declares an efficiency that is smooth on the scale of a
    /// radian (Fresnel reflection away from grazing and critical angles).
    virtual double AngularBandwidth(double kappaMax) const {
        (void)kappaMax;
        return 0;
    }
    /// The weight [radiance throughput, as NearDeltaLobe::Weight()] listed lobe `id` would have if the
    /// kernel were prepared at the same hit (same textures, wavelengths, media) for the incident
    /// direction wiPrime (local, unit, on Query().wi's side of the surface) instead of Query().wi:
    /// per carried wavelength slot i with bit i set in `slots` (the others may be anything), 0 where
    /// it would not be listed. Equal, bit for bit, to Prepare(query with wi = wiPrime).FindLobe(id)->
    /// weight in those slots (the contract suite checks it). What the angular-spectrum averages of
    /// theory §0 D15 ask at each quadrature node (core/render/lobe_average.h; a dispersive lobe's
    /// wavelengths have rules of their own, so one slot at a time): kernels that list many lobes (a
    /// grating's orders) or evaluate textures when prepared answer it without a listing. nullopt (the
    /// default): the kernel does not answer, and the caller prepares the material again at wiPrime.
    virtual std::optional<SampledSpectrum> LobeWeightAt(int id, const Vec3 &wiPrime, unsigned slots) const {
        (void)id;
        (void)wiPrime;
        (void)slots;
        return std::nullopt;
    }

  protected:
    /// Keeps q without its `gr` and `si` (see above). Kernels set caps_, lobes_ and continuous_.
    explicit PreparedKernel(const ScatterQuery &q) : q_(q) {
        q_.gr = nullptr;
        q_.si = nullptr;
    }
    /// Not virtual: prepared kernels live in a ScratchBuffer, which runs no destructors (every
    /// prepared kernel is trivially destructible).
    ~PreparedKernel() = default;

    /// Sample over all lobes (Sample applies the mask). The default serves kernels whose lobes are
    /// all listed: it picks one of lobes_ with its `prob` (SampleListedLobe).
    virtual std::optional<ScatterSample> SampleLobes(double u0, const Vec2 &u) const;
    /// The continuous lobes' value [1/sr] (Eval without the mask); 0 for delta-only kernels.
    virtual SampledSpectrum EvalContinuous(const Vec3 &wo) const {
        (void)wo;
        return SampledSpectrum(0.0);
    }
    /// Footprint-aware kernels: the continuous lobes' value for the incident wave w.
    virtual SampledSpectrum EvalContinuousFrom(const Vec3 &wo, const IncidentWave &w) const {
        (void)w;
        return EvalContinuous(wo);
    }
    /// The continuous lobes' density [1/sr] (Pdf without the mask).
    virtual double PdfContinuous(const Vec3 &wo) const {
        (void)wo;
        return 0;
    }
    /// EvalContinuousFrom and PdfContinuous together; a kernel overrides it where the two share work.
    virtual KernelValue EvalPdfContinuous(const Vec3 &wo, const IncidentWave &w) const {
        return KernelValue{EvalContinuousFrom(wo, w), PdfContinuous(wo)};
    }

    ScatterQuery q_;
    unsigned caps_ = 0;
    std::span<const NearDeltaLobe> lobes_;
    ContinuousLobeIds continuous_;
};

/// A diffraction kernel (a plug-in of family `material`): its parameters and what holds for every
/// query. Everything a query asks goes through Prepare (PreparedKernel). Properties that one client
/// alone reads are not here but facets that client asks for (the `aperture`'s openings for `rs`:
/// core/render/aperture.h; a smooth kernel's optics and a coating's layers for the kernels built on
/// them: materials/smooth_kernel.h; a grating's reference direction for `probe`:
/// ReferenceDirection below).
class Material {
  public:
    virtual ~Material() = default;

    /// The kernel prepared for query q, in `scratch`: valid until `scratch` is reset. Reads *q.gr
    /// and *q.si (when given) only here (see PreparedKernel).
    virtual const PreparedKernel &Prepare(const ScatterQuery &q, ScratchBuffer &scratch) const = 0;
    /// True if the kernel is footprint-aware for a generalized ray (CapFootprintAware for every
    /// wave-regime query; checked by the contract suite). Scene checks and `mix` ask without a query.
    virtual bool IsFootprintAware() const { return false; }
    /// True if some lobe's EvalLobe may report coherence terms (LobeCoherence::any: a coated
    /// surface, thin_film, multilayer); false promises that none does (checked by the contract
    /// suite), which lets a polarised integrator skip evaluating lobes whose response cannot matter.
    virtual bool HasCoherenceTerms() const { return false; }
    /// How `phasor probe` names near-delta lobe `id` in its "order" column: the kernel's own
    /// numbering of its lobes (a grating's diffraction order j on either side); by default the id.
    /// A composite that renumbers its children's lobes names the child and the child's own name
    /// ("b: -1"), never the renumbered id.
    virtual std::string LobeName(int id) const { return std::to_string(id); }
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
    /// True if some query's listing may hold a straight-through lobe (IsStraightThrough: the same
    /// index on both sides and no tangential shift — a free-standing film, an index-matched
    /// boundary). Shadow rays cross the surfaces of such kernels with that lobe's weight
    /// (Scene::Transmittance) and integrators never measure light through the lobe itself; false
    /// (the default) promises that no listing holds one (checked by the contract suite), so shadow
    /// rays stop at the surface.
    virtual bool MayPassStraight() const { return false; }
    virtual std::string ToString() const = 0;
};

/// True if `lobe`, listed for a query from `wi` (local), goes straight on: a transmission lobe
/// whose direction is −wi at every one of the `count` carried wavelengths (to 1e-12), with the same
/// index on both sides and no tangential shift. Its weight is then the surface's transmittance
/// along the line (the (η_i/η_t)² factor is 1).
bool IsStraightThrough(const NearDeltaLobe &lobe, const Vec3 &wi, int count);
/// Shadow rays cross `lobe` (listed by `mat` for a query from `wi`): `mat` declares
/// MayPassStraight and the lobe IsStraightThrough. Light is never measured through such a lobe,
/// and a path that leaves through it is not a new vertex for the light it finds (theory §3.5).
bool PassesStraight(const Material &mat, const NearDeltaLobe &lobe, const Vec3 &wi, int count);
/// The same for the lobe of id `lobeId` of k (prepared for `mat`).
bool PassesStraight(const Material &mat, const PreparedKernel &k, int lobeId);

/// The facet of a kernel with a reference direction in the tangent plane (a grating's grating
/// vector), from which `phasor probe` measures azimuths; composite kernels forward their children's.
class ReferenceDirection {
  public:
    /// The direction at `tex` as an angle [rad] counter-clockwise from the shading frame's x axis
    /// (dp/du), or nullopt where the kernel has none (a mix of two isotropic kernels).
    virtual std::optional<double> ReferenceAngle(const TextureEvalContext &tex) const = 0;

  protected:
    ~ReferenceDirection() = default;
};
/// m's reference angle at tex (ReferenceDirection), or nullopt for a kernel without one (isotropic).
std::optional<double> ReferenceAngleOf(const Material &m, const TextureEvalContext &tex);

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
/// Whether that lobe propagates (NearDeltaDirection's answer, without the direction).
bool NearDeltaPropagates(const Vec3 &wi, double nIn, double nOut, const Vec2 &shift, double lambda);
/// The orders j ∈ [−maxOrder, maxOrder] whose lobe of shift j·unit propagates: those for which
/// NearDeltaPropagates(wi, nIn, nOut, unit·double(j), λ) holds, found without asking every order.
/// They form an interval (the tangential wave vectors lie on a line, the propagating ones in a
/// disc): from the roots of |−nIn·wi.xy + j·unit·λ/2π|² = nOut², its ends settled by the predicate
/// itself. Empty when lo > hi.
struct OrderRange {
    int lo = 0, hi = -1;
    bool Contains(int j) const { return j >= lo && j <= hi; }
};
OrderRange PropagatingOrders(const Vec3 &wi, double nIn, double nOut, const Vec2 &unit, double lambda, int maxOrder);

/// A kernel's SampleLobes for lobes it has listed: picks lobe j with probability `prob` (u0) and
/// returns its hero direction with weight a_j/p_j (with `heroOnlyIfDispersive`, a dispersive lobe's
/// at the hero only: ScatterQuery::heroAfterDispersive), pdf p_j, its id, flags and η. Nullopt if no
/// lobe is listed or the pick has p = 0.
std::optional<ScatterSample> SampleListedLobe(std::span<const NearDeltaLobe> lobes, double u0, bool heroOnlyIfDispersive = false);

/// True if unit directions a and b agree to `tol` [rad] (EvalLobe's test for a near-delta lobe).
inline bool SameDirection(const Vec3 &a, const Vec3 &b, double tol = 1e-9) { return Length(a - b) <= tol; }

}  // namespace phasor
