// SPDX-License-Identifier: Apache-2.0
// `sample_solve`: the paper's second integrator (supplement S7, Fig. S9–S10; theory §3.4, §5, §4.9,
// §0 D5, D9): `grt`'s path sampling, then, in place of the generalized-ray measurement, a forward
// partially coherent, polarised solve of each sampled path from the light to the detector.
//
// Sample. The path is sampled exactly as `grt` samples it (integrators/gr_path.h: same sampler
// dimensions, same lobes, same NEE, MIS, D4a, D14 and Russian roulette), and each measurement
// event — every term `grt` adds to its estimate — is solved forward:
// Solve. A PLT beam (core/render/beam.h) is sourced at the event's light: unpolarised Stokes
// (1, 0, 0, 0) per carried wavelength, travelling along the light's direction of arrival, with the
// coherence of what the event measures (below). It meets the event's own interaction (the
// continuous lobes towards an NEE sample, or the listed lobe a closed-form source is measured
// through), then the sampled lobes of the path's vertices back to the detector; at each, its frame
// is rotated into the lobe's s/p frame (LobeSAxis) and the lobe's Mueller matrix is applied —
// reciprocally, P·Mᵀ·P with P = diag(1, 1, −1, 1), since kernels state their response for the
// backward direction (the wave arriving along −wi) — divided by the scalar value `grt` weighted
// the path with (M00), so the beam carries the polarisation and coherence *relative* to `grt`'s
// estimate: the pixel receives the event's grt value × the measured Stokes vector. At the detector
// an optional ideal linear polariser acts in the detector's frame (DetectorPolarization), and the
// film keeps S0 (= `intensity`) and, with `stokes = true`, S0..S3.
//
// Coherence (docs/sample_solve.md; theory §0 D5, §5.3). The beam's K is the angular covariance of
// the source ensemble that the event integrates analytically: a `distant` source measured in closed
// form (D4a at a sensor plane, D14 through listed lobes, a camera looking at it) keeps its profile's
// Ω (Light::Coherence); every other event has picked one coherent mode of its source — a point of
// an area light, a direction of a distant source chosen by NEE or by an escaping ray, a point or
// spot light, a plane wave, a laser — and the Monte Carlo average over those samples is the
// ensemble average (the van Cittert–Zernike washing-out of fringes then comes out of the sampling;
// weighting a sampled mode by its source's coherence as well would count it twice). K survives
// near-delta lobes (with the anamorphic factor of refraction and grating orders) and is reset at a
// continuous lobe (a diffuse or rough point is a new, sampled, coherent secondary source; theory
// §4.7's "more physical choice"). A lobe with coherence terms (a coated surface, thin_film,
// multilayer: LobeCoherence) responds with μR_coh + (1 − μ)R_incoh, μ = exp(−½k₀²·Δ⊥ᵀKΔ⊥), Δ the
// lateral shear of its two interfering waves projected on the incident beam (theory §4.4, D5).
//
// force_coherent = true is the fully coherent transport of Fig. S10: μ ≡ 1, and a source ensemble
// is never integrated analytically — each closed-form measurement of a `distant` source measures one
// coherent plane wave whose direction is drawn from the source's profile (a mode, irradiance
// L/pdf), so both solves converge to the same image (to O(α²) of the source's angular radius and,
// where interference terms are weighted by μ, to D5's Gaussian-vs-disc O(v⁴)); the fully coherent
// one needs more samples.
//
// Scalar parts. `aperture` (footprint-aware, scalar Kirchhoff diffraction) passes the polarisation
// unchanged. Kernels without a Jones matrix (diffuse: a depolariser) give their Mueller matrix.
#include "core/render/beam.h"
#include "core/render/registry.h"
#include "integrators/gr_path.h"
#include "lights/closed_form.h"

namespace phasor {

namespace {

/// One coherent plane-wave mode of a `distant` source (force_coherent): direction of travel
/// `travel`, irradiance `e` per carried wavelength (normal to `travel`).
class CoherentMode final : public Light {
  public:
    CoherentMode(const Light &of, const Vec3 &travel, const SampledSpectrum &e) : of_(&of), travel_(travel), e_(e) {}
    std::optional<LightSample> SampleLi(const LightSampleContext &, const Vec2 &, const SampledWavelengths &) const override {
        return LightSample{e_, -travel_, Infinity, 1.0, true};
    }
    double PdfLi(const LightSampleContext &, const Vec3 &, const Vec3 &, const Vec3 &) const override { return 0; }
    LightType Type() const override { return LightType::DeltaDirection; }
    std::optional<GrMeasurement> MeasureGR(const SpectralGenRay &g, const SampledWavelengths &) const override {
        return MeasureDistantGR(g, travel_, e_, false, 0, 0);
    }
    std::optional<GrIncidence> IncidenceOnGR(const SpectralGenRay &g, const SampledWavelengths &) const override {
        return DistantIncidence(g, travel_, e_, 0);
    }
    LightCoherence Coherence(const Vec3 &) const override { return LightCoherence{-travel_, 0}; }
    const Spectrum &EmissionSpectrum() const override { return of_->EmissionSpectrum(); }
    double PowerScale() const override { return of_->PowerScale(); }
    std::string ToString() const override { return "coherent mode of " + of_->ToString(); }

  private:
    const Light *of_;
    Vec3 travel_;
    SampledSpectrum e_;
};

}  // namespace

class SampleSolveIntegrator final : public PixelIntegrator {
  public:
    SampleSolveIntegrator(int maxDepth, int rrDepth, int lightSamples, bool forceCoherent)
        : paths_(maxDepth, rrDepth, lightSamples), forceCoherent_(forceCoherent) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "integrator", "sample_solve",
            "Sample-solve (supplement S7): grt's path sampling, then a forward partially coherent, polarised (PLT) "
            "solve of each sampled path; Stokes output and polarisers on the detector.",
            [] {
                std::vector<ParamSpec> p = grpath::PathParams();
                p.push_back(P::Bool("force_coherent",
                                    "fully coherent transport (Fig. S10): mu = 1, and distant sources measured in "
                                    "closed form as one coherent plane wave drawn from their profile per measurement "
                                    "(same image, more noise)")
                                .Default(Value::Bool(false)));
                return p;
            }()};
        return s;
    }
    static std::unique_ptr<Integrator> Create(const ParamDict &d, BuildContext &) {
        return std::make_unique<SampleSolveIntegrator>(d.GetInt("max_depth"), d.GetInt("rr_depth"),
                                                       d.GetInt("light_samples"), d.GetBool("force_coherent"));
    }
    /// The integrator contract cases sample_solve supports (tests/integrators/integrator_contract_test.cpp):
    /// grt's (its path sampling is grt's; unpolarised sources and scalar measurements).
    static std::vector<std::string> ContractCases() {
        return {"furnace",           "direct_light",        "camera_emitter",
                "plane_wave_sensor", "point_source_sensor", "pairwise_cornell"};
    }

    bool WaveOptical() const override { return true; }
    /// grt's, and it carries polarisation.
    IntegratorSupport Support() const override {
        IntegratorSupport s = grpath::PathSupport();
        s.polarization = true;
        return s;
    }

    RenderStats Render(const Scene &scene, Film &film, const RenderOptions &opt) const override {
        if (scene.GetDetector().Polarization().stokes && !film.HasStokes()) film.EnableStokes();
        return PixelIntegrator::Render(scene, film, opt);
    }

    SampledSpectrum EstimatePixel(const Scene &scene, int x, int y, SampledWavelengths &wl, Sampler &sampler,
                                  ScratchBuffer &scratch, PathStats &stats) const override {
        return Solve(scene, x, y, wl, sampler, scratch, stats)[0];
    }
    std::array<SampledSpectrum, 4> EstimatePixelStokes(const Scene &scene, int x, int y, SampledWavelengths &wl,
                                                       Sampler &sampler, ScratchBuffer &scratch,
                                                       PathStats &stats) const override {
        return Solve(scene, x, y, wl, sampler, scratch, stats);
    }

    std::string ToString() const override {
        return "sample_solve { max_depth = " + std::to_string(paths_.MaxDepth()) +
               ", rr_depth = " + std::to_string(paths_.RrDepth()) +
               ", light_samples = " + std::to_string(paths_.LightSamples()) +
               ", force_coherent = " + (forceCoherent_ ? "true" : "false") + " }";
    }

  private:
    /// The forward solve of one pixel sample's events (see the top of the file).
    struct Sink {
        static constexpr bool Records = true;
        const Scene &scene;
        const SampledWavelengths &wl;
        bool forceCoherent;
        Pcg32 rng;  // draws coherent modes (force_coherent) without touching the path's dimensions
        std::array<SampledSpectrum, 4> stokes{SampledSpectrum(0.0), SampledSpectrum(0.0), SampledSpectrum(0.0),
                                              SampledSpectrum(0.0)};
        ScratchBuffer &scratch;  // the sample's: the path's kernels live here, and what OnEvent prepares
        // The coherent modes drawn (alive for the sample: the sampler measures them right away).
        std::vector<std::unique_ptr<CoherentMode>> modes{};
        /// Per path vertex, its sampled lobe's response (computed on first use) and whether it passes
        /// polarisation unchanged; in the scratch buffer, grown with the path.
        struct VertexResponse {
            bool done = false;
            bool scalar = false;
            std::optional<LobeResponse> response;
        };
        std::span<VertexResponse> vertices{};

        const Light *Measured(const Light *light, const Vec3 &p, const SampledWavelengths &w) {
            // A distant source with an angular profile is an ensemble; fully coherent transport
            // measures one plane-wave mode of it, drawn from its profile.
            if (!forceCoherent || light->IsDelta() || !light->IsInfinite()) return light;
            const Vec2 u(rng.Uniform(), rng.Uniform());
            auto ls = light->SampleLi(LightSampleContext{p, Vec3(0, 0, 0)}, u, w);
            SampledSpectrum e(0.0);
            if (ls && ls->pdf > 0) e = ls->L / ls->pdf;
            modes.push_back(std::make_unique<CoherentMode>(*light, ls ? -ls->wi : Vec3(0, 0, -1), e));
            return modes.back().get();
        }

        /// One interaction of the beam at si, which the path left along wi (local): the lobe's
        /// response `r` (nullopt: no response, the beam is extinguished) towards the light along wo
        /// (local), relative to its M00; `scalar`: the vertex passes polarisation unchanged
        /// (footprint-aware kernels).
        void Interact(PltBeam &beam, const SurfaceInteraction &si, const Vec3 &wi, const Vec3 &wo,
                      const std::optional<LobeResponse> &r, bool nearDelta, bool scalar) const {
            const Vec3 out = si.shading.ToWorld(wi);
            const Vec3 sAxis = si.shading.ToWorld(LobeSAxis(wi, wo));
            beam.d = -si.shading.ToWorld(wo);  // the light arrives along −wo
            beam.t = PerpendicularTo(beam.d, beam.t);
            std::array<Mueller, NumWavelengths> m{};
            for (int i = 0; i < beam.count; ++i) {
                if (scalar) {
                    m[std::size_t(i)] = Mueller::Identity();
                    continue;
                }
                if (!r) continue;  // zero
                const double n = r->mueller[i].m[0][0];
                if (!(n > 0)) continue;
                Mueller mi = r->mueller[i];
                if (r->coherence.any && !forceCoherent) {
                    // theory §4.4: μR_coh + (1 − μ)R_incoh, μ at the two waves' shear (D5).
                    const Vec2 sh = r->coherence.shear[i];
                    const double mu = beam.MutualCoherence(si.shading.ToWorld(Vec3(sh.x, sh.y, 0)), 2 * Pi / wl.lambda[i], i);
                    mi = mi * mu + r->coherence.incoherent[i] * (1 - mu);
                }
                m[std::size_t(i)] = ReciprocalMueller(mi) * (1 / n);
            }
            const double scale = std::abs(wi.z) > 0 ? std::abs(wo.z) / std::abs(wi.z) : 1;
            beam.Interact(sAxis, out, m, scale, !nearDelta || scalar);
        }

        /// Vertex v's sampled lobe's response (computed once per sample) and whether it is scalar.
        const VertexResponse &ResponseAt(const std::vector<grpath::Vertex> &path, int v) {
            if (vertices.size() < path.size()) {
                const std::size_t n = std::max<std::size_t>({8, 2 * vertices.size(), path.size()});
                VertexResponse *grown = scratch.Room<VertexResponse>(n);
                for (std::size_t i = 0; i < n; ++i)
                    ::new (grown + i) VertexResponse(i < vertices.size() ? vertices[i] : VertexResponse{});
                vertices = std::span<VertexResponse>(grown, n);
            }
            VertexResponse &r = vertices[std::size_t(v)];
            const grpath::Vertex &vx = path[std::size_t(v)];
            if (!r.done) {
                r.done = true;
                if (vx.bs.flags & ScatterSpreadFree) r.scalar = true;
                else if (vx.bs.flags & ScatterNearDelta) r.response = vx.kernel->EvalLobe(vx.bs.lobe, vx.bs.wo);
                else r.response = vx.kernel->EvalContinuousLobes(vx.bs.wo);
            }
            return r;
        }

        /// True if a vertex's response is a pure depolariser (only M00) at every carried wavelength.
        static bool Depolarizes(const LobeResponse &r, int count) {
            for (int i = 0; i < count; ++i)
                for (int a = 0; a < 4; ++a)
                    for (int b = 0; b < 4; ++b)
                        if ((a || b) && std::abs(r.mueller[i].m[a][b]) > 1e-14 * std::abs(r.mueller[i].m[0][0])) return false;
            return true;
        }
        /// True if a response neither polarises unpolarised light nor reads polarisation into S0:
        /// its first row and column are (M00, 0, 0, 0) at every carried wavelength.
        static bool Decoupled(const LobeResponse &r, int count) {
            for (int i = 0; i < count; ++i)
                for (int c = 1; c < 4; ++c)
                    if (std::abs(r.mueller[i].m[0][c]) > 1e-14 * std::abs(r.mueller[i].m[0][0]) ||
                        std::abs(r.mueller[i].m[c][0]) > 1e-14 * std::abs(r.mueller[i].m[0][0]))
                        return false;
            return true;
        }

        /// True if the forward solve's S0 is the event's scalar value exactly, without a polariser
        /// or Stokes output: no coherence term can act (a coherent beam, or no lobe that has
        /// one before the beam's coherence is reset), and between depolarisers at most one
        /// interaction couples S0 and polarisation (a single one acting on unpolarised light gives
        /// S0 = M00, its weight). Only the path vertices' (cached) responses are looked at: the
        /// event's own interaction is counted as coupling, and its response is never computed here.
        bool ScalarSuffices(const grpath::Event &e, const std::vector<grpath::Vertex> &path, bool partial) {
            if (e.at && partial && e.at->material->HasCoherenceTerms()) return false;
            bool coherenceAlive = partial && e.kind != grpath::EventKind::DirectLight;
            int coupling = e.at ? 1 : 0;
            for (int v = e.prefix - 1; v >= 0; --v) {
                const grpath::Vertex &vx = path[std::size_t(v)];
                const VertexResponse &vr = ResponseAt(path, v);
                const std::optional<LobeResponse> &r = vr.response;
                if (vr.scalar) {
                    coherenceAlive = false;
                    continue;
                }
                if (!r) return false;
                if (Depolarizes(*r, wl.Count())) {
                    coupling = 0;
                    coherenceAlive = false;
                    continue;
                }
                if (coherenceAlive && r->coherence.any) return false;
                if (!(vx.bs.flags & ScatterNearDelta)) coherenceAlive = false;
                if (!Decoupled(*r, wl.Count()) && ++coupling >= 2) return false;
            }
            return true;
        }

        void OnEvent(const grpath::Event &e, const std::vector<grpath::Vertex> &path, const DetectorGrSample &ds) {
            const Detector &det = scene.GetDetector();
            // Where the light first interacts (for its coherence there).
            const Vec3 first = e.at ? e.at->p : e.prefix > 0 ? path[std::size_t(e.prefix - 1)].si.p : ds.ray.o;
            const double omega = e.ensemble && e.light && !forceCoherent ? e.light->Coherence(first).omega : 0;
            if (!det.Polarization().Any() && ScalarSuffices(e, path, omega > 0)) {
                stokes[0] += e.value;  // unpolarised detection of an uncoupled chain: grt's value
                return;
            }
            PltBeam beam = PltBeam::Source(e.travel, wl.Count(), omega);
            for (int i = 0; i < wl.Count(); ++i) beam.SetWindow(i, e.window[std::size_t(i)]);
            if (std::isfinite(e.dist)) beam.Propagate(e.dist);
            if (e.at) {
                // The kernel at the event's interaction: the vertex's, or prepared for the hit a
                // LobeIncidence solve found.
                const PreparedKernel &k =
                    e.kernel ? *e.kernel : e.at->material->Prepare(grpath::GrQuery(*e.at, *e.gr, e.rayOptics, wl), scratch);
                const Vec3 &wi = k.Query().wi;
                if (e.kind == grpath::EventKind::DirectLight) {
                    const bool scalar = e.at->material->IsFootprintAware() && !e.rayOptics;
                    Interact(beam, *e.at, wi, e.woLocal, scalar ? std::nullopt : k.EvalContinuousLobes(e.woLocal), false,
                             scalar);
                } else {
                    // EvalLobe answers at the lobe's hero direction (a dispersive companion's own differs).
                    std::optional<LobeResponse> r;
                    const NearDeltaLobe *lobe = e.wavelength > 0 ? k.FindLobe(e.lobe) : nullptr;
                    if (e.wavelength <= 0 || lobe) r = k.EvalLobe(e.lobe, lobe ? lobe->wo[0] : e.woLocal);
                    Interact(beam, *e.at, wi, e.woLocal, r, true, false);
                }
            }
            for (int v = e.prefix - 1; v >= 0; --v) {
                const grpath::Vertex &vx = path[std::size_t(v)];
                const VertexResponse &vr = ResponseAt(path, v);
                beam.Propagate(Length(vx.si.p - (v + 1 < int(path.size()) ? path[std::size_t(v + 1)].si.p : vx.si.p)));
                Interact(beam, vx.si, vx.kernel->Query().wi, vx.bs.wo, vr.response, (vx.bs.flags & ScatterNearDelta) != 0,
                         vr.scalar);
            }
            const Vec3 x = det.PolarizationX(ds);
            const std::optional<double> &pol = det.Polarization().polarizer;
            for (int i = 0; i < wl.Count(); ++i) {
                if (e.wavelength >= 0 && i != e.wavelength) continue;
                if (e.value[i] == 0) continue;
                const Stokes s = beam.Measure(i, x, pol);
                for (int c = 0; c < 4; ++c) stokes[std::size_t(c)][i] += e.value[i] * s[std::size_t(c)];
            }
        }
    };

    std::array<SampledSpectrum, 4> Solve(const Scene &scene, int x, int y, SampledWavelengths &wl, Sampler &sampler,
                                         ScratchBuffer &scratch, PathStats &stats) const {
        Sink sink{scene,
                  wl,
                  forceCoherent_,
                  Pcg32(Hash(stats.sample.seed, uint64_t(uint32_t(x)), uint64_t(uint32_t(y))),
                        uint64_t(stats.sample.index)),
                  {SampledSpectrum(0.0), SampledSpectrum(0.0), SampledSpectrum(0.0), SampledSpectrum(0.0)},
                  scratch};
        paths_.Estimate(scene, x, y, wl, sampler, scratch, stats, sink);
        return sink.stokes;
    }

    grpath::GrPathSampler paths_;
    bool forceCoherent_;
};

PHASOR_EXPORT_PLUGIN(Integrator, SampleSolveIntegrator)

}  // namespace phasor
