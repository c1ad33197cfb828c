// SPDX-License-Identifier: Apache-2.0
// `blackbody`: Planck's law at a temperature (Blackbody() in spectrum.h). With normalize = true
// (the default) the spectrum is scaled to 1 at its peak λ_max = b/T (Wien's displacement law,
// b = 2.897771955e-3 m·K), so the light's own scale sets the power; with normalize = false it is the
// absolute spectral radiance in W/(m²·sr·m).
#include <cmath>

#include "core/render/registry.h"
#include "spectra/common.h"
#include "core/spectrum/spectrum.h"

namespace phasor {

namespace {

// In x = hc/(λkT) Planck's law is ∝ x⁵/(eˣ − 1), which peaks at x_p = 4.965114231744276
// (the root of (x − 5)eˣ + 5 = 0; Wien's displacement law). XRatio(x) is the value relative to the
// peak.
constexpr double WienX = 4.965114231744276;
double XRatio(double x) { return std::pow(x / WienX, 5) * std::expm1(WienX) / std::expm1(x); }

// The x < x_p (long wavelength) or x > x_p (short wavelength) root of XRatio(x) = r, by bisection.
double XAtRatio(double r, bool longSide) {
    double lo = longSide ? 1e-12 : WienX, hi = longSide ? WienX : 200.0;
    for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        const bool above = XRatio(mid) > r;
        // XRatio rises with x below x_p and falls above it.
        if (longSide == above)
            hi = mid;
        else
            lo = mid;
    }
    return 0.5 * (lo + hi);
}

}  // namespace

class BlackbodySpectrum final : public Spectrum {
  public:
    BlackbodySpectrum(double T, bool normalize) : T_(T), normalize_(normalize) {
        lambdaPeak_ = WienB / T;
        peak_ = Blackbody(lambdaPeak_, T);
        // Support: where B ≥ 1e-6 of its peak (spectrum.h). λ = λ_max · x_p / x.
        static const double xShort = XAtRatio(1e-6, false), xLong = XAtRatio(1e-6, true);
        support_ = {lambdaPeak_ * WienX / xShort, lambdaPeak_ * WienX / xLong};
    }

    static const Schema &GetSchema() {
        static const Schema s{
            "spectrum",
            "blackbody",
            "Black-body emitter (Planck's law); normalised to 1 at its peak unless normalize = false.",
            {P::Number("temperature", "temperature", Dim::Temperature()).Required().Min(0, true),
             P::Bool("normalize", "scale to a peak value of 1 (else absolute radiance in W/(m²·sr·m))")
                 .Default(Value::Bool(true))}};
        return s;
    }
    static std::unique_ptr<Spectrum> Create(const ParamDict &d, BuildContext &) {
        return std::make_unique<BlackbodySpectrum>(d.GetNumber("temperature"), d.GetBool("normalize"));
    }
    static std::vector<ParamDict> TestPresets() {
        return {ParamDict().Set("temperature", Value::Number(5800, Dim::Temperature())),
                ParamDict()
                    .Set("temperature", Value::Number(3200, Dim::Temperature()))
                    .Set("normalize", Value::Bool(false))};
    }

    double Eval(double lambda) const override {
        const double b = Blackbody(lambda, T_);
        return normalize_ ? b / peak_ : b;
    }
    double MaxValue() const override { return normalize_ ? 1.0 : peak_; }
    std::pair<double, double> Support() const override { return support_; }
    std::string ToString() const override {
        return "blackbody(" + spectra::Num(T_) + " K, normalize = " + (normalize_ ? "true" : "false") + ")";
    }

  private:
    static constexpr double WienB = 2.897771955e-3;  // Wien's displacement constant [m·K]
    double T_;
    bool normalize_;
    double lambdaPeak_ = 0, peak_ = 1;
    std::pair<double, double> support_;
};

PHASOR_EXPORT_PLUGIN(Spectrum, BlackbodySpectrum)

}  // namespace phasor
