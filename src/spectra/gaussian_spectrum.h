// SPDX-License-Identifier: Apache-2.0
// phasor — the Gaussian spectrum, shared by the `gaussian` plug-in (gaussian.cpp, which also
// defines its schema and factory) and the `line` plug-in (a line with a finite width).
#pragma once

#include <cmath>
#include <memory>

#include "core/render/registry.h"
#include "spectra/common.h"
#include "core/spectrum/spectrum.h"

namespace phasor {

/// peak · exp(−(λ − center)² / (2σ²)) with σ = FWHM / (2√(2 ln 2)).
class GaussianSpectrum final : public Spectrum {
  public:
    /// `center`, `fwhm` [m] (fwhm > 0); `peak` is the value at the centre.
    GaussianSpectrum(double center, double fwhm, double peak)
        : center_(center), fwhm_(fwhm), sigma_(fwhm / (2 * std::sqrt(2 * std::log(2.0)))), peak_(peak) {}
    /// The Gaussian whose integral over wavelength is `power` (a line of finite width).
    static std::unique_ptr<GaussianSpectrum> WithIntegral(double center, double fwhm, double power) {
        const double sigma = fwhm / (2 * std::sqrt(2 * std::log(2.0)));
        return std::make_unique<GaussianSpectrum>(center, fwhm, power / (sigma * std::sqrt(2 * Pi)));
    }

    static const Schema &GetSchema();
    static std::unique_ptr<Spectrum> Create(const ParamDict &d, BuildContext &ctx);
    static std::vector<ParamDict> TestPresets();

    double Eval(double lambda) const override {
        const double t = (lambda - center_) / sigma_;
        return peak_ * std::exp(-0.5 * t * t);
    }
    double MaxValue() const override { return peak_; }
    std::pair<double, double> Support() const override {
        // exp(−k²/2) = 1e-6 at k = √(2 ln 1e6) ≈ 5.2565 standard deviations.
        const double k = std::sqrt(2 * std::log(1e6));
        return {std::max(0.0, center_ - k * sigma_), center_ + k * sigma_};
    }
    std::string ToString() const override {
        return "gaussian(center = " + spectra::Nm(center_) + ", fwhm = " + spectra::Nm(fwhm_) +
               ", peak = " + spectra::Num(peak_) + ")";
    }

  private:
    double center_, fwhm_, sigma_, peak_;
};

}  // namespace phasor
