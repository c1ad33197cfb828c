// SPDX-License-Identifier: Apache-2.0
// phasor — `constant` texture: the same value everywhere on the surface.
//
// By value kind: a number makes a scalar texture of the number's dimension (`value = 300 nm` is
// a length texture; a plain number is dimensionless and also serves where a spectrum is
// expected); a spectrum call or @spectrum makes a spectral texture.
#include <memory>
#include <sstream>

#include "core/render/registry.h"
#include "core/render/texture.h"

namespace phasor {

namespace {

class ConstantScalarTexture final : public ScalarTexture {
  public:
    ConstantScalarTexture(double value, Dim dim) : ScalarTexture(dim), value_(value) {}
    double EvalScalar(const TextureEvalContext &) const override { return value_; }
    double MinValue() const override { return value_; }
    double MaxValue() const override { return value_; }
    std::string ToString() const override {
        return "ConstantTexture[ value = " + Value::Number(value_, GetDim()).ToString() + " ]";
    }

  private:
    double value_;
};

class ConstantSpectralTexture final : public Texture {
  public:
    explicit ConstantSpectralTexture(std::shared_ptr<const Spectrum> value) : value_(std::move(value)) {}
    std::optional<Dim> ScalarDim() const override { return std::nullopt; }
    SampledSpectrum Eval(const TextureEvalContext &ctx, const SampledWavelengths &wl) const override {
        return value_.Eval(ctx, wl);
    }
    double MinValue() const override { return value_.MinValue(); }
    double MaxValue() const override { return value_.MaxValue(); }
    std::string ToString() const override { return "ConstantTexture[ value = " + value_.ToString() + " ]"; }

  private:
    SpectrumTexture value_;  // holds a spectrum, never a texture
};

}  // namespace

/// The plug-in: builds one of the two classes above.
class ConstantTexture {
  public:
    static const Schema &GetSchema() {
        static const Schema s{"texture",
                              "constant",
                              "the same value everywhere: a number (its unit gives the texture's dimension) or a "
                              "spectrum",
                              {P::Spectrum("value", "the value at every point").Default(Value::Number(0.5)).AnyDim()}};
        return s;
    }

    static std::unique_ptr<Texture> Create(const ParamDict &dict, BuildContext &ctx) {
        const Value &v = dict.GetValue("value");
        if (v.kind == Value::Kind::Number) return std::make_unique<ConstantScalarTexture>(v.number, v.dim);
        return std::make_unique<ConstantSpectralTexture>(ctx.GetSpectrum(dict, "value"));
    }
};

PHASOR_EXPORT_PLUGIN(Texture, ConstantTexture)

}  // namespace phasor
