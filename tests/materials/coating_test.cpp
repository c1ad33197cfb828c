// SPDX-License-Identifier: Apache-2.0
// `coating = @film` on `conductor` and `dielectric`: the coated kernel reflects (and transmits)
// exactly the layer stack's R and T at every angle, in both regimes, with the stack's Jones
// amplitudes; it equals the coating definition given the host's index as its substrate; the
// dielectric's bare interface still has Brewster's zero and ((n−1)/(n+1))²; and the `coating`
// reference is checked.
#include <gtest/gtest.h>

#include "core/spectrum/named_ior.h"
#include "materials/fresnel.h"
#include "materials/layer_stack.h"
#include "stack_kernel_test_util.h"

namespace phasor::test {
namespace {

// Cu₂O on copper (the bornite ore of the paper's Fig. 1): the fixture @contract_film.
Layer Cu2OAt(double lambda) { return {FindNamedIndex("Cu2O")->index(lambda), 150e-9}; }

TEST(Coating, CoatedConductorReflectsTheStacksRAtEveryAngle) {
    auto coated = Kernel("conductor", ParamDict().Set("ior", Value::String("Cu")).Set("coating", Value::Ref("contract_film")));
    auto bare = Kernel("conductor", ParamDict().Set("ior", Value::String("Cu")));
    ASSERT_TRUE(coated && bare);
    double largestChange = 0;
    for (double lambda = 400e-9; lambda <= 700e-9; lambda += 20e-9)
        for (double deg = 0; deg < 90; deg += 2.5) {
            const double c = std::cos(deg * Pi / 180);
            const Complex cu = FindNamedIndex("Cu")->index(lambda);
            const Layer film[] = {Cu2OAt(lambda)};
            const StackResponse coh = LayerStackResponse(lambda, 1.0, c, film, cu);
            const IncoherentStackResponse inc = LayerStackIncoherent(lambda, 1.0, c, film, cu);
            for (double side : {1.0, -1.0}) {  // two-sided: from below as from above
                const OneWave w(lambda, side * c);
                EXPECT_NEAR(List(*coated, w).R, coh.R(), 1e-15) << lambda << " " << deg;
                EXPECT_NEAR(List(*coated, OneWave(lambda, side * c, 0.3, true)).R, inc.R(), 1e-15);
                auto r = Response(*coated, w, 0);
                ASSERT_TRUE(r && r->hasJones);
                EXPECT_LT(std::abs(r->jones[0].m[0][0] - coh.rs), 1e-15);
                EXPECT_LT(std::abs(r->jones[0].m[1][1] - coh.rp), 1e-15);
            }
            largestChange = std::max(largestChange, std::abs(coh.R() - List(*bare, OneWave(lambda, c)).R));
        }
    // The coating matters (the film's interference colours): the test can tell coated from bare.
    EXPECT_GT(largestChange, 0.2);
}

TEST(Coating, CoatedKernelsEqualTheDefinitionOnTheHostsIndex) {
    // conductor(Cu, coating = @film) = thin_film(film, substrate_ior = Cu), and
    // dielectric(1.33, coating = @stack) = multilayer(stack, substrate_ior = 1.33), in both regimes
    // and from both sides.
    auto conductor = Kernel("conductor", ParamDict().Set("ior", Value::String("Cu")).Set("coating", Value::Ref("contract_film")));
    auto film = Kernel("thin_film",
                       ParamDict().Set("ior", Value::String("Cu2O")).Set("thickness", Nm(150)).Set("substrate_ior", Value::String("Cu")));
    auto dielectric = Kernel("dielectric", ParamDict().Set("ior", Value::Number(1.33)).Set("coating", Value::Ref("contract_stack")));
    ParamDict stack;
    stack.Set("layers", Value::List({LayerCall(Value::String("MgF2"), 100), LayerCall(Value::Number(2.1), 65)}))
        .Set("substrate_ior", Value::Number(1.33));
    auto multilayer = Kernel("multilayer", stack);
    ASSERT_TRUE(conductor && film && dielectric && multilayer);
    for (double lambda : {410e-9, 555e-9, 680e-9})
        for (double c : {1.0, 0.55, 0.12, -0.3, -0.9})
            for (bool ray : {false, true}) {
                const OneWave w(lambda, c, 1.3, ray);
                // 1e-13: 150e-9 and 150·1e-9 differ in the last bit, the film phase by ~1e-16 rad.
                EXPECT_NEAR(List(*conductor, w).R, List(*film, w).R, 1e-13);
                const Listed a = List(*dielectric, w), b = List(*multilayer, w);
                EXPECT_NEAR(a.R, b.R, 1e-13);
                EXPECT_NEAR(a.T, b.T, 1e-13);
                EXPECT_NEAR(a.R + a.T, 1, 1e-12);  // lossless layers on water
            }
}

TEST(Coating, AntiReflectionCoatedGlassTransmitsMore) {
    // A quarter-wave MgF₂-like layer on glass: the coated dielectric reflects the quarter-wave
    // minimum ((n_s − n_f²)/(n_s + n_f²))² at normal incidence instead of ((n−1)/(n+1))².
    const double nf = 1.38, ns = 1.52, lambda0 = 550e-9;
    SceneDesc desc;
    AddFixtures(desc);
    SceneEntity ar;
    ar.keyword = "Material";
    ar.type = "thin_film";
    ar.name = "ar";
    ar.params.Set("ior", Value::Number(nf)).Set("thickness", Nm(lambda0 / (4 * nf) * 1e9));
    desc.entities.push_back(ar);
    SceneEntity glass;
    glass.keyword = "Material";
    glass.type = "dielectric";
    glass.name = "glass";
    glass.params.Set("ior", Value::Number(ns)).Set("coating", Value::Ref("ar"));
    desc.entities.push_back(glass);
    Diagnostics diag;
    BuildContext ctx(desc, diag);
    ctx.BuildAll();
    ASSERT_FALSE(diag.HasErrors());
    std::shared_ptr<Material> coated;
    for (const auto &m : ctx.All<Material>())
        if (ctx.EntityOf(m.get())->name == "glass") coated = m;
    ASSERT_TRUE(coated);
    const Listed l = List(*coated, OneWave(lambda0, 1.0));
    EXPECT_NEAR(l.R, Sqr((ns - nf * nf) / (ns + nf * nf)), 1e-12);
    EXPECT_NEAR(l.T, 1 - l.R, 1e-12);
}

TEST(Dielectric, BrewsterZeroAndNormalIncidence) {
    // The bare dielectric kernel: R_p = 0 at Brewster's angle atan(n) (its Jones r_p vanishes and
    // R = R_s/2), and R = ((n − 1)/(n + 1))² at normal incidence (Hecht §4.6).
    for (double n : {1.33, 1.5, 2.42}) {
        auto glass = Kernel("dielectric", ParamDict().Set("ior", Value::Number(n)));
        ASSERT_TRUE(glass);
        EXPECT_NEAR(List(*glass, OneWave(550e-9, 1.0)).R, Sqr((n - 1) / (n + 1)), 1e-15) << n;
        const double brewster = std::atan(n);
        const OneWave w(550e-9, std::cos(brewster));
        auto r = Response(*glass, w, 0);
        ASSERT_TRUE(r);
        EXPECT_LT(std::abs(r->jones[0].m[1][1]), 1e-15) << n;
        EXPECT_NEAR(List(*glass, w).R, 0.5 * std::norm(r->jones[0].m[0][0]), 1e-15);
        // Half a degree off, R_p is clearly non-zero: the test can fail.
        auto off = Response(*glass, OneWave(550e-9, std::cos(brewster + 0.5 * Pi / 180)), 0);
        EXPECT_GT(std::norm(off->jones[0].m[1][1]), 1e-7) << n;
        // From inside, Brewster's angle is atan(1/n).
        auto inside = Response(*glass, OneWave(550e-9, -std::cos(std::atan(1 / n))), 0);
        ASSERT_TRUE(inside);
        EXPECT_LT(std::abs(inside->jones[0].m[1][1]), 1e-15) << n;
    }
}

std::string BuildError(const SceneDesc &desc) {
    Diagnostics diag;
    BuildContext ctx(desc, diag);
    ctx.BuildAll();
    std::ostringstream os;
    diag.Print(os);
    EXPECT_TRUE(diag.HasErrors());
    return os.str();
}

SceneDesc Scene(const std::string &hostType, const std::string &coatingType, const ParamDict &coatingParams) {
    SceneDesc desc;
    SceneEntity c;
    c.keyword = "Material";
    c.type = coatingType;
    c.name = "x";
    c.params = coatingParams;
    desc.entities.push_back(c);
    SceneEntity h;
    h.keyword = "Material";
    h.type = hostType;
    h.name = "host";
    h.params.Set("coating", Value::Ref("x"));
    desc.entities.push_back(h);
    return desc;
}

TEST(Coating, TheReferenceMustBeACoatingDefinitionWithoutItsOwnSubstrate) {
    auto has = [](const std::string &all, const std::string &text) { return all.find(text) != std::string::npos; };
    for (const char *host : {"conductor", "dielectric"}) {
        EXPECT_TRUE(has(BuildError(Scene(host, "diffuse", ParamDict())),
                        "'coating' must name a thin_film or multilayer definition; '@x' is a diffuse material"))
            << host;
        EXPECT_TRUE(has(BuildError(Scene(host, "conductor", ParamDict())), "'@x' is a conductor material")) << host;
        ParamDict own;
        own.Set("ior", Value::Number(1.4)).Set("thickness", Nm(100)).Set("substrate_ior", Value::String("BK7"));
        EXPECT_TRUE(has(BuildError(Scene(host, "thin_film", own)), "coating '@x' sets its own 'substrate_ior'")) << host;
    }
}

}  // namespace
}  // namespace phasor::test
