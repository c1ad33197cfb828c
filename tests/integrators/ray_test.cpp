// SPDX-License-Identifier: Apache-2.0
// The classical `ray` integrator against closed forms: the furnace (closed diffuse enclosure with
// uniform emission → L = Le/(1 − a)) and direct lighting of a diffuse plane by a disk emitter.
#include <gtest/gtest.h>

#include "support/scene_builder.h"
#include "support/stats.h"

namespace phasor::test {
namespace {

// Camera inside a sphere whose inner surface is diffuse (albedo a) and emits radiance Le:
// every path sees Le·Σ aᵏ = Le/(1 − a) (style.md §2.6 furnace test).
TEST(RayIntegrator, FurnaceClosedDiffuseSphere) {
    for (double albedo : {0.0, 0.5, 0.8}) {  // 0: the camera reads the emitted radiance itself
        SceneBuilder b;
        b.Add("Material", "diffuse", "wall").Set("reflectance", Num(albedo));
        b.Add("Shape", "sphere", "room").Set("radius", Len(1)).Set("material", Ref("wall"));
        b.Add("Light", "area").Set("shape", Ref("room")).Set("two_sided", Value::Bool(true))
            .Set("radiance", Value::Number(1.0, Dim::Radiance()));
        b.Add("Detector", "perspective", "cam").Set("resolution", Value::List({Int(8), Int(8)}))
            .Set("fov", Value::Number(Radians(90), Dim::Angle()));
        b.Add("Integrator", "ray").Set("max_depth", Int(-1)).Set("rr_depth", Int(1));
        std::string log;
        auto scene = b.Build(&log);
        ASSERT_TRUE(scene) << log;
        Image img = RenderImage(*scene, 256, 7);
        BlockMean m = MeanOver(img, 0, 0, 8, 8);
        double expected = 1 / (1 - albedo);
        TTestResult t = MeanTTest(m.mean, m.varianceOfMean, 64.0 * 256 - 1, expected);
        EXPECT_GT(t.pValue, 0.001) << "albedo " << albedo << ": mean " << m.mean << " ± "
                                   << std::sqrt(m.varianceOfMean) << " vs " << expected << " (" << t.ToString() << ")";
        // Also bound the error absolutely, so a large variance cannot hide a bias.
        EXPECT_NEAR(m.mean, expected, 0.02 * expected);
    }
}

// A downward-facing disk emitter of radiance L and radius R at height h over a diffuse plane of
// albedo a: on the axis E = π L R²/(h² + R²), so the plane's radiance is a·L·R²/(h² + R²).
TEST(RayIntegrator, DirectLightingFromDiskMatchesClosedForm) {
    const double L = 5, R = 0.2, h = 1, a = 0.6;
    SceneBuilder b;
    b.Add("Material", "diffuse", "floor_mat").Set("reflectance", Num(a));
    b.Add("Shape", "rectangle", "floor").Set("material", Ref("floor_mat"))
        .Set("to_world", Call("scale", {Num(10)}));
    b.Add("Shape", "disk", "lamp").Set("radius", Len(R))
        .Set("to_world", Value::List({Call("rotate", {Value::Number(Pi, Dim::Angle()), Vec(1, 0, 0)}),
                                      Call("translate", {LenVec(0, 0, h)})}));
    b.Add("Light", "area").Set("shape", Ref("lamp")).Set("radiance", Value::Number(L, Dim::Radiance()));
    // Oblique view of a ~4 mm patch around the axis point (irradiance varies by < 1e-5 there).
    b.Add("Detector", "perspective", "cam").Set("resolution", Value::List({Int(4), Int(4)}))
        .Set("fov", Value::Number(Radians(0.2), Dim::Angle()))
        .Set("to_world", Call("lookat", {LenVec(1, 0, 0.8), LenVec(0, 0, 0), Vec(0, 0, 1)}));
    b.Add("Integrator", "ray").Set("max_depth", Int(1));
    std::string log;
    auto scene = b.Build(&log);
    ASSERT_TRUE(scene) << log;
    Image img = RenderImage(*scene, 1024, 3);
    BlockMean m = MeanOver(img, 0, 0, 4, 4);
    double expected = a * L * R * R / (h * h + R * R);
    TTestResult t = MeanTTest(m.mean, m.varianceOfMean, 16.0 * 1024 - 1, expected);
    EXPECT_GT(t.pValue, 0.001) << m.mean << " vs " << expected << " (" << t.ToString() << ")";
    EXPECT_NEAR(m.mean, expected, 0.01 * expected);
}

}  // namespace
}  // namespace phasor::test
