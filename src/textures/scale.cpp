// SPDX-License-Identifier: Apache-2.0
// phasor — `scale` texture: a scalar texture (or number) times a dimensionless factor (or
// texture). The result has the dimension of `tex`.
#include <algorithm>
#include <array>
#include <memory>

#include "core/render/registry.h"
#include "core/render/texture.h"

namespace phasor {

class ScaleTexture final : public ScalarTexture {
  public:
    ScaleTexture(FloatTexture tex, FloatTexture factor)
        : ScalarTexture(tex.GetDim()), tex_(std::move(tex)), factor_(std::move(factor)) {}

    static const Schema &GetSchema() {
        static const Schema s{"texture",
                              "scale",
                              "a scalar texture times a dimensionless factor: tex·factor (the dimension of 'tex')",
                              {
                                  P::FloatTexture("tex", "the value scaled (a number or a scalar texture)").Required().AnyDim(),
                                  P::FloatTexture("factor", "dimensionless factor (a number or a texture)")
                                      .Default(Value::Number(1)),
                              }};
        return s;
    }

    static std::unique_ptr<Texture> Create(const ParamDict &dict, BuildContext &ctx) {
        return std::make_unique<ScaleTexture>(ctx.GetFloatTexture(dict, "tex"), ctx.GetFloatTexture(dict, "factor"));
    }

    double EvalScalar(const TextureEvalContext &ctx) const override { return tex_.Eval(ctx) * factor_.Eval(ctx); }

    // The product's bounds are among the products of the factors' bounds.
    double MinValue() const override {
        const auto c = Corners();
        return *std::min_element(c.begin(), c.end());
    }
    double MaxValue() const override {
        const auto c = Corners();
        return *std::max_element(c.begin(), c.end());
    }

    std::string ToString() const override {
        return "ScaleTexture[ tex = " + tex_.ToString() + ", factor = " + factor_.ToString() + " ]";
    }

  private:
    std::array<double, 4> Corners() const {
        const double a0 = tex_.MinValue(), a1 = tex_.MaxValue(), b0 = factor_.MinValue(), b1 = factor_.MaxValue();
        return {a0 * b0, a0 * b1, a1 * b0, a1 * b1};
    }
    FloatTexture tex_, factor_;
};

PHASOR_EXPORT_PLUGIN(Texture, ScaleTexture)

}  // namespace phasor
