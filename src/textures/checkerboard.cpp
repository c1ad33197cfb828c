// SPDX-License-Identifier: Apache-2.0
// phasor — `checkerboard` texture: alternating squares of two spectra in uv space.
//
// The check containing (u, v) is (⌊u·scale⌋, ⌊v·scale⌋); it shows color0 when the sum of the two
// indices is even and color1 when it is odd, so `scale` checks span one unit of u (and of v).
// Point-sampled (no filtering: a generalized ray's footprint is not used here).
#include <cmath>
#include <memory>
#include <sstream>

#include "core/render/registry.h"
#include "core/render/texture.h"

namespace phasor {

class CheckerboardTexture final : public Texture {
  public:
    CheckerboardTexture(std::shared_ptr<const Spectrum> c0, std::shared_ptr<const Spectrum> c1, double scale)
        : c0_(std::move(c0)), c1_(std::move(c1)), scale_(scale) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "texture",
            "checkerboard",
            "alternating squares of two spectra in uv space",
            {
                P::Spectrum("color0", "value of the check at the uv origin").Default(Value::Number(0.8)),
                P::Spectrum("color1", "value of the other checks").Default(Value::Number(0.2)),
                P::Number("scale", "number of checks per unit of u (and of v)")
                    .Default(Value::Number(8))
                    .Min(0, true),
            }};
        return s;
    }

    static std::unique_ptr<Texture> Create(const ParamDict &dict, BuildContext &ctx) {
        return std::make_unique<CheckerboardTexture>(
            ctx.GetSpectrum(dict, "color0"), ctx.GetSpectrum(dict, "color1"), dict.GetNumber("scale"));
    }

    /// 0 for a color0 check, 1 for a color1 check.
    int CheckAt(const Vec2 &uv) const {
        const double iu = std::floor(uv.x * scale_), iv = std::floor(uv.y * scale_);
        return std::fmod(std::abs(iu + iv), 2.0) == 0 ? 0 : 1;
    }

    std::optional<Dim> ScalarDim() const override { return std::nullopt; }

    SampledSpectrum Eval(const TextureEvalContext &ctx, const SampledWavelengths &wl) const override {
        const Spectrum &s = CheckAt(ctx.uv) == 0 ? *c0_ : *c1_;
        SampledSpectrum r;
        for (int i = 0; i < wl.Count(); ++i) r[i] = s.Eval(wl.lambda[i]);
        return r;
    }

    double MinValue() const override { return 0; }  // a lower bound: spectra are never negative
    double MaxValue() const override { return std::max(c0_->MaxValue(), c1_->MaxValue()); }

    std::string ToString() const override {
        std::ostringstream os;
        os << "CheckerboardTexture[ color0 = " << c0_->ToString() << ", color1 = " << c1_->ToString()
           << ", scale = " << scale_ << " ]";
        return os.str();
    }

  private:
    std::shared_ptr<const Spectrum> c0_, c1_;
    double scale_;
};

PHASOR_EXPORT_PLUGIN(Texture, CheckerboardTexture)

}  // namespace phasor
