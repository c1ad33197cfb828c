// SPDX-License-Identifier: Apache-2.0
// Coherence terms (LobeCoherence) of lobes over a coated substrate, which sample_solve weights by
// the light's mutual coherence (μR_coh + (1 − μ)R_incoh, theory §4.4): harvey_shack's specular lobe
// and a grating's reflected orders carry the coated substrate's terms — its incoherent Mueller matrix
// times the lobe's share (α_spec; the order's J_j²·scale, at the source's angle) and its shear —
// exactly as the coated conductor itself reports them (to 1e-12). Over a bare substrate they report
// none, and HasCoherenceTerms() says which.
#include <gtest/gtest.h>

#include "materials/fresnel.h"
#include "materials/material_test_util.h"

namespace phasor::test {
namespace {

std::shared_ptr<Material> Build(const std::string &name, bool coated) {
    MiniScene s;
    s.Add("Material", "thin_film", "film",
          ParamDict().Set("ior", Value::Number(1.45)).Set("thickness", Value::Number(2e-6, Dim::Length())));
    ParamDict c;
    c.Set("ior", Value::ComplexNumber({0.2, 3.4}));
    if (coated) c.Set("coating", Value::Ref("film"));
    s.Add("Material", "conductor", "metal", c);
    s.Add("Material", "harvey_shack", "rough",
          ParamDict()
              .Set("substrate", Value::Ref("metal"))
              .Set("sigma_h", Value::Number(20e-9, Dim::Length()))
              .Set("alpha_r", Value::Number(0.01)));
    s.Add("Material", "grating", "grooves",
          ParamDict()
              .Set("substrate", Value::Ref("metal"))
              .Set("period", Value::Number(2e-6, Dim::Length()))
              .Set("height", Value::Number(0.1e-6, Dim::Length())));
    auto m = s.Build<Material>(name);
    EXPECT_TRUE(m) << s.FirstError();
    return m;
}

void ExpectMuellerNear(const Mueller &a, const Mueller &b, double tol, const std::string &what) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) EXPECT_NEAR(a.m[i][j], b.m[i][j], tol) << what << " (" << i << ", " << j << ")";
}

TEST(CoherenceTerms, RoughAndGratedCoatedSurfacesCarryTheCoatingsTerms) {
    const SampledWavelengths wl = TestWavelengths(550e-9);
    for (bool coated : {true, false}) {
        auto metal = Build("metal", coated), rough = Build("rough", coated), grooves = Build("grooves", coated);
        ASSERT_TRUE(metal && rough && grooves);
        EXPECT_EQ(metal->HasCoherenceTerms(), coated);
        EXPECT_EQ(rough->HasCoherenceTerms(), coated);
        EXPECT_EQ(grooves->HasCoherenceTerms(), coated);
        for (double thetaDeg : {20.0, 50.0}) {
            ScatterQuery q;
            q.wl = &wl;
            q.rayOptics = false;
            const double th = Radians(thetaDeg);
            q.wi = Vec3(std::sin(th) * std::cos(0.3), std::sin(th) * std::sin(0.3), std::cos(th));
            // The coated conductor's own terms at θ.
            const auto base = Prep(*metal, q)->EvalLobe(0, ReflectLocal(q.wi));
            ASSERT_TRUE(base);
            EXPECT_EQ(base->coherence.any, coated);
            // harvey_shack: α_spec × the substrate's incoherent response, the same shear.
            const Prep kRough(*rough, q);
            const std::span<const NearDeltaLobe> lobes = kRough->ListNearDelta();
            ASSERT_GE(lobes.size(), 1u);
            const auto spec = kRough->EvalLobe(lobes[0].id, lobes[0].wo[0]);
            ASSERT_TRUE(spec);
            EXPECT_EQ(spec->coherence.any, coated);
            if (coated)
                for (int i = 0; i < wl.Count(); ++i) {
                    const double alpha = spec->mueller[i].m[0][0] / base->mueller[i].m[0][0];  // α_spec
                    EXPECT_GT(alpha, 0.5);
                    EXPECT_LT(alpha, 1);
                    ExpectMuellerNear(spec->coherence.incoherent[i], base->coherence.incoherent[i] * alpha, 1e-12,
                                      "harvey_shack incoherent, slot " + std::to_string(i));
                    EXPECT_NEAR(Length(spec->coherence.shear[i] - base->coherence.shear[i]), 0, 1e-18);
                    EXPECT_GT(Length(spec->coherence.shear[i]), 1e-7);  // 2d·tanθ_t: µm
                }
            // The grating's reflected orders: the order's share J_j²·scale (= M00 over the substrate's
            // coherent R at the source's angle) × the substrate's incoherent response there.
            const Prep kGrooves(*grooves, q);
            const std::span<const NearDeltaLobe> orders = kGrooves->ListNearDelta();
            ASSERT_GE(orders.size(), 3u);
            for (const NearDeltaLobe &o : orders) {
                const auto r = kGrooves->EvalLobe(o.id, o.wo[0]);
                ASSERT_TRUE(r);
                EXPECT_EQ(r->coherence.any, coated);
                if (!coated) continue;
                for (int i = 0; i < wl.Count(); ++i) {
                    if (!(o.Weight()[i] > 0)) continue;
                    ScatterQuery src = q;  // the substrate as the light from the order's source direction meets it
                    src.wi = o.wo[std::size_t(i)];
                    const auto sub = Prep(*metal, src)->EvalLobe(0, ReflectLocal(src.wi));
                    ASSERT_TRUE(sub);
                    const double share = r->mueller[i].m[0][0] / sub->mueller[i].m[0][0];
                    ExpectMuellerNear(r->coherence.incoherent[i], sub->coherence.incoherent[i] * share,
                                      1e-12 * std::max(1.0, share), "grating order " + std::to_string(o.id));
                    EXPECT_NEAR(Length(r->coherence.shear[i] - sub->coherence.shear[i]), 0, 1e-18);
                }
            }
        }
    }
}

}  // namespace
}  // namespace phasor::test
