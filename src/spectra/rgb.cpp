// SPDX-License-Identifier: Apache-2.0
// `rgb`: a linear RGB reflectance / albedo uplifted to a smooth spectrum bounded in [0, 1], by
// Smits' method (B. Smits, "An RGB-to-Spectrum Conversion for Reflectances", Journal of Graphics
// Tools 4(4), 1999): the colour is spent as white (the smallest component), then one secondary
// (cyan, magenta or yellow), then one primary, using his seven published basis spectra sampled in
// ten equal bins over 380–720 nm. We place each bin value at the bin centre and interpolate
// linearly between centres (holding the end values outside 397–703 nm, so a reflectance stays
// defined in the infrared and ultraviolet), then clamp to [0, 1] (the published bases slightly
// exceed 1 in places).
#include <algorithm>
#include <array>

#include "core/render/registry.h"
#include "spectra/common.h"
#include "core/spectrum/spectrum.h"

namespace phasor {

namespace {

constexpr int SmitsBins = 10;
constexpr double SmitsLo = 380e-9, SmitsHi = 720e-9;  // [m]
using Basis = std::array<double, SmitsBins>;
// Smits (1999): the published basis spectra (numbers from the paper), one row per colour.
enum SmitsColour { White, Cyan, Magenta, Yellow, Red, Green, Blue };
// clang-format off
constexpr Basis SmitsBasis[7] = {
    {1.0000, 1.0000, 0.9999, 0.9993, 0.9992, 0.9998, 1.0000, 1.0000, 1.0000, 1.0000},  // white
    {0.9710, 0.9426, 1.0007, 1.0007, 1.0007, 1.0007, 0.1564, 0.0000, 0.0000, 0.0000},  // cyan
    {1.0000, 1.0000, 0.9685, 0.2229, 0.0000, 0.0458, 0.8369, 1.0000, 1.0000, 0.9959},  // magenta
    {0.0001, 0.0000, 0.1088, 0.6651, 1.0000, 1.0000, 0.9996, 0.9586, 0.9685, 0.9840},  // yellow
    {0.1012, 0.0515, 0.0000, 0.0000, 0.0000, 0.0000, 0.8325, 1.0149, 1.0149, 1.0149},  // red
    {0.0000, 0.0000, 0.0273, 0.7937, 1.0000, 0.9418, 0.1719, 0.0000, 0.0000, 0.0025},  // green
    {1.0000, 1.0000, 0.8916, 0.3323, 0.0000, 0.0000, 0.0003, 0.0369, 0.0483, 0.0496},  // blue
};
// clang-format on

// Smits (1999): white × the smallest component, the secondary between the two larger ones ×
// (middle − smallest), the primary of the largest × (largest − middle).
Basis SmitsUplift(double r, double g, double b) {
    Basis out{};
    auto add = [&](SmitsColour c, double w) {
        for (int i = 0; i < SmitsBins; ++i) out[i] += w * SmitsBasis[c][i];
    };
    if (r <= g && r <= b) {
        add(White, r);
        if (g <= b) {
            add(Cyan, g - r);
            add(Blue, b - g);
        } else {
            add(Cyan, b - r);
            add(Green, g - b);
        }
    } else if (g <= r && g <= b) {
        add(White, g);
        if (r <= b) {
            add(Magenta, r - g);
            add(Blue, b - r);
        } else {
            add(Magenta, b - g);
            add(Red, r - b);
        }
    } else {
        add(White, b);
        if (r <= g) {
            add(Yellow, r - b);
            add(Green, g - r);
        } else {
            add(Yellow, g - b);
            add(Red, r - g);
        }
    }
    for (double &v : out) v = std::clamp(v, 0.0, 1.0);
    return out;
}

}  // namespace

class RgbSpectrum final : public Spectrum {
  public:
    explicit RgbSpectrum(const Vec3 &rgb) : rgb_(rgb), bins_(SmitsUplift(rgb.x, rgb.y, rgb.z)) {}

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

    double Eval(double lambda) const override {
        // Bin centres at SmitsLo + (i + ½)·Δ; linear between them, constant beyond the outer ones.
        const double delta = (SmitsHi - SmitsLo) / SmitsBins;
        const double t = (lambda - SmitsLo) / delta - 0.5;
        if (!(t > 0)) return bins_[0];
        if (t >= SmitsBins - 1) return bins_[SmitsBins - 1];
        const int i = int(t);
        const double f = t - i;
        return (1 - f) * bins_[i] + f * bins_[i + 1];
    }
    double MaxValue() const override { return *std::max_element(bins_.begin(), bins_.end()); }
    std::pair<double, double> Support() const override { return {0, Infinity}; }
    std::string ToString() const override {
        return "rgb([" + spectra::Num(rgb_.x) + " " + spectra::Num(rgb_.y) + " " + spectra::Num(rgb_.z) +
               "])";
    }

  private:
    Vec3 rgb_;
    Basis bins_;
};

PHASOR_EXPORT_PLUGIN(Spectrum, RgbSpectrum)

}  // namespace phasor
