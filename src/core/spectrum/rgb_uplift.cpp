// SPDX-License-Identifier: Apache-2.0
// phasor — Smits' RGB → spectrum uplift (rgb_uplift.h).
#include "core/spectrum/rgb_uplift.h"

#include <algorithm>

namespace phasor {

namespace {

constexpr double SmitsLo = 380e-9, SmitsHi = 720e-9;  // [m]
using Basis = std::array<double, SmitsSpectrum::Bins>;
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
Basis Uplift(double r, double g, double b) {
    Basis out{};
    auto add = [&](SmitsColour c, double w) {
        for (int i = 0; i < SmitsSpectrum::Bins; ++i) out[i] += w * SmitsBasis[c][i];
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

SmitsSpectrum::SmitsSpectrum(const Vec3 &rgb) : bins_(Uplift(rgb.x, rgb.y, rgb.z)) {}

double SmitsSpectrum::Eval(double lambda) const {
    // Bin centres at SmitsLo + (i + ½)·Δ; linear between them, constant beyond the outer ones.
    const double delta = (SmitsHi - SmitsLo) / Bins;
    const double t = (lambda - SmitsLo) / delta - 0.5;
    if (!(t > 0)) return bins_[0];
    if (t >= Bins - 1) return bins_[Bins - 1];
    const int i = int(t);
    const double f = t - i;
    return (1 - f) * bins_[i] + f * bins_[i + 1];
}

double SmitsSpectrum::MaxValue() const { return *std::max_element(bins_.begin(), bins_.end()); }

double SmitsSpectrum::UpperBound(double maxComponent) {
    double basisMax = 0;
    for (const Basis &b : SmitsBasis) basisMax = std::max(basisMax, *std::max_element(b.begin(), b.end()));
    return std::min(1.0, std::max(0.0, maxComponent) * basisMax);
}

}  // namespace phasor
