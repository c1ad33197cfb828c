// SPDX-License-Identifier: Apache-2.0
// Texture plug-ins (src/core/textures): constant and checkerboard. They live here because the
// diffuse kernel is their first user (tests/CMakeLists.txt has no core/textures folder yet).
#include <gtest/gtest.h>

#include "material_test_util.h"

namespace phasor::test {
namespace {

std::shared_ptr<Texture> BuildTexture(const std::string &type, const ParamDict &d, Diagnostics &diag) {
    return BuildObject<Texture>("Texture", type, d, diag);
}

TEST(Textures, AreRegistered) {
    EXPECT_NE(Registry<Texture>::Find("constant"), nullptr);
    EXPECT_NE(Registry<Texture>::Find("checkerboard"), nullptr);
}

TEST(Textures, ConstantIsTheSameEverywhere) {
    Diagnostics diag;
    auto t = BuildTexture("constant", ParamDict().Set("value", Value::Number(0.25)), diag);
    ASSERT_TRUE(t && diag.All().empty());
    const SampledWavelengths wl = TestWavelengths(500e-9);
    for (Vec2 uv : {Vec2(0, 0), Vec2(0.7, -3.2), Vec2(1e6, 2)}) {
        const SampledSpectrum v = t->Eval(TextureEvalContext::AtUV(uv), wl);
        for (int j = 0; j < NumWavelengths; ++j) EXPECT_EQ(v[j], 0.25);
    }
    EXPECT_EQ(t->MaxValue(), 0.25);
}

TEST(Textures, CheckerboardPattern) {
    Diagnostics diag;
    auto t = BuildTexture("checkerboard",
                          ParamDict()
                              .Set("color0", Value::Number(0.1))
                              .Set("color1", Value::Number(0.7))
                              .Set("scale", Value::Number(4)),
                          diag);
    ASSERT_TRUE(t && diag.All().empty());
    const SampledWavelengths wl = LineWavelength(550e-9);
    auto at = [&](double u, double v) { return t->Eval(TextureEvalContext::AtUV(Vec2(u, v)), wl)[0]; };
    EXPECT_EQ(at(0.1, 0.1), 0.1);    // check (0, 0)
    EXPECT_EQ(at(0.3, 0.1), 0.7);    // (1, 0)
    EXPECT_EQ(at(0.3, 0.3), 0.1);    // (1, 1)
    EXPECT_EQ(at(0.1, 0.3), 0.7);    // (0, 1)
    EXPECT_EQ(at(-0.1, 0.1), 0.7);   // (−1, 0): the pattern continues across 0
    EXPECT_EQ(at(-0.1, -0.1), 0.1);  // (−1, −1)
    EXPECT_EQ(at(0.99, 0.01), 0.7);  // (3, 0): four checks per unit
    EXPECT_EQ(at(1.01, 0.01), 0.1);  // (4, 0)
    EXPECT_EQ(t->MaxValue(), 0.7);
    // Half of a large uv area is each colour.
    int n0 = 0;
    for (int i = 0; i < 100; ++i)
        for (int j = 0; j < 100; ++j) n0 += at((i + 0.5) / 37.0, (j + 0.5) / 41.0) == 0.1;
    EXPECT_NEAR(n0 / 10000.0, 0.5, 0.02);
}

TEST(Textures, CheckerboardRejectsNonPositiveScale) {
    Diagnostics diag;
    EXPECT_FALSE(BuildTexture("checkerboard", ParamDict().Set("scale", Value::Number(0)), diag));
    EXPECT_TRUE(diag.HasErrors());
}

}  // namespace
}  // namespace phasor::test
