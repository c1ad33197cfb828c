// SPDX-License-Identifier: Apache-2.0
// `gaussian`: a Gaussian band, peak · exp(−(λ − center)²/(2σ²)), σ = FWHM/(2√(2 ln 2)).
// Sampled as a continuous spectrum; the wavelength grid refines itself to ≥ 64 cells over the
// band's ±5.26σ support, so arbitrarily narrow bands work.
#include "spectra/gaussian_spectrum.h"

namespace phasor {

const Schema &GaussianSpectrum::GetSchema() {
    static const Schema s{"spectrum",
                          "gaussian",
                          "Gaussian band given by its centre, full width at half maximum and peak value.",
                          {P::Length("center", "centre wavelength").Required().Min(0, true),
                           P::Length("fwhm", "full width at half maximum").Required().Min(0, true),
                           P::Number("peak", "value at the centre").Default(Value::Number(1)).Min(0)}};
    return s;
}

std::unique_ptr<Spectrum> GaussianSpectrum::Create(const ParamDict &d, BuildContext &) {
    return std::make_unique<GaussianSpectrum>(d.GetNumber("center"), d.GetNumber("fwhm"),
                                              d.GetNumber("peak"));
}

std::vector<ParamDict> GaussianSpectrum::TestPresets() {
    return {ParamDict()
                .Set("center", Value::Number(550e-9, Dim::Length()))
                .Set("fwhm", Value::Number(40e-9, Dim::Length())),
            ParamDict()
                .Set("center", Value::Number(1064e-9, Dim::Length()))
                .Set("fwhm", Value::Number(0.01e-9, Dim::Length()))
                .Set("peak", Value::Number(3))};
}

PHASOR_EXPORT_PLUGIN(Spectrum, GaussianSpectrum)

}  // namespace phasor
