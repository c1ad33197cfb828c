// SPDX-License-Identifier: Apache-2.0
// phasor — light selection for next-event estimation (light_sampler.h).
#include "core/render/light_sampler.h"

#include <algorithm>
#include <cmath>

#include "core/diagnostics.h"

namespace phasor {

ParamSpec LightSamplerParam() {
    return P::String("light_sampler",
                     "how next-event estimation picks a light: \"exhaustive\" (in proportion to each light's "
                     "estimated irradiance at the receiver: lamps behind it or far away get few samples; "
                     "O(lights) per choice), \"power\" (in proportion to each light's power) or \"uniform\" "
                     "(1/N each)")
        .Default(Value::String("exhaustive"))
        .Choices({"exhaustive", "power", "uniform"});
}

LightSelection LightSelectionFromName(const std::string &name) {
    if (name == "power") return LightSelection::Power;
    return name == "uniform" ? LightSelection::Uniform : LightSelection::Exhaustive;
}

const char *LightSelectionName(LightSelection s) {
    return s == LightSelection::Power ? "power" : (s == LightSelection::Uniform ? "uniform" : "exhaustive");
}

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

namespace {
// Every weight at least 1e-3 of their mean, so that none is unreachable; all 1 if the mean is 0.
void FloorAtMean(std::vector<double> &w) {
    double mean = 0;
    for (double x : w) mean += x / double(w.size());
    for (double &x : w) x = mean > 0 ? std::max(x, 1e-3 * mean) : 1.0;
}
}  // namespace

LightSampler::LightSampler(const std::vector<const Light *> &lights, LightSelection how) : how_(how), lights_(lights) {
    const std::size_t n = lights_.size();
    if (n == 0) return;
    const bool uniform = how_ == LightSelection::Uniform;
    std::vector<double> w(n, 1.0);
    if (!uniform) {
        for (std::size_t i = 0; i < n; ++i) w[i] = LightPower(*lights_[i]);
        if (how_ == LightSelection::Exhaustive) {
            // ∫ S dλ per light (Φ / PowerScale), floored like the powers.
            unit_.resize(n);
            for (std::size_t i = 0; i < n; ++i) {
                const double scale = lights_[i]->PowerScale();
                unit_[i] = scale > 0 && std::isfinite(scale) ? w[i] / scale : 0.0;
            }
            FloorAtMean(unit_);
        }
        FloorAtMean(w);
    }
    double total = 0;
    for (double x : w) total += x;
    pmf_.resize(n);
    cdf_.resize(n);
    double run = 0;
    for (std::size_t i = 0; i < n; ++i) {
        // Uniform: exactly 1/N (as light selection always was).
        pmf_[i] = uniform ? 1.0 / double(n) : w[i] / total;
        run += pmf_[i];
        cdf_[i] = run;
        pmfOf_[lights_[i]] += pmf_[i];
    }
    cdf_.back() = 1;
}

bool LightSampler::ReachWeights(const LightSampleContext &ctx, std::vector<double> &w, double *total) const {
    w.resize(lights_.size());
    *total = 0;
    for (std::size_t i = 0; i < lights_.size(); ++i) {
        const double r = lights_[i]->Reach(ctx);
        if (!(r >= 0) || !std::isfinite(r)) return false;  // no estimate (NaN), or unusable
        w[i] = r * unit_[i];
        *total += w[i];
    }
    return std::isfinite(*total);  // (an overflowing sum: power instead)
}

const Light *LightSampler::FromTable(double u, double *pmf) const {
    const std::size_t n = lights_.size();
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

const Light *LightSampler::Sample(double u, const LightSampleContext &ctx, double *pmf) const {
    *pmf = 0;
    if (lights_.empty()) return nullptr;
    if (how_ != LightSelection::Exhaustive) return FromTable(u, pmf);
    thread_local std::vector<double> w;
    double total = 0;
    if (!ReachWeights(ctx, w, &total)) return FromTable(u, pmf);
    if (!(total > 0)) return nullptr;  // no light reaches ctx
    // The first light whose running sum exceeds u·total (never one of weight 0).
    const double target = u * total;
    double run = 0;
    std::size_t pick = lights_.size();
    for (std::size_t i = 0; i < w.size(); ++i) {
        if (!(w[i] > 0)) continue;
        pick = i;
        run += w[i];
        if (target < run) break;
    }
    *pmf = w[pick] / total;
    return lights_[pick];
}

double LightSampler::Pmf(const Light *light, const LightSampleContext &ctx) const {
    if (lights_.empty()) return 0;
    if (how_ == LightSelection::Uniform) return 1.0 / double(lights_.size());
    if (how_ == LightSelection::Exhaustive) {
        thread_local std::vector<double> w;
        double total = 0;
        if (ReachWeights(ctx, w, &total)) {
            double mine = 0;
            for (std::size_t i = 0; i < w.size(); ++i)
                if (lights_[i] == light) mine += w[i];
            return total > 0 ? mine / total : 0.0;
        }
    }
    const auto it = pmfOf_.find(light);
    return it == pmfOf_.end() ? 0 : it->second;
}

}  // namespace phasor
