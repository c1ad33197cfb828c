// SPDX-License-Identifier: Apache-2.0
// phasor — double-precision ray–primitive intersection helpers shared by the mesh shapes, the
// accelerator (which recomputes Embree's float hits in double) and the tests.
#pragma once

#include <optional>

#include "core/math.h"
#include "core/geometry/shape.h"

namespace phasor {

/// Ray parameter and barycentrics (of vertices 1 and 2) where a ray meets a triangle's plane.
struct TriangleHit {
    double t = 0, b1 = 0, b2 = 0;
};

/// Intersection of the ray with the *plane* of triangle (p0, p1, p2), without testing whether
/// the point lies inside the triangle; nullopt only if the ray is parallel to the plane or the
/// triangle is degenerate. Möller & Trumbore, "Fast, minimum storage ray-triangle
/// intersection" (JGT 1997), evaluated in double precision.
inline std::optional<TriangleHit> RayTrianglePlane(const Ray &ray, const Vec3 &p0, const Vec3 &p1,
                                                   const Vec3 &p2) {
    Vec3 e1 = p1 - p0, e2 = p2 - p0;
    Vec3 pv = Cross(ray.d, e2);
    double det = Dot(e1, pv);
    if (det == 0 || !std::isfinite(det)) return std::nullopt;
    double inv = 1.0 / det;
    Vec3 tv = ray.o - p0;
    Vec3 qv = Cross(tv, e1);
    return TriangleHit{Dot(e2, qv) * inv, Dot(tv, pv) * inv, Dot(ray.d, qv) * inv};
}

/// Ray–triangle intersection with t in (tMin, tMax), double precision (Möller–Trumbore).
inline std::optional<TriangleHit> RayTriangle(const Ray &ray, const Vec3 &p0, const Vec3 &p1, const Vec3 &p2,
                                              double tMin, double tMax) {
    auto h = RayTrianglePlane(ray, p0, p1, p2);
    if (!h || h->b1 < 0 || h->b2 < 0 || h->b1 + h->b2 > 1) return std::nullopt;
    if (!(h->t > tMin && h->t < tMax)) return std::nullopt;
    return h;
}

}  // namespace phasor
