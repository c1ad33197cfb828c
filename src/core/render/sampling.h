// SPDX-License-Identifier: Apache-2.0
// phasor — warping uniform samples to shapes (shared by kernels, lights and detectors).
#pragma once

#include "core/math.h"

namespace phasor {

/// Shirley & Chiu (1997) concentric map of [0,1)² onto the unit disc: area-preserving, low
/// distortion.
inline Vec2 ConcentricDisc(const Vec2 &u) {
    const double ox = 2 * u.x - 1, oy = 2 * u.y - 1;
    if (ox == 0 && oy == 0) return {0, 0};
    double r, theta;
    if (std::abs(ox) > std::abs(oy)) {
        r = ox;
        theta = (Pi / 4) * (oy / ox);
    } else {
        r = oy;
        theta = Pi / 2 - (Pi / 4) * (ox / oy);
    }
    return {r * std::cos(theta), r * std::sin(theta)};
}

}  // namespace phasor
