// SPDX-License-Identifier: Apache-2.0
// phasor — how next-event estimation picks a light (integrator parameter `light_sampler`):
// uniformly, in proportion to each light's power (pbrt-v4's PowerLightSampler), or in proportion to
// each light's reach at the receiver (pbrt-v4's ExhaustiveLightSampler).
#pragma once

#include <string>
#include <unordered_map>
#include <vector>

#include "core/params/schema.h"
#include "core/render/light.h"

namespace phasor {

enum class LightSelection { Uniform, Power, Exhaustive };

/// The `light_sampler` parameter an integrator that samples lights declares (default "exhaustive").
ParamSpec LightSamplerParam();
/// Its value ("uniform", "power" or "exhaustive").
LightSelection LightSelectionFromName(const std::string &name);
const char *LightSelectionName(LightSelection s);

/// A discrete distribution over the scene's lights. Uniform: 1/N each. Power: ∝ the light's power
/// Φ = PowerScale × ∫ emission spectrum dλ (a line counts 1; Light::PowerScale is the strength
/// times the light's area, solid angle or the scene's cross-section for lights at infinity), the
/// lights of zero power keeping a share of 1e-3 of the mean so that none is unreachable.
/// Exhaustive: at each receiver ∝ Light::Reach(ctx) × ∫ emission spectrum dλ (the same floor), an
/// estimate of the light's irradiance there that is 0 only where the light sends nothing, so a lamp
/// behind the receiver or far away gets few samples; O(N) per choice. Where a light gives no
/// estimate (Reach NaN) that receiver falls back to power. All are unbiased: the probability is
/// the same function of the receiver in Sample and Pmf, which MIS at emission hits asks with the
/// vertex the path came from.
class LightSampler {
  public:
    LightSampler(const std::vector<const Light *> &lights, LightSelection how);
    /// The light u ∈ [0, 1) picks for a receiver at ctx and the probability of that pick; nullptr
    /// (pmf 0) without lights, or where no light reaches ctx (exhaustive).
    const Light *Sample(double u, const LightSampleContext &ctx, double *pmf) const;
    /// The probability that Sample picks `light` for a receiver at ctx (0 for a light it never picks).
    double Pmf(const Light *light, const LightSampleContext &ctx) const;
    LightSelection Selection() const { return how_; }

  private:
    /// Exhaustive: every light's weight at ctx into w and their sum into *total (false where some
    /// light gives no estimate or the sum overflows: then power).
    bool ReachWeights(const LightSampleContext &ctx, std::vector<double> &w, double *total) const;
    const Light *FromTable(double u, double *pmf) const;  // uniform or power

    LightSelection how_;
    std::vector<const Light *> lights_;
    std::vector<double> cdf_, pmf_;  // uniform or power (exhaustive: power, its fallback)
    std::unordered_map<const Light *, double> pmfOf_;
    std::vector<double> unit_;       // exhaustive: ∫ emission spectrum dλ per light, floored
};

/// The relative power of a light as LightSampler weighs it (see above) [W, up to a common factor].
double LightPower(const Light &light);

}  // namespace phasor
