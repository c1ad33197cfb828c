// SPDX-License-Identifier: Apache-2.0
// Issue 12 (c): a `harvey_shack` plate under a `distant` source seen by a camera with `grt`
// (scenes/validation/harvey_shack.wscene) — the specular glint (closed form through the listed
// lobe, D14) plus the halo (NEE through the continuous lobe) carry the total reflected flux F·E·cosθ.
//
// Measurement: the plate is effectively infinite and the source at infinity, so pixel (x, y) reads
// the reflected radiance L(ω_o) of its own viewing direction, and Σ L·cosθ_o·Ω_pixel (Ω_pixel =
// the pinhole's pixel solid angle, scale²·cos³ of the angle to the optical axis) is the flux per
// unit plate area reflected into the field. Its error comes from independent Sobol' replicas
// (support/replicas.h). Reference: F·E·cosθ with F from fresnel.h's closed form for the
// substrate's index — and the test checks that this is what the scene measures at these values:
// the flux into the field predicted from the kernel's own Eval (the halo's part outside the field,
// and the kernel's non-reciprocity, docs/kernels.md) differs from F·E·cosθ by < 3e-4 of it.
// Power: the same data against a source 5 % too bright must be rejected (the image is linear in
// the source irradiance, so this is exactly the render of a biased source).
#include <gtest/gtest.h>

#include "core/render/detector.h"
#include "core/render/material.h"
#include "materials/fresnel.h"
#include "render_row.h"
#include "support/stats.h"

namespace phasor::test {
namespace {

TEST(HarveyShackPlate, GlintPlusHaloCarryTheTotalReflectedFlux) {
    const double thetaDeg = 30, lambda = 550e-9, E = 1;
    const Complex ior(0.2, 3.4);
    const int res = 101, spp = 8, replicas = 8;
    const double fovDeg = 20;
    const DefineList defines = {{"theta", "30 deg"},     {"lambda", "550 nm"},       {"ior", "0.2+3.4i"},
                                {"sigma_h", "40 nm"},    {"alpha_r", "0.005"},       {"gamma", "6"},
                                {"radius", "4.65 mrad"}, {"irradiance", "1 W/m^2"},  {"res", std::to_string(res)},
                                {"fov", "20 deg"}};
    auto scene = BuildValidation(ValidationScene("harvey_shack.wscene"), defines, "");
    ASSERT_TRUE(scene);
    const Detector &cam = scene->GetDetector();
    ASSERT_EQ(cam.Width(), res);

    // Per-pixel weight cosθ_o·Ω_pixel from the camera's own rays (pixel centres).
    const double scale = 2 * std::tan(Radians(fovDeg) / 2) / res;
    const Vec3 axis = cam.Generate(Vec2(0.5 * res, 0.5 * res), Vec2())->ray.d;
    std::vector<double> weight(std::size_t(res) * res);
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            const Vec3 d = cam.Generate(Vec2(x + 0.5, y + 0.5), Vec2())->ray.d;
            const double cosAxis = Dot(d, axis);
            weight[std::size_t(y) * res + x] = std::max(0.0, -d.z) * scale * scale * cosAxis * cosAxis * cosAxis;
        }

    // The reference F·E·cosθ (fresnel.h's closed form for the conductor).
    const double cosT = std::cos(Radians(thetaDeg));
    const double F = FresnelComplex(cosT, 1.0, ior);
    const double expected = F * E * cosT;

    // What the scene should read by the kernel itself: the glint α_spec·F·E·cosθ plus, per pixel
    // (4×4 points), E·cosθ·f(ω_view → ω_sun)·cosθ_o·Ω — the flux into the field.
    {
        const Vec3 toSun = Normalize(Vec3(-std::sin(Radians(thetaDeg)), 0, cosT));
        const auto si0 = scene->Intersect(cam.Generate(Vec2(0.5 * res, 0.5 * res), Vec2())->ray);
        ASSERT_TRUE(si0 && si0->material);
        const Material &m = *si0->material;
        SampledWavelengths wl;
        wl.lambda[0] = lambda;
        wl.pdf[0] = 1;
        wl.delta = true;
        double field = 0;
        for (int y = 0; y < res; ++y)
            for (int x = 0; x < res; ++x)
                for (int a = 0; a < 4; ++a)
                    for (int b = 0; b < 4; ++b) {
                        const Vec3 d = cam.Generate(Vec2(x + (a + 0.5) / 4, y + (b + 0.5) / 4), Vec2())->ray.d;
                        const double cosAxis = Dot(d, axis);
                        ScatterQuery q;
                        q.wl = &wl;
                        q.wi = si0->shading.ToLocal(-d);
                        const double f = m.Eval(q, si0->shading.ToLocal(toSun))[0];
                        field += f * cosT * E * std::max(0.0, -d.z) * scale * scale * Sqr(cosAxis) * cosAxis / 16;
                    }
        ScatterQuery q;
        q.wl = &wl;
        q.wi = si0->shading.ToLocal(toSun);
        NearDeltaLobes lobes;
        m.ListNearDelta(q, lobes);
        ASSERT_EQ(lobes.count, 1);
        const double glint = lobes.lobe[0].weight[0] * E * cosT;
        RecordProperty("alpha_spec", std::to_string(lobes.lobe[0].weight[0] / F));
        std::printf("harvey_shack plate: predicted glint %.6f + halo in field %.6f = %.6f (F·E·cosθ %.6f, %+.1e)\n",
                    glint, field, glint + field, expected, (glint + field) / expected - 1);
        EXPECT_NEAR(glint + field, expected, 3e-4 * expected)
            << "the scene does not measure F at these values: glint " << glint << " + halo in field " << field;
    }

    const auto images = RenderReplicas(*scene, spp, replicas, 101);
    std::vector<double> sums;
    for (const Image &img : images) {
        const int c = img.ChannelIndex("intensity");
        double s = 0;
        for (int y = 0; y < res; ++y)
            for (int x = 0; x < res; ++x) s += img.At(x, y, c) * weight[std::size_t(y) * res + x];
        sums.push_back(s);
    }
    double mean = 0;
    for (double s : sums) mean += s / replicas;
    double ss = 0;
    for (double s : sums) ss += Sqr(s - mean);
    const double sigma = std::sqrt(ss / (replicas - 1) / replicas);
    RecordProperty("flux_over_E", std::to_string(mean));
    RecordProperty("sigma", std::to_string(sigma));
    EXPECT_LE(std::abs(mean - expected), 3 * sigma)
        << "reflected flux " << mean << " ± " << sigma << " vs F·E·cosθ = " << expected;
    // Power: a source 5 % too bright is rejected by the same 3σ criterion.
    EXPECT_GT(std::abs(mean - 1.05 * expected), 3 * sigma)
        << "a 5 % brighter source would pass: σ = " << sigma << " (" << sigma / expected << " relative)";
    EXPECT_GT(std::abs(mean - 0.95 * expected), 3 * sigma);
    std::printf("harvey_shack plate: flux %.6f ± %.6f (rel %.2e), expected F·E·cosθ = %.6f\n", mean, sigma,
                sigma / expected, expected);
}

}  // namespace
}  // namespace phasor::test
