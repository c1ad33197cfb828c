// SPDX-License-Identifier: Apache-2.0
// Small spectra for the spectrum-module tests (the real plug-ins live in the `phasor` library,
// which these tests do not link).
#pragma once

#include <cmath>

#include "core/spectrum/spectrum.h"

namespace phasor::test {

/// A discrete emission line of integrated strength `power` at `lambda` [m].
class TestLine final : public Spectrum {
  public:
    TestLine(double lambda, double power) : lambda_(lambda), power_(power) {}
    double Eval(double l) const override { return l == lambda_ ? power_ : 0.0; }
    double MaxValue() const override { return power_; }
    std::pair<double, double> Support() const override { return {lambda_, lambda_}; }
    std::optional<double> LineWavelength() const override { return lambda_; }
    std::string ToString() const override { return "test line"; }

  private:
    double lambda_, power_;
};

/// peak · exp(−(λ − c)²/(2σ²)), support ±6σ.
class TestGaussian final : public Spectrum {
  public:
    TestGaussian(double center, double sigma, double peak) : c_(center), s_(sigma), p_(peak) {}
    double Eval(double l) const override {
        const double t = (l - c_) / s_;
        return std::abs(t) > 6 ? 0.0 : p_ * std::exp(-0.5 * t * t);
    }
    double MaxValue() const override { return p_; }
    std::pair<double, double> Support() const override { return {c_ - 6 * s_, c_ + 6 * s_}; }
    std::string ToString() const override { return "test gaussian"; }

  private:
    double c_, s_, p_;
};

/// Planck's law at T normalised to peak 1, cut to [λ_max/5, 60 λ_max] (below 1e-6 of the peak
/// outside).
class TestPlanck final : public Spectrum {
  public:
    explicit TestPlanck(double T) : T_(T), lMax_(2.897771955e-3 / T), peak_(Blackbody(lMax_, T)) {}
    double Eval(double l) const override {
        return (l < lMax_ / 5 || l > 60 * lMax_) ? 0.0 : Blackbody(l, T_) / peak_;
    }
    double MaxValue() const override { return 1; }
    std::pair<double, double> Support() const override { return {lMax_ / 5, 60 * lMax_}; }
    std::string ToString() const override { return "test planck"; }

  private:
    double T_, lMax_, peak_;
};

}  // namespace phasor::test
