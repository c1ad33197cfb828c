// SPDX-License-Identifier: Apache-2.0
// phasor — `constant` texture: the same spectrum everywhere on the surface.
#include <memory>

#include "core/material.h"
#include "core/registry.h"

namespace phasor {

class ConstantTexture final : public Texture {
  public:
    explicit ConstantTexture(std::shared_ptr<const Spectrum> value) : value_(std::move(value)) {}

    static const Schema &GetSchema() {
        static const Schema s{"texture",
                              "constant",
                              "a spectrum that does not vary over the surface",
                              {P::Spectrum("value", "the value at every point").Default(Value::Number(0.5))}};
        return s;
    }

    static std::unique_ptr<Texture> Create(const ParamDict &dict, BuildContext &ctx) {
        return std::make_unique<ConstantTexture>(ctx.GetSpectrum(dict, "value"));
    }

    SampledSpectrum Eval(const Vec2 &, const SampledWavelengths &wl) const override {
        SampledSpectrum r;
        for (int i = 0; i < wl.Count(); ++i) r[i] = value_->Eval(wl.lambda[i]);
        return r;
    }

    double MaxValue() const override { return value_->MaxValue(); }

    std::string ToString() const override { return "ConstantTexture[ value = " + value_->ToString() + " ]"; }

  private:
    std::shared_ptr<const Spectrum> value_;
};

PHASOR_EXPORT_PLUGIN(Texture, ConstantTexture)

}  // namespace phasor
