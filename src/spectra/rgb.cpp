// SPDX-License-Identifier: Apache-2.0
// `rgb`: a linear RGB reflectance / albedo uplifted to a smooth spectrum bounded in [0, 1], by
// Smits' method (B. Smits, "An RGB-to-Spectrum Conversion for Reflectances", Journal of Graphics
// Tools 4(4), 1999; core/spectrum/rgb_uplift.h, shared with the `bitmap` texture).
#include "core/render/registry.h"
#include "core/spectrum/rgb_uplift.h"
#include "core/spectrum/spectrum.h"
#include "spectra/common.h"

namespace phasor {

class RgbSpectrum final : public Spectrum {
  public:
    explicit RgbSpectrum(const Vec3 &rgb) : rgb_(rgb), uplift_(rgb) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "spectrum",
            "rgb",
            "Linear RGB reflectance/albedo uplifted to a smooth spectrum in [0, 1] (Smits 1999).",
            {P::Vector("color", "linear RGB components, each in [0, 1]").Required().Min(0).Max(1)}};
        return s;
    }
    static std::unique_ptr<Spectrum> Create(const ParamDict &d, BuildContext &) {
        const Vec3 c = d.GetVector("color");
        for (int i = 0; i < 3; ++i)
            if (!(c[i] >= 0 && c[i] <= 1))
                throw Error(d.Loc("color"),
                            "rgb colour components must lie in [0, 1]; got " + spectra::Num(c[i]));
        return std::make_unique<RgbSpectrum>(c);
    }
    static std::vector<ParamDict> TestPresets() {
        return {ParamDict().Set("color", Value::Vector({1, 1, 1})),
                ParamDict().Set("color", Value::Vector({0.8, 0.2, 0.1}))};
    }

    double Eval(double lambda) const override { return uplift_.Eval(lambda); }
    double MaxValue() const override { return uplift_.MaxValue(); }
    std::pair<double, double> Support() const override { return {0, Infinity}; }
    std::string ToString() const override {
        return "rgb([" + spectra::Num(rgb_.x) + " " + spectra::Num(rgb_.y) + " " + spectra::Num(rgb_.z) +
               "])";
    }

  private:
    Vec3 rgb_;
    SmitsSpectrum uplift_;
};

PHASOR_EXPORT_PLUGIN(Spectrum, RgbSpectrum)

}  // namespace phasor
