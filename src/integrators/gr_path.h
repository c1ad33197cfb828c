// SPDX-License-Identifier: Apache-2.0
// phasor — the generalized-ray path sampler shared by `grt` and `sample_solve` (theory §3.3–3.4,
// §5.1): Algorithm 1 with next-event estimation, MIS, the closed-form measurements of theory §0
// D4a/D14 and Russian roulette, exactly as `grt` estimates a pixel (grt.cpp describes the
// estimator). It returns `grt`'s estimate and, for a Sink that asks for them, records the path's
// vertices and reports every *measurement event* — each term the estimate adds — with what a
// forward solve over the path needs (sample_solve.cpp):
//   * Detector       a camera GR measures a closed-form source in closed form (D4a/Eq. 24);
//   * Incidence      a sensor plane integrates a closed-form source over its directions (D4a);
//   * LobeIncidence  the same through a listed lobe of a planar near-delta surface (lobe_incidence.h);
//   * Emission       the path hits an area light (L_e, MIS-weighted);
//   * Escape         the path escapes to the infinite lights (Le, MIS-weighted);
//   * DirectLight    next-event estimation through the continuous lobes at a vertex;
//   * ThroughLobe    a closed-form source measured through a listed near-delta lobe at a vertex (D14).
// Each event's value is the term the estimate adds (throughput included), computed separately from
// the estimate (per light, per light sample), so a Sink that records changes nothing in it: the
// sum of the events equals the estimate up to rounding, and `grt` (NullSink) is the old loop.
#pragma once

#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "core/render/path_common.h"
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
    q.tex = TextureEvalContext(si, rayOptics ? 0 : std::sqrt(gr.beta2[0]));  // hero footprint radius β
    q.gr = rayOptics ? nullptr : &gr;
    q.si = &si;
    return q;
}

/// One vertex of a sampled path: the hit, the GR arriving there (tracing direction gr.d into the
/// surface, footprint propagated to the hit) and the lobe the path left through.
struct Vertex {
    SurfaceInteraction si;
    SpectralGenRay gr;
    const Material *mat = nullptr;
    bool rayOptics = false;       // a spread-free GR: the kernel was asked in its ray-optics limit
    bool left = false;            // the path continued from here through `bs`
    ScatterSample bs;             // the sampled lobe (local wo, weight a_j/p_j or f|cos|/pdf, pdf, id, flags)
    /// The query the sampler asked here (its pointers refer to this vertex and to wl).
    ScatterQuery Query(const SampledWavelengths &wl) const { return GrQuery(si, gr, rayOptics, wl); }
};

enum class EventKind { Detector, Incidence, LobeIncidence, Emission, Escape, DirectLight, ThroughLobe };

/// A measurement event (see the top of the file). Light flows from the light to the event's own
/// interaction (if any), then through the sampled lobes of vertices prefix−1, …, 0 to the detector.
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
    /// Per carried wavelength, the angular variance [rad²] of the Gaussian window through which a
    /// closed form measured the light (Detector, ThroughLobe: the GR's σ_k²/k², D14); Infinity where
    /// the detector integrates every direction of its acceptance (Incidence, LobeIncidence) or the
    /// path sampled the light.
    std::array<double, NumWavelengths> window = [] { std::array<double, NumWavelengths> a; a.fill(Infinity); return a; }();
};

/// Where a detector sample sits, for the polarisation frame of a forward solve.
struct DetectorView {
    const DetectorGrSample *ds = nullptr;
};

/// The Sink interface (a template parameter of GrPathSampler::Estimate):
///   static constexpr bool Records;                         // record vertices and report events
///   void OnEvent(const Event &, const std::vector<Vertex> &path, const DetectorGrSample &);
///   const Light *Measured(const Light *light, const Vec3 &p, const SampledWavelengths &wl);
/// Measured() may replace a closed-form light by another one (sample_solve's coherent modes) for
/// one measurement seen from p; it is asked only when Records.
struct NullSink {
    static constexpr bool Records = false;
    void OnEvent(const Event &, const std::vector<Vertex> &, const DetectorGrSample &) {}
    const Light *Measured(const Light *light, const Vec3 &, const SampledWavelengths &) { return light; }
};

/// The parameters of the path sampling (`grt`'s, which `sample_solve` shares): max_depth,
/// rr_depth, light_samples.
std::vector<ParamSpec> PathParams();

/// The sampler: `grt`'s parameters and the per-scene D4a-through-lobes table.
class GrPathSampler {
  public:
    GrPathSampler(int maxDepth, int rrDepth, int lightSamples)
        : maxDepth_(maxDepth), rrDepth_(rrDepth), lightSamples_(lightSamples) {}
    int MaxDepth() const { return maxDepth_; }
    int RrDepth() const { return rrDepth_; }
    int LightSamples() const { return lightSamples_; }

    /// `grt`'s estimate for pixel (x, y) (PixelIntegrator::EstimatePixel), reporting to `sink`.
    template <class Sink>
    SampledSpectrum Estimate(const Scene &scene, int x, int y, SampledWavelengths &wl, Sampler &sampler,
                             PathStats &stats, Sink &sink) const;

    /// Throws phasor::Error if the scene's detector cannot generate GRs; `integrator` names the caller.
    static void CheckDetector(const Scene &scene, const std::string &integrator);

    /// D4a through listed lobes for the scene (an integrator belongs to one scene): built on first use.
    const LobeIncidence &Lobes(const Scene &scene) const {
        std::call_once(lobesOnce_, [&] { lobes_ = std::make_unique<const LobeIncidence>(scene); });
        return *lobes_;
    }

    // ---- helpers shared with sample_solve -------------------------------------------------------
    static bool HasDeltaLights(const Scene &scene);
    static bool HasHittableEmitters(const Scene &scene);
    static bool HasClosedFormLights(const Scene &scene);
    /// Drops the companion wavelengths from the throughput (theory §0 D10); false for a line sample.
    static bool DropCompanions(SampledSpectrum &T, const SampledWavelengths &wl);

    /// One closed-form light seen by the GR g (traced; measured as its time reverse, D3) from g's
    /// origin (from the surface `si` when g leaves one): its k²·M if unoccluded, else nullopt.
    static std::optional<GrMeasurement> MeasureOne(const Scene &scene, const Light &light, const SpectralGenRay &g,
                                                   const SurfaceInteraction *si, const SampledWavelengths &wl,
                                                   PathStats &stats);
    /// Σ over closed-form lights of MeasureOne (grt's closed-form measurement).
    static SampledSpectrum MeasureClosedForm(const Scene &scene, const SpectralGenRay &g,
                                             const SurfaceInteraction *si, const SampledWavelengths &wl,
                                             PathStats &stats);
    /// The GR leaving `si` through listed lobe `lobe` at carried wavelength i.
    static SpectralGenRay AlongLobe(const SpectralGenRay &g, const SurfaceInteraction &si, const NearDeltaLobe &lobe,
                                    int i);
    /// True if the lobe's direction and index are the same at every carried wavelength.
    static bool UniformLobe(const NearDeltaLobe &lobe, const SampledWavelengths &wl);
    /// k²·M of the closed-form sources seen through one listed lobe, times its weight a_j (D14).
    static SampledSpectrum MeasureThroughLobe(const Scene &scene, const SpectralGenRay &g,
                                              const SurfaceInteraction &si, const NearDeltaLobe &lobe,
                                              const SampledWavelengths &wl, PathStats &stats);

  private:
    /// A sample of a footprint-aware kernel (theory §9) waiting for the distance to what its ray
    /// hits: the kernel's response depends on the incident wave's curvature (EvalFrom), and its
    /// Sample weight assumed a plane wave.
    struct FootprintSample {
        bool active = false;
        ScatterQuery q;
        SurfaceInteraction si;
        SpectralGenRay gr;
        const Material *mat = nullptr;
        Vec3 wo;            // local
        SampledSpectrum f;  // Eval(q, wo) (plane wave)
        void Remember(const ScatterQuery &query, const SurfaceInteraction &hit, const SpectralGenRay &g,
                      const Material &m, const ScatterSample &bs);
        /// EvalFrom(q, wo, dist) / Eval(q, wo) per wavelength (0 where Eval is 0).
        SampledSpectrum Correction(double dist) const;
    };

    int maxDepth_, rrDepth_, lightSamples_;
    mutable std::once_flag lobesOnce_;
    mutable std::unique_ptr<const LobeIncidence> lobes_;
};

// ---- the estimate ---------------------------------------------------------------------------------

template <class Sink>
SampledSpectrum GrPathSampler::Estimate(const Scene &scene, int x, int y, SampledWavelengths &wl, Sampler &sampler,
                                        PathStats &stats, Sink &sink) const {
    constexpr bool rec = Sink::Records;
    auto ds = scene.GetDetector().GenerateGR(x, y, stats.sample, sampler, wl);
    if (!ds) return SampledSpectrum(0.0);
    SpectralGenRay g;
    g.o = ds->ray.o;
    g.d = ds->ray.d;
    g.count = wl.Count();
    for (int i = 0; i < g.count; ++i) {
        g.k[i] = 2 * Pi / wl.lambda[i];  // detectors sit in vacuum/air (η = 1)
        g.beta2[i] = ds->beta2[i];
        g.rho[i] = ds->rho[i];
    }
    SampledSpectrum T(ds->weight), L(0.0);
    bool measured = false;  // a measurement (NEE or closed form) happened: RR may start
    // The recorded path (only with a recording sink), in a per-thread buffer reused across samples.
    thread_local std::vector<Vertex> pathBuffer;
    std::vector<Vertex> &path = pathBuffer;
    path.clear();
    auto report = [&](const Event &e) {
        if constexpr (rec) sink.OnEvent(e, path, *ds);
    };
    // An Emission or Escape event: light `le` met by the path after `depth` vertices, arriving along −g.d.
    auto reportFound = [&](EventKind kind, const SampledSpectrum &le, int depth, const Light *light, double dist) {
        if constexpr (rec) {
            if (le.IsZero()) return;
            Event e;
            e.kind = kind;
            e.value = T * le;
            e.prefix = depth;
            e.light = light;
            e.travel = -g.d;
            e.dist = dist;
            report(e);
        }
    };

    // Primary GRs facing closed-form sources (theory §0 D4a).
    if (ds->integratesIncidence) {
        for (const Light *sceneLight : scene.Lights()) {
            if (!sceneLight->MeasuredInClosedForm()) continue;
            const Light *light = rec ? sink.Measured(sceneLight, g.o, wl) : sceneLight;
            auto inc = light->IncidenceOnGR(g, wl);
            if (!inc || inc->irradiance.IsZero()) continue;
            const SampledSpectrum v = scene.GetDetector().IntegrateIncidence(*ds, *inc);
            if (v.IsZero()) continue;
            ++stats.rays;
            if (!scene.GetAccel().Occluded(Ray{g.o, inc->wi}, 0, inc->dist * (1 - 1e-7))) {
                L += v;
                if constexpr (rec) {
                    Event e;
                    e.kind = EventKind::Incidence;
                    e.value = v;
                    e.light = sceneLight;
                    e.ensemble = light == sceneLight;
                    e.travel = -inc->wi;
                    e.dist = inc->dist;
                    report(e);
                }
            }
        }
        // …and through every listed lobe of a planar near-delta surface (D4a through lobes).
        if (const LobeIncidence &lobes = Lobes(scene); !lobes.Empty()) {
            if constexpr (rec) {
                const LobeIncidence::Report onLobe = [&](const LobeIncidence::Contribution &c) {
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
                    report(e);
                };
                const LobeIncidence::ModeOf mode = [&](const Light *l, const Vec3 &p) {
                    return sink.Measured(l, p, wl);
                };
                L += lobes.Integrate(scene, *ds, g, wl, stats, &onLobe, &mode);
            } else {
                L += lobes.Integrate(scene, *ds, g, wl, stats);
            }
        }
    } else {
        if constexpr (rec) {
            // Per light, as MeasureClosedForm sums them.
            const SpectralGenRay physical = g.TimeReversed();
            for (const Light *sceneLight : scene.Lights()) {
                if (!sceneLight->MeasuredInClosedForm()) continue;
                const Light *light = sink.Measured(sceneLight, g.o, wl);
                auto m = light->MeasureGR(physical, wl);
                if (!m || m->value.IsZero()) continue;
                ++stats.rays;
                if (scene.GetAccel().Occluded(Ray{g.o, m->wi}, 0, m->dist * (1 - 1e-7))) continue;
                L += T * m->value;
                Event e;
                e.kind = EventKind::Detector;
                e.value = T * m->value;
                e.light = sceneLight;
                e.ensemble = light == sceneLight;
                e.travel = -m->wi;
                e.dist = m->dist;
                for (int i = 0; i < physical.count; ++i) e.window[std::size_t(i)] = physical.At(i).AngularVariance();
                report(e);
            }
        } else {
            L += T * MeasureClosedForm(scene, g, nullptr, wl, stats);
        }
    }
    measured = true;
    if (!(ds->weight > 0)) return L;

    path::MisState mis;          // the detector counts as a delta vertex
    bool closedFormDone = true;  // the current GR has measured the closed-form sources
    // After a footprint-aware kernel the GR is spread-free (theory §9 item 5): its angular
    // spread is inside that kernel's lobe, so later vertices see a classical ray (near-delta
    // lobes become deltas, delta sources are not measured again, area and distant sources by
    // direction only).
    bool spreadFree = false;
    FootprintSample footprint;  // the last spread-free sample, until its ray hits something
    auto skipClosedForm = [](const Light *l) { return l->MeasuredInClosedForm(); };
    const bool hasClosedForm = HasClosedFormLights(scene);
    bool companionsDropped = false;
    for (int depth = 0;; ++depth) {
        ++stats.rays;
        auto si = scene.Intersect(g.MeanRay());
        if (!si) {
            const SampledSpectrum le = closedFormDone ? path::EscapedEmission(scene, g.d, wl, mis, skipClosedForm)
                                                      : path::EscapedEmission(scene, g.d, wl, mis);
            L += T * le;
            reportFound(EventKind::Escape, le, depth, nullptr, Infinity);
            break;
        }
        g.Propagate(si->t);  // ABCD free-space update of every wavelength's footprint
        g.o = si->p;
        if (footprint.active) {
            // The footprint-aware lobe was sampled as a response to a plane wave; light from
            // this hit arrives as a spherical wave from distance t (the same integrand as
            // NEE, EvalFrom): re-weight the throughput by EvalFrom(t)/Eval.
            T *= footprint.Correction(si->t);
            footprint.active = false;
        }
        const SampledSpectrum le = path::HitEmission(scene, *si, g.d, wl, mis);
        L += T * le;
        reportFound(EventKind::Emission, le, depth, si->areaLight, si->t);
        const Material *mat = si->material;
        if (!mat || depth == maxDepth_) break;

        if constexpr (rec) {
            Vertex v;
            v.si = *si;
            v.gr = g;
            v.mat = mat;
            v.rayOptics = spreadFree;
            path.push_back(v);
        }
        const Frame &frame = si->shading;
        const ScatterQuery q = GrQuery(*si, g, spreadFree, wl);
        const unsigned caps = mat->Capabilities(q);
        if (spreadFree && mat->IsFootprintAware()) stats.counters.Add(RenderEvent::FootprintAfterSpreadFree);

        // Next-event estimation through the continuous lobes.
        const double uLight = sampler.Get1D();
        const Vec2 uLightPos = sampler.Get2D();
        if (caps & CapContinuous) {
            ScatterQuery qc = q;
            qc.lobes = LobeContinuous;  // near-delta lobes are measured in closed form below
            // `light_samples` estimates per vertex, their light positions on a rotated
            // m×m lattice when the count is a square m² (stratified), else independent.
            const int m = int(std::lround(std::sqrt(double(lightSamples_))));
            SampledSpectrum direct(0.0);
            for (int j = 0; j < lightSamples_; ++j) {
                Vec2 u = uLightPos;
                double ul = uLight;
                if (j > 0 && m * m == lightSamples_) {
                    u = Vec2(std::fmod(uLightPos.x + double(j % m) / m, 1.0),
                             std::fmod(uLightPos.y + double(j / m) / m, 1.0));
                    ul = std::fmod(uLight + double(j) / lightSamples_, 1.0);
                } else if (j > 0) {
                    ul = sampler.Get1D();
                    u = sampler.Get2D();
                }
                if constexpr (rec) {
                    path::DirectLightInfo info;
                    const SampledSpectrum d = path::SampleDirectLight(scene, *si, *mat, qc, ul, u, wl, stats, &info);
                    direct += d;
                    if (!d.IsZero()) {
                        Event e;
                        e.kind = EventKind::DirectLight;
                        e.value = T * d / double(lightSamples_);
                        e.prefix = depth;
                        e.light = info.light;
                        e.at = &path.back().si;
                        e.gr = &path.back().gr;
                        e.rayOptics = spreadFree;
                        e.woLocal = frame.ToLocal(info.wi);
                        e.travel = -info.wi;
                        e.dist = info.dist;
                        report(e);
                    }
                } else {
                    direct += path::SampleDirectLight(scene, *si, *mat, qc, ul, u, wl, stats);
                }
            }
            L += T * direct / double(lightSamples_);
            measured = true;
        }

        // D14 through every listed near-delta lobe: delta and small sources (plane waves, lasers,
        // point and spot lights, the sun) are measured in closed form along each lobe, weighted
        // by its a_j — all of a grating's orders show their glints in one sample. The path then
        // follows one sampled lobe, which does not measure them again (closedFormDone).
        // At a detector's first vertex on a surface LobeIncidence covers, this was integrated
        // over the detector's directions already.
        const bool lobesIntegrated = depth == 0 && ds->integratesIncidence && Lobes(scene).Covers(si->shape);
        if ((caps & CapNearDelta) && !spreadFree && hasClosedForm && !lobesIntegrated) {
            NearDeltaLobes lobes;
            mat->ListNearDelta(q, lobes);
            for (const NearDeltaLobe &lobe : lobes) {
                if constexpr (rec) {
                    // Per light and, for a dispersive lobe, per wavelength along its own direction.
                    if (lobe.weight.IsZero()) continue;
                    const bool uniform = UniformLobe(lobe, wl);
                    for (int i = 0; i < (uniform ? 1 : wl.Count()); ++i) {
                        if (!uniform && !(lobe.weight[i] > 0)) continue;
                        const SpectralGenRay out = AlongLobe(g, *si, lobe, i);
                        for (const Light *sceneLight : scene.Lights()) {
                            if (!sceneLight->MeasuredInClosedForm()) continue;
                            const Light *light = sink.Measured(sceneLight, si->p, wl);
                            auto m = MeasureOne(scene, *light, out, &*si, wl, stats);
                            if (!m) continue;
                            SampledSpectrum v(0.0);
                            if (uniform) v = lobe.weight * m->value;
                            else v[i] = lobe.weight[i] * m->value[i];
                            if (v.IsZero()) continue;
                            L += T * v;
                            Event e;
                            e.kind = EventKind::ThroughLobe;
                            e.value = T * v;
                            e.prefix = depth;
                            e.light = sceneLight;
                            e.ensemble = light == sceneLight;
                            e.at = &path.back().si;
                            e.gr = &path.back().gr;
                            e.lobe = lobe.id;
                            e.woLocal = lobe.wo[i];
                            e.wavelength = uniform ? -1 : i;
                            e.travel = -m->wi;
                            e.dist = m->dist;
                            for (int j = 0; j < out.count; ++j) e.window[std::size_t(j)] = out.At(j).AngularVariance();
                            report(e);
                        }
                    }
                } else {
                    L += T * MeasureThroughLobe(scene, g, *si, lobe, wl, stats);
                }
            }
            measured = true;
        }

        // A sampled direction at the last vertex can only find emission; without emitters a
        // ray can hit (only delta lights), it would contribute nothing.
        if (depth + 1 == maxDepth_ && !HasHittableEmitters(scene)) break;

        // One term of the Eq. 22 mixture: the GR keeps β, ρ; its mean direction turns and |k|
        // follows the medium (S6.4).
        auto bs = mat->Sample(q, sampler.Get1D(), sampler.Get2D());
        if (!bs || bs->weight.IsZero()) break;
        // A dispersive lobe is followed at the hero wavelength only (D10). The companions are
        // dropped from the throughput (T[0]·N, the same bookkeeping as TerminateSecondary), not
        // from `wl`: what they collected up to here, including this vertex's closed-form
        // measurement along their own directions, stays in the estimate.
        if ((bs->flags & ScatterDispersive) && !companionsDropped) {
            companionsDropped = DropCompanions(T, wl);
        }
        T *= bs->weight;
        if constexpr (rec) {
            path.back().left = true;
            path.back().bs = *bs;
        }
        if ((bs->flags & ScatterSpreadFree) && q.gr) footprint.Remember(q, *si, g, *mat, *bs);
        const Vec3 wo = frame.ToWorld(bs->wo);
        g.Redirect(wo, bs->eta);
        g.o = si->SpawnOrigin(wo);
        const bool nearDelta = (bs->flags & ScatterNearDelta) != 0;
        if (spreadFree && nearDelta && HasDeltaLights(scene)) stats.counters.Add(RenderEvent::SpecularAfterSpreadFree);
        spreadFree = spreadFree || (bs->flags & ScatterSpreadFree) != 0;
        mis = path::MisState{nearDelta, bs->pdf, LightSampleContext{si->p, si->n}};
        // After a near-delta lobe of a GR the closed-form sources were measured at this vertex.
        closedFormDone = nearDelta && !spreadFree;

        if (depth + 1 >= rrDepth_ && measured && !path::RussianRoulette(T, sampler.Get1D())) break;
    }
    return L;
}

}  // namespace phasor::grpath
