// SPDX-License-Identifier: Apache-2.0
// `conductor`: kernel-specific properties beyond the generic contract suite.
#include <gtest/gtest.h>

#include "material_test_util.h"
#include "materials/fresnel.h"
#include "core/spectrum/named_ior.h"

namespace phasor::test {
namespace {

std::shared_ptr<Material> Conductor(const ParamDict &d, Diagnostics &diag) {
    return BuildMaterial("conductor", d, diag);
}

std::shared_ptr<Material> Conductor(const ParamDict &d) {
    Diagnostics diag;
    auto m = Conductor(d, diag);
    EXPECT_TRUE(m && diag.All().empty());
    return m;
}

TEST(Conductor, WeightIsComplexFresnel) {
    auto m = Conductor(ParamDict().Set("ior", Value::ComplexNumber(Complex(0.2, 3.0))));
    const SampledWavelengths wl = TestWavelengths(550e-9);
    for (double cosI : {1.0, 0.5, 0.05, -0.7}) {
        ScatterQuery q;
        q.wi = DirectionFromCosTheta(cosI, 1.1);
        q.wl = &wl;
        auto s = Prep(*m, q)->Sample(0.3, Vec2(0.2, 0.7));
        ASSERT_TRUE(s);
        EXPECT_EQ(s->flags, unsigned(ScatterReflection | ScatterNearDelta));
        EXPECT_EQ(s->pdf, 1);
        EXPECT_LT(Length(s->wo - ReflectLocal(q.wi)), 1e-15);  // two-sided: mirrored on wi's side
        for (int j = 0; j < NumWavelengths; ++j)
            EXPECT_NEAR(s->weight[j], FresnelConductor(std::abs(cosI), Complex(0.2, 3.0)), 1e-15);
    }
}

Value Nk(Value n, Value k) { return Value::Call("nk", {std::move(n), std::move(k)}, {"n", "k"}); }

TEST(Conductor, NkSpectraEqualTheComplexIor) {
    auto a = Conductor(ParamDict().Set("ior", Value::ComplexNumber(Complex(1.2, 7.26))));
    auto b = Conductor(ParamDict().Set("ior", Nk(Value::Number(1.2), Value::Number(7.26))));
    const SampledWavelengths wl = TestWavelengths(700e-9);
    ScatterQuery q;
    q.wi = DirectionFromCosTheta(0.3, 0.0);
    q.wl = &wl;
    auto sa = Prep(*a, q)->Sample(0.5, Vec2()), sb = Prep(*b, q)->Sample(0.5, Vec2());
    ASSERT_TRUE(sa && sb);
    for (int j = 0; j < NumWavelengths; ++j) EXPECT_EQ(sa->weight[j], sb->weight[j]);
}

TEST(Conductor, TabulatedMetalsPerWavelength) {
    const std::pair<std::string, Metal> metals[] = {
        {"Al", Metal::Al}, {"Ag", Metal::Ag}, {"Au", Metal::Au}, {"Cu", Metal::Cu}};
    for (const auto &[name, metal] : metals) {
        auto m = Conductor(ParamDict().Set("ior", Value::String(name)));
        const SampledWavelengths wl = TestWavelengths(450e-9);
        ScatterQuery q;
        q.wi = DirectionFromCosTheta(0.8, 0.0);
        q.wl = &wl;
        auto s = Prep(*m, q)->Sample(0.5, Vec2());
        ASSERT_TRUE(s);
        for (int j = 0; j < NumWavelengths; ++j)
            EXPECT_NEAR(s->weight[j], FresnelConductor(0.8, MetalIndex(metal, wl.lambda[j])), 1e-15)
                << name;
    }
    // Gold is yellow: it reflects red far better than blue.
    auto au = Conductor(ParamDict().Set("ior", Value::String("Au")));
    const SampledWavelengths blue = LineWavelength(450e-9), red = LineWavelength(700e-9);
    ScatterQuery q;
    q.wi = Vec3(0, 0, 1);
    q.wl = &blue;
    const double rBlue = Prep(*au, q)->Sample(0.5, Vec2())->weight[0];
    q.wl = &red;
    const double rRed = Prep(*au, q)->Sample(0.5, Vec2())->weight[0];
    EXPECT_GT(rRed, rBlue + 0.4);
}

TEST(Conductor, DefaultIsAluminium) {
    auto def = Conductor(ParamDict());
    auto al = Conductor(ParamDict().Set("ior", Value::String("Al")));
    const SampledWavelengths wl = TestWavelengths(550e-9);
    ScatterQuery q;
    q.wi = DirectionFromCosTheta(0.9, 0.0);
    q.wl = &wl;
    EXPECT_EQ(Prep(*def, q)->Sample(0.5, Vec2())->weight[0], Prep(*al, q)->Sample(0.5, Vec2())->weight[0]);
}

TEST(Conductor, OutsideMediumEntersTheFresnelTerm) {
    auto m = Conductor(ParamDict().Set("ior", Value::ComplexNumber(Complex(0.2, 3.0))));
    const SampledWavelengths wl = LineWavelength(550e-9);
    ScatterQuery q;
    q.wi = DirectionFromCosTheta(0.6, 0.0);
    q.wl = &wl;
    q.etaOutside = 1.33;
    EXPECT_NEAR(Prep(*m, q)->Sample(0.5, Vec2())->weight[0], FresnelComplex(0.6, 1.33, Complex(0.2, 3.0)), 1e-15);
}

TEST(Conductor, ConflictingOrInvalidParametersAreErrors) {
    const ParamDict bad[] = {
        ParamDict().Set("metal", Value::String("Au")),  // the old parameter: now ior = "Au"
        ParamDict().Set("ior", Value::ComplexNumber(Complex(0.2, -3.0))),
        ParamDict().Set("ior", Value::ComplexNumber(Complex(-0.2, 3.0))),
        ParamDict().Set("ior", Nk(Value::Number(-1), Value::Number(1))),
        ParamDict().Set("ior", Nk(Value::Number(1), Value::Number(-1))),
        ParamDict().Set("ior", Value::String("Pt")),
        ParamDict().Set("ior", Value::Call("nk", {Value::Number(1)}, {"kappa"})),
        ParamDict().Set("ior", Value::Number(1, Dim::Length())),
    };
    for (const ParamDict &d : bad) {
        Diagnostics diag;
        EXPECT_FALSE(Conductor(d, diag));
        EXPECT_TRUE(diag.HasErrors());
    }
}

}  // namespace
}  // namespace phasor::test
