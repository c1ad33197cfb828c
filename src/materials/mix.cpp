// SPDX-License-Identifier: Apache-2.0
// phasor — `mix`: a weighted blend of two kernels, f = (1 − w)·f_a + w·f_b (pbrt-v4's
// MixMaterial, Mitsuba 3's blendbsdf: weight 0 gives the first kernel, `a`; weight 1 the second, `b`).
//
// Models a surface made of two kinds of patches finer than the footprint but much coarser than the
// wavelength — scratches or corrosion spots on a metal, dust on a mirror — that scatter
// independently: their responses add in intensity (an incoherent, area-weighted mixture; light
// scattered by one patch kind does not interfere with the other's). The weight w ∈ [0, 1] is a
// constant or a dimensionless texture evaluated at the hit (ScatterQuery::tex), so it may vary over
// the surface. Every quantity is the weighted sum of the children's: Eval and Pdf are
// (1 − w)·(…)_a + w·(…)_b, so the mixture's pdf is Σ w_i pdf_i (one-sample MIS over the two
// children, theory §3.1); Sample picks child a with probability 1 − w and b with probability w
// (from u0, which is then rescaled for the child) and, for a continuous lobe, weights the sample
// by the mixture's f·|cosθo|/pdf (so the weight is the same whichever child produced wo).
// Near-delta lobes: the children's listed lobes, each with weight and probability scaled by its
// child's share; lobe ids are remapped to stay unique — a's id j becomes 2j, b's becomes 2j + 1
// (continuous lobes too), and EvalLobe maps them back (the Jones matrix scaled by √share, so its
// Mueller matrix is share × the child's). Capabilities are the union over the children with a
// non-zero share at the query. Footprint-aware children (`aperture`) are refused: their lobes
// depend on the incident generalized ray in a way a scalar blend does not represent.
// Valid wherever both children are. Energy (CombinedEnergySense, core/render/material.h): f and
// every listed lobe are (1 − w)·(child a's) + w·(child b's) with w fixed at the hit, so the mix is
// reciprocal if both children are, and conserves energy per incident direction (the light from a
// direction d leaves with (1 − w)·E_a(d) + w·E_b(d) ≤ 1) if each child is reciprocal or conserves
// it per incident direction — a grating and a conductor, a grating and a rough surface — and per
// query likewise. A child that conserves energy only per query beside one that conserves it only
// per incident direction is refused: their mix bounds neither.
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "core/diagnostics.h"
#include "core/render/material.h"
#include "core/render/registry.h"

namespace phasor {

namespace {
constexpr double OneMinusEpsilon = 0x1.fffffffffffffp-1;  // the largest double below 1
}  // namespace

class MixMaterial final : public Material, public ReferenceDirection {
  public:
    /// The children must have a combined energy sense (CombinedEnergySense; Create checks it).
    MixMaterial(std::shared_ptr<const Material> a, std::shared_ptr<const Material> b, FloatTexture weight)
        : a_(std::move(a)), b_(std::move(b)), weight_(std::move(weight)) {
        const Material *children[] = {a_.get(), b_.get()};
        sense_ = CombinedEnergySense(children).value_or(EnergySense::PerQuery);
    }

    static const Schema &GetSchema() {
        static const Schema s{
            "material",
            "mix",
            "blend of two kernels, f = (1 − weight)·f_a + weight·f_b (weight 0: a; 1: b), constant or textured",
            {
                P::Ref("a", "material", "the kernel where weight = 0").Required(),
                P::Ref("b", "material", "the kernel where weight = 1").Required(),
                P::FloatTexture("weight", "share w of 'b' in [0, 1] (a number or a dimensionless texture); a has 1 − w")
                    .Default(Value::Number(0.5))
                    .Min(0)
                    .Max(1),
                P::Ref("weight_texture", "texture",
                       "the same as weight = @texture (a dimensionless scalar texture in [0, 1]); not together "
                       "with 'weight'")
                    .Min(0)
                    .Max(1),
            }};
        return s;
    }

    static std::unique_ptr<Material> Create(const ParamDict &d, BuildContext &ctx) {
        if (d.Has("weight") && d.Has("weight_texture"))
            throw Error(d.Loc("weight_texture"), "give 'weight' or 'weight_texture', not both");
        auto child = [&](const char *name) {
            std::shared_ptr<const Material> m = ctx.GetRef<Material>(d, name);
            if (m->IsFootprintAware())
                throw Error(d.Loc(name), std::string("'") + name + "' is footprint-aware (" + m->ToString() +
                                             "): mix cannot blend a kernel whose lobes depend on the incident "
                                             "generalized ray's footprint");
            return m;
        };
        std::shared_ptr<const Material> a = child("a"), b = child("b");
        const Material *children[] = {a.get(), b.get()};
        if (!CombinedEnergySense(children))
            throw Error(d.Loc("b"), std::string("'a' ") + Describe(EnergySenseOf(*a)) + " (" + a->ToString() + ") but 'b' " +
                                        Describe(EnergySenseOf(*b)) + " (" + b->ToString() +
                                        "): their mix would bound neither what one direction gathers nor what the "
                                        "light from one direction leaves with");
        FloatTexture w = ctx.GetFloatTexture(d, d.Has("weight_texture") ? "weight_texture" : "weight");
        return std::make_unique<MixMaterial>(std::move(a), std::move(b), std::move(w));
    }

    /// Presets for the contract suite (fixtures of tests/materials/material_test_util.h). Four keep
    /// its run time down; the end points w = 0 and 1 and a mix of two continuous kernels are tested
    /// against the children themselves (tests/materials/mix_test.cpp).
    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(4);
        // Two metals under a textured weight (a ramp over u from 0.1 to 0.9): two lobes in the same
        // direction.
        p[0].Set("a", Value::Ref("contract_gold"))
            .Set("b", Value::Ref("contract_aluminium"))
            .Set("weight_texture", Value::Ref("contract_ramp"));
        // Glass (reflection and refraction) and a diffuser: near-delta and continuous lobes, with a
        // texture given as 'weight'.
        p[1].Set("a", Value::Ref("contract_glass")).Set("b", Value::Ref("contract_matte")).Set("weight", Value::Ref("contract_half"));
        // A grating and a rough surface, both conserving energy per incident direction (the suite's
        // EnergyPerIncidentDirection: listed orders, a glint and a halo), under a textured weight.
        p[2].Set("a", Value::Ref("contract_grating"))
            .Set("b", Value::Ref("contract_rough"))
            .Set("weight_texture", Value::Ref("contract_ramp"));
        // A mixture of mixtures: a grating's orders scaled twice (deferred weights bit for bit as
        // the eager listing's, (a·s₁)·s₂).
        p[3].Set("a", Value::Ref("contract_grating_mix")).Set("b", Value::Ref("contract_grating")).Set("weight", Value::Number(0.6));
        return p;
    }

    /// Both children prepared for the query (a child with share 0 is not); lists a's lobes (ids 2j)
    /// and b's (ids 2j + 1), weights and probabilities times the child's share, merged in id order.
    /// EvalLobe: the child's response, times its share (the Jones matrix times √share).
    const PreparedKernel &Prepare(const ScatterQuery &q, ScratchBuffer &scratch) const override {
        return *scratch.New<Prepared>(*this, q, scratch);
    }

    bool IsReciprocal() const override { return sense_ == EnergySense::Reciprocal; }
    bool ConservesEnergyPerIncidentDirection() const override { return sense_ == EnergySense::PerIncidentDirection; }
    bool HasCoherenceTerms() const override { return a_->HasCoherenceTerms() || b_->HasCoherenceTerms(); }
    bool MayPassStraight() const override { return a_->MayPassStraight() || b_->MayPassStraight(); }
    /// Lobe 2j is a's lobe j, 2j + 1 is b's (MixId).
    std::string LobeName(int id) const override {
        const int child = id >= 0 ? id / 2 : -((-id + 1) / 2);  // floor(id / 2)
        return (id - 2 * child == 0 ? "a: " + a_->LobeName(child) : "b: " + b_->LobeName(child));
    }
    /// a's reference direction, else b's.
    std::optional<double> ReferenceAngle(const TextureEvalContext &tex) const override {
        const std::optional<double> a = ReferenceAngleOf(*a_, tex);
        return a ? a : ReferenceAngleOf(*b_, tex);
    }

    void CheckShape(const Shape &shape) const override {
        a_->CheckShape(shape);
        b_->CheckShape(shape);
    }

    std::string ToString() const override {
        std::ostringstream os;
        os << "MixMaterial[ a = " << a_->ToString() << ", b = " << b_->ToString() << ", weight = " << weight_.ToString()
           << " ]";
        return os.str();
    }

  private:
    /// w at the query, in [0, 1] (the accessor checked the texture's range; the clamp only guards
    /// against rounding and a NaN from a texture, which counts as 0).
    double Weight(const ScatterQuery &q) const {
        const double w = weight_.Eval(q.tex);
        return w > 0 ? std::min(w, 1.0) : 0.0;
    }

    /// The mixture's id of child lobe `id` (a: 2·id, b: 2·id + 1).
    static int MixId(int id, bool isB) { return 2 * id + int(isB); }

    /// A child's listed lobe as the mixture's: id remapped, weight and probability times `share`;
    /// weights the child deferred are the mixture's LobeWeightAt (the child's times `share`).
    static void Scale(NearDeltaLobe &l, bool isB, double share, const PreparedKernel &mixture) {
        l.id = MixId(l.id, isB);
        l.ScaleWeight(share);
        l.prob *= share;
        l.DeferWeights(l.PendingSlots(), mixture);
    }

    /// The mixture at one hit: w there and the children prepared (a if w < 1, b if w > 0).
    class Prepared final : public PreparedKernel {
      public:
        Prepared(const MixMaterial &m, const ScatterQuery &q, ScratchBuffer &scratch) : PreparedKernel(q), w_(m.Weight(q)) {
            a_ = w_ < 1 ? &m.a_->Prepare(q, scratch) : nullptr;
            b_ = w_ > 0 ? &m.b_->Prepare(q, scratch) : nullptr;
            caps_ = (a_ ? a_->Capabilities() : 0u) | (b_ ? b_->Capabilities() : 0u);
            const std::span<const NearDeltaLobe> la = a_ ? a_->ListNearDelta() : std::span<const NearDeltaLobe>();
            const std::span<const NearDeltaLobe> lb = b_ ? b_->ListNearDelta() : std::span<const NearDeltaLobe>();
            if (!la.empty() || !lb.empty()) {
                // Both lists are in id order; so is their merge (a's ids even, b's odd).
                LobeList out(scratch, int(la.size() + lb.size()));
                std::size_t ia = 0, ib = 0;
                while (ia < la.size() || ib < lb.size()) {
                    const bool takeA = ib == lb.size() || (ia < la.size() && MixId(la[ia].id, false) < MixId(lb[ib].id, true));
                    NearDeltaLobe &l = out.Add();
                    l = takeA ? la[ia++] : lb[ib++];
                    Scale(l, !takeA, takeA ? 1 - w_ : w_, *this);
                }
                lobes_ = out.Lobes();
            }
            if (a_)
                for (int id : a_->ContinuousLobes()) continuous_.Add(MixId(id, false));
            if (b_)
                for (int id : b_->ContinuousLobes()) continuous_.Add(MixId(id, true));
        }

        /// The larger of the prepared children's.
        double AngularBandwidth(double kappaMax) const override {
            return std::max(a_ ? a_->AngularBandwidth(kappaMax) : 0.0, b_ ? b_->AngularBandwidth(kappaMax) : 0.0);
        }
        std::optional<LobeResponse> EvalLobe(int lobe, const Vec3 &wo) const override {
            const bool isB = (lobe & 1) != 0;
            const double share = isB ? w_ : 1 - w_;
            if (!(share > 0)) return std::nullopt;
            std::optional<LobeResponse> r = (isB ? b_ : a_)->EvalLobe((lobe - int(isB)) / 2, wo);
            if (!r) return std::nullopt;
            const Complex amp(std::sqrt(share), 0);
            for (int i = 0; i < q_.wl->Count(); ++i) {
                r->mueller[i] = r->mueller[i] * share;
                r->jones[i] = r->jones[i] * amp;
                r->coherence.incoherent[i] = r->coherence.incoherent[i] * share;
            }
            return r;
        }
        /// The owning child's, times its share (as the listing scales it).
        std::optional<SampledSpectrum> LobeWeightAt(int lobe, const Vec3 &wiPrime, unsigned slots) const override {
            const bool isB = (lobe & 1) != 0;
            const PreparedKernel *child = isB ? b_ : a_;
            if (!child) return SampledSpectrum();  // a child with share 0 lists nothing
            std::optional<SampledSpectrum> a = child->LobeWeightAt((lobe - int(isB)) / 2, wiPrime, slots);
            if (!a) return std::nullopt;
            return *a * (isB ? w_ : 1 - w_);
        }

      private:
        std::optional<ScatterSample> SampleLobes(double u0, const Vec2 &u) const override {
            const double w = w_;
            // Child b with probability w, a with 1 − w; u0 rescaled to [0, 1) within the choice.
            const bool isB = w >= 1 || (w > 0 && u0 >= 1 - w);
            const double share = isB ? w : 1 - w;
            const double uc = std::min((isB ? u0 - (1 - w) : u0) / share, OneMinusEpsilon);
            std::optional<ScatterSample> s = (isB ? b_ : a_)->Sample(std::max(uc, 0.0), u);
            if (!s) return std::nullopt;
            s->lobe = MixId(s->lobe, isB);
            if (s->flags & ScatterNearDelta) {
                s->pdf *= share;  // the lobe's probability in the mixture; a_j·share / (p_j·share) = a_j/p_j
                return s;
            }
            // A continuous direction: the mixture's density and value there (either child may reach wo).
            const double pdf = PdfContinuous(s->wo);
            if (!(pdf > 0)) return std::nullopt;
            s->weight = EvalContinuous(s->wo) * (std::abs(s->wo.z) / pdf);
            s->pdf = pdf;
            return s;
        }
        SampledSpectrum EvalContinuous(const Vec3 &wo) const override {
            SampledSpectrum f(0.0);
            if (a_) f += a_->Eval(wo) * (1 - w_);
            if (b_) f += b_->Eval(wo) * w_;
            return f;
        }
        double PdfContinuous(const Vec3 &wo) const override {
            return (a_ ? (1 - w_) * a_->Pdf(wo) : 0.0) + (b_ ? w_ * b_->Pdf(wo) : 0.0);
        }
        KernelValue EvalPdfContinuous(const Vec3 &wo, const IncidentWave &w) const override {
            KernelValue v;
            double pa = 0, pb = 0;
            if (a_) {
                const KernelValue c = a_->EvalPdf(wo, w);
                v.f += c.f * (1 - w_);
                pa = (1 - w_) * c.pdf;
            }
            if (b_) {
                const KernelValue c = b_->EvalPdf(wo, w);
                v.f += c.f * w_;
                pb = w_ * c.pdf;
            }
            v.pdf = pa + pb;
            return v;
        }

        double w_;  // b's share at the hit
        const PreparedKernel *a_ = nullptr, *b_ = nullptr;
    };

    std::shared_ptr<const Material> a_, b_;
    FloatTexture weight_;  // w: b's share, dimensionless, in [0, 1]
    EnergySense sense_ = EnergySense::Reciprocal;  // CombinedEnergySense of a and b
};

PHASOR_EXPORT_PLUGIN(Material, MixMaterial)

}  // namespace phasor
