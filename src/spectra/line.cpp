// SPDX-License-Identifier: Apache-2.0
// `line`: an emission line (theory §0 D10). With fwhm = 0 (the default) it is a true discrete
// line: Eval is the integrated strength `power` at exactly the line wavelength and 0 elsewhere,
// the wavelength sampler treats it as an atom, and a path carrying it is deterministic
// (delta sample, companions off). With fwhm > 0 it is a narrow Gaussian whose integral over
// wavelength is `power` (so switching the width on keeps the emitted power), sampled as a
// continuous spectrum.
#include <cmath>

#include "spectra/gaussian_spectrum.h"

namespace phasor {

class LineSpectrum final : public Spectrum {
  public:
    LineSpectrum(double lambda, double power) : lambda_(lambda), power_(power) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "spectrum",
            "line",
            "Emission line: a discrete line of integrated strength `power`, or, with fwhm > 0, a "
            "Gaussian of that integral.",
            {P::Length("wavelength", "vacuum wavelength of the line").Required().Min(0, true),
             P::Number("power", "integrated strength (the spectrum's integral over wavelength)")
                 .Default(Value::Number(1))
                 .Min(0),
             P::Length("fwhm", "full width at half maximum; 0 = an infinitely narrow (discrete) line")
                 .Default(Value::Number(0, Dim::Length()))
                 .Min(0)}};
        return s;
    }
    static std::unique_ptr<Spectrum> Create(const ParamDict &d, BuildContext &) {
        const double lambda = d.GetNumber("wavelength"), power = d.GetNumber("power"),
                     fwhm = d.GetNumber("fwhm");
        if (fwhm > 0) return GaussianSpectrum::WithIntegral(lambda, fwhm, power);
        return std::make_unique<LineSpectrum>(lambda, power);
    }
    static std::vector<ParamDict> TestPresets() {
        return {ParamDict().Set("wavelength", Value::Number(632.8e-9, Dim::Length())),
                ParamDict()
                    .Set("wavelength", Value::Number(1e-6, Dim::Length()))
                    .Set("power", Value::Number(2))
                    .Set("fwhm", Value::Number(0.002e-9, Dim::Length()))};
    }

    double Eval(double lambda) const override {
        return std::abs(lambda - lambda_) <= 1e-12 * lambda_ ? power_ : 0.0;
    }
    double MaxValue() const override { return power_; }
    std::pair<double, double> Support() const override { return {lambda_, lambda_}; }
    std::optional<double> LineWavelength() const override { return lambda_; }
    std::string ToString() const override {
        return "line(" + spectra::Nm(lambda_) + ", power = " + spectra::Num(power_) + ")";
    }

  private:
    double lambda_, power_;
};

PHASOR_EXPORT_PLUGIN(Spectrum, LineSpectrum)

}  // namespace phasor
