// SPDX-License-Identifier: Apache-2.0
// phasor — the linear ramp shared by the `gradient` and `uv_ramp` textures.
//
// With c = axis·x, where x is (u, v, 0) or the world position p [m], t = clamp((c − start)/(end −
// start), 0, 1) and the value is value0 + t·(value1 − value0): value0 up to `start`, value1 from
// `end` on, linear between (values SI, of the texture's dimension).
#pragma once

#include <algorithm>

#include "core/math.h"
#include "core/render/texture.h"

namespace phasor {

struct LinearRamp {
    double value0 = 0, value1 = 1;
    bool world = false;       // x is the world position p [m] instead of (u, v, 0)
    Vec3 axis{1, 0, 0};       // the coordinate is c = axis·x (a unit vector)
    double start = 0, end = 1;  // in the coordinate's unit (plain for uv, m for world); start ≠ end

    double Eval(const TextureEvalContext &ctx) const {
        const Vec3 x = world ? ctx.p : Vec3(ctx.uv.x, ctx.uv.y, 0);
        const double t = Clamp((Dot(axis, x) - start) / (end - start), 0, 1);
        return value0 + t * (value1 - value0);
    }
    double MinValue() const { return std::min(value0, value1); }
    double MaxValue() const { return std::max(value0, value1); }
};

}  // namespace phasor
