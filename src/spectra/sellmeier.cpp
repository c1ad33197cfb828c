// SPDX-License-Identifier: Apache-2.0
// `sellmeier`: a refractive index from Sellmeier's dispersion formula (Sellmeier 1871),
//     n²(λ) = 1 + Σ_{j=1..3} B_j λ² / (λ² − C_j),
// λ the vacuum wavelength, B_j dimensionless and C_j areas (the squared resonance wavelengths,
// conventionally in µm²: `c1 = 0.00600069867 um^2`). The form of glass catalogues (Schott, Ohara)
// and of most published fits; the named glasses of core/spectrum/named_ior.h use the same
// implementation (core/spectrum/dispersion.h). Usable wherever a spectrum or an index is:
// `ior = sellmeier(1.03961212, 0.231792344, 1.01046945, 0.00600069867 um^2, 0.0200179144 um^2,
// 103.560653 um^2)` is N-BK7. Outside `range` (the fit's band; default 200 nm–3.7 µm) the value
// at the nearer end is used; a resonance inside the band is an error.
#include "spectra/index_formula.h"

#include <array>

#include "core/spectrum/dispersion.h"

namespace phasor {

class SellmeierSpectrum final : public IndexFormulaSpectrum {
  public:
    SellmeierSpectrum(std::array<double, 3> b, std::array<double, 3> c, double lo, double hi)
        : IndexFormulaSpectrum(lo, hi), b_(b), c_(c) {}

    static const Schema &GetSchema() {
        static const Schema s{"spectrum",
                              "sellmeier",
                              "Refractive index from Sellmeier's formula n² = 1 + Σ B_j λ²/(λ² − C_j), three terms.",
                              {P::Number("b1", "B₁ (dimensionless)").Required(),
                               P::Number("b2", "B₂").Default(Value::Number(0)),
                               P::Number("b3", "B₃").Default(Value::Number(0)),
                               P::Number("c1", "C₁: squared resonance wavelength (e.g. 0.0060 um^2)", Dim::Area())
                                   .Required()
                                   .Min(0),
                               P::Number("c2", "C₂", Dim::Area()).Default(Value::Number(0, Dim::Area())).Min(0),
                               P::Number("c3", "C₃", Dim::Area()).Default(Value::Number(0, Dim::Area())).Min(0),
                               RangeSpec()}};
        return s;
    }

    static std::unique_ptr<Spectrum> Create(const ParamDict &d, BuildContext &) {
        const auto [lo, hi] = ReadRange(d);
        std::array<double, 3> b{}, c{};
        for (int j = 0; j < 3; ++j) {
            const std::string bj = "b" + std::to_string(j + 1), cj = "c" + std::to_string(j + 1);
            b[j] = d.GetNumber(bj);
            c[j] = d.GetNumber(cj);
            const double resonance = std::sqrt(c[j]);
            if (b[j] != 0 && resonance >= lo && resonance <= hi)
                throw Error(d.Loc(cj), "the resonance √" + cj + " = " + spectra::Nm(resonance) +
                                           " lies inside 'range' (" + spectra::Nm(lo) + " – " + spectra::Nm(hi) +
                                           "), where the formula has a pole");
        }
        auto s = std::make_unique<SellmeierSpectrum>(b, c, lo, hi);
        s->Finish(d.EntityLoc());
        return s;
    }

    static std::vector<ParamDict> TestPresets() {
        auto um2 = [](double v) { return Value::Number(v * 1e-12, Dim::Area()); };
        return {ParamDict()  // N-BK7 (Schott)
                    .Set("b1", Value::Number(1.03961212))
                    .Set("b2", Value::Number(0.231792344))
                    .Set("b3", Value::Number(1.01046945))
                    .Set("c1", um2(0.00600069867))
                    .Set("c2", um2(0.0200179144))
                    .Set("c3", um2(103.560653)),
                ParamDict().Set("b1", Value::Number(1.2)).Set("c1", um2(0.01))};
    }

    double Eval(double lambda) const override { return dispersion::Sellmeier(lambda, b_, c_, lo_, hi_); }

    std::string ToString() const override {
        std::string s = "sellmeier(";
        for (int j = 0; j < 3; ++j) s += "b" + std::to_string(j + 1) + " = " + spectra::Num(b_[j]) + ", ";
        for (int j = 0; j < 3; ++j) s += "c" + std::to_string(j + 1) + " = " + spectra::Num(c_[j] * 1e12) + " um^2, ";
        return s + RangeText() + ")";
    }

  private:
    std::array<double, 3> b_, c_;  // C_j [m²]
};

PHASOR_EXPORT_PLUGIN(Spectrum, SellmeierSpectrum)

}  // namespace phasor
