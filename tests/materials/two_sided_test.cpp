// SPDX-License-Identifier: Apache-2.0
// `two_sided` beyond the generic contract suite: a query from below is the back kernel's answer to
// the mirrored query, mirrored back (listing, sampling, Eval, EvalLobe); the mirror's change of
// the s/p basis on a Jones matrix with off-diagonal terms; refused transmitting children; bad input.
//
// Registers a test kernel, `test_rotator` (also run through the contract suite): another kernel's
// lobes with the polarisation rotated by α after reflection — Jones R(α)·J, R(α) = [[cos α,
// −sin α], [sin α, cos α]], which leaves every weight unchanged. Not a physical surface, only a
// response with off-diagonal Jones terms.
#include <gtest/gtest.h>

#include <sstream>

#include "energy_test_util.h"
#include "material_test_util.h"
#include "materials/fresnel.h"
#include "support/stats.h"

namespace phasor {

class RotatorMaterial final : public Material {
  public:
    RotatorMaterial(std::shared_ptr<const Material> child, double angle) : child_(std::move(child)), angle_(angle) {}
    static const Schema &GetSchema() {
        static const Schema s{"material",
                              "test_rotator",
                              "test kernel: a near-delta kernel's lobes with the polarisation rotated by 'angle'",
                              {P::Ref("material", "material", "the kernel whose lobes are rotated").Required(),
                               P::Angle("angle", "rotation α").Default(Value::Number(0.3, Dim::Angle()))}};
        return s;
    }
    static std::unique_ptr<Material> Create(const ParamDict &d, BuildContext &ctx) {
        return std::make_unique<RotatorMaterial>(ctx.GetRef<Material>(d, "material"), d.GetNumber("angle"));
    }
    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(2);
        p[0].Set("material", Value::Ref("contract_gold"));
        p[1].Set("material", Value::Ref("contract_aluminium")).Set("angle", Value::Number(1.2, Dim::Angle()));
        return p;
    }
    const PreparedKernel &Prepare(const ScatterQuery &q, ScratchBuffer &scratch) const override {
        return *scratch.New<Prepared>(*this, q, scratch);
    }
    std::string ToString() const override {
        std::ostringstream os;
        os << "RotatorMaterial[ material = " << child_->ToString() << ", angle = " << angle_ << " ]";
        return os.str();
    }

  private:
    /// The child prepared for the query: its lobes and samples, its Jones matrices rotated.
    class Prepared final : public PreparedKernel {
      public:
        Prepared(const RotatorMaterial &m, const ScatterQuery &q, ScratchBuffer &scratch)
            : PreparedKernel(q), child_(&m.child_->Prepare(q, scratch)), angle_(m.angle_) {
            caps_ = child_->Capabilities();
            lobes_ = child_->ListNearDelta();
            continuous_ = child_->ContinuousLobes();
        }
        std::optional<LobeResponse> EvalLobe(int lobe, const Vec3 &wo) const override {
            std::optional<LobeResponse> r = child_->EvalLobe(lobe, wo);
            if (!r || !r->hasJones) return r;
            Jones rot;
            rot.m[0][0] = rot.m[1][1] = std::cos(angle_);
            rot.m[0][1] = -std::sin(angle_);
            rot.m[1][0] = std::sin(angle_);
            for (int i = 0; i < q_.wl->Count(); ++i) {
                r->jones[i] = rot * r->jones[i];
                r->mueller[i] = Mueller::FromJones(r->jones[i]);
            }
            return r;
        }

      private:
        std::optional<ScatterSample> SampleLobes(double u0, const Vec2 &u) const override {
            return child_->Sample(u0, u);
        }
        const PreparedKernel *child_;
        double angle_;
    };

    std::shared_ptr<const Material> child_;
    double angle_;
};

PHASOR_REGISTER_PLUGIN(Material, RotatorMaterial, "test_rotator");

namespace test {
namespace {

Vec3 Mirror(const Vec3 &v) { return {v.x, v.y, -v.z}; }

std::shared_ptr<Material> Get(MiniScene &s, const std::string &name) {
    auto m = s.Build<Material>(name);
    EXPECT_TRUE(m) << s.FirstError();
    return m;
}

// From below, two_sided(material = M) answers what M answers for the mirrored query, mirrored
// back; from above, what M answers. M is the toy grating (tests/materials/toy_grating_test.cpp):
// many dispersive lobes with shifts along x, so a mirror that moved x or y would show.
TEST(TwoSided, FromBelowIsTheKernelMirrored) {
    MiniScene s;
    s.Add("Material", "toy_grating", "g", ParamDict().Set("period", Value::Number(4e-6, Dim::Length())))
        .Add("Material", "two_sided", "t", ParamDict().Set("material", Value::Ref("g")));
    auto t = Get(s, "t"), g = Get(s, "g");
    ASSERT_TRUE(t && g);
    const SampledWavelengths wl = TestWavelengths(520e-9);
    for (const Vec3 &up : {DirectionFromCosTheta(0.9, 0.3), DirectionFromCosTheta(0.35, 2.2)}) {
        for (const bool below : {false, true}) {
            ScatterQuery qt, qg;
            qt.wl = qg.wl = &wl;
            qg.wi = up;
            qt.wi = below ? Mirror(up) : up;
            auto map = [&](const Vec3 &w) { return below ? Mirror(w) : w; };
            const Prep kt(*t, qt), kg(*g, qg);
            EXPECT_EQ(kt->Capabilities(), kg->Capabilities());
            const std::span<const NearDeltaLobe> lt = kt->ListNearDelta(), lg = kg->ListNearDelta();
            ASSERT_EQ(lt.size(), lg.size());
            ASSERT_GT(lt.size(), 3u);
            for (std::size_t k = 0; k < lt.size(); ++k) {
                const NearDeltaLobe &a = lt[k], &b = lg[k];
                EXPECT_EQ(a.id, b.id);
                EXPECT_EQ(a.flags, b.flags);
                EXPECT_EQ(a.prob, b.prob);
                EXPECT_EQ(a.shift.x, b.shift.x);
                EXPECT_EQ(a.shift.y, b.shift.y);
                for (int j = 0; j < NumWavelengths; ++j) {
                    EXPECT_EQ(a.wo[j], map(b.wo[j])) << "lobe " << a.id << ", slot " << j;
                    EXPECT_EQ(a.Weight()[j], b.Weight()[j]);
                }
                // Below, the lobe leaves on wi's (lower) side.
                EXPECT_GT(a.wo[0].z * qt.wi.z, 0) << "lobe " << a.id << " on the wrong side";
                auto ra = kt->EvalLobe(a.id, a.wo[0]);
                auto rb = kg->EvalLobe(b.id, b.wo[0]);
                ASSERT_TRUE(ra && rb);
                EXPECT_EQ(ra->mueller[0].m[0][0], rb->mueller[0].m[0][0]);
                EXPECT_FALSE(kt->EvalLobe(a.id, b.wo[0]) && below) << "answers towards the unmirrored direction";
            }
            for (int k = 0; k < 32; ++k) {
                const double u0 = (k + 0.5) / 32;
                auto st = kt->Sample(u0, Vec2(0.3, 0.7)), sg = kg->Sample(u0, Vec2(0.3, 0.7));
                ASSERT_EQ(bool(st), bool(sg));
                if (!st) continue;
                EXPECT_EQ(st->wo, map(sg->wo));
                EXPECT_EQ(st->lobe, sg->lobe);
                EXPECT_EQ(st->pdf, sg->pdf);
                EXPECT_EQ(st->weight[0], sg->weight[0]);
            }
        }
    }
}

// front = gold, back = a diffuser: above, the gold mirror; below, the diffuser mirrored (Eval,
// Pdf and samples on the lower side, no near-delta lobe).
TEST(TwoSided, FrontAndBackAreDifferentKernels) {
    MiniScene s;
    s.WithFixtures().Add("Material", "two_sided", "t",
                         ParamDict().Set("front", Value::Ref("contract_gold")).Set("back", Value::Ref("contract_matte")));
    auto t = Get(s, "t"), gold = Get(s, "contract_gold"), matte = Get(s, "contract_matte");
    ASSERT_TRUE(t && gold && matte);
    const SampledWavelengths wl = TestWavelengths(650e-9);
    ScatterQuery above;
    above.wi = DirectionFromCosTheta(0.6, 1.0);
    above.wl = &wl;
    ScatterQuery below = above;
    below.wi = Mirror(above.wi);

    const Prep kAbove(*t, above), kBelow(*t, below), kGold(*gold, above);
    EXPECT_EQ(kAbove->Capabilities(), unsigned(CapNearDelta));
    EXPECT_EQ(kBelow->Capabilities(), unsigned(CapContinuous));
    const std::span<const NearDeltaLobe> la = kAbove->ListNearDelta(), lgold = kGold->ListNearDelta(),
                                         lb = kBelow->ListNearDelta();
    ASSERT_EQ(la.size(), 1u);
    EXPECT_EQ(la[0].Weight()[0], lgold[0].Weight()[0]);
    EXPECT_EQ(lb.size(), 0u);

    TestRng rng(3);
    for (int i = 0; i < 200; ++i) {
        const Vec3 wo = UniformSphere(rng.Uniform(), rng.Uniform());
        EXPECT_TRUE(kAbove->Eval(wo).IsZero());
        const double expected = wo.z < 0 ? 0.6 / Pi : 0.0;  // the diffuser, on the lower side only
        EXPECT_NEAR(kBelow->Eval(wo)[0], expected, 1e-15) << ToString(wo);
        EXPECT_NEAR(kBelow->Pdf(wo), wo.z < 0 ? -wo.z / Pi : 0.0, 1e-15);
        auto smp = kBelow->Sample(rng.Uniform(), Vec2(rng.Uniform(), rng.Uniform()));
        ASSERT_TRUE(smp);
        EXPECT_LT(smp->wo.z, 0);
        EXPECT_NEAR(smp->weight[0], 0.6, 1e-15);
    }
}

// The mirror reverses handedness: in the s/p basis p̂ = k̂ × ŝ maps to minus its mirror image, so
// from below the back's Jones matrix J is seen as D·J·D, D = diag(1, −1). For the rotated gold
// mirror J = R(α)·diag(r_s, r_p), so from below it is R(−α)·diag(r_s, r_p); the Mueller matrix
// stays FromJones of the Jones matrix.
TEST(TwoSided, MirrorChangesTheSignOfOffDiagonalJonesTerms) {
    MiniScene s;
    s.Add("Material", "conductor", "gold", ParamDict().Set("ior", Value::ComplexNumber(Complex(0.2, 3.0))))
        .Add("Material", "test_rotator", "rot", ParamDict().Set("material", Value::Ref("gold")).Set("angle", Value::Number(0.4, Dim::Angle())))
        .Add("Material", "two_sided", "t", ParamDict().Set("material", Value::Ref("rot")));
    auto t = Get(s, "t");
    ASSERT_TRUE(t);
    const SampledWavelengths wl = TestWavelengths(550e-9);
    ScatterQuery q;
    q.wl = &wl;
    const double c = std::cos(0.4), sn = std::sin(0.4);
    for (const bool below : {false, true}) {
        q.wi = DirectionFromCosTheta(below ? -0.7 : 0.7, 0.9);
        auto r = Prep(*t, q)->EvalLobe(0, ReflectLocal(q.wi));
        ASSERT_TRUE(r && r->hasJones);
        const FresnelCoefficients f = FresnelAmplitudes(0.7, 1.0, Complex(0.2, 3.0));
        const double sign = below ? -1 : 1;  // rotation by ±α
        EXPECT_LT(std::abs(r->jones[0].m[0][0] - c * f.rs), 1e-15);
        EXPECT_LT(std::abs(r->jones[0].m[0][1] + sign * sn * f.rp), 1e-15);
        EXPECT_LT(std::abs(r->jones[0].m[1][0] - sign * sn * f.rs), 1e-15);
        EXPECT_LT(std::abs(r->jones[0].m[1][1] - c * f.rp), 1e-15);
        const Mueller m = Mueller::FromJones(r->jones[0]);
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) EXPECT_NEAR(r->mueller[0].m[i][j], m.m[i][j], 1e-15) << i << j;
        EXPECT_NEAR(r->mueller[0].m[0][0], FresnelConductor(0.7, Complex(0.2, 3.0)), 1e-15);
    }
}

// The faces keep their kernels' energy sense (CombinedEnergySense): reciprocal faces a reciprocal
// sheet; a grating below and gold above, or a rough surface above and a grating below, a sheet that
// conserves energy per incident direction; the per-query toy grating on both faces one per query.
// The light arriving from d on either face leaves with F_gold(θ_d) (listed lobes pointing back at d
// plus the halo's ∫ f(w → d)·cosθ_w dω_w, by quadrature; tolerance as in mix_test.cpp).
TEST(TwoSided, FacesKeepTheirEnergySense) {
    MiniScene s;
    s.WithFixtures()
        .Add("Material", "toy_grating", "toy", ParamDict())
        .Add("Material", "two_sided", "metal", ParamDict().Set("material", Value::Ref("contract_gold")))
        .Add("Material", "two_sided", "gold_grating",
             ParamDict().Set("front", Value::Ref("contract_gold")).Set("back", Value::Ref("contract_grating")))
        .Add("Material", "two_sided", "rough_grating",
             ParamDict().Set("front", Value::Ref("contract_rough")).Set("back", Value::Ref("contract_grating")))
        .Add("Material", "two_sided", "toys", ParamDict().Set("material", Value::Ref("toy")));
    const std::pair<const char *, EnergySense> expected[] = {{"metal", EnergySense::Reciprocal},
                                                             {"gold_grating", EnergySense::PerIncidentDirection},
                                                             {"rough_grating", EnergySense::PerIncidentDirection},
                                                             {"toys", EnergySense::PerQuery}};
    for (const auto &[name, sense] : expected) {
        auto m = Get(s, name);
        ASSERT_TRUE(m);
        EXPECT_EQ(int(EnergySenseOf(*m)), int(sense)) << name << ": " << Describe(EnergySenseOf(*m));
    }
    auto t = Get(s, "rough_grating"), gold = Get(s, "contract_gold");
    ASSERT_TRUE(t && gold);
    const SampledWavelengths wl = TestWavelengths(480e-9);
    for (const Vec3 &up : {DirectionFromCosTheta(0.95, 0.3), DirectionFromCosTheta(0.5, 2.2)})
        for (const bool below : {false, true}) {
            ScatterQuery q;
            q.wi = below ? Mirror(up) : up;
            q.wl = &wl;
            q.rayOptics = false;
            const Prep refK(*gold, q);
            const std::span<const NearDeltaLobe> ref = refK->ListNearDelta();
            ASSERT_EQ(ref.size(), 1u);
            const SampledSpectrum halo = ContinuousFrom(*t, q, q.wi, 0.02);
            if (below) {
                EXPECT_TRUE(halo.IsZero()) << "the grating face has no halo";
            }
            for (int i = 0; i < wl.Count(); ++i) {
                const double listed = ListedEnergyFrom(*t, q, i).energy, F = ref[0].Weight()[i];
                EXPECT_NEAR(listed + halo[i], F, 3.5e-4 * F + 1e-7)
                    << "light from " << ToString(q.wi) << ", slot " << i << ": listed " << listed << " + halo " << halo[i];
            }
        }
}

// Children that send light through the surface are refused (Mitsuba's twosided does the same):
// a dielectric, a mix holding one, an aperture. So are a missing or doubled face and faces that
// conserve energy in different senses.
TEST(TwoSided, BadInput) {
    auto firstError = [](MiniScene &s) {
        EXPECT_FALSE(s.Build<Material>("t"));
        return s.FirstError();
    };
    {
        MiniScene s;
        s.WithFixtures().Add("Material", "two_sided", "t", ParamDict().Set("material", Value::Ref("contract_glass")));
        EXPECT_NE(firstError(s).find("'material' transmits: it lists a transmitted lobe"), std::string::npos)
            << s.FirstError();
    }
    {
        MiniScene s;
        s.WithFixtures()
            .Add("Material", "mix", "dusty_glass",
                 ParamDict().Set("a", Value::Ref("contract_matte")).Set("b", Value::Ref("contract_glass")).Set("weight", Value::Number(0.1)))
            .Add("Material", "two_sided", "t",
                 ParamDict().Set("front", Value::Ref("contract_gold")).Set("back", Value::Ref("dusty_glass")));
        EXPECT_NE(firstError(s).find("'back' transmits: it lists a transmitted lobe (MixMaterial"), std::string::npos) << s.FirstError();
    }
    {
        MiniScene s;
        s.Add("Material", "aperture", "slit",
              ParamDict().Set("rects", Value::List({Value::Number(-1e-6, Dim::Length()), Value::Number(-5e-5, Dim::Length()),
                                                    Value::Number(1e-6, Dim::Length()), Value::Number(5e-5, Dim::Length())})))
            .Add("Material", "two_sided", "t", ParamDict().Set("material", Value::Ref("slit")));
        EXPECT_NE(firstError(s).find("'material' transmits: it is footprint-aware"), std::string::npos) << s.FirstError();
    }
    {
        MiniScene s;
        s.WithFixtures().Add("Material", "two_sided", "t", ParamDict().Set("front", Value::Ref("contract_gold")));
        EXPECT_NE(firstError(s).find("'front' needs 'back'"), std::string::npos) << s.FirstError();
    }
    {
        MiniScene s;
        s.WithFixtures().Add("Material", "two_sided", "t",
                             ParamDict().Set("material", Value::Ref("contract_gold")).Set("back", Value::Ref("contract_matte")));
        EXPECT_NE(firstError(s).find("give 'material' (both faces) or 'front' and 'back', not both"), std::string::npos)
            << s.FirstError();
    }
    {
        MiniScene s;
        s.Add("Material", "two_sided", "t", ParamDict());
        EXPECT_NE(firstError(s).find("two_sided needs 'material'"), std::string::npos) << s.FirstError();
    }
    {
        MiniScene s;
        s.WithFixtures()
            .Add("Material", "toy_grating", "toy", ParamDict())
            .Add("Material", "two_sided", "t", ParamDict().Set("front", Value::Ref("toy")).Set("back", Value::Ref("contract_rough")));
        EXPECT_NE(firstError(s).find("'front' conserves energy per query (ToyGratingMaterial"), std::string::npos)
            << s.FirstError();
        EXPECT_NE(s.FirstError().find("but 'back' conserves energy per incident direction (HarveyShackMaterial"),
                  std::string::npos)
            << s.FirstError();
    }
}

}  // namespace
}  // namespace test
}  // namespace phasor
