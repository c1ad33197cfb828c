// SPDX-License-Identifier: Apache-2.0
// materials/smooth_surface.h: a bare surface is the Fresnel interface, a coated one the layer
// stack (in order from outside, reversed from inside), and kernels expose theirs as `substrate`.
#include "materials/smooth_surface.h"

#include <gtest/gtest.h>

#include "materials/fresnel.h"
#include "materials/smooth_kernel.h"
#include "material_test_util.h"

namespace phasor {
namespace {

constexpr double Lambda = 550e-9;

TEST(SmoothSurface, BareIsTheFresnelInterface) {
    const SmoothSurface s(std::make_shared<ConstantComplexSpectrum>(Complex(0.2, 3.0)), 0, nullptr);
    for (double c : {1.0, 0.6, 0.05}) {
        const StackResponse r = s.Response(Lambda, 1.0, c, false, TextureEvalContext());
        const FresnelCoefficients f = FresnelAmplitudes(c, 1.0, Complex(0.2, 3.0));
        EXPECT_EQ(r.rs, f.rs);
        EXPECT_EQ(r.rp, f.rp);
    }
}

TEST(SmoothSurface, CauchyTermAddsToTheSubstrateIndex) {
    const SmoothSurface s(std::make_shared<ConstantComplexSpectrum>(Complex(1.5, 0)), 0.01e-12, nullptr);
    EXPECT_NEAR(s.SubstrateIndex(500e-9).real(), 1.5 + 0.01e-12 / (500e-9 * 500e-9), 1e-15);
    EXPECT_FALSE(s.Absorbing(500e-9));
}

TEST(SmoothSurface, CoatingLayersInOrderFromOutsideAndReversedFromInside) {
    auto c = std::make_shared<Coating>();
    c->layers.push_back({std::make_shared<ConstantComplexSpectrum>(Complex(1.38, 0)), FloatTexture(100e-9, Dim::Length())});
    c->layers.push_back({std::make_shared<ConstantComplexSpectrum>(Complex(2.3, 0.01)), FloatTexture(60e-9, Dim::Length())});
    const SmoothSurface s(std::make_shared<ConstantComplexSpectrum>(Complex(1.52, 0)), 0, c);
    const double cosI = std::cos(0.4);
    std::vector<Layer> down = {{Complex(1.38, 0), 100e-9}, {Complex(2.3, 0.01), 60e-9}};
    const StackResponse a = s.Response(Lambda, 1.0, cosI, false, TextureEvalContext());
    const StackResponse b = LayerStackResponse(Lambda, 1.0, cosI, down, Complex(1.52, 0));
    EXPECT_EQ(a.rs, b.rs);
    EXPECT_EQ(a.tp, b.tp);
    std::vector<Layer> up = {down[1], down[0]};
    const StackResponse ai = s.Response(Lambda, 1.0, cosI, true, TextureEvalContext());
    const StackResponse bi = LayerStackResponse(Lambda, 1.52, cosI, up, Complex(1, 0));
    EXPECT_EQ(ai.rp, bi.rp);
    EXPECT_EQ(ai.ts, bi.ts);
}

TEST(SmoothSurface, ConductorAndDielectricExposeTheirSurface) {
    // The facets the kernels built on a substrate or a coating ask for (smooth_kernel.h).
    Diagnostics diag;
    auto gold = std::dynamic_pointer_cast<const SmoothKernel>(
        test::BuildMaterial("conductor", ParamDict().Set("ior", Value::String("Au")), diag));
    ASSERT_TRUE(gold);
    EXPECT_TRUE(gold->Surface().Absorbing(550e-9));
    auto glass = std::dynamic_pointer_cast<const SmoothKernel>(
        test::BuildMaterial("dielectric", ParamDict().Set("ior", Value::Number(1.5)), diag));
    ASSERT_TRUE(glass);
    EXPECT_DOUBLE_EQ(glass->Surface().SubstrateIndex(550e-9).real(), 1.5);
    EXPECT_FALSE(dynamic_cast<const CoatingKernel *>(glass.get()));
    auto film = test::BuildMaterial(
        "thin_film", ParamDict().Set("ior", Value::Number(1.33)).Set("thickness", Value::Number(300e-9, Dim::Length())), diag);
    const auto *coating = dynamic_cast<const CoatingKernel *>(film.get());
    ASSERT_TRUE(coating);
    ASSERT_TRUE(coating->Layers());
    EXPECT_EQ(coating->Layers()->layers.size(), 1u);
    auto diffuse = test::BuildMaterial("diffuse", ParamDict(), diag);
    ASSERT_TRUE(diffuse);
    EXPECT_FALSE(dynamic_cast<const SmoothKernel *>(diffuse.get()));
}

}  // namespace
}  // namespace phasor
