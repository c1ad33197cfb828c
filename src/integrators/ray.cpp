// SPDX-License-Identifier: Apache-2.0
// `ray`: the classical spectral path tracer — phasor's baseline (design.md §4.3). Kernels are
// queried in their ray-optics limit (ScatterQuery::rayOptics): near-delta lobes are true deltas.
// Next-event estimation to one uniformly chosen light per vertex, multiple importance sampling
// (power heuristic) between light and kernel sampling for area lights, Russian roulette on the
// throughput after `rr_depth` bounces.
#include "core/pixel_integrator.h"
#include "core/registry.h"

namespace phasor {

namespace {
double PowerHeuristic(double f, double g) {
    if (std::isinf(f)) return 1;
    double f2 = f * f, g2 = g * g;
    return f2 + g2 > 0 ? f2 / (f2 + g2) : 0;
}
}  // namespace

class RayIntegrator final : public PixelIntegrator {
  public:
    RayIntegrator(int maxDepth, int rrDepth) : maxDepth_(maxDepth), rrDepth_(rrDepth) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "integrator", "ray", "Classical spectral path tracer (ray-optics limit); the baseline.",
            {P::Integer("max_depth", "maximum number of scattering events (-1: unlimited, Russian roulette ends paths)")
                 .Default(Value::Integer(16))
                 .Min(-1),
             P::Integer("rr_depth", "bounces before Russian roulette starts").Default(Value::Integer(3)).Min(0)}};
        return s;
    }
    static std::unique_ptr<Integrator> Create(const ParamDict &d, BuildContext &) {
        return std::make_unique<RayIntegrator>(d.GetInt("max_depth"), d.GetInt("rr_depth"));
    }

    SampledSpectrum EstimatePixel(const Scene &scene, int x, int y, SampledWavelengths &wl, Sampler &sampler,
                                  PathStats &stats) const override {
        Vec2 pFilm = Vec2(x, y) + sampler.GetPixel2D();
        auto ds = scene.GetDetector().Generate(pFilm, sampler.Get2D());
        if (!ds) return SampledSpectrum(0.0);
        Ray ray = ds->ray;
        SampledSpectrum beta(ds->weight), L(0.0);
        const auto &lights = scene.Lights();
        const double lightSelectPdf = lights.empty() ? 0 : 1.0 / lights.size();
        bool deltaBounce = true;  // the camera vertex counts as a delta for MIS
        double prevPdf = 0;
        LightSampleContext prevCtx;

        for (int depth = 0;; ++depth) {
            ++stats.rays;
            auto si = scene.Intersect(ray);
            if (!si) {
                for (const Light *l : scene.InfiniteLights()) L += beta * l->Le(ray.d, wl);
                break;
            }
            // Emission seen by the path (MIS-weighted against light sampling).
            if (si->areaLight) {
                SampledSpectrum Le = si->areaLight->L(si->p, si->n, -ray.d, wl);
                if (!Le.IsZero()) {
                    if (deltaBounce) L += beta * Le;
                    else {
                        double lightPdf = si->areaLight->PdfLi(prevCtx, ray.d, si->p, si->n) * lightSelectPdf;
                        L += beta * Le * PowerHeuristic(prevPdf, lightPdf);
                    }
                }
            }
            const Material *mat = si->material;
            if (!mat || depth == maxDepth_) break;

            const Frame &frame = si->shading;
            ScatterQuery q;
            q.wi = frame.ToLocal(-ray.d);
            q.wl = &wl;
            q.rayOptics = true;
            q.uv = si->uv;

            // Next-event estimation.
            double uLight = sampler.Get1D();
            Vec2 uLightPos = sampler.Get2D();
            if (!mat->IsDeltaOnly() && !lights.empty()) {
                std::size_t li = std::min(lights.size() - 1, std::size_t(uLight * lights.size()));
                const Light *light = lights[li];
                LightSampleContext ctx{si->p, si->n};
                if (auto ls = light->SampleLi(ctx, uLightPos, wl); ls && ls->pdf > 0 && !ls->L.IsZero()) {
                    Vec3 wo = frame.ToLocal(ls->wi);
                    SampledSpectrum f = mat->Eval(q, wo) * std::abs(wo.z);
                    if (!f.IsZero()) {
                        ++stats.rays;
                        bool blocked = std::isinf(ls->dist) ? scene.OccludedDirection(*si, ls->wi)
                                                            : scene.Occluded(*si, si->p + ls->wi * ls->dist);
                        if (!blocked) {
                            if (ls->delta) L += beta * f * ls->L / lightSelectPdf;
                            else {
                                double pl = ls->pdf * lightSelectPdf;
                                double w = PowerHeuristic(pl, mat->Pdf(q, wo));
                                L += beta * f * ls->L * (w / pl);
                            }
                        }
                    }
                }
            }

            // Continue the path by sampling the kernel.
            auto bs = mat->Sample(q, sampler.Get1D(), sampler.Get2D());
            if (!bs || bs->weight.IsZero()) break;
            if (bs->flags & ScatterDispersive) wl.TerminateSecondary();
            beta *= bs->weight;
            deltaBounce = (bs->flags & ScatterNearDelta) != 0;
            prevPdf = bs->pdf;
            prevCtx = LightSampleContext{si->p, si->n};
            Vec3 wo = frame.ToWorld(bs->wo);
            ray = Ray{si->SpawnOrigin(wo), wo};

            // Russian roulette on the throughput.
            if (depth + 1 >= rrDepth_) {
                double m = beta.Max();
                if (!(m > 0)) break;
                if (m < 1) {
                    double survive = std::max(0.05, m);
                    if (sampler.Get1D() >= survive) break;
                    beta /= survive;
                }
            }
        }
        return L;
    }

    std::string ToString() const override {
        return "ray { max_depth = " + std::to_string(maxDepth_) + ", rr_depth = " + std::to_string(rrDepth_) + " }";
    }

  private:
    int maxDepth_, rrDepth_;
};

PHASOR_EXPORT_PLUGIN(Integrator, RayIntegrator)

}  // namespace phasor
