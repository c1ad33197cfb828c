// SPDX-License-Identifier: Apache-2.0
// `dielectric`: kernel-specific properties beyond the generic contract suite.
#include <gtest/gtest.h>

#include "material_test_util.h"
#include "materials/fresnel.h"

namespace phasor::test {
namespace {

std::shared_ptr<Material> Dielectric(double ior, double cauchyB = 0) {
    ParamDict d;
    d.Set("ior", Value::Number(ior));
    if (cauchyB != 0) d.Set("cauchy_b", Value::Number(cauchyB, Dim::Area()));
    Diagnostics diag;
    auto m = BuildMaterial("dielectric", d, diag);
    EXPECT_TRUE(m && diag.All().empty());
    return m;
}

ScatterQuery Query(const Vec3 &wi, const SampledWavelengths &wl) {
    ScatterQuery q;
    q.wi = wi;
    q.wl = &wl;
    return q;
}

TEST(Dielectric, LobeChoiceIsFresnelAtTheHero) {
    auto m = Dielectric(1.5);
    const SampledWavelengths wl = TestWavelengths(550e-9);
    for (double cosI : {1.0, 0.7, 0.2, 0.02, -0.95, -0.8}) {
        const ScatterQuery q = Query(DirectionFromCosTheta(cosI, 0.4), wl);
        const double eta = cosI > 0 ? 1.5 : 1 / 1.5;
        const double r = FresnelDielectric(std::abs(cosI), eta);
        auto below = Prep(*m, q)->Sample(r * (1 - 1e-9), Vec2(0.5, 0.5));
        auto above = Prep(*m, q)->Sample(r * (1 + 1e-9) + 1e-12, Vec2(0.5, 0.5));
        ASSERT_TRUE(below && above);
        EXPECT_EQ(below->lobe, 0);
        EXPECT_TRUE(below->flags & ScatterReflection);
        EXPECT_NEAR(below->pdf, r, 1e-15);
        EXPECT_EQ(above->lobe, 1);
        EXPECT_TRUE(above->flags & ScatterTransmission);
        EXPECT_NEAR(above->pdf, 1 - r, 1e-15);
        EXPECT_NEAR(above->eta, eta, 1e-15);
        // Lossless: reflected + transmitted power = incident power (R + T = 1) at every slot.
        for (int j = 0; j < NumWavelengths; ++j) {
            EXPECT_NEAR(below->weight[j] * below->pdf + above->weight[j] * above->pdf * eta * eta, 1, 1e-14);
        }
        // Radiance scaling (η_i/η_t)² on refraction: a/p = T/T·(1/η²).
        EXPECT_NEAR(above->weight[0], 1 / (eta * eta), 1e-14);
    }
}

TEST(Dielectric, TotalInternalReflectionFromInside) {
    auto m = Dielectric(1.5);
    const SampledWavelengths wl = TestWavelengths(550e-9);
    const ScatterQuery q = Query(DirectionFromCosTheta(-0.5, 1.0), wl);  // 60° > critical 41.8°
    for (double u0 : {0.0, 0.5, 1 - 1e-12}) {
        auto s = Prep(*m, q)->Sample(u0, Vec2(0.1, 0.9));
        ASSERT_TRUE(s);
        EXPECT_TRUE(s->flags & ScatterReflection);
        EXPECT_EQ(s->pdf, 1);
        EXPECT_NEAR(s->weight[0], 1, 1e-15);  // |r|² of the complex Fresnel amplitude: 1 to round-off
        EXPECT_LT(Length(s->wo - ReflectLocal(q.wi)), 1e-15);
    }
}

TEST(Dielectric, IndexMatchedPassesStraightThrough) {
    auto m = Dielectric(1.0);
    const SampledWavelengths wl = TestWavelengths(400e-9);
    const ScatterQuery q = Query(DirectionFromCosTheta(0.3, 2.0), wl);
    auto s = Prep(*m, q)->Sample(0.0, Vec2(0.5, 0.5));
    ASSERT_TRUE(s);
    EXPECT_TRUE(s->flags & ScatterTransmission);
    EXPECT_LT(Length(s->wo + q.wi), 1e-15);
    EXPECT_EQ(s->weight[0], 1);
}

TEST(Dielectric, OutsideMediumSetsTheRelativeIndex) {
    auto m = Dielectric(1.5);
    const SampledWavelengths wl = TestWavelengths(550e-9);
    ScatterQuery q = Query(DirectionFromCosTheta(0.6, 0.0), wl);
    q.etaOutside = 1.33;  // glass under water
    auto s = Prep(*m, q)->Sample(0.999999, Vec2(0.5, 0.5));
    ASSERT_TRUE(s);
    EXPECT_NEAR(s->eta, 1.5 / 1.33, 1e-15);
    EXPECT_NEAR(s->pdf, 1 - FresnelDielectric(0.6, 1.5 / 1.33), 1e-15);
}

TEST(Dielectric, CauchyDispersion) {
    const double b = 0.0042e-12;  // 0.0042 µm²
    auto m = Dielectric(1.5, b);
    auto plain = Dielectric(1.5);
    for (double lambda : {400e-9, 550e-9, 700e-9}) {
        const SampledWavelengths wl = TestWavelengths(lambda);
        const ScatterQuery q = Query(DirectionFromCosTheta(0.5, 0.3), wl);
        auto s = Prep(*m, q)->Sample(0.99, Vec2(0.5, 0.5));
        ASSERT_TRUE(s);
        const double n = 1.5 + b / (lambda * lambda);  // η(λ) = A + B/λ²
        EXPECT_NEAR(s->eta, n, 1e-14) << lambda;
        EXPECT_TRUE(s->flags & ScatterDispersive);
        // The companions' weights use their own index: T(λ_j)/η_j²/p, where the lobe's probability
        // p = ½·T(λ_hero) + ½·mean_i T(λ_i) (lossless: R + T = 1; smooth_kernel.h).
        double meanT = 0;
        for (int j = 0; j < NumWavelengths; ++j) meanT += (1 - FresnelDielectric(0.5, 1.5 + b / Sqr(wl.lambda[j])));
        meanT /= NumWavelengths;
        const double pT = 0.5 * (1 - FresnelDielectric(0.5, n)) + 0.5 * meanT;
        for (int j = 1; j < NumWavelengths; ++j) {
            const double nj = 1.5 + b / Sqr(wl.lambda[j]);
            const double expected = (1 - FresnelDielectric(0.5, nj)) / pT / (nj * nj);
            EXPECT_NEAR(s->weight[j], expected, 1e-14);
        }
        // Reflection is not dispersive (the mirror direction does not depend on λ).
        auto r = Prep(*m, q)->Sample(0.0, Vec2(0.5, 0.5));
        ASSERT_TRUE(r);
        EXPECT_FALSE(r->flags & ScatterDispersive);
        // A constant index never flags dispersion.
        auto p = Prep(*plain, q)->Sample(0.99, Vec2(0.5, 0.5));
        ASSERT_TRUE(p);
        EXPECT_FALSE(p->flags & ScatterDispersive);
    }
}

TEST(Dielectric, DeltaOnlyInTheRayLimit) {
    auto m = Dielectric(1.5);
    const SampledWavelengths wl = TestWavelengths(550e-9);
    const ScatterQuery q = Query(DirectionFromCosTheta(0.5, 0.3), wl);
    EXPECT_TRUE(Prep(*m, q)->IsDeltaOnly());
    EXPECT_TRUE(Prep(*m, q)->Eval(ReflectLocal(q.wi)).IsZero());
    EXPECT_EQ(Prep(*m, q)->Pdf(ReflectLocal(q.wi)), 0);
}

TEST(Dielectric, RejectsNonPositiveOrAbsorbingIndex) {
    // The index is a complex spectrum (ctx.GetComplexSpectrum): n ≤ 0 is no passive medium, and the
    // dielectric's interior does not absorb, so κ must be 0.
    const std::pair<Value, const char *> bad[] = {
        {Value::Number(-1.2), "must be n + iκ with n > 0 and κ ≥ 0; it is -1.2+0i at 360 nm"},
        {Value::Number(0.0), "must be n + iκ with n > 0"},
        {Value::ComplexNumber({1.5, 0.01}), "dielectric 'ior' must be real"},
        {Value::String("Au"), "dielectric 'ior' must be real"},
    };
    for (const auto &[ior, fragment] : bad) {
        ParamDict d;
        d.Set("ior", ior);
        Diagnostics diag;
        EXPECT_FALSE(BuildMaterial("dielectric", d, diag));
        ASSERT_TRUE(diag.HasErrors());
        EXPECT_NE(diag.All()[0].message.find(fragment), std::string::npos) << diag.All()[0].message;
    }
}

TEST(Dielectric, NamedGlassIsDispersive) {
    // ior = "BK7" (Sellmeier, core/spectrum/named_ior.h): the kernel sees the glass's index per wavelength.
    ParamDict d;
    d.Set("ior", Value::String("BK7"));
    Diagnostics diag;
    auto m = BuildMaterial("dielectric", d, diag);
    ASSERT_TRUE(m && diag.All().empty());
    const SampledWavelengths blue = LineWavelength(486.13e-9), red = LineWavelength(656.27e-9);
    for (const auto &[wl, n] : {std::pair{&blue, 1.5224}, std::pair{&red, 1.5143}}) {
        const ScatterQuery q = Query(Vec3(0, 0, 1), *wl);
        auto s = Prep(*m, q)->Sample(1 - 1e-12, Vec2(0.5, 0.5));  // the refracted lobe
        ASSERT_TRUE(s);
        EXPECT_NEAR(s->eta, n, 1e-4);  // Schott's n_F, n_C (4 decimals)
    }
}

}  // namespace
}  // namespace phasor::test
