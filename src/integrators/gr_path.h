// SPDX-License-Identifier: Apache-2.0
// phasor — the generalized-ray path sampler shared by `grt` and `sample_solve` (theory §3.3–3.4,
// §5.1): Algorithm 1 with next-event estimation, MIS, the closed-form measurements of theory §0
// D4a/D14 and Russian roulette, exactly as `grt` estimates a pixel (grt.cpp describes the
// estimator). It returns `grt`'s estimate and reports every *measurement event* — each term the
// estimate adds — to a Sink, with what a forward solve over the path needs (sample_solve.cpp):
//   * Detector       a camera GR measures a closed-form source in closed form (D4a/Eq. 24);
//   * Incidence      a sensor plane integrates a closed-form source over its directions (D4a);
//   * LobeIncidence  the same through a listed lobe of a planar near-delta surface (lobe_incidence.h);
//   * Emission       the path hits an area light (L_e, MIS-weighted);
//   * Escape         the path escapes to the infinite lights (Le, MIS-weighted);
//   * DirectLight    next-event estimation through the continuous lobes at a vertex;
//   * ThroughLobe    a closed-form source measured through a listed near-delta lobe at a vertex (D14).
//
// The estimate is one pass over the path in named steps (PathEstimate below; pbrt-v4's Li and
// SampleLd): MeasureAtDetector (the primary GR's closed-form measurements), FoundEmission (emission
// where the path hits an area light or escapes), DirectLight (NEE), ThroughListedLobes (D14),
// EmissionThroughListedLobes (area lights met along the listed lobes; `grt` only, with a sink that
// does not record, GrPathSampler::SetListedEmission) and Continue (the sampled lobe, Russian
// roulette). Each step computes each term once, adds it to the estimate and reports it as an event;
// a Sink that does not record (`grt`'s NullSink) has the reports compiled away. The estimate groups
// some terms before multiplying by the throughput (T·Σ_lights M, T·Σ_j d_j/n) where each event
// carries its own product (T·M_l), so the events sum to the estimate up to rounding (gr_path_test
// checks it sample by sample on every validation scene).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <list>
#include <memory>
#include <mutex>
#include <vector>

#include "core/render/lobe_average.h"
#include "core/render/path_common.h"
#include "integrators/fsd/fsd_kernel.h"
#include "integrators/lobe_incidence.h"

namespace phasor::grpath {

/// The query a GR `gr` (tracing direction into the surface) makes at the hit `si`: its footprint
/// (hero β for textures) unless it is spread-free (`rayOptics`, a classical ray). Its pointers refer
/// to si, gr and wl.
inline ScatterQuery GrQuery(const SurfaceInteraction &si, const SpectralGenRay &gr, bool rayOptics,
                            const SampledWavelengths &wl) {
    ScatterQuery q;
    q.wi = si.shading.ToLocal(-gr.d);
    q.wl = &wl;
    q.rayOptics = rayOptics;  // a spread-free GR continues as a classical ray (theory §9 item 5)
    q.heroAfterDispersive = true;  // PathEstimate::Continue drops the companions after a dispersive lobe
    q.tex = TextureEvalContext(si, rayOptics ? 0 : std::sqrt(gr.beta2[0]));  // hero footprint radius β
    q.gr = rayOptics ? nullptr : &gr;
    q.si = &si;
    return q;
}

/// One vertex of a sampled path: the hit, the GR arriving there (tracing direction gr.d into the
/// surface, footprint propagated to the hit), the kernel prepared there and the lobe the path left
/// through.
struct Vertex {
    SurfaceInteraction si;
    SpectralGenRay gr;
    const Material *mat = nullptr;
    /// The kernel prepared for the vertex's query (GrQuery(si, gr, rayOptics)), in the sample's
    /// scratch buffer: valid until the estimate returns.
    const PreparedKernel *kernel = nullptr;
    bool rayOptics = false;       // a spread-free GR: the kernel was asked in its ray-optics limit
    bool left = false;            // the path continued from here through `bs`
    ScatterSample bs;             // the sampled lobe (local wo, weight a_j/p_j or f|cos|/pdf, pdf, id, flags)
};

enum class EventKind { Detector, Incidence, LobeIncidence, Emission, Escape, DirectLight, ThroughLobe };

/// A measurement event (see the top of the file). Light flows from the light to the event's own
/// interaction (if any), then through the sampled lobes of vertices prefix−1, …, 0 to the detector.
/// Pointers are valid during Sink::OnEvent only.
struct Event {
    EventKind kind = EventKind::Detector;
    SampledSpectrum value;         // the term the estimate adds (throughput and 1/pdfs included)
    int prefix = 0;                // path vertices between the light (or the own interaction) and the detector
    const Light *light = nullptr;  // the light measured (nullptr on Escape: the sum of the infinite lights)
    /// The light's whole angular profile was integrated in closed form (Detector, Incidence,
    /// LobeIncidence, ThroughLobe); otherwise the path picked one point or direction of it.
    bool ensemble = false;
    /// The event's own interaction: DirectLight (all continuous lobes towards woLocal), ThroughLobe
    /// and LobeIncidence (lobe `lobe`); `at` is null for the other kinds.
    const SurfaceInteraction *at = nullptr;
    const SpectralGenRay *gr = nullptr;  // the GR arriving at `at` (tracing direction, footprint)
    /// The kernel prepared at `at` (DirectLight, ThroughLobe: the vertex's); null for LobeIncidence,
    /// whose hit the Newton solve of lobe_incidence.cpp found (prepare GrQuery(*at, *gr, rayOptics)).
    const PreparedKernel *kernel = nullptr;
    bool rayOptics = false;
    int lobe = -1;
    Vec3 woLocal;                  // at `at`: unit direction towards the light (local)
    /// ≥ 0: the event concerns this carried wavelength only (a dispersive lobe measured along that
    /// wavelength's own direction); −1: every carried wavelength.
    int wavelength = -1;
    /// World direction of travel of the light where it arrives at the first interaction of the
    /// chain (at `at`, else at vertex prefix−1, else at the detector).
    Vec3 travel;
    /// The distance the light travels to get there (Infinity for lights at infinity).
    double dist = Infinity;
    /// The light's angular profile as the closed form integrated it (ThroughLobe, LobeIncidence; about
    /// −travel, or its own centre): the ensemble the event's lobe is averaged over (theory §0 D15).
    AngularProfile profile;
};

/// The Sink interface (a template parameter of GrPathSampler::Estimate):
///   static constexpr bool Records;                         // record vertices and receive events
///   void OnEvent(const Event &, const std::vector<Vertex> &path, const DetectorGrSample &);
///   const Light *Measured(const Light *light, const Vec3 &p, const SampledWavelengths &wl);
/// Measured() may replace a closed-form light by another one (sample_solve's coherent modes) for
/// one measurement seen from p. A sink that does not record receives no event and no path.
struct NullSink {
    static constexpr bool Records = false;
    void OnEvent(const Event &, const std::vector<Vertex> &, const DetectorGrSample &) {}
    const Light *Measured(const Light *light, const Vec3 &, const SampledWavelengths &) { return light; }
};

/// The parameters of the path sampling (`grt`'s, which `sample_solve` shares): max_depth,
/// rr_depth, light_samples.
std::vector<ParamSpec> PathParams();
/// What the path sampling renders (integrator_support.h): every light (delta and distant ones in
/// closed form), detectors that generate generalized rays, every kernel as a GR sees it; no
/// polarisation (sample_solve adds it).
IntegratorSupport PathSupport();

/// The parameters of the path sampling and of free-space diffraction (fsd::Params()).
std::vector<ParamSpec> PathAndFsdParams();

/// The sampler: `grt`'s parameters and the per-scene D4a-through-lobes table.
class GrPathSampler {
  public:
    GrPathSampler(int maxDepth, int rrDepth, int lightSamples, const fsd::Settings &fsd = {},
                  LightSelection lights = LightSelection::Exhaustive)
        : maxDepth_(maxDepth), rrDepth_(rrDepth), lightSamples_(lightSamples), fsd_(fsd), lights_(lights) {}
    /// From the parameters of PathAndFsdParams().
    explicit GrPathSampler(const ParamDict &d);
    int MaxDepth() const { return maxDepth_; }
    int RrDepth() const { return rrDepth_; }
    int LightSamples() const { return lightSamples_; }
    /// How next-event estimation picks a light (`light_sampler`).
    LightSelection Lights() const { return lights_; }
    const fsd::Settings &Fsd() const { return fsd_; }
    /// Area emission through the listed near-delta lobes (`grt`): at each vertex every listed lobe
    /// that is the same at all carried wavelengths (not dispersive) and does not pass straight
    /// through a film is traced once, and the area light it meets is counted with the lobe's a_j —
    /// the expectation of what the path finds when it samples that lobe (a_j/p_j with probability
    /// p_j), whose hit emission is then not counted again. Off for integrators that record the
    /// sampled chain (sample_solve's forward solve): they find emission by the sampled lobe alone.
    void SetListedEmission(bool on) { listedEmission_ = on; }
    bool ListedEmission() const { return listedEmission_; }
    /// `max_depth = …, rr_depth = …, light_samples = …, fsd = …` for ToString.
    std::string ParamString() const;
    /// Integrator::Validate's part for FSD: with `fsd = false` a note when the scene's longest
    /// wavelength is at least 10⁻³ of its size and opaque geometry could diffract (docs/fsd.md §6).
    void NoteFsd(const Scene &scene, Diagnostics &diag) const;

    /// `grt`'s estimate for pixel (x, y) (PixelIntegrator::EstimatePixel), reporting to `sink`.
    /// Kernels are prepared in `scratch` (the caller resets it between samples).
    template <class Sink>
    SampledSpectrum Estimate(const Scene &scene, int x, int y, SampledWavelengths &wl, Sampler &sampler,
                             ScratchBuffer &scratch, PathStats &stats, Sink &sink) const;

    /// D4a through listed lobes for the scene (an integrator belongs to one scene): built on first use.
    const LobeIncidence &Lobes(const Scene &scene) const {
        std::call_once(lobesOnce_, [&] { lobes_ = std::make_unique<const LobeIncidence>(scene); });
        return *lobes_;
    }
    /// The shapes that cast FSD shadows in the scene: built on first use.
    const fsd::Occluders &FsdOccluders(const Scene &scene) const {
        std::call_once(occludersOnce_, [&] { occluders_ = std::make_unique<const fsd::Occluders>(scene); });
        return *occluders_;
    }

    // ---- helpers of the estimate ----------------------------------------------------------------
    /// Drops the companion wavelengths from the throughput (theory §0 D10); false for a line sample.
    static bool DropCompanions(SampledSpectrum &T, const SampledWavelengths &wl);
    /// One closed-form light seen by the GR g (traced; measured as its time reverse `reversed` =
    /// g.TimeReversed(), D3) from g's origin (from the surface `si` when g leaves one): its k²·M
    /// times the transmittance of the way there (Transmitted), or nullopt if nothing arrives.
    static std::optional<GrMeasurement> MeasureOne(const Scene &scene, const Light &light, const SpectralGenRay &g,
                                                   const SpectralGenRay &reversed, const SurfaceInteraction *si,
                                                   const SampledWavelengths &wl,
                                                   ScratchBuffer &scratch, PathStats &stats);
    /// The shadow ray of MeasureOne, from g's origin (or si) towards the measurement m's source:
    /// 0 if blocked, else the product of the straight-through surfaces' weights on the way
    /// (Scene::Transmittance), each averaged over the plane waves m integrates as the GR aimed
    /// at the source meets it (ThroughLobeWeight, theory §0 D15) — what measuring m through that
    /// surface's lobe at a vertex of its own would weigh it by.
    static SampledSpectrum Transmitted(const Scene &scene, const GrMeasurement &m, const SpectralGenRay &g,
                                       const SurfaceInteraction *si, const SampledWavelengths &wl,
                                       ScratchBuffer &scratch, PathStats &stats);
    /// The time reverse (what a light's MeasureGR takes) of the GR leaving `si` through listed lobe
    /// `lobe` at carried wavelength i (g redirected along it, every wavenumber scaled by its η, from
    /// the spawn origin), written into `rev`, which must hold g.TimeReversed() with pixel.valid =
    /// false or an earlier result of this call for the same g: only the direction, the wavenumbers
    /// and the origin change. rev.TimeReversed() is the GR leaving along the lobe. `origins`:
    /// si.SpawnOrigin towards +si.n and towards −si.n (it depends on the direction only so).
    /// `revEta`: the η rev's wavenumbers carry (g's times it; NaN for none yet), kept up to date
    /// here — the wavenumbers are written only when the lobe's η differs.
    static void ReversedAlongLobe(SpectralGenRay &rev, const SpectralGenRay &g, const SurfaceInteraction &si,
                                  const std::array<Vec3, 2> &origins, const NearDeltaLobe &lobe, int i,
                                  double &revEta);
    /// True if the lobe's direction and index are the same at every carried wavelength.
    static bool UniformLobe(const NearDeltaLobe &lobe, const SampledWavelengths &wl);
    /// ⟨a_j⟩ for a closed-form measurement `m` through listed lobe `lobe` of k (the kernel prepared
    /// at si for the GR g arriving there): the lobe's weight averaged over the product of the
    /// measurement's light profile and the outgoing GR's angular spectrum (theory §0 D15,
    /// core/render/lobe_average.h); for `wavelength` only when ≥ 0.
    static SampledSpectrum ThroughLobeWeight(const SurfaceInteraction &si, const PreparedKernel &k,
                                             const SpectralGenRay &g, const NearDeltaLobe &lobe,
                                             const GrMeasurement &m, int wavelength);

  private:
    int maxDepth_, rrDepth_, lightSamples_;
    fsd::Settings fsd_;
    LightSelection lights_;
    bool listedEmission_ = false;
    mutable std::once_flag lobesOnce_, occludersOnce_;
    mutable std::unique_ptr<const LobeIncidence> lobes_;
    mutable std::unique_ptr<const fsd::Occluders> occluders_;
};

// ---- the estimate ---------------------------------------------------------------------------------

/// One pixel sample's estimate: the state its steps share and the steps, in the order Run takes
/// them (see the top of the file).
template <class Sink>
class PathEstimate {
  public:
    PathEstimate(const GrPathSampler &paths, const Scene &scene, SampledWavelengths &wl, Sampler &sampler,
                 ScratchBuffer &scratch, PathStats &stats, Sink &sink)
        : paths_(paths), scene_(scene), wl_(wl), sampler_(sampler), scratch_(scratch), stats_(stats), sink_(sink) {}

    SampledSpectrum Run(int x, int y);

  private:
    /// The primary GR's closed-form measurements (theory §0 D4a): a sensor plane integrates every
    /// closed-form source over its directions, directly and through the listed lobes of planar
    /// near-delta surfaces (LobeIncidence); a camera GR measures each in closed form (Eq. 24).
    void MeasureAtDetector();
    /// Emission the path meets after `depth` vertices, arriving along −g.d (a hit area light, or the
    /// infinite lights on escape), MIS-weighted by the caller.
    void FoundEmission(EventKind kind, const SampledSpectrum &le, int depth, const Light *light, double dist);
    /// Next-event estimation through the continuous lobes at the vertex (si, k): `light_samples`
    /// estimates, their light positions on a rotated m×m lattice when the count is a square m²
    /// (stratified), else independent.
    /// With skipClosedForm the lights measured in closed form are left out (the GR measured them).
    void DirectLight(const SurfaceInteraction &si, const PreparedKernel &k, int depth, bool skipClosedForm = false);
    /// D14 through every listed near-delta lobe at the vertex: delta and small sources (plane waves,
    /// lasers, point and spot lights, the sun) measured in closed form along each lobe, weighted by
    /// its a_j averaged over the plane waves each measurement integrates (ThroughLobeWeight, D15);
    /// a dispersive lobe per carried wavelength along its own direction.
    void ThroughListedLobes(const SurfaceInteraction &si, const PreparedKernel &k, int depth);
    /// Area emission through the listed non-dispersive near-delta lobes at the vertex
    /// (GrPathSampler::SetListedEmission); remembers which lobes it traced for Continue.
    void EmissionThroughListedLobes(const SurfaceInteraction &si, const PreparedKernel &k, int depth);
    /// Samples one lobe at the vertex and turns the GR into it (theory §3.3, S6.4); Russian roulette.
    /// False if the path ends here.
    bool Continue(const SurfaceInteraction &si, const PreparedKernel &k, int depth);

    /// Free-space diffraction on the segment the current GR g_ is about to travel (docs/fsd.md §8),
    /// `si` its mean ray's hit. Pass: no event (or the segment ends in an ordinary hit, si as it
    /// may have been replaced by the covered share's hit); Scattered: the open share left through
    /// the event's lobe (a vertex at `depth`); Ended: the path ends.
    enum class FsdStep { Pass, Scattered, Ended };
    FsdStep FreeSpaceDiffraction(std::optional<SurfaceInteraction> &si, int depth);
    /// A closed-form wave arriving along −wi from distance `dist` at the GR g (from its origin, or
    /// from the surface si), with an FSD event on the way: nullopt without an event (the caller's
    /// shadow ray decides), else the factor the measurement keeps (fsd::Transmission; 0 if
    /// blocked).
    std::optional<SampledSpectrum> FsdTransmission(const SpectralGenRay &g, const Vec3 &wi, double dist,
                                                   const SurfaceInteraction *si);

    /// Σ over the closed-form lights of their terms value(m), m what the GR `out` measures of each
    /// from `from` (MeasureOne; from the surface `si` when it leaves one), each light's term reported
    /// through event(light, ensemble, m, term) (an Event, or nullopt to report nothing).
    /// `reversed` is out.TimeReversed() (what each light measures, D3), made once by the caller.
    /// Lights with skip(index in Scene::ClosedFormLights()) true are left out.
    template <class Value, class MakeEvent, class Skip = bool (*)(std::size_t)>
    SampledSpectrum ClosedForm(const SpectralGenRay &out, const SpectralGenRay &reversed, const SurfaceInteraction *si,
                               const Vec3 &from, Value &&value, MakeEvent &&event,
                               Skip &&skip = [](std::size_t) { return false; });
    /// Reports the event `make()` builds, if the sink records.
    template <class Make>
    void Report(Make &&make) {
        if constexpr (Sink::Records)
            if (std::optional<Event> e = make()) sink_.OnEvent(*e, path_, *ds_);
    }

    const GrPathSampler &paths_;
    const Scene &scene_;
    SampledWavelengths &wl_;
    Sampler &sampler_;
    ScratchBuffer &scratch_;
    PathStats &stats_;
    Sink &sink_;

    std::optional<DetectorGrSample> ds_;
    SpectralGenRay g_;                     // the path's current GR (tracing direction, footprint)
    SampledSpectrum T_, L_;                // throughput and estimate
    bool measured_ = false;                // a measurement (NEE or closed form) happened: RR may start
    std::vector<Vertex> path_;             // the recorded vertices (recording sinks only)
    path::MisState mis_;                   // the detector counts as a delta vertex
    bool closedFormDone_ = true;           // the current GR has measured the closed-form sources
    /// The lobes EmissionThroughListedLobes traced at the current vertex, and whether the GR now
    /// follows one of them (then the emission at its next hit was counted already).
    static constexpr int MaxListedEmission = 8;
    std::array<int, MaxListedEmission> listedEmissionLobes_{};
    int listedEmissionCount_ = 0;
    bool emissionListed_ = false;
    /// After a footprint-aware kernel the GR is spread-free (theory §9 item 5): its angular spread
    /// is inside that kernel's lobe, so later vertices see a classical ray (near-delta lobes become
    /// deltas, delta sources are not measured again, area and distant sources by direction only).
    bool spreadFree_ = false;
    bool companionsDropped_ = false;
    /// The last sample of a footprint-aware kernel (theory §9), until its ray hits something: its
    /// response depends on the incident wave's curvature (EvalFrom), and its Sample weight assumed
    /// a plane wave. f = the sample's Eval (plane wave).
    struct {
        const PreparedKernel *kernel = nullptr;
        Vec3 wo;  // local
        SampledSpectrum f;
    } footprint_;
    /// FSD events of this sample (their kernels are the path's vertices until Run returns; a list:
    /// stable references, and no allocation for a sample without events — std::deque allocates
    /// its map and a block when constructed, ~4 % of a boa sample's instructions).
    std::list<fsd::EventKernel> fsdEvents_;
    const Shape *leaving_ = nullptr;  // the shape the current GR leaves (not an FSD occluder for it)
};

template <class Sink>
SampledSpectrum GrPathSampler::Estimate(const Scene &scene, int x, int y, SampledWavelengths &wl, Sampler &sampler,
                                        ScratchBuffer &scratch, PathStats &stats, Sink &sink) const {
    return PathEstimate<Sink>(*this, scene, wl, sampler, scratch, stats, sink).Run(x, y);
}

template <class Sink>
SampledSpectrum PathEstimate<Sink>::Run(int x, int y) {
    // Lobe averages whose quadrature hit its cap (theory §4.11) during this sample, counted for the
    // render's warnings (the sink's solves included).
    struct CappedAverages {
        PathStats &stats;
        long long before = LobeAverageCost().capped;
        ~CappedAverages() { stats.counters.Add(RenderEvent::LobeAverageCapped, LobeAverageCost().capped - before); }
    } cappedAverages{stats_};
    ds_ = scene_.GetDetector().GenerateGR(x, y, stats_.sample, sampler_, wl_);
    if (!ds_) return SampledSpectrum(0.0);
    g_.o = ds_->ray.o;
    g_.d = ds_->ray.d;
    g_.count = wl_.Count();
    for (int i = 0; i < g_.count; ++i) {
        g_.k[i] = 2 * Pi / wl_.lambda[i];  // detectors sit in vacuum/air (η = 1)
        g_.beta2[i] = ds_->beta2[i];
        g_.rho[i] = ds_->rho[i];
    }
    g_.pixel = ds_->pixel;
    T_ = SampledSpectrum(ds_->weight);
    MeasureAtDetector();
    measured_ = true;
    if (!(ds_->weight > 0)) return L_;

    const int maxDepth = paths_.MaxDepth();
    for (int depth = 0;; ++depth) {
        ++stats_.rays;
        auto si = scene_.Intersect(g_.MeanRay());
        // A pixel state whose ray only aims it at an aperture plate (PixelState::labelOnly) is
        // measured by a footprint-aware kernel alone.
        if (g_.pixel.LabelOnly() && !(si && si->material && si->material->IsFootprintAware())) break;
        // Free-space diffraction at edges inside the footprint (docs/fsd.md §8); a spread-free GR
        // is a classical ray and shadows sharply.
        if (paths_.Fsd().enabled && !spreadFree_ && depth != maxDepth) {
            const FsdStep step = FreeSpaceDiffraction(si, depth);
            if (step == FsdStep::Scattered) continue;
            if (step == FsdStep::Ended) break;
        }
        if (!si) {
            const SampledSpectrum le = path::EscapedEmission(scene_, scene_.GetLightSampler(paths_.Lights()), g_.d, wl_, mis_, closedFormDone_);
            FoundEmission(EventKind::Escape, le, depth, nullptr, Infinity);
            break;
        }
        g_.Propagate(si->t);  // ABCD free-space update of every wavelength's footprint
        g_.o = si->p;
        if (footprint_.kernel) {
            // The footprint-aware lobe was sampled as a response to a plane wave; light from this
            // hit arrives as a spherical wave from distance t (the same integrand as NEE, EvalFrom):
            // re-weight the throughput by EvalFrom(t)/Eval.
            const SampledSpectrum from = footprint_.kernel->EvalFrom(footprint_.wo, IncidentWave{si->t});
            SampledSpectrum r(0.0);
            for (int i = 0; i < NumWavelengths; ++i) r[i] = footprint_.f[i] > 0 ? from[i] / footprint_.f[i] : 0;
            T_ *= r;
            footprint_.kernel = nullptr;
        }
        if (!emissionListed_)
            FoundEmission(EventKind::Emission, path::HitEmission(scene_.GetLightSampler(paths_.Lights()), *si, g_.d, wl_, mis_),
                          depth, si->areaLight, si->t);
        const Material *mat = si->material;
        if (!mat || depth == maxDepth) break;

        const PreparedKernel &k = mat->Prepare(GrQuery(*si, g_, spreadFree_, wl_), scratch_);
        if constexpr (Sink::Records) {
            Vertex v;
            v.si = *si;
            v.gr = g_;
            v.mat = mat;
            v.kernel = &k;
            v.rayOptics = spreadFree_;
            path_.push_back(v);
        }
        if (spreadFree_ && mat->IsFootprintAware()) stats_.counters.Add(RenderEvent::FootprintAfterSpreadFree);
        DirectLight(*si, k, depth);
        ThroughListedLobes(*si, k, depth);
        EmissionThroughListedLobes(*si, k, depth);
        if (!Continue(*si, k, depth)) break;
        leaving_ = si->shape;
    }
    return L_;
}

template <class Sink>
typename PathEstimate<Sink>::FsdStep PathEstimate<Sink>::FreeSpaceDiffraction(std::optional<SurfaceInteraction> &si,
                                                                              int depth) {
    fsd::Event ev;
    const fsd::Settings &settings = paths_.Fsd();
    if (fsd::FindEvent(scene_, paths_.FsdOccluders(scene_), g_, si ? si->t : Infinity, leaving_, settings, &ev) !=
        fsd::Search::Event)
        return FsdStep::Pass;  // nothing in the footprint, or all of it: the ordinary hit  // nothing in the footprint, or all of it: the ordinary hit
    const double covered = ev.coveredFraction;
    const fsd::EventKernel &k = fsdEvents_.emplace_back(std::move(ev), g_, wl_, settings);
    const SurfaceInteraction &at = k.Interaction();
    const SpectralGenRay arriving = g_;
    g_ = k.Gr();
    if constexpr (Sink::Records) {
        Vertex v;
        v.si = at;
        v.gr = g_;
        v.kernel = &k;
        path_.push_back(v);
    }
    // Light through the open share: NEE through the lobe, f·cos·E (the closed-form lights this GR
    // has measured already are left out: they were scaled by fsd::Transmission).
    DirectLight(at, k, depth, closedFormDone_);
    // The covered share goes on to the geometry, the open one leaves through the lobe: one of them,
    // with the probabilities of their |ψ|² shares.
    const double u = sampler_.Get1D();
    const Vec2 u2 = sampler_.Get2D();
    if (u < covered) {
        if constexpr (Sink::Records) path_.pop_back();
        double w = 0;
        const std::optional<Vec2> x = fsd::SampleCovered(k.GetEvent(), u / covered, u2, &w);
        if (!x) return FsdStep::Ended;
        // A ray of the covered share: the segment's origin moved across to the sampled point.
        const Frame &f = k.GetEvent().frame;
        g_ = arriving;
        g_.o += f.s * x->x + f.t * x->y;
        T_ *= w;
        ++stats_.rays;
        si = scene_.Intersect(g_.MeanRay());
        return FsdStep::Pass;
    }
    T_ /= 1 - covered;
    // The lobe's GR is spread-free; it measures no closed-form light this GR has measured.
    const bool closedFormDone = closedFormDone_;
    if (!Continue(at, k, depth)) return FsdStep::Ended;
    closedFormDone_ = closedFormDone;
    leaving_ = nullptr;
    return FsdStep::Scattered;
}

template <class Sink>
std::optional<SampledSpectrum> PathEstimate<Sink>::FsdTransmission(const SpectralGenRay &g, const Vec3 &wi, double dist,
                                                                   const SurfaceInteraction *si) {
    // The GR aimed at the source (its footprint kept), on its way there.
    SpectralGenRay h = g;
    h.Redirect(wi, 1);
    h.o = si ? si->SpawnOrigin(wi) : g.o;
    double tEnd = dist;
    if (auto hit = scene_.Intersect(h.MeanRay())) tEnd = std::min(tEnd, hit->t);
    fsd::Event ev;
    const fsd::Settings &settings = paths_.Fsd();
    const fsd::Search r = fsd::FindEvent(scene_, paths_.FsdOccluders(scene_), h, tEnd, si ? si->shape : nullptr,
                                         settings, &ev, nullptr, dist);
    if (r == fsd::Search::None) return std::nullopt;
    if (r == fsd::Search::Blocked) return SampledSpectrum(0.0);
    // A source closer than 4ϱ to the event: its spherical wave is not paraxial over the footprint
    // (docs/fsd.md §5); measured as without FSD.
    if (dist - ev.t < 4 * ev.halfWidth) return std::nullopt;
    // The rest of the way, from the far side of the event's geometry (fsd_kernel.h); nothing is
    // left when the source lies within it.
    const double from = ev.t + fsd::LeaveDistance(ev);
    SampledSpectrum beyond(1.0);
    if (from < dist) {
        beyond = scene_.Transmittance(Ray{h.o + wi * from, wi}, std::isinf(dist) ? Infinity : (dist - from) * (1 - 1e-7),
                                      wl_, false, scratch_, stats_.rays);
        if (beyond.IsZero()) return beyond;
    }
    h.Propagate(ev.t);
    h.o = ev.p;
    return beyond * fsd::Transmission(ev, h, wl_, settings, wi, IncidentWave{dist - ev.t});
}

template <class Sink>
void PathEstimate<Sink>::MeasureAtDetector() {
    if (!ds_->integratesIncidence) {
        if (scene_.ClosedFormLights().empty()) return;  // nothing to measure (and no GR to reverse)
        const SampledSpectrum m = ClosedForm(
            g_, g_.TimeReversed(), nullptr, g_.o, [](const GrMeasurement &mi) { return mi.value; },
            [&](const Light *light, bool ensemble, const GrMeasurement &mi, const SampledSpectrum &) {
                Event e;
                e.kind = EventKind::Detector;
                e.value = T_ * mi.value;
                e.light = light;
                e.ensemble = ensemble;
                e.travel = -mi.wi;
                e.dist = mi.dist;
                return std::optional<Event>(e);
            });
        L_ += T_ * m;
        return;
    }
    // A sensor plane integrates each closed-form source over its directions (D4a)…
    for (const Light *sceneLight : scene_.ClosedFormLights()) {
        const Light *light = sink_.Measured(sceneLight, g_.o, wl_);
        auto inc = light->IncidenceOnGR(g_, wl_);
        if (!inc || inc->irradiance.IsZero()) continue;
        SampledSpectrum v = scene_.GetDetector().IntegrateIncidence(*ds_, *inc);
        if (v.IsZero()) continue;
        // Through an FSD event on the way, else the shadow ray. The event's transmission is taken
        // for a GR of the pixel's sensitivity width σ_pix (β² = β_D²/2): its overlap weights the
        // interference of the incident and diffracted waves as the pixel's integral of |U|² does
        // (docs/fsd.md §5).
        std::optional<SampledSpectrum> fsdT;
        if (paths_.Fsd().enabled) {
            SpectralGenRay pixel = g_;
            for (int i = 0; i < pixel.count; ++i) pixel.beta2[i] *= 0.5;
            fsdT = FsdTransmission(pixel, inc->wi, inc->dist, nullptr);
        }
        // Or crosses the straight-through surfaces on the way (Scene::Transmittance), each lobe's
        // weight averaged over the source's profile as D4a through it would (D15, as LobeIncidence).
        if (fsdT) {
            v *= *fsdT;
        } else {
            const auto averaged = [&](const SurfaceInteraction &at, const PreparedKernel &k, const NearDeltaLobe &l,
                                      double) {
                return AverageLobeWeight(*at.material, k, l, SourceEnsemble(at.shading, inc->wi, inc->profile),
                                         LobeTransfer::Irradiance, -1);
            };
            v *= scene_.Transmittance(Ray{g_.o, inc->wi}, inc->dist * (1 - 1e-7), wl_, false, scratch_, stats_.rays,
                                      averaged);
        }
        if (v.IsZero()) continue;
        L_ += v;
        Report([&] {
            Event e;
            e.kind = EventKind::Incidence;
            e.value = v;
            e.light = sceneLight;
            e.ensemble = light == sceneLight;
            e.travel = -inc->wi;
            e.dist = inc->dist;
            return std::optional<Event>(e);
        });
    }
    // …and through every listed lobe of a planar near-delta surface (D4a through lobes).
    const LobeIncidence &lobes = paths_.Lobes(scene_);
    if (lobes.Empty()) return;
    if constexpr (Sink::Records) {
        const LobeIncidence::Report onLobe = [&](const LobeIncidence::Contribution &c) {
            Report([&] {
                Event e;
                e.kind = EventKind::LobeIncidence;
                e.value = c.value;
                e.light = c.light;
                e.ensemble = c.ensemble;
                e.at = c.si;
                e.gr = c.gr;
                e.rayOptics = false;
                e.lobe = c.lobe;
                e.woLocal = c.woLocal;
                e.wavelength = c.wavelength;
                e.travel = c.travel;
                e.dist = c.dist;
                e.profile = c.profile;
                return std::optional<Event>(e);
            });
        };
        const LobeIncidence::ModeOf mode = [&](const Light *l, const Vec3 &p) { return sink_.Measured(l, p, wl_); };
        L_ += lobes.Integrate(scene_, *ds_, g_, wl_, scratch_, stats_, &onLobe, &mode);
    } else {
        L_ += lobes.Integrate(scene_, *ds_, g_, wl_, scratch_, stats_);
    }
}

template <class Sink>
void PathEstimate<Sink>::FoundEmission(EventKind kind, const SampledSpectrum &le, int depth, const Light *light,
                                       double dist) {
    L_ += T_ * le;
    Report([&]() -> std::optional<Event> {
        if (le.IsZero()) return std::nullopt;
        Event e;
        e.kind = kind;
        e.value = T_ * le;
        e.prefix = depth;
        e.light = light;
        e.travel = -g_.d;
        e.dist = dist;
        return e;
    });
}

template <class Sink>
void PathEstimate<Sink>::DirectLight(const SurfaceInteraction &si, const PreparedKernel &k, int depth,
                                     bool skipClosedForm) {
    // The light samples are drawn even when unused, to keep the sampler's dimensions aligned.
    const double uLight = sampler_.Get1D();
    const Vec2 uLightPos = sampler_.Get2D();
    if (!(k.Capabilities() & CapContinuous)) return;
    const int n = paths_.LightSamples();
    const int m = int(std::lround(std::sqrt(double(n))));
    SampledSpectrum direct(0.0);
    for (int j = 0; j < n; ++j) {
        Vec2 u = uLightPos;
        double ul = uLight;
        if (j > 0 && m * m == n) {
            u = Vec2(std::fmod(uLightPos.x + double(j % m) / m, 1.0), std::fmod(uLightPos.y + double(j / m) / m, 1.0));
            ul = std::fmod(uLight + double(j) / n, 1.0);
        } else if (j > 0) {
            ul = sampler_.Get1D();
            u = sampler_.Get2D();
        }
        path::DirectLightInfo info;
        SampledSpectrum d = path::SampleDirectLight(scene_, si, k, scene_.GetLightSampler(paths_.Lights()), ul, u, wl_, stats_,
                                                    scratch_, spreadFree_, &info);
        if (skipClosedForm && info.light && info.light->MeasuredInClosedForm()) d = SampledSpectrum(0.0);
        direct += d;
        Report([&]() -> std::optional<Event> {
            if (d.IsZero()) return std::nullopt;
            Event e;
            e.kind = EventKind::DirectLight;
            e.value = T_ * d / double(n);
            e.prefix = depth;
            e.light = info.light;
            e.at = &si;
            e.gr = &g_;
            e.kernel = &k;
            e.rayOptics = spreadFree_;
            e.woLocal = si.shading.ToLocal(info.wi);
            e.travel = -info.wi;
            e.dist = info.dist;
            return e;
        });
    }
    L_ += T_ * direct / double(n);
    measured_ = true;
}

template <class Sink>
void PathEstimate<Sink>::ThroughListedLobes(const SurfaceInteraction &si, const PreparedKernel &k, int depth) {
    // The path then follows one sampled lobe, which does not measure these sources again
    // (closedFormDone_). At a detector's first vertex on a surface LobeIncidence covers, they were
    // integrated over the detector's directions already.
    const bool integrated = depth == 0 && ds_->integratesIncidence && paths_.Lobes(scene_).Covers(si.shape);
    if (!(k.Capabilities() & CapNearDelta) || spreadFree_ || scene_.ClosedFormLights().empty() || integrated) return;
    // Most lobes point far from every small source: each light first says of the GR it would
    // measure (the time reverse of the one along the lobe, `probe`, changed in place per lobe and
    // wavelength) whether it certainly measures nothing (Light::MeasuresNothing), and the GR along
    // the lobe is built only for a lobe some light may reach (lights 0…63 of
    // Scene::ClosedFormLights(); later ones are always measured). No skipping with a recording
    // sink: it may measure another light in place of the scene's (Sink::Measured, sample_solve's
    // modes).
    const auto &lights = scene_.ClosedFormLights();
    SpectralGenRay probe = g_.TimeReversed();
    probe.pixel.valid = false;  // as Redirect
    const std::array<Vec3, 2> origins{si.SpawnOrigin(si.n), si.SpawnOrigin(-si.n)};
    double probeEta = std::numeric_limits<double>::quiet_NaN();  // no wavenumbers written yet
    for (const NearDeltaLobe &lobe : k.ListNearDelta()) {
        // Light straight through the surface was measured by the shadow rays of the vertex before,
        // which cross it (Scene::Transmittance, theory §3.5).
        if (PassesStraight(*si.material, lobe, k.Query().wi, wl_.Count())) continue;
        const bool uniform = GrPathSampler::UniformLobe(lobe, wl_);
        SampledSpectrum v(0.0);
        for (int i = 0; i < (uniform ? 1 : wl_.Count()) && lobe.MayCarryAny(); ++i) {
            if (!uniform && !lobe.MayCarry(i)) continue;
            const unsigned measured = uniform ? g_.measured : 1u << i;  // along λ_i's direction only λ_i is used (w[i] below)
            GrPathSampler::ReversedAlongLobe(probe, g_, si, origins, lobe, i, probeEta);
            probe.measured = measured;
            std::uint64_t skipped = 0;  // bit b: light b measures nothing
            if constexpr (!Sink::Records) {
                bool any = lights.size() > 64;  // some light may see the GR
                for (std::size_t b = 0; b < std::min<std::size_t>(lights.size(), 64); ++b) {
                    if (lights[b]->MeasuresNothing(probe)) skipped |= std::uint64_t(1) << b;
                    else any = true;
                }
                if (!any) continue;
            }
            if (!uniform && !(lobe.Weight(1u << i)[i] > 0)) continue;  // a deferred weight that came out 0
            const SpectralGenRay out = probe.TimeReversed();  // the GR leaving along the lobe
            // a_j·M per light, a_j averaged over the plane waves that light's measurement integrates
            // (ThroughLobeWeight; per wavelength along a dispersive lobe's own direction).
            auto weighted = [&](const GrMeasurement &mi) {
                const SampledSpectrum a = GrPathSampler::ThroughLobeWeight(si, k, g_, lobe, mi, uniform ? -1 : i);
                SampledSpectrum w(0.0);
                if (uniform) w = a * mi.value;
                else w[i] = a[i] * mi.value[i];
                return w;
            };
            v += ClosedForm(out, probe, &si, si.p, weighted,
                            [&](const Light *light, bool ensemble, const GrMeasurement &mi,
                                const SampledSpectrum &w) -> std::optional<Event> {
                                if (w.IsZero()) return std::nullopt;
                                Event e;
                                e.kind = EventKind::ThroughLobe;
                                e.value = T_ * w;
                                e.prefix = depth;
                                e.light = light;
                                e.ensemble = ensemble;
                                e.at = &si;
                                e.gr = &g_;
                                e.kernel = &k;
                                e.lobe = lobe.id;
                                e.woLocal = lobe.wo[i];
                                e.wavelength = uniform ? -1 : i;
                                e.travel = -mi.wi;
                                e.dist = mi.dist;
                                e.profile = mi.profile;
                                return e;
                            },
                            [&](std::size_t b) { return b < 64 && ((skipped >> b) & 1u); });
        }
        L_ += T_ * v;
    }
    measured_ = true;
}

template <class Sink>
void PathEstimate<Sink>::EmissionThroughListedLobes(const SurfaceInteraction &si, const PreparedKernel &k, int depth) {
    listedEmissionCount_ = 0;
    if constexpr (!Sink::Records) {
        // Where the sampled lobe's ray is not a plain ray to the next hit, the path keeps finding
        // emission by sampling: FSD on the way, a footprint-aware kernel (EvalFrom re-weighting), a
        // pixel state that only labels an aperture, a detector that integrated the lobes' incidence.
        if (!paths_.ListedEmission() || !(k.Capabilities() & CapNearDelta) || scene_.AreaLights().empty() ||
            paths_.Fsd().enabled || si.material->IsFootprintAware() || g_.pixel.LabelOnly() ||
            (depth == 0 && ds_->integratesIncidence && paths_.Lobes(scene_).Covers(si.shape)))
            return;
        SampledSpectrum v(0.0);
        for (const NearDeltaLobe &lobe : k.ListNearDelta()) {
            if (listedEmissionCount_ == MaxListedEmission) break;
            // A dispersive lobe would need a ray per wavelength; straight through a film the shadow
            // rays of the vertex before measured what lies beyond (theory §3.5): both stay sampled.
            if (!lobe.MayCarryAny() || !GrPathSampler::UniformLobe(lobe, wl_) ||
                PassesStraight(*si.material, lobe, k.Query().wi, wl_.Count()))
                continue;
            listedEmissionLobes_[std::size_t(listedEmissionCount_++)] = lobe.id;
            const Vec3 wo = si.shading.ToWorld(lobe.wo[0]);
            ++stats_.rays;
            const std::optional<SurfaceInteraction> hit = scene_.Intersect(Ray{si.SpawnOrigin(wo), wo});
            if (!hit || !hit->areaLight) continue;
            // As the path would find it after this lobe: L_e in full (no MIS after a near-delta lobe).
            v += lobe.Weight() * hit->areaLight->L(hit->p, hit->n, -wo, wl_);
        }
        L_ += T_ * v;
    }
}

template <class Sink>
bool PathEstimate<Sink>::Continue(const SurfaceInteraction &si, const PreparedKernel &k, int depth) {
    // A sampled direction at the last vertex can only find emission; without emitters a ray can
    // hit (only delta lights), it would contribute nothing.
    if (depth + 1 == paths_.MaxDepth() && scene_.HittableEmitters().empty()) return false;
    // One term of the Eq. 22 mixture: the GR keeps β, ρ; its mean direction turns and |k|
    // follows the medium (S6.4). A sampled near-delta lobe keeps its weight at the GR's mean
    // direction (theory §0 D15): the detector's own direction sampling integrates the GR's spectrum
    // over what follows (measured by the mean ray: emitters, escapes, NEE after a later continuous
    // lobe), so averaging the lobe over the spectrum as well would smooth it twice (docs/accuracy.md).
    auto bs = k.Sample(sampler_.Get1D(), sampler_.Get2D());
    if (!bs || bs->weight.IsZero()) return false;
    // A dispersive lobe is followed at the hero wavelength only (D10). The companions are dropped
    // from the throughput (T[0]·N, the same bookkeeping as TerminateSecondary), not from `wl`: what
    // they collected up to here, including this vertex's closed-form measurement along their own
    // directions, stays in the estimate.
    if ((bs->flags & ScatterDispersive) && !companionsDropped_)
        companionsDropped_ = GrPathSampler::DropCompanions(T_, wl_);
    T_ *= bs->weight;
    if constexpr (Sink::Records) {
        path_.back().left = true;
        path_.back().bs = *bs;
    }
    if ((bs->flags & ScatterSpreadFree) && !spreadFree_) {
        // Footprint-aware: re-weighted by the distance its ray travels (Run).
        footprint_.kernel = &k;
        footprint_.wo = bs->wo;
        footprint_.f = bs->weight * (bs->pdf / std::max(std::abs(bs->wo.z), 1e-300));
    }
    const Vec3 wo = si.shading.ToWorld(bs->wo);
    g_.Redirect(wo, bs->eta);
    g_.o = si.SpawnOrigin(wo);
    const bool nearDelta = (bs->flags & ScatterNearDelta) != 0;
    emissionListed_ = nearDelta && std::find(listedEmissionLobes_.begin(), listedEmissionLobes_.begin() + listedEmissionCount_,
                                             bs->lobe) != listedEmissionLobes_.begin() + listedEmissionCount_;
    if (spreadFree_ && nearDelta && !scene_.DeltaLights().empty())
        stats_.counters.Add(RenderEvent::SpecularAfterSpreadFree);
    spreadFree_ = spreadFree_ || (bs->flags & ScatterSpreadFree) != 0;
    // Straight through a film the GR goes where the shadow rays of the vertex before went (they
    // cross it): what it finds beyond is weighed as that vertex's (MIS state, closed-form sources
    // measured or not; theory §3.5).
    if (!(nearDelta && PassesStraight(*si.material, k, bs->lobe))) {
        mis_ = path::MisState{nearDelta, bs->pdf, LightSampleContext{si.p, si.n}};
        // After a near-delta lobe of a GR the closed-form sources were measured at this vertex.
        closedFormDone_ = nearDelta && !spreadFree_;
    }
    return !(depth + 1 >= paths_.RrDepth() && measured_ && !path::RussianRoulette(T_, sampler_.Get1D()));
}

template <class Sink>
template <class Value, class MakeEvent, class Skip>
SampledSpectrum PathEstimate<Sink>::ClosedForm(const SpectralGenRay &out, const SpectralGenRay &reversed,
                                               const SurfaceInteraction *si, const Vec3 &from, Value &&value,
                                               MakeEvent &&event, Skip &&skip) {
    SampledSpectrum sum(0.0);
    const auto &lights = scene_.ClosedFormLights();
    for (std::size_t index = 0; index < lights.size(); ++index) {
        if (skip(index)) continue;
        const Light *sceneLight = lights[index];
        const Light *light = sink_.Measured(sceneLight, from, wl_);
        std::optional<GrMeasurement> m;
        if (paths_.Fsd().enabled) {
            // Through an FSD event on the way to the source, else the shadow ray.
            m = light->MeasureGR(reversed, wl_);
            if (!m || m->value.IsZero()) continue;
            if (auto fsdT = FsdTransmission(out, m->wi, m->dist, si)) m->value *= *fsdT;
            else m->value *= GrPathSampler::Transmitted(scene_, *m, out, si, wl_, scratch_, stats_);
            if (m->value.IsZero()) continue;
        } else {
            m = GrPathSampler::MeasureOne(scene_, *light, out, reversed, si, wl_, scratch_, stats_);
            if (!m) continue;
        }
        const SampledSpectrum v = value(*m);
        sum += v;
        Report([&] { return event(sceneLight, light == sceneLight, *m, v); });
    }
    return sum;
}

}  // namespace phasor::grpath
