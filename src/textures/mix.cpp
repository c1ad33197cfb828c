// SPDX-License-Identifier: Apache-2.0
// phasor — `mix` texture: (1 − amount)·tex0 + amount·tex1 of two scalar textures (or numbers) of
// one dimension, with a dimensionless amount in [0, 1] (a number or a texture).
#include <algorithm>
#include <memory>

#include "core/render/registry.h"
#include "core/render/texture.h"
#include "textures/texture_common.h"

namespace phasor {

class MixTexture final : public ScalarTexture {
  public:
    MixTexture(FloatTexture t0, FloatTexture t1, FloatTexture amount)
        : ScalarTexture(t0.GetDim()), t0_(std::move(t0)), t1_(std::move(t1)), amount_(std::move(amount)) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "texture",
            "mix",
            "blend of two scalar textures of one dimension: (1 − amount)·tex0 + amount·tex1",
            {
                P::FloatTexture("tex0", "value where amount = 0 (a number or a scalar texture)").Required().AnyDim(),
                P::FloatTexture("tex1", "value where amount = 1 (same dimension as tex0)").Required().AnyDim(),
                P::FloatTexture("amount", "blend weight (a number or a texture)").Default(Value::Number(0.5)).Min(0).Max(1),
            }};
        return s;
    }

    static std::unique_ptr<Texture> Create(const ParamDict &dict, BuildContext &ctx) {
        FloatTexture t0 = ctx.GetFloatTexture(dict, "tex0"), t1 = ctx.GetFloatTexture(dict, "tex1");
        texture_common::CommonDim(dict, {{"tex0", t0.GetDim()}, {"tex1", t1.GetDim()}});
        return std::make_unique<MixTexture>(std::move(t0), std::move(t1), ctx.GetFloatTexture(dict, "amount"));
    }

    double EvalScalar(const TextureEvalContext &ctx) const override {
        const double a = amount_.Eval(ctx);
        return (1 - a) * t0_.Eval(ctx) + a * t1_.Eval(ctx);
    }

    // A convex combination stays within the two textures' joint bounds.
    double MinValue() const override { return std::min(t0_.MinValue(), t1_.MinValue()); }
    double MaxValue() const override { return std::max(t0_.MaxValue(), t1_.MaxValue()); }

    std::string ToString() const override {
        return "MixTexture[ tex0 = " + t0_.ToString() + ", tex1 = " + t1_.ToString() +
               ", amount = " + amount_.ToString() + " ]";
    }

  private:
    FloatTexture t0_, t1_, amount_;
};

PHASOR_EXPORT_PLUGIN(Texture, MixTexture)

}  // namespace phasor
