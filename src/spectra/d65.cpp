// SPDX-License-Identifier: Apache-2.0
// `d65`: CIE standard illuminant D65 (CieD65() in spectrum.h, 5 nm table over 300–830 nm, linear
// interpolation, 0 outside), scaled so that it is `scale` at 560 nm.
#include <algorithm>

#include "core/render/registry.h"
#include "spectra/common.h"
#include "core/spectrum/spectrum.h"

namespace phasor {

class D65Spectrum final : public Spectrum {
  public:
    explicit D65Spectrum(double scale) : scale_(scale) {}

    static const Schema &GetSchema() {
        static const Schema s{"spectrum",
                              "d65",
                              "CIE standard illuminant D65, equal to `scale` at 560 nm.",
                              {P::Number("scale", "value at 560 nm").Default(Value::Number(1)).Min(0)}};
        return s;
    }
    static std::unique_ptr<Spectrum> Create(const ParamDict &d, BuildContext &) {
        return std::make_unique<D65Spectrum>(d.GetNumber("scale"));
    }
    static std::vector<ParamDict> TestPresets() {
        return {ParamDict(), ParamDict().Set("scale", Value::Number(2))};
    }

    double Eval(double lambda) const override { return scale_ * 0.01 * CieD65(lambda); }
    double MaxValue() const override {
        // The table's maximum (117.812 at 460 nm) relative to 100 at 560 nm.
        static const double maxRel = [] {
            double m = 0;
            for (int nm = 300; nm <= 830; ++nm) m = std::max(m, CieD65(nm * 1e-9));
            return 0.01 * m;
        }();
        return scale_ * maxRel;
    }
    std::pair<double, double> Support() const override { return {300e-9, 830e-9}; }
    std::string ToString() const override { return "d65(scale = " + spectra::Num(scale_) + ")"; }

  private:
    double scale_;
};

PHASOR_EXPORT_PLUGIN(Spectrum, D65Spectrum)

}  // namespace phasor
