// SPDX-License-Identifier: Apache-2.0
// Light selection for next-event estimation (core/render/light_sampler.h, the integrators'
// `light_sampler` parameter): the power distribution is proportional to each light's power and
// samples it (χ²); uniform selection is the rule light sampling always had (bit for bit); and on
// a floor under a dim and a 400× brighter panel, rendering with "power" gives the same mean as
// "uniform" (Welch's t on independent-sampler replicas, shown able to reject a 4 % bias) with a
// much smaller spread — for `ray` and `grt`, whose MIS weights of hit emission use the same
// probabilities (a panel is also reached by kernel sampling). The exhaustive sampler (the default)
// weighs the lights by Light::Reach at the receiver: its probabilities sum to 1, are sampled (χ²),
// give 0 to a panel that faces away and fall back to power where a light has no estimate; it keeps
// the mean and cuts the noise of a floor under three panels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "core/render/light_sampler.h"
#include "support/replicas.h"
#include "support/scene_text.h"
#include "support/stats.h"

namespace phasor::test {
namespace {

// A paper floor 10 m wide, the lamps in `lamps` (shapes and lights), a camera at `eye` looking at
// the floor's centre, and the integrator with `light_sampler`.
std::unique_ptr<Scene> FloorUnderLamps(const std::string &lamps, const std::string &eye, const std::string &fov,
                                       const std::string &integrator, const std::string &lightSampler,
                                       const std::string &file) {
    const std::string text =
        "wscene 2\n"
        "Material \"diffuse\" \"paper\" { reflectance = 0.5 }\n"
        "Shape \"rectangle\" \"floor\" { material = @paper  to_world = scale(5) }\n" + lamps +
        "Detector \"perspective\" \"cam\" { to_world = lookat(eye = " + eye + ", target = [0 0 0] m, up = [0 0 1])"
        "  fov = " + fov + "  resolution = [8 8]  response = \"radiometric\" }\n"
        "Integrator \"" + integrator + "\" \"it\" { max_depth = 2  light_sampler = \"" + lightSampler + "\" }\n"
        "Render { integrator = @it }\n";
    return SceneFromText(text, file);
}

// `misleading`: the dim panel large and close above the floor (it gives most of the light, much of
// it through kernel sampling, which MIS shares with light sampling), the bright one far away
// (36× the power, under half of the light): power selection is a poor guess here, but the mean
// must not move, and a wrong selection probability in MIS would move it.
std::unique_ptr<Scene> TwoPanels(const std::string &integrator, const std::string &lightSampler, bool misleading = false) {
    const std::string lamps =
        std::string(misleading
              ? "Shape \"rectangle\" \"dim\" { to_world = [scale(1), rotate(180 deg, [1 0 0]), translate([0 0 0.5] m)] }\n"
                "Shape \"rectangle\" \"bright\" { to_world = [scale(0.05), rotate(180 deg, [1 0 0]), translate([0 0 10] m)] }\n"
              : "Shape \"rectangle\" \"dim\" { to_world = [scale(0.3), rotate(180 deg, [1 0 0]), translate([-0.6 0 1] m)] }\n"
                "Shape \"rectangle\" \"bright\" { to_world = [scale(0.05), rotate(180 deg, [1 0 0]), translate([0.6 0 0.8] m)] }\n") +
        "Light \"area\" \"dim_lamp\" { shape = @dim  radiance = 1 W/m^2/sr  spectrum = line(550 nm) }\n"
        "Light \"area\" \"bright_lamp\" { shape = @bright  radiance = 14400 W/m^2/sr  spectrum = line(550 nm) }\n";
    return FloorUnderLamps(lamps, misleading ? "[0 -3 0.3] m" : "[0 -3 2] m", "20 deg", integrator, lightSampler,
                           "panels.wscene");
}

// χ² of 10⁵ draws (a fixed LCG from `seed`) of `sampler` at ctx against Pmf, over the lights
// `lights` (every draw must be one of them, and Sample's pmf must be Pmf's); its p-value.
double SamplingPValue(const LightSampler &sampler, const LightSampleContext &ctx,
                      const std::vector<const Light *> &lights, uint64_t seed) {
    std::vector<double> observed(lights.size(), 0.0), expected;
    for (const Light *l : lights) expected.push_back(sampler.Pmf(l, ctx) * 1e5);
    uint64_t state = seed;
    for (int i = 0; i < 100000; ++i) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        double pmf = 0;
        const Light *l = sampler.Sample(double(state >> 11) * 0x1.0p-53, ctx, &pmf);
        const auto it = std::find(lights.begin(), lights.end(), l);
        EXPECT_TRUE(it != lights.end()) << "a light outside the expected ones";
        if (it == lights.end()) return 0;
        observed[std::size_t(it - lights.begin())] += 1;
        EXPECT_EQ(pmf, sampler.Pmf(l, ctx));
        if (pmf != sampler.Pmf(l, ctx)) return 0;
    }
    return Chi2Test(observed, expected).pValue;
}

TEST(LightSampler, PowerIsProportionalAndSampled) {
    auto scene = TwoPanels("ray", "power");
    ASSERT_TRUE(scene);
    const std::vector<const Light *> &lights = scene->Lights();
    ASSERT_EQ(lights.size(), 2u);
    const LightSampler &power = scene->GetLightSampler(LightSelection::Power);
    // Φ = radiance·π·area: 1·π·0.36 against 14400·π·0.01 = 400×.
    const double p0 = power.Pmf(lights[0], {}), p1 = power.Pmf(lights[1], {});
    EXPECT_NEAR(p0 + p1, 1, 1e-12);
    EXPECT_NEAR(p1 / p0, 400, 400 * 1e-9);
    EXPECT_NEAR(LightPower(*lights[1]) / LightPower(*lights[0]), 400, 400 * 1e-9);
    // Sampling frequencies (χ² with 1 dof on 10⁵ draws of a fixed LCG).
    EXPECT_GT(SamplingPValue(power, {}, {lights[0], lights[1]}, 12345), 1e-3);
    // Uniform: the rule of light sampling before the parameter, exactly.
    const LightSampler &uniform = scene->GetLightSampler(LightSelection::Uniform);
    for (double u : {0.0, 0.25, 0.4999999, 0.5, 0.75, 0.9999999}) {
        double pmf = 0;
        EXPECT_EQ(uniform.Sample(u, {}, &pmf), lights[std::min<std::size_t>(1, std::size_t(u * 2))]);
        EXPECT_EQ(pmf, 0.5);
    }
}

TEST(LightSampler, PowerSelectionKeepsTheMeanAndCutsTheNoise) {
    for (const char *integrator : {"ray", "grt"}) {
        SCOPED_TRACE(integrator);
        auto uniform = TwoPanels(integrator, "uniform"), power = TwoPanels(integrator, "power");
        ASSERT_TRUE(uniform && power);
        const ReplicaEstimate u = ImageOverReplicas(RenderReplicas(*uniform, 256, 10, 1, "independent"));
        const ReplicaEstimate p = ImageOverReplicas(RenderReplicas(*power, 256, 10, 101, "independent"));
        ASSERT_GT(u.mean, 0);
        std::printf("MEASURED %s: uniform %.6g +- %.3g, power %.6g +- %.3g (standard errors of 10 x 256 spp)\n", integrator,
                    u.mean, u.StdError(), p.mean, p.StdError());
        const TTestResult same = WelchTTest(p.mean, p.varianceOfMean, p.dof, u.mean, u.varianceOfMean, u.dof);
        EXPECT_GT(same.pValue, 1e-3) << "power " << p.mean << " vs uniform " << u.mean << ": " << same.ToString();
        // The test can fail: a mean 6 % off is rejected (≈ 10 standard errors of the uniform
        // estimate, which with 9 degrees of freedom leaves room for its own scatter).
        const TTestResult biased = WelchTTest(1.06 * p.mean, 1.06 * 1.06 * p.varianceOfMean, p.dof, u.mean,
                                              u.varianceOfMean, u.dof);
        EXPECT_LT(biased.pValue, 1e-3) << biased.ToString();
        // The point of it: the bright panel no longer waits for half of the samples.
        EXPECT_LT(p.varianceOfMean, 0.25 * u.varianceOfMean)
            << "standard errors: power " << p.StdError() << ", uniform " << u.StdError();
    }
}

TEST(LightSampler, PowerSelectionIsUnbiasedWhereItGuessesBadly) {
    for (const char *integrator : {"ray", "grt"}) {
        SCOPED_TRACE(integrator);
        auto uniform = TwoPanels(integrator, "uniform", true), power = TwoPanels(integrator, "power", true);
        ASSERT_TRUE(uniform && power);
        const ReplicaEstimate u = ImageOverReplicas(RenderReplicas(*uniform, 256, 10, 1, "independent"));
        const ReplicaEstimate p = ImageOverReplicas(RenderReplicas(*power, 256, 10, 101, "independent"));
        std::printf("MEASURED %s (misleading): uniform %.6g +- %.3g, power %.6g +- %.3g\n", integrator, u.mean,
                    u.StdError(), p.mean, p.StdError());
        ASSERT_GT(u.mean, 0);
        const TTestResult same = WelchTTest(p.mean, p.varianceOfMean, p.dof, u.mean, u.varianceOfMean, u.dof);
        EXPECT_GT(same.pValue, 1e-3) << "power " << p.mean << " vs uniform " << u.mean << ": " << same.ToString();
        const TTestResult biased = WelchTTest(1.04 * p.mean, 1.04 * 1.04 * p.varianceOfMean, p.dof, u.mean,
                                              u.varianceOfMean, u.dof);
        EXPECT_LT(biased.pValue, 1e-3) << biased.ToString();
    }
}

// A floor under three panels, none in the camera's view: `near` (dim, large, low), `far` (bright,
// small, high, off to the side) and `away` (the brightest, 1 m above the floor but emitting upwards: it lights nothing
// the camera sees); optionally one more light (`extra`: a Gaussian beam, which gives no Reach, or a
// point light, a delta light that only next-event estimation reaches).
std::unique_ptr<Scene> ThreePanels(const std::string &integrator, const std::string &lightSampler,
                                   const std::string &extra = "") {
    const std::string lamps =
        "Shape \"rectangle\" \"near\" { to_world = [scale(0.4), rotate(180 deg, [1 0 0]), translate([-0.8 0.3 0.8] m)] }\n"
        "Shape \"rectangle\" \"far\" { to_world = [scale(0.1), rotate(150 deg, [1 0 0]), translate([1.5 1 2] m)] }\n"
        "Shape \"rectangle\" \"away\" { to_world = [scale(0.3), translate([0.6 -0.4 1] m)] }\n"
        "Light \"area\" \"near_lamp\" { shape = @near  radiance = 1 W/m^2/sr  spectrum = line(550 nm) }\n"
        "Light \"area\" \"far_lamp\" { shape = @far  radiance = 40 W/m^2/sr  spectrum = line(550 nm) }\n"
        "Light \"area\" \"away_lamp\" { shape = @away  radiance = 100 W/m^2/sr  spectrum = line(550 nm) }\n" +
        std::string(extra == "beam" ? "Light \"gaussian_beam\" \"laser\" { position = [0 0 3] m  direction = [0 0 -1]  "
                                      "waist_radius = 1 mm  power = 1 mW  spectrum = line(550 nm) }\n"
                    : extra == "point" ? "Light \"point\" \"bulb\" { position = [0.3 -0.8 0.5] m  intensity = 0.05 W/sr  "
                                         "spectrum = line(550 nm) }\n"
                                       : "");
    return FloorUnderLamps(lamps, "[0 -3 2.5] m", "10 deg", integrator, lightSampler, "three_panels.wscene");
}

TEST(LightSampler, ExhaustiveFollowsReachAndIsSampled) {
    auto scene = ThreePanels("ray", "exhaustive");
    ASSERT_TRUE(scene);
    const std::vector<const Light *> &lights = scene->Lights();
    ASSERT_EQ(lights.size(), 3u);
    const LightSampler &ex = scene->GetLightSampler(LightSelection::Exhaustive);
    TestRng rng(3);
    for (int k = 0; k < 4; ++k) {
        // A point of the floor (normal +z) under the lamps.
        const LightSampleContext ctx{Vec3(rng.Uniform() - 0.5, rng.Uniform() - 0.5, 0), Vec3(0, 0, 1)};
        double sum = 0;
        std::vector<double> pmf(3), reach(3);
        for (int i = 0; i < 3; ++i) {
            sum += pmf[std::size_t(i)] = ex.Pmf(lights[std::size_t(i)], ctx);
            reach[std::size_t(i)] = lights[std::size_t(i)]->Reach(ctx);
        }
        EXPECT_NEAR(sum, 1, 1e-12);
        EXPECT_EQ(pmf[2], 0) << "the panel that faces away";
        // A line spectrum: ∫S = 1 for every lamp, so the probabilities are the reaches' shares.
        EXPECT_NEAR(pmf[0] / pmf[1], reach[0] / reach[1], 1e-9 * reach[0] / reach[1]);
        // Sampling frequencies (χ², 1 dof, 10⁵ draws): never `away`; Sample's pmf is Pmf's.
        EXPECT_GT(SamplingPValue(ex, ctx, {lights[0], lights[1]}, 777 + uint64_t(k)), 1e-3);
    }
    // High above the lamps, facing down: `near` and `far` face down, away from it; only `away` reaches it.
    const LightSampleContext above{Vec3(0.6, -0.4, 6), Vec3(0, 0, -1)};
    EXPECT_EQ(ex.Pmf(lights[0], above), 0);
    EXPECT_EQ(ex.Pmf(lights[1], above), 0);
    EXPECT_NEAR(ex.Pmf(lights[2], above), 1, 1e-12);
    double p = 0;
    EXPECT_EQ(ex.Sample(0.5, above, &p), lights[2]);
    // A light without an estimate (a Gaussian beam): every receiver falls back to power.
    auto withBeam = ThreePanels("ray", "exhaustive", "beam");
    ASSERT_TRUE(withBeam);
    const LightSampler &fallback = withBeam->GetLightSampler(LightSelection::Exhaustive);
    const LightSampler &power = withBeam->GetLightSampler(LightSelection::Power);
    ASSERT_EQ(withBeam->Lights().size(), 4u);
    EXPECT_TRUE(std::isnan(withBeam->Lights().back()->Reach(above)));
    for (const Light *l : withBeam->Lights()) EXPECT_EQ(fallback.Pmf(l, above), power.Pmf(l, above));
}

TEST(LightSampler, ExhaustiveSelectionKeepsTheMeanAndCutsTheNoise) {
    for (const char *integrator : {"ray", "grt"}) {
        SCOPED_TRACE(integrator);
        // (with a point light: a delta light's Reach decides alone whether it is ever sampled)
        auto uniform = ThreePanels(integrator, "uniform", "point"), ex = ThreePanels(integrator, "exhaustive", "point");
        ASSERT_TRUE(uniform && ex);
        const std::vector<Image> ru = RenderReplicas(*uniform, 1024, 10, 1, "independent");
        const std::vector<Image> re = RenderReplicas(*ex, 1024, 10, 101, "independent");
        const ReplicaEstimate u = ImageOverReplicas(ru), e = ImageOverReplicas(re);
        ASSERT_GT(u.mean, 0);
        std::printf("MEASURED %s: uniform %.6g +- %.3g, exhaustive %.6g +- %.3g (standard errors of 10 x 1024 spp)\n",
                    integrator, u.mean, u.StdError(), e.mean, e.StdError());
        const TTestResult same = WelchTTest(e.mean, e.varianceOfMean, e.dof, u.mean, u.varianceOfMean, u.dof);
        EXPECT_GT(same.pValue, 1e-3) << "exhaustive " << e.mean << " vs uniform " << u.mean << ": " << same.ToString();
        // The test can fail: a mean 4 % off is rejected.
        const TTestResult biased = WelchTTest(1.04 * e.mean, 1.04 * 1.04 * e.varianceOfMean, e.dof, u.mean,
                                              u.varianceOfMean, u.dof);
        EXPECT_LT(biased.pValue, 1e-3) << biased.ToString();
        // The point of it: a quarter of uniform's samples went to the panel that faces away. The
        // pixels' own variance (the `variance` channel, honest under the independent sampler,
        // averaged over 64 pixels × 10 replicas of 1024 samples each: its relative error is ~1 %).
        const double vu = ImageOverReplicas(ru, "variance").mean, ve = ImageOverReplicas(re, "variance").mean;
        std::printf("MEASURED %s: pixel variance exhaustive / uniform = %.3f\n", integrator, ve / vu);
        EXPECT_LT(ve, 0.75 * vu) << "pixel variances: exhaustive " << ve << ", uniform " << vu;
    }
}

}  // namespace
}  // namespace phasor::test
