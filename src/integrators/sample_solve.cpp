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
// Partial coherence (docs/sample_solve.md; theory §0 D15). A closed-form measurement integrates a
// light's angular profile (a `distant` disc or Gaussian; a beam's spectrum) through the measuring
// GR's angular spectrum; every interaction whose response varies with direction answers for that
// ensemble of plane waves its Mueller matrix *averaged* over it (core/render/lobe_average.h; per
// polarisation, not a scalar μ mixing coherent and incoherent sums): the measured lobe over the
// profile × the GR's spectrum, exactly as `grt` weighs it; sampled vertices respond at the GR's mean
// direction, as in `grt` (the detector's direction sampling integrates the spectrum there). So S0 is
// `grt`'s estimate, and the fully coherent transport below converges to it (it draws the plane waves
// one at a time); Stokes components come from the averaged matrices. Of a chain of near-delta
// vertices only the measured lobe is averaged (exact when the sampled ones vary little over the
// ensemble; docs/accuracy.md).
//
// force_coherent = true is the fully coherent transport of Fig. S10: a source ensemble is never
// integrated analytically — each closed-form measurement of a `distant` source measures one
// coherent plane wave whose direction is drawn from the source's profile (a mode, irradiance
// L/pdf), and the measured lobe responds at that direction: the same image in the mean, noisier.
//
// Scalar parts. `aperture` (footprint-aware, scalar Kirchhoff diffraction) passes the polarisation
// unchanged. Kernels without a Jones matrix (diffuse: a depolariser) give their Mueller matrix.
#include "core/render/beam.h"
#include "core/render/lobe_average.h"
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
    explicit SampleSolveIntegrator(const ParamDict &d) : paths_(d), forceCoherent_(d.GetBool("force_coherent")) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "integrator", "sample_solve",
            "Sample-solve (supplement S7): grt's path sampling, then a forward partially coherent, polarised (PLT) "
            "solve of each sampled path; Stokes output and polarisers on the detector.",
            [] {
                std::vector<ParamSpec> p = grpath::PathAndFsdParams();
                p.push_back(P::Bool("force_coherent",
                                    "fully coherent transport (Fig. S10): distant sources measured in closed form as "
                                    "one coherent plane wave drawn from their profile per measurement (same image, "
                                    "more noise)")
                                .Default(Value::Bool(false)));
                return p;
            }()};
        return s;
    }
    static std::unique_ptr<Integrator> Create(const ParamDict &d, BuildContext &) {
        return std::make_unique<SampleSolveIntegrator>(d);
    }
    /// The integrator contract cases sample_solve supports (tests/integrators/integrator_contract_test.cpp):
    /// grt's (its path sampling is grt's; unpolarised sources and scalar measurements).
    static std::vector<std::string> ContractCases() {
        return {"furnace",           "direct_light",        "camera_emitter",
                "plane_wave_sensor", "point_source_sensor", "pairwise_cornell"};
    }

    bool WaveOptical() const override { return true; }
    void Validate(const Scene &scene, Diagnostics &diag) const override {
        PixelIntegrator::Validate(scene, diag);
        paths_.NoteFsd(scene, diag);
    }
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
        return "sample_solve { " + paths_.ParamString() +
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
                      const std::optional<LobeResponse> &r, bool scalar) const {
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
                m[std::size_t(i)] = ReciprocalMueller(r->mueller[i]) * (1 / n);
            }
            beam.Interact(sAxis, out, m);
        }

        /// The response of an event's own near-delta lobe of k (the kernel prepared at the event's
        /// hit): averaged over the plane waves the closed form integrated (theory §0 D15) — the
        /// light's profile through the GR's spectrum for D14 (ThroughLobe, as
        /// GrPathSampler::ThroughLobeWeight), the light's profile weighted by the lobe's irradiance
        /// transfer at a sensor plane (LobeIncidence, as lobe_incidence.cpp). Every average answers at
        /// the lobe's hero direction (a dispersive companion's own differs).
        std::optional<LobeResponse> EventLobe(const grpath::Event &e, const PreparedKernel &k) const {
            const Material &mat = *e.at->material;
            const NearDeltaLobe *l = k.FindLobe(e.lobe);
            if (!l) return std::nullopt;
            if (e.kind == grpath::EventKind::ThroughLobe)
                return AverageLobeResponse(mat, k, e.lobe, MeasurementEnsemble(e.at->shading, *e.gr, *l, -e.travel, e.profile));
            return AverageLobeResponse(mat, k, e.lobe, SourceEnsemble(e.at->shading, -e.travel, e.profile),
                                       LobeTransfer::Irradiance);
        }

        /// Vertex v's sampled lobe's response (computed once per sample, at the GR's mean direction,
        /// as grt weighs it) and whether it is scalar.
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
        /// or Stokes output: between depolarisers at most one interaction couples S0 and
        /// polarisation (a single one acting on unpolarised light gives S0 = M00, its weight; every
        /// response here is the one `grt` weighted the path with, averaged where it averaged). Only
        /// the path vertices' (cached) responses are looked at: the event's own interaction is
        /// counted as coupling, and its response is never computed here.
        bool ScalarSuffices(const grpath::Event &e, const std::vector<grpath::Vertex> &path) {
            int coupling = e.at ? 1 : 0;
            for (int v = e.prefix - 1; v >= 0; --v) {
                const VertexResponse &vr = ResponseAt(path, v);
                const std::optional<LobeResponse> &r = vr.response;
                if (vr.scalar) continue;
                if (!r) return false;
                if (Depolarizes(*r, wl.Count())) {
                    coupling = 0;
                    continue;
                }
                if (!Decoupled(*r, wl.Count()) && ++coupling >= 2) return false;
            }
            return true;
        }

        void OnEvent(const grpath::Event &e, const std::vector<grpath::Vertex> &path, const DetectorGrSample &ds) {
            const Detector &det = scene.GetDetector();
            if (!det.Polarization().Any() && ScalarSuffices(e, path)) {
                stokes[0] += e.value;  // unpolarised detection of an uncoupled chain: grt's value
                return;
            }
            PltBeam beam = PltBeam::Source(e.travel, wl.Count());
            if (std::isfinite(e.dist)) beam.Propagate(e.dist);
            if (e.at) {
                // The kernel at the event's interaction: the vertex's, or prepared for the hit a
                // LobeIncidence solve found.
                const PreparedKernel &k =
                    e.kernel ? *e.kernel : e.at->material->Prepare(grpath::GrQuery(*e.at, *e.gr, e.rayOptics, wl), scratch);
                const Vec3 &wi = k.Query().wi;
                if (e.kind == grpath::EventKind::DirectLight) {
                    const bool scalar = e.at->material->IsFootprintAware() && !e.rayOptics;
                    Interact(beam, *e.at, wi, e.woLocal, scalar ? std::nullopt : k.EvalContinuousLobes(e.woLocal), scalar);
                } else {
                    Interact(beam, *e.at, wi, e.woLocal, EventLobe(e, k), false);
                }
            }
            for (int v = e.prefix - 1; v >= 0; --v) {
                const grpath::Vertex &vx = path[std::size_t(v)];
                const VertexResponse &vr = ResponseAt(path, v);
                beam.Propagate(Length(vx.si.p - (v + 1 < int(path.size()) ? path[std::size_t(v + 1)].si.p : vx.si.p)));
                Interact(beam, vx.si, vx.kernel->Query().wi, vx.bs.wo, vr.response, vr.scalar);
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
