// SPDX-License-Identifier: Apache-2.0
// phasor — a rectangle as seen from a point: its solid angle and directions uniform over it
// (Ureña, Fajardo & King 2013, "An Area-Preserving Parametrization for Spherical Rectangles").
// What an area light on a `rectangle` samples for next-event estimation (lights/area.cpp): the
// density 1/Ω instead of area sampling's r²/(A·cos θ), which swings by orders of magnitude over a
// large panel close to the point lit.
#pragma once

#include <optional>

#include "core/math.h"

namespace phasor {

class SphericalRectangle {
  public:
    /// The rectangle corner + a·ex + b·ey (a, b ∈ [0, 1]; ex ⟂ ey) [m, world] seen from `o`; nullopt
    /// where uniform solid-angle sampling is not used: edges not orthogonal (a sheared rectangle), or
    /// a solid angle outside [MinSolidAngle, MaxSolidAngle] — below it the parametrisation loses its
    /// digits (a far or grazing panel, where area sampling is as good), above it `o` is on the panel.
    static std::optional<SphericalRectangle> From(const Vec3 &o, const Vec3 &corner, const Vec3 &ex, const Vec3 &ey);
    static constexpr double MinSolidAngle = 3e-4, MaxSolidAngle = 6.22;  // [sr]

    /// The solid angle the rectangle subtends at o [sr].
    double SolidAngle() const { return solidAngle_; }
    /// The point of the rectangle [m, world] whose direction from o is uniform over the solid angle
    /// for u uniform in [0, 1)².
    Vec3 Sample(const Vec2 &u) const;

  private:
    Vec3 o_, x_, y_, z_;           // origin; the local frame (x ∥ ex, y ∥ ey, z towards the rectangle's far side)
    double x0_, x1_, y0_, y1_, z0_;  // the rectangle in that frame: [x0, x1] × [y0, y1] at z = z0 < 0
    double b0_, b1_, k_, solidAngle_;
};

}  // namespace phasor
