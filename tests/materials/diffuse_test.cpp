// SPDX-License-Identifier: Apache-2.0
// `diffuse`: kernel-specific properties beyond the generic contract suite.
#include <gtest/gtest.h>

#include "material_test_util.h"

namespace phasor::test {
namespace {

TEST(Diffuse, LambertianValueAndTwoSidedness) {
    Diagnostics diag;
    auto m = BuildMaterial("diffuse", ParamDict().Set("reflectance", Value::Number(0.7)), diag);
    ASSERT_TRUE(m && diag.All().empty());
    const SampledWavelengths wl = TestWavelengths(550e-9);
    for (double side : {1.0, -1.0}) {
        ScatterQuery q;
        q.wi = DirectionFromCosTheta(side * 0.6, 0.2);
        q.wl = &wl;
        const Vec3 same = DirectionFromCosTheta(side * 0.3, 2.0),
                   other = DirectionFromCosTheta(-side * 0.3, 2.0);
        const Prep k(*m, q);
        EXPECT_NEAR(k->Eval(same)[0], 0.7 / Pi, 1e-15);  // f = R/π
        EXPECT_NEAR(k->Pdf(same), 0.3 / Pi, 1e-15);      // cosine-weighted
        EXPECT_TRUE(k->Eval(other).IsZero());            // never transmits
        EXPECT_EQ(k->Pdf(other), 0);
        EXPECT_FALSE(k->IsDeltaOnly());
        auto s = k->Sample(0.5, Vec2(0.3, 0.8));
        ASSERT_TRUE(s);
        EXPECT_GT(s->wo.z * side, 0);  // reflected on wi's side
        EXPECT_NEAR(s->weight[0], 0.7, 1e-15);
    }
}

TEST(Diffuse, TextureDrivesTheReflectance) {
    Diagnostics diag;
    auto m = BuildMaterial("diffuse", ParamDict().Set("texture", Value::Ref("contract_checker")), diag);
    ASSERT_TRUE(m && diag.All().empty());
    const SampledWavelengths wl = TestWavelengths(550e-9);
    ScatterQuery q;
    q.wi = Vec3(0, 0, 1);
    q.wl = &wl;
    q.tex.uv = Vec2(0.1, 0.1);  // check (0, 0): color0 = 0.1 (scale 4)
    EXPECT_NEAR(Prep(*m, q)->Sample(0.5, Vec2(0.5, 0.5))->weight[0], 0.1, 1e-15);
    q.tex.uv = Vec2(0.3, 0.1);  // check (1, 0): color1 = 0.9
    EXPECT_NEAR(Prep(*m, q)->Sample(0.5, Vec2(0.5, 0.5))->weight[0], 0.9, 1e-15);
    EXPECT_NEAR(Prep(*m, q)->Eval(Vec3(0, 0.6, 0.8))[0], 0.9 / Pi, 1e-15);
}

TEST(Diffuse, ReflectanceAboveOneIsAnError) {
    Diagnostics diag;
    EXPECT_FALSE(BuildMaterial("diffuse", ParamDict().Set("reflectance", Value::Number(1.2)), diag));
    EXPECT_TRUE(diag.HasErrors());
}

TEST(Diffuse, TextureWinsOverReflectanceWithAWarning) {
    Diagnostics diag;
    auto m = BuildMaterial(
        "diffuse",
        ParamDict().Set("reflectance", Value::Number(0.3)).Set("texture", Value::Ref("contract_half")), diag);
    ASSERT_TRUE(m);
    EXPECT_FALSE(diag.HasErrors());
    ASSERT_EQ(diag.WarningCount(), 1u);
    EXPECT_NE(diag.All()[0].message.find("ignoring 'reflectance'"), std::string::npos);
    const SampledWavelengths wl = LineWavelength(600e-9);
    ScatterQuery q;
    q.wi = Vec3(0, 0, 1);
    q.wl = &wl;
    EXPECT_NEAR(Prep(*m, q)->Sample(0.5, Vec2(0.5, 0.5))->weight[0], 0.5, 1e-15);
}

}  // namespace
}  // namespace phasor::test
