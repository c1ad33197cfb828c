// SPDX-License-Identifier: Apache-2.0
// phasor — spherical rectangles (spherical_rectangle.h). Notation of Ureña et al. 2013, §3–4.
#include "core/geometry/spherical_rectangle.h"

#include <algorithm>
#include <cmath>

namespace phasor {

std::optional<SphericalRectangle> SphericalRectangle::From(const Vec3 &o, const Vec3 &corner, const Vec3 &ex,
                                                           const Vec3 &ey) {
    const double exl = Length(ex), eyl = Length(ey);
    if (!(exl > 0) || !(eyl > 0) || std::abs(Dot(ex, ey)) > 1e-9 * exl * eyl) return std::nullopt;
    SphericalRectangle r;
    r.o_ = o;
    r.x_ = ex / exl;
    r.y_ = ey / eyl;
    r.z_ = Cross(r.x_, r.y_);
    const Vec3 d = corner - o;
    r.x0_ = Dot(d, r.x_);
    r.y0_ = Dot(d, r.y_);
    r.z0_ = Dot(d, r.z_);
    if (r.z0_ > 0) {  // the frame's z points away from the rectangle's plane as seen from o
        r.z0_ = -r.z0_;
        r.z_ = -r.z_;
    }
    if (!(r.z0_ < 0)) return std::nullopt;  // o in the rectangle's plane
    r.x1_ = r.x0_ + exl;
    r.y1_ = r.y0_ + eyl;
    // The four vertex directions, the normals of the great circles through neighbouring ones, and
    // the interior angles γ_i at the vertices (eq. 3–4); Ω = Σγ − 2π.
    const Vec3 v00(r.x0_, r.y0_, r.z0_), v01(r.x0_, r.y1_, r.z0_), v10(r.x1_, r.y0_, r.z0_), v11(r.x1_, r.y1_, r.z0_);
    const Vec3 n0 = Normalize(Cross(v00, v10)), n1 = Normalize(Cross(v10, v11)), n2 = Normalize(Cross(v11, v01)),
               n3 = Normalize(Cross(v01, v00));
    auto angle = [](const Vec3 &a, const Vec3 &b) { return std::acos(std::clamp(-Dot(a, b), -1.0, 1.0)); };
    const double g0 = angle(n0, n1), g1 = angle(n1, n2), g2 = angle(n2, n3), g3 = angle(n3, n0);
    r.b0_ = n0.z;
    r.b1_ = n2.z;
    r.k_ = 2 * Pi - g2 - g3;
    r.solidAngle_ = g0 + g1 - r.k_;
    if (!(r.solidAngle_ >= MinSolidAngle && r.solidAngle_ <= MaxSolidAngle)) return std::nullopt;
    return r;
}

Vec3 SphericalRectangle::Sample(const Vec2 &u) const {
    // u.x: the sub-rectangle [x0, xu] that holds the fraction u.x of the solid angle (eq. 6–8).
    const double au = u.x * solidAngle_ + k_;
    const double fu = (std::cos(au) * b0_ - b1_) / std::sin(au);
    double cu = std::copysign(1.0, fu) / std::sqrt(fu * fu + b0_ * b0_);
    cu = std::clamp(cu, -1.0, 1.0);
    const double xu = std::clamp(-(cu * z0_) / SafeSqrt(1 - cu * cu), x0_, x1_);
    // u.y: uniform in the solid angle along the column x = xu, i.e. in h = y/√(x² + y² + z²) (eq. 9–10).
    const double dist = std::sqrt(xu * xu + z0_ * z0_);
    const double h0 = y0_ / std::sqrt(dist * dist + y0_ * y0_), h1 = y1_ / std::sqrt(dist * dist + y1_ * y1_);
    const double hv = h0 + u.y * (h1 - h0), hv2 = hv * hv;
    const double yv = hv2 < 1 - 1e-12 ? std::clamp(hv * dist / std::sqrt(1 - hv2), y0_, y1_) : y1_;
    return o_ + xu * x_ + yv * y_ + z0_ * z_;
}

}  // namespace phasor
