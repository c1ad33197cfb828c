// SPDX-License-Identifier: Apache-2.0
// phasor — how next-event estimation picks a light (integrator parameter `light_sampler`):
// uniformly, or in proportion to each light's power (pbrt-v4's PowerLightSampler).
#pragma once

#include <string>
#include <unordered_map>
#include <vector>

#include "core/params/schema.h"
#include "core/render/light.h"

namespace phasor {

enum class LightSelection { Uniform, Power };

/// The `light_sampler` parameter an integrator that samples lights declares (default "uniform").
ParamSpec LightSamplerParam();
/// Its value ("uniform" or "power").
LightSelection LightSelectionFromName(const std::string &name);
const char *LightSelectionName(LightSelection s);

/// A discrete distribution over the scene's lights. Uniform: 1/N each. Power: ∝ the light's power
/// Φ = PowerScale × ∫ emission spectrum dλ (a line counts 1; Light::PowerScale is the strength
/// times the light's area, solid angle or the scene's cross-section for lights at infinity), the
/// lights of zero power keeping a share of 1e-3 of the mean so that none is unreachable. Either
/// is unbiased; power puts the samples where the light is when strengths differ by orders.
class LightSampler {
  public:
    LightSampler(const std::vector<const Light *> &lights, LightSelection how);
    /// The light u ∈ [0, 1) picks and the probability of that pick; nullptr without lights.
    const Light *Sample(double u, double *pmf) const;
    /// The probability that Sample picks `light` (0 for a light it never picks).
    double Pmf(const Light *light) const;
    LightSelection Selection() const { return how_; }

  private:
    LightSelection how_;
    std::vector<const Light *> lights_;
    std::vector<double> cdf_, pmf_;
    std::unordered_map<const Light *, double> pmfOf_;
};

/// The relative power of a light as LightSampler weighs it (see above) [W, up to a common factor].
double LightPower(const Light &light);

}  // namespace phasor
