// SPDX-License-Identifier: Apache-2.0
// `cauchy`: a refractive index from Cauchy's dispersion formula (Cauchy 1836),
//     n(λ) = A + B/λ² + C/λ⁴,
// λ the vacuum wavelength, A dimensionless, B an area and C a length⁴, each written with its unit,
// so any length unit works: `b = 4200 nm^2` and `b = 0.0042 um^2` are the same term (with λ in
// µm the conventional tabulated B is in µm², with λ in nm in nm²). An empirical fit for
// transparent materials in the visible (chitin: A = 1.517, B = 8800 nm², Leertouwer et al. 2011);
// the named `chitin` uses the same implementation (core/spectrum/dispersion.h). Usable wherever a
// spectrum or an index is: `ior = cauchy(1.5046, 0.0042 um^2)`. Outside `range` (default
// 200 nm–3.7 µm) the value at the nearer end is used.
#include "spectra/index_formula.h"

#include "core/spectrum/dispersion.h"

namespace phasor {

class CauchySpectrum final : public IndexFormulaSpectrum {
  public:
    CauchySpectrum(double a, double b, double c, double lo, double hi)
        : IndexFormulaSpectrum(lo, hi), a_(a), b_(b), c_(c) {}

    static const Schema &GetSchema() {
        static const Schema s{"spectrum",
                              "cauchy",
                              "Refractive index from Cauchy's formula n = A + B/λ² + C/λ⁴.",
                              {P::Number("a", "A, the index at long wavelengths").Required().Min(0, true),
                               P::Number("b", "B (an area: 0.0042 um^2 = 4200 nm^2)", Dim::Area())
                                   .Default(Value::Number(0, Dim::Area())),
                               P::Number("c", "C (a length to the fourth: e.g. 0.0001 um^4)", Dim::Length().Pow(4))
                                   .Default(Value::Number(0, Dim::Length().Pow(4))),
                               RangeSpec()}};
        return s;
    }

    static std::unique_ptr<Spectrum> Create(const ParamDict &d, BuildContext &) {
        const auto [lo, hi] = ReadRange(d);
        auto s = std::make_unique<CauchySpectrum>(d.GetNumber("a"), d.GetNumber("b"), d.GetNumber("c"), lo, hi);
        s->Finish(d.Loc(d.Has("c") ? "c" : d.Has("b") ? "b" : "a"));
        return s;
    }

    static std::vector<ParamDict> TestPresets() {
        return {ParamDict().Set("a", Value::Number(1.5046)).Set("b", Value::Number(0.0042e-12, Dim::Area())),
                ParamDict()
                    .Set("a", Value::Number(1.517))
                    .Set("b", Value::Number(8.8e3 * 1e-18, Dim::Area()))
                    .Set("c", Value::Number(1e-4 * 1e-24, Dim::Length().Pow(4)))};
    }

    double Eval(double lambda) const override { return dispersion::Cauchy(lambda, a_, b_, c_, lo_, hi_); }

    std::string ToString() const override {
        return "cauchy(a = " + spectra::Num(a_) + ", b = " + spectra::Num(b_ * 1e12) + " um^2, c = " +
               spectra::Num(c_ * 1e24) + " um^4, " + RangeText() + ")";
    }

  private:
    double a_, b_, c_;  // B [m²], C [m⁴]
};

PHASOR_EXPORT_PLUGIN(Spectrum, CauchySpectrum)

}  // namespace phasor
