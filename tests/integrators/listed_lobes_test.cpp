// SPDX-License-Identifier: Apache-2.0
// `grt` measures delta and small sources through *every* listed near-delta lobe at a vertex
// (core/render/material.h ListNearDelta, theory §0 D14), not only through the lobe it follows: a kernel
// with two lobes lit by a tiny sun shows both glints, each at its closed-form value, in one
// sample per pixel. The kernel is a test kernel registered here (PHASOR_REGISTER_PLUGIN): a mirror
// lobe (id 0, weight a₀) and one "order" (id 1, weight a₁) that adds a tangential wave vector
// 2π/Λ along the local x axis, on the scene of scenes/validation/grt_sun_glint.wscene.
#include <gtest/gtest.h>

#include <sstream>

#include "core/render/pixel_integrator.h"
#include "core/render/registry.h"
#include "materials/material_test_util.h"
#include "parser/parser.h"
#include "support/scene_builder.h"

namespace phasor {

class TwoLobeTestMaterial final : public Material {
  public:
    TwoLobeTestMaterial(double a0, double a1, double period) : a_{a0, a1}, period_(period) {}
    static const Schema &GetSchema() {
        static const Schema s{"material",
                              "two_lobe_test",
                              "test kernel: a mirror lobe and one shifted order",
                              {P::Number("a0", "mirror lobe weight").Default(Value::Number(0.6)).Min(0).Max(1),
                               P::Number("a1", "order weight").Default(Value::Number(0.3)).Min(0).Max(1),
                               P::Length("period", "period of the order's shift 2π/Λ").Default(Value::Number(0.5e-3, Dim::Length()))}};
        return s;
    }
    static std::unique_ptr<Material> Create(const ParamDict &d, BuildContext &) {
        return std::make_unique<TwoLobeTestMaterial>(d.GetNumber("a0"), d.GetNumber("a1"), d.GetNumber("period"));
    }
    const PreparedKernel &Prepare(const ScatterQuery &q, ScratchBuffer &scratch) const override {
        return *scratch.New<Prepared>(*this, q, scratch);
    }
    std::string ToString() const override { return "TwoLobeTestMaterial"; }

  private:
    /// Lists the two lobes (the default Sample picks one of them).
    class Prepared final : public PreparedKernel {
      public:
        Prepared(const TwoLobeTestMaterial &m, const ScatterQuery &q, ScratchBuffer &scratch) : PreparedKernel(q) {
            caps_ = CapNearDelta;
            LobeList out(scratch, 2);
            for (int j = 0; j < 2; ++j) {
                if (m.a_[j] == 0) continue;
                const Vec2 shift(j * 2 * Pi / m.period_, 0);
                Vec3 wo;
                if (!NearDeltaDirection(q.wi, 1, 1, shift, q.wl->lambda[0], false, &wo)) continue;
                NearDeltaLobe &l = out.Add();
                l.id = j;
                l.flags = ScatterReflection | ScatterNearDelta;
                l.shift = shift;
                l.nIn.fill(1);
                l.nOut.fill(1);
                for (int i = 0; i < q.wl->Count(); ++i) {
                    NearDeltaDirection(q.wi, 1, 1, shift, q.wl->lambda[i], false, &l.wo[i]);
                    l.SetWeight(i, m.a_[j]);
                }
                if (j == 1 && q.wl->Count() > 1) l.flags |= ScatterDispersive;
                l.prob = m.a_[j] / (m.a_[0] + m.a_[1]);
            }
            lobes_ = out.Lobes();
        }
        std::optional<LobeResponse> EvalLobe(int, const Vec3 &) const override { return std::nullopt; }
    };

    double a_[2], period_;
};

PHASOR_REGISTER_PLUGIN(Material, TwoLobeTestMaterial, "two_lobe_test");

namespace test {
namespace {

// The sun-glint scene with the plate's conductor replaced by the two-lobe kernel; with `laser`
// the 1 µrad sun is replaced by a plane wave of the same direction, irradiance and line.
std::unique_ptr<Scene> TwoLobeScene(double a0, double a1, bool laser) {
    Diagnostics diag;
    auto desc = ParseSceneFile(std::string(PHASOR_SOURCE_DIR) + "/scenes/validation/grt_sun_glint.wscene",
                               {{"profile", "gaussian"}, {"radius", "1 urad"}, {"res", "9"}}, diag);
    EXPECT_TRUE(desc);
    if (!desc) return nullptr;
    for (SceneEntity &e : desc->entities)
        if (e.keyword == "Material") {
            e.type = "two_lobe_test";
            e.params = ParamDict(e.loc);
            e.params.Set("a0", Value::Number(a0)).Set("a1", Value::Number(a1));
        } else if (e.keyword == "Light" && laser) {
            ParamDict p(e.loc);
            p.Set("direction", e.params.GetValue("direction"))
                .Set("irradiance", e.params.GetValue("irradiance"))
                .Set("spectrum", e.params.GetValue("spectrum"));
            e.type = "plane_wave";
            e.params = p;
        }
    auto scene = Scene::Build(*desc, diag);
    std::ostringstream os;
    diag.Print(os);
    EXPECT_TRUE(scene) << os.str();
    return scene;
}

// One pixel estimate (sample 0 of 1, Sobol', seed 1) reduced as the film does (intensity).
double OneSample(const Scene &scene, int x, int y) {
    const auto &integrator = dynamic_cast<const PixelIntegrator &>(scene.GetIntegrator());
    auto sampler = MakeSobolSampler(1);
    sampler->StartPixelSample(x, y, 0);
    SampledWavelengths wl = scene.Wavelengths().Sample(sampler->Get1D());
    PathStats stats;
    stats.sample = PixelSampleIndex{0, 1, 1};
    ScratchBuffer scratch;
    const SampledSpectrum L = integrator.EstimatePixel(scene, x, y, wl, *sampler, scratch, stats);
    double v = 0;
    for (int i = 0; i < wl.Count(); ++i)
        if (wl.pdf[i] > 0) v += scene.GetDetector().Response().Intensity(wl.lambda[i]) * L[i] / wl.pdf[i];
    return v / wl.Count();
}

// D14 in closed form for every lobe: Σ_j a_j·E·N₂(s⊥; 0, σ_θ² + α²/4) with s⊥ the sun's direction
// transverse to lobe j's outgoing direction (the same formula as grt_test's GlintExpected, with
// the mirror direction replaced by each listed lobe's).
double Expected(const Scene &scene, int x, int y, bool laser) {
    const double elevation = Radians(50), offset = 0.15e-3, E = 1000, alpha = laser ? 0 : 1e-6;
    const Vec3 s(std::cos(elevation + offset), 0, -std::sin(elevation + offset));
    const double sigmaTheta = std::tan(0.5e-3) / std::sqrt(12.0), var = sigmaTheta * sigmaTheta + alpha * alpha / 4;
    auto ds = scene.GetDetector().Generate(Vec2(x + 0.5, y + 0.5), Vec2(0.5, 0.5));
    auto si = scene.Intersect(ds->ray);
    if (!si) return 0;
    const SampledWavelengths wl = test::LineWavelength(550e-9);
    ScatterQuery q;
    q.wi = si->shading.ToLocal(-ds->ray.d);
    q.wl = &wl;
    ScratchBuffer scratch;
    double v = 0;
    for (const NearDeltaLobe &l : si->material->Prepare(q, scratch).ListNearDelta()) {
        const double cosG = -Dot(s, si->shading.ToWorld(l.wo[0])), sin2 = std::max(0.0, 1 - cosG * cosG);
        v += l.Weight()[0] * E * std::exp(-0.5 * sin2 / var) / (2 * Pi * var);
    }
    return v;
}

TEST(GrtListedLobes, BothGlintsAtTheirClosedFormValuesInOneSample) {
  for (bool laser : {true, false}) {
    SCOPED_TRACE(laser ? "plane wave (laser)" : "1 urad distant source");
    auto scene = TwoLobeScene(0.6, 0.3, laser);
    ASSERT_TRUE(scene);
    const int n = scene->GetDetector().Width();
    double peak = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) peak = std::max(peak, Expected(*scene, x, y, laser));
    ASSERT_GT(peak, 1e8);
    // Both glints are in the image: the brightest pixel of each lobe alone.
    int glints = 0;
    for (double a0 : {1.0, 0.0}) {
        auto single = TwoLobeScene(a0, 1 - a0, laser);
        double best = 0;
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) best = std::max(best, Expected(*single, x, y, laser));
        glints += best > 1e-2 * peak;
    }
    ASSERT_EQ(glints, 2) << "each lobe's glint must fall on a pixel centre of the image";
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const double e = Expected(*scene, x, y, laser);
            EXPECT_NEAR(OneSample(*scene, x, y), e, 1e-6 * e + 1e-9 * peak) << "pixel " << x << " " << y;
        }
  }
}

}  // namespace
}  // namespace test
}  // namespace phasor
