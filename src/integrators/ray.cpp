// SPDX-License-Identifier: Apache-2.0
// `ray`: the classical spectral path tracer — phasor's baseline (docs/architecture.md). Kernels are
// queried in their ray-optics limit (ScatterQuery::rayOptics): near-delta lobes are true deltas.
// Next-event estimation to one uniformly chosen light per vertex, multiple importance sampling
// (power heuristic) between light and kernel sampling for area and infinite lights, Russian
// roulette on the throughput after `rr_depth` bounces. Shared pieces live in core/render/path_common.h.
#include "core/render/path_common.h"
#include "core/render/registry.h"

namespace phasor {

class RayIntegrator final : public PixelIntegrator {
  public:
    RayIntegrator(int maxDepth, int rrDepth, LightSelection lights = LightSelection::Exhaustive)
        : maxDepth_(maxDepth), rrDepth_(rrDepth), lights_(lights) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "integrator", "ray", "Classical spectral path tracer (ray-optics limit); the baseline.",
            {P::Integer("max_depth", "maximum number of scattering events (-1: unlimited, Russian roulette ends paths)")
                 .Default(Value::Integer(16))
                 .Min(-1),
             P::Integer("rr_depth", "bounces before Russian roulette starts").Default(Value::Integer(3)).Min(0),
             LightSamplerParam()}};
        return s;
    }
    static std::unique_ptr<Integrator> Create(const ParamDict &d, BuildContext &) {
        return std::make_unique<RayIntegrator>(d.GetInt("max_depth"), d.GetInt("rr_depth"),
                                               LightSelectionFromName(d.GetString("light_sampler")));
    }
    /// The integrator of a scene that names none (Render.integrator's default).
    static constexpr bool IsDefault = true;
    /// The integrator contract cases `ray` supports (tests/integrators/integrator_contract_test.cpp).
    /// Not the sensor-plane normalisations: a ray cannot reach a delta light (plane wave, point).
    static std::vector<std::string> ContractCases() {
        return {"furnace", "direct_light", "camera_emitter", "pairwise_cornell"};
    }

    /// Delta lights only through next-event estimation at continuous lobes (a ray never hits them);
    /// any detector; every kernel in its ray-optics limit; no polarisation.
    IntegratorSupport Support() const override {
        IntegratorSupport s;
        s.lights = {LightReach::SampledOnly, LightReach::SampledOnly, LightReach::HitAndSampled,
                    LightReach::HitAndSampled};
        s.detector = DetectorNeed::Rays;
        s.kernels = {KernelReach::RayOpticsLimit, KernelReach::RayOpticsLimit, KernelReach::RayOpticsLimit};
        return s;
    }

    SampledSpectrum EstimatePixel(const Scene &scene, int x, int y, SampledWavelengths &wl, Sampler &sampler,
                                  ScratchBuffer &scratch, PathStats &stats) const override {
        Vec2 pFilm = Vec2(x, y) + sampler.GetPixel2D();
        auto ds = scene.GetDetector().Generate(pFilm, sampler.Get2D());
        if (!ds) return SampledSpectrum(0.0);
        Ray ray = ds->ray;
        SampledSpectrum beta(ds->weight), L(0.0);
        path::MisState mis;  // the camera vertex counts as a delta for MIS
        const LightSampler &lights = scene.GetLightSampler(lights_);

        for (int depth = 0;; ++depth) {
            ++stats.rays;
            // No phase is carried: Embree's float distance is enough (HitPrecision).
            auto si = scene.Intersect(ray, Infinity, HitPrecision::Embree);
            if (!si) {
                L += beta * path::EscapedEmission(scene, lights, ray.d, wl, mis);
                break;
            }
            // Emission seen by the path (MIS-weighted against light sampling).
            L += beta * path::HitEmission(lights, *si, ray.d, wl, mis);
            const Material *mat = si->material;
            if (!mat || depth == maxDepth_) break;

            const Frame &frame = si->shading;
            ScatterQuery q;
            q.wi = frame.ToLocal(-ray.d);
            q.wl = &wl;
            q.rayOptics = true;
            q.tex = TextureEvalContext(*si);  // a classical ray: footprint 0
            q.si = &*si;
            const PreparedKernel &k = mat->Prepare(q, scratch);

            // Next-event estimation (the samples are drawn even when unused, to keep dimensions aligned).
            double uLight = sampler.Get1D();
            Vec2 uLightPos = sampler.Get2D();
            if (!k.IsDeltaOnly()) L += beta * path::SampleDirectLight(scene, *si, k, lights, uLight, uLightPos, wl, stats, scratch, true);

            // Continue the path by sampling the kernel.
            auto bs = k.Sample(sampler.Get1D(), sampler.Get2D());
            if (!bs || bs->weight.IsZero()) break;
            if (bs->flags & ScatterDispersive) wl.TerminateSecondary();
            beta *= bs->weight;
            const bool delta = (bs->flags & ScatterNearDelta) != 0;
            // Straight through a film the path is where the previous vertex's shadow rays went
            // (they cross it): emission found beyond keeps that vertex's MIS state (theory §3.5).
            if (!(delta && PassesStraight(*mat, k, bs->lobe)))
                mis = path::MisState{delta, bs->pdf, LightSampleContext{si->p, si->n}};
            Vec3 wo = frame.ToWorld(bs->wo);
            ray = Ray{si->SpawnOrigin(wo), wo};

            // Russian roulette on the throughput.
            if (depth + 1 >= rrDepth_ && !path::RussianRoulette(beta, sampler.Get1D())) break;
        }
        return L;
    }

    bool WaveOptical() const override { return false; }  // classical ray optics
    std::string ToString() const override {
        return "ray { max_depth = " + std::to_string(maxDepth_) + ", rr_depth = " + std::to_string(rrDepth_) +
               (lights_ != LightSelection::Exhaustive ? std::string(", light_sampler = ") + LightSelectionName(lights_) : "") + " }";
    }

  private:
    int maxDepth_, rrDepth_;
    LightSelection lights_;
};

PHASOR_EXPORT_PLUGIN(Integrator, RayIntegrator)

}  // namespace phasor
