// SPDX-License-Identifier: Apache-2.0
// `mix`: the blend f = (1 − w)·f_a + w·f_b beyond the generic contract suite — the end points equal
// the children, Eval/Pdf are the weighted sums (with a textured weight), the listed lobes of two
// conductors against the Fresnel formula, id remapping with negative child ids, the energy sense the
// children share (a grating and a rough surface on gold reflect F of the light from each direction,
// and so does their mix), and bad input.
#include <gtest/gtest.h>

#include "energy_test_util.h"
#include "material_test_util.h"
#include "materials/fresnel.h"
#include "support/stats.h"

namespace phasor::test {
namespace {

std::shared_ptr<Material> Get(MiniScene &s, const std::string &name) {
    auto m = s.Build<Material>(name);
    EXPECT_TRUE(m) << s.FirstError();
    return m;
}

ParamDict Mix(const char *a, const char *b, Value weight) {
    return ParamDict().Set("a", Value::Ref(a)).Set("b", Value::Ref(b)).Set("weight", std::move(weight));
}

// Incident directions above and below the shading normal.
const Vec3 Incidents[] = {DirectionFromCosTheta(0.9, 0.4), DirectionFromCosTheta(0.3, 2.0),
                          DirectionFromCosTheta(-0.6, 4.0)};

// w = 0 is `a` and w = 1 is `b`: every query answered as the child answers it. Eval, Pdf and the
// near-delta samples are bit-identical (the other child's term is skipped, the share is exactly 1);
// a continuous sample's weight is recomputed as f·|cosθo|/pdf, so it agrees to rounding (1e-14).
TEST(Mix, EndPointsAreTheChildren) {
    MiniScene s;
    s.WithFixtures()
        .Add("Material", "mix", "w0", Mix("contract_matte", "contract_gold", Value::Number(0)))
        .Add("Material", "mix", "w1", Mix("contract_matte", "contract_gold", Value::Number(1)));
    auto w0 = Get(s, "w0"), w1 = Get(s, "w1");
    auto matte = Get(s, "contract_matte"), gold = Get(s, "contract_gold");
    ASSERT_TRUE(w0 && w1 && matte && gold);
    const SampledWavelengths wl = TestWavelengths(550e-9);
    TestRng rng(7);
    for (const auto &[mix, child, isB] : {std::tuple{w0, matte, false}, std::tuple{w1, gold, true}}) {
        for (const Vec3 &wi : Incidents) {
            ScatterQuery q;
            q.wi = wi;
            q.wl = &wl;
            const Prep km(*mix, q), kc(*child, q);
            EXPECT_EQ(km->Capabilities(), kc->Capabilities());
            for (int i = 0; i < 100; ++i) {
                const Vec3 wo = UniformSphere(rng.Uniform(), rng.Uniform());
                const SampledSpectrum fm = km->Eval(wo), fc = kc->Eval(wo);
                for (int j = 0; j < NumWavelengths; ++j) ASSERT_EQ(fm[j], fc[j]);
                ASSERT_EQ(km->Pdf(wo), kc->Pdf(wo));
                const double u0 = rng.Uniform();
                const Vec2 u(rng.Uniform(), rng.Uniform());
                auto sm = km->Sample(u0, u), sc = kc->Sample(u0, u);
                ASSERT_EQ(bool(sm), bool(sc));
                if (!sm) continue;
                EXPECT_EQ(sm->wo, sc->wo);
                EXPECT_EQ(sm->pdf, sc->pdf);
                EXPECT_EQ(sm->flags, sc->flags);
                EXPECT_EQ(sm->lobe, 2 * sc->lobe + int(isB));
                for (int j = 0; j < NumWavelengths; ++j)
                    EXPECT_NEAR(sm->weight[j], sc->weight[j], 1e-14 * sc->weight[j]);
            }
            const std::span<const NearDeltaLobe> lm = km->ListNearDelta(), lc = kc->ListNearDelta();
            ASSERT_EQ(lm.size(), lc.size());
            for (std::size_t k = 0; k < lc.size(); ++k) {
                EXPECT_EQ(lm[k].id, 2 * lc[k].id + int(isB));
                EXPECT_EQ(lm[k].prob, lc[k].prob);
                for (int j = 0; j < NumWavelengths; ++j) EXPECT_EQ(lm[k].Weight()[j], lc[k].Weight()[j]);
                auto rm = km->EvalLobe(lm[k].id, lm[k].wo[0]);
                auto rc = kc->EvalLobe(lc[k].id, lc[k].wo[0]);
                ASSERT_TRUE(rm && rc);
                EXPECT_EQ(rm->mueller[0].m[0][0], rc->mueller[0].m[0][0]);
            }
        }
    }
}

// Eval = (1 − w)·f_a + w·f_b and Pdf = (1 − w)·p_a + w·p_b, with w read from a texture at the
// query's uv: two Lambertian children (f = R/π, pdf = |cosθo|/π) under a ramp w = u.
TEST(Mix, EvalAndPdfAreTheWeightedSums) {
    MiniScene s;
    s.Add("Material", "diffuse", "dark", ParamDict().Set("reflectance", Value::Number(0.2)))
        .Add("Material", "diffuse", "light", ParamDict().Set("reflectance", Value::Number(0.8)))
        .Add("Texture", "uv_ramp", "ramp", ParamDict().Set("value0", Value::Number(0)).Set("value1", Value::Number(1)))
        .Add("Material", "mix", "m",
             ParamDict().Set("a", Value::Ref("dark")).Set("b", Value::Ref("light")).Set("weight_texture", Value::Ref("ramp")));
    auto m = Get(s, "m");
    ASSERT_TRUE(m);
    const SampledWavelengths wl = TestWavelengths(480e-9);
    for (double u : {0.0, 0.15, 0.5, 0.9, 1.0}) {
        ScatterQuery q;
        q.wi = DirectionFromCosTheta(0.7, 0.3);
        q.wl = &wl;
        q.tex.uv = Vec2(u, 0.4);
        const double w = u;  // the ramp
        const Prep k(*m, q);
        for (double c : {0.95, 0.4, 0.05}) {
            const Vec3 wo = DirectionFromCosTheta(c, 2.5);
            const double expected = ((1 - w) * 0.2 + w * 0.8) / Pi;
            EXPECT_NEAR(k->Eval(wo)[0], expected, 1e-15) << "u = " << u;
            EXPECT_NEAR(k->Pdf(wo), c / Pi, 1e-15);
            EXPECT_EQ(k->Eval(DirectionFromCosTheta(-c, 2.5))[0], 0);  // no transmission
        }
        // Every sample's weight is the mixture's albedo (1 − w)·0.2 + w·0.8, whichever child drew it.
        for (double u0 : {0.05, 0.5, 0.95}) {
            auto smp = k->Sample(u0, Vec2(0.3, 0.6));
            ASSERT_TRUE(smp);
            EXPECT_NEAR(smp->weight[0], (1 - w) * 0.2 + w * 0.8, 1e-14);
        }
    }
}

// A mix of two metals lists both mirror lobes: ids 0 (a) and 1 (b), weights (1 − w)·R_a and
// w·R_b with R the complex Fresnel reflectance (fresnel.h, tested against textbook values in
// fresnel_test.cpp), probabilities 1 − w and w; EvalLobe gives √share·diag(r_s, r_p).
TEST(Mix, ListsTheLobesOfTwoConductors) {
    const Complex na(0.2, 3.0), nb(1.2, 7.26);
    MiniScene s;
    s.Add("Material", "conductor", "a", ParamDict().Set("ior", Value::ComplexNumber(na)))
        .Add("Material", "conductor", "b", ParamDict().Set("ior", Value::ComplexNumber(nb)))
        .Add("Material", "mix", "m", Mix("a", "b", Value::Number(0.25)));
    auto m = Get(s, "m");
    ASSERT_TRUE(m);
    const SampledWavelengths wl = TestWavelengths(600e-9);
    for (const Vec3 &wi : Incidents) {
        ScatterQuery q;
        q.wi = wi;
        q.wl = &wl;
        const Prep k(*m, q);
        EXPECT_EQ(k->Capabilities(), unsigned(CapNearDelta));
        const std::span<const NearDeltaLobe> lobes = k->ListNearDelta();
        ASSERT_EQ(lobes.size(), 2u);
        const double cosI = std::abs(wi.z);
        const double share[2] = {0.75, 0.25};
        const Complex n[2] = {na, nb};
        for (int id = 0; id < 2; ++id) {
            const NearDeltaLobe &l = lobes[std::size_t(id)];
            EXPECT_EQ(l.id, id);
            EXPECT_EQ(l.flags, unsigned(ScatterReflection | ScatterNearDelta));
            EXPECT_LT(Length(l.wo[0] - ReflectLocal(wi)), 1e-15);
            EXPECT_NEAR(l.prob, share[id], 1e-15);
            for (int j = 0; j < NumWavelengths; ++j)
                EXPECT_NEAR(l.Weight()[j], share[id] * FresnelConductor(cosI, n[id]), 1e-14);
            auto r = k->EvalLobe(l.id, l.wo[0]);
            ASSERT_TRUE(r && r->hasJones);
            const FresnelCoefficients c = FresnelAmplitudes(cosI, 1.0, n[id]);
            EXPECT_LT(std::abs(r->jones[0].m[0][0] - std::sqrt(share[id]) * c.rs), 1e-14);
            EXPECT_LT(std::abs(r->jones[0].m[1][1] - std::sqrt(share[id]) * c.rp), 1e-14);
            EXPECT_NEAR(r->mueller[0].m[0][0], l.Weight()[0], 1e-14);
        }
        EXPECT_FALSE(k->EvalLobe(2, ReflectLocal(wi))) << "a's lobe 1 does not exist";
        EXPECT_FALSE(k->EvalLobe(-1, ReflectLocal(wi))) << "b's lobe −1 does not exist";
    }
}

// Children with negative lobe ids (a grating's orders −3 … 3): the mix lists them as 2j, its other
// child's lobe as 2·0 + 1, in increasing id order, and maps every id back in EvalLobe and Sample.
TEST(Mix, RemapsNegativeIdsAndKeepsTheirOrder) {
    MiniScene s;
    s.WithFixtures()
        .Add("Material", "toy_grating", "g", ParamDict().Set("period", Value::Number(5e-6, Dim::Length())))
        .Add("Material", "mix", "m", Mix("g", "contract_gold", Value::Number(0.4)));
    auto m = Get(s, "m"), g = Get(s, "g");
    ASSERT_TRUE(m && g);
    const SampledWavelengths wl = TestWavelengths(550e-9);
    ScatterQuery q;
    q.wi = DirectionFromCosTheta(0.8, 0.2);
    q.wl = &wl;
    const Prep lmK(*m, q);
    const std::span<const NearDeltaLobe> lm = lmK->ListNearDelta();
    const Prep lgK(*g, q);
    const std::span<const NearDeltaLobe> lg = lgK->ListNearDelta();
    ASSERT_EQ(lm.size(), lg.size() + 1);
    for (std::size_t k = 1; k < lm.size(); ++k) EXPECT_LT(lm[k - 1].id, lm[k].id);
    int fromGrating = 0;
    for (const NearDeltaLobe &l : lm) {
        if (l.id == 1) continue;  // gold's mirror lobe
        ASSERT_EQ(l.id % 2, 0);
        const NearDeltaLobe *src = nullptr;
        for (const NearDeltaLobe &x : lg)
            if (x.id == l.id / 2) src = &x;
        ASSERT_NE(src, nullptr) << "mix lobe " << l.id;
        ++fromGrating;
        EXPECT_NEAR(l.Weight()[0], 0.6 * src->Weight()[0], 1e-15);
        EXPECT_NEAR(l.prob, 0.6 * src->prob, 1e-15);
        auto rm = lmK->EvalLobe(l.id, l.wo[0]);
        auto rg = lgK->EvalLobe(src->id, src->wo[0]);
        ASSERT_TRUE(rm && rg);
        EXPECT_NEAR(rm->mueller[0].m[0][0], 0.6 * rg->mueller[0].m[0][0], 1e-15);
    }
    EXPECT_EQ(fromGrating, int(lg.size()));
    EXPECT_LT(lg[0].id, 0) << "the test needs negative child ids";
    // Sample across u0: every sample is a listed lobe of the mix.
    for (int k = 0; k < 64; ++k) {
        auto smp = lmK->Sample((k + 0.5) / 64, Vec2(0.5, 0.5));
        ASSERT_TRUE(smp);
        bool listed = false;
        for (const NearDeltaLobe &l : lm) listed = listed || (l.id == smp->lobe && Length(l.wo[0] - smp->wo) < 1e-12);
        EXPECT_TRUE(listed) << "sampled lobe " << smp->lobe;
    }
}

// The mix declares the energy sense its children share (CombinedEnergySense): reciprocal children
// give a reciprocal mix; a kernel that conserves energy per incident direction (grating,
// harvey_shack) with another such or a reciprocal one gives one that does; the per-query toy
// grating (toy_grating_test.cpp) with a reciprocal kernel one that conserves it per query.
TEST(Mix, DeclaresTheEnergySenseOfItsChildren) {
    MiniScene s;
    s.WithFixtures()
        .Add("Material", "toy_grating", "toy", ParamDict())
        .Add("Material", "mix", "metals", Mix("contract_gold", "contract_matte", Value::Number(0.5)))
        .Add("Material", "mix", "grating_gold", Mix("contract_grating", "contract_gold", Value::Number(0.3)))
        .Add("Material", "mix", "grating_rough", Mix("contract_grating", "contract_rough", Value::Number(0.3)))
        .Add("Material", "mix", "toy_gold", Mix("toy", "contract_gold", Value::Number(0.3)));
    const std::pair<const char *, EnergySense> expected[] = {{"metals", EnergySense::Reciprocal},
                                                             {"grating_gold", EnergySense::PerIncidentDirection},
                                                             {"grating_rough", EnergySense::PerIncidentDirection},
                                                             {"toy_gold", EnergySense::PerQuery}};
    for (const auto &[name, sense] : expected) {
        auto m = Get(s, name);
        ASSERT_TRUE(m);
        EXPECT_EQ(int(EnergySenseOf(*m)), int(sense)) << name << ": " << Describe(EnergySenseOf(*m));
    }
}

// A grating and a rough surface on gold each reflect F_gold(θ) of the light arriving from any
// direction (their own tests); so does their mix at w = 0.3, in the sense it declares: the light
// from d leaves through the listed lobes that point back at d (orders and glint) and the halo's
// ∫ f(w → d)·cosθ_w dω_w (a deterministic quadrature), per carried wavelength. Tolerance: the
// rough surface's V table (≤ 3.5e-4 of its halo share, harvey_shack_test.cpp) and the quadrature.
TEST(Mix, GratingAndRoughSurfaceReflectFOfTheLightFromEachDirection) {
    MiniScene s;
    s.WithFixtures().Add("Material", "mix", "m", Mix("contract_grating", "contract_rough", Value::Number(0.3)));
    auto m = Get(s, "m"), gold = Get(s, "contract_gold");
    ASSERT_TRUE(m && gold);
    const SampledWavelengths wl = TestWavelengths(550e-9);
    for (const Vec3 &d : Incidents) {
        ScatterQuery q;
        q.wi = d;
        q.wl = &wl;
        q.rayOptics = false;
        const Prep refK(*gold, q);
        const std::span<const NearDeltaLobe> ref = refK->ListNearDelta();
        ASSERT_EQ(ref.size(), 1u);
        const SampledSpectrum halo = ContinuousFrom(*m, q, d, 0.02);
        for (int i = 0; i < wl.Count(); ++i) {
            const double listed = ListedEnergyFrom(*m, q, i).energy, F = ref[0].Weight()[i];
            EXPECT_NEAR(listed + halo[i], F, 3.5e-4 * F + 1e-7)
                << "light from " << ToString(d) << ", slot " << i << ": listed " << listed << " + halo " << halo[i];
        }
    }
}

// Bad input: both weights, a weight outside [0, 1] (number or texture), a texture of another
// dimension, a footprint-aware child, children that conserve energy in different senses.
TEST(Mix, BadInput) {
    auto firstError = [](MiniScene &s) {
        EXPECT_FALSE(s.Build<Material>("m"));
        return s.FirstError();
    };
    {
        MiniScene s;
        s.WithFixtures().Add("Material", "mix", "m",
                             Mix("contract_gold", "contract_matte", Value::Number(0.5)).Set("weight_texture", Value::Ref("contract_half")));
        EXPECT_NE(firstError(s).find("give 'weight' or 'weight_texture', not both"), std::string::npos) << s.FirstError();
    }
    {
        MiniScene s;
        s.WithFixtures().Add("Material", "mix", "m", Mix("contract_gold", "contract_matte", Value::Number(1.5)));
        EXPECT_NE(firstError(s).find("'weight' is out of range"), std::string::npos) << s.FirstError();
    }
    {
        MiniScene s;
        s.WithFixtures()
            .Add("Texture", "noise", "wide", ParamDict().Set("offset", Value::Number(0.5)).Set("amplitude", Value::Number(0.8)))
            .Add("Material", "mix", "m", Mix("contract_gold", "contract_matte", Value::Ref("wide")));
        EXPECT_NE(firstError(s).find("'weight' must be ≥ 0 and ≤ 1 everywhere, but texture '@wide' ranges over"),
                  std::string::npos)
            << s.FirstError();
    }
    {
        MiniScene s;
        s.WithFixtures()
            .Add("Texture", "constant", "thick", ParamDict().Set("value", Value::Number(1e-7, Dim::Length())))
            .Add("Material", "mix", "m",
                 ParamDict().Set("a", Value::Ref("contract_gold")).Set("b", Value::Ref("contract_matte")).Set("weight_texture", Value::Ref("thick")));
        EXPECT_NE(firstError(s).find("texture '@thick' yields a length"), std::string::npos) << s.FirstError();
    }
    {
        MiniScene s;
        s.WithFixtures()
            .Add("Material", "aperture", "slit",
                 ParamDict().Set("rects", Value::List({Value::Number(-1e-6, Dim::Length()), Value::Number(-5e-5, Dim::Length()),
                                                       Value::Number(1e-6, Dim::Length()), Value::Number(5e-5, Dim::Length())})))
            .Add("Material", "mix", "m", Mix("slit", "contract_matte", Value::Number(0.5)));
        EXPECT_NE(firstError(s).find("'a' is footprint-aware"), std::string::npos) << s.FirstError();
    }
    {
        MiniScene s;
        s.WithFixtures()
            .Add("Material", "toy_grating", "toy", ParamDict())
            .Add("Material", "mix", "m", Mix("toy", "contract_grating", Value::Number(0.5)));
        EXPECT_NE(firstError(s).find("'a' conserves energy per query (ToyGratingMaterial"), std::string::npos)
            << s.FirstError();
        EXPECT_NE(s.FirstError().find("but 'b' conserves energy per incident direction (GratingMaterial"),
                  std::string::npos)
            << s.FirstError();
    }
}

}  // namespace
}  // namespace phasor::test
