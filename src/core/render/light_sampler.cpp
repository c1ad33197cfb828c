// SPDX-License-Identifier: Apache-2.0
// phasor — light selection for next-event estimation (light_sampler.h).
#include "core/render/light_sampler.h"

#include <algorithm>
#include <cmath>

#include "core/diagnostics.h"

namespace phasor {

ParamSpec LightSamplerParam() {
    return P::String("light_sampler",
                     "how next-event estimation picks a light: \"uniform\" (1/N each) or \"power\" (in "
                     "proportion to each light's power: fewer noisy samples on weak lights)")
        .Default(Value::String("uniform"))
        .Choices({"uniform", "power"});
}

LightSelection LightSelectionFromName(const std::string &name) {
    return name == "power" ? LightSelection::Power : LightSelection::Uniform;
}

const char *LightSelectionName(LightSelection s) { return s == LightSelection::Power ? "power" : "uniform"; }

double LightPower(const Light &light) {
    const Spectrum &s = light.EmissionSpectrum();
    double integral = 1;  // a line: its strength is the scale
    if (!s.LineWavelength()) {
        // ∫ S dλ over its support (midpoint rule, 2000 cells; spectra are smooth or tabulated).
        const auto [lo, hi] = s.Support();
        const double a = std::max(lo, 1e-9), b = std::min(hi, 1e-3);
        integral = 0;
        if (b > a) {
            constexpr int N = 2000;
            for (int i = 0; i < N; ++i) integral += s.Eval(a + (b - a) * (i + 0.5) / N);
            integral *= (b - a) / N;
        }
    }
    const double phi = light.PowerScale() * integral;
    return std::isfinite(phi) && phi > 0 ? phi : 0;
}

LightSampler::LightSampler(const std::vector<const Light *> &lights, LightSelection how) : how_(how), lights_(lights) {
    const std::size_t n = lights_.size();
    if (n == 0) return;
    std::vector<double> w(n, 1.0);
    if (how_ == LightSelection::Power) {
        double mean = 0;
        for (std::size_t i = 0; i < n; ++i) mean += (w[i] = LightPower(*lights_[i])) / double(n);
        if (mean > 0)
            for (double &x : w) x = std::max(x, 1e-3 * mean);
        else
            std::fill(w.begin(), w.end(), 1.0);
    }
    double total = 0;
    for (double x : w) total += x;
    pmf_.resize(n);
    cdf_.resize(n);
    double run = 0;
    for (std::size_t i = 0; i < n; ++i) {
        // Uniform: exactly 1/N (as light selection always was).
        pmf_[i] = how_ == LightSelection::Uniform ? 1.0 / double(n) : w[i] / total;
        run += pmf_[i];
        cdf_[i] = run;
        pmfOf_[lights_[i]] += pmf_[i];
    }
    cdf_.back() = 1;
}

const Light *LightSampler::Sample(double u, double *pmf) const {
    const std::size_t n = lights_.size();
    if (n == 0) {
        *pmf = 0;
        return nullptr;
    }
    std::size_t i;
    if (how_ == LightSelection::Uniform) {
        i = std::min(n - 1, std::size_t(u * double(n)));
    } else {
        i = std::size_t(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin());
        i = std::min(i, n - 1);  // every pmf is > 0 (the floor above): no empty cell to skip
    }
    *pmf = pmf_[i];
    return lights_[i];
}

double LightSampler::Pmf(const Light *light) const {
    if (how_ == LightSelection::Uniform) return lights_.empty() ? 0 : 1.0 / double(lights_.size());
    const auto it = pmfOf_.find(light);
    return it == pmfOf_.end() ? 0 : it->second;
}

}  // namespace phasor
