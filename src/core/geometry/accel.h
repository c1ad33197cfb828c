// SPDX-License-Identifier: Apache-2.0
// phasor — the ray-query accelerator. Embree 3 is used for every ray query; this header does not
// include Embree, accel.cpp is the only translation unit that does.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "core/geometry/shape.h"

namespace phasor {

struct Hit {
    double t = 0;
    unsigned shapeIndex = 0;  // index into the shape list given to Build
    unsigned prim = 0;        // triangle index (meshes)
    double b1 = 0, b2 = 0;    // barycentrics of vertices 1 and 2 (meshes)
};

/// How a triangle hit's distance and barycentrics are reported (analytic shapes are always
/// double precision). Double: recomputed in double precision on the winning triangle — the path
/// length to ~1e-16 relative, which a phase k·ℓ needs (at 1 m and 500 nm Embree's float t is off by
/// ~0.1 µm, 1.3 rad); one more vertex fetch and ~40 flops per hit. Embree: Embree's float t and
/// barycentrics (relative error ~1e-7) — enough where no phase is carried (the classical `ray`
/// integrator), as the hit point is still interpolated from the vertices in double precision.
enum class HitPrecision { Double, Embree };

class Accel {
  public:
    /// The BVH over `shapes` (pointers must outlive the Accel): the one an earlier Accel built if
    /// its shapes had the same geometry keys in the same order (core/geometry/geometry_cache.h),
    /// else a new one. Throws phasor::Error if Embree cannot be initialised.
    explicit Accel(std::vector<const Shape *> shapes);
    ~Accel();
    Accel(const Accel &) = delete;
    Accel &operator=(const Accel &) = delete;

    /// Nearest hit with t in (tMin, tMax). Thread-safe.
    std::optional<Hit> Intersect(const Ray &ray, double tMin = 0, double tMax = Infinity,
                                 HitPrecision precision = HitPrecision::Double) const;
    /// True if anything is hit with t in (tMin, tMax). Thread-safe.
    bool Occluded(const Ray &ray, double tMin, double tMax) const;
    /// Calls f(shapeIndex, prim) for every primitive whose bounding box Embree finds within
    /// `radius` [m] of `center` (an rtcPointQuery ball query; analytic shapes count as one
    /// primitive, 0). Conservative: the caller tests the primitive itself. Thread-safe.
    void ForEachNear(const Vec3 &center, double radius,
                     const std::function<void(unsigned shapeIndex, unsigned prim)> &f) const;
    /// Intersect + Shape::Interaction.
    std::optional<SurfaceInteraction> IntersectSurface(const Ray &ray, double tMin = 0, double tMax = Infinity,
                                                       HitPrecision precision = HitPrecision::Double) const;
    Bounds3 Bounds() const { return bounds_; }
    const std::vector<const Shape *> &Shapes() const { return shapes_; }

    /// Raw Embree throughput probe for benchmarks: intersects `rays` with rtcIntersect1 and
    /// nothing else; returns the number of hits.
    std::size_t RawIntersectCount(const std::vector<Ray> &rays) const;

    /// BVHs built and shared by the process-wide cache (GetGeometryCacheStats reports them).
    struct CacheCounts {
        long long builds = 0, reuses = 0;
    };
    static CacheCounts BvhCacheCounts();
    static void ClearBvhCache();

    struct Bvh;  // the Embree device and scene (accel.cpp)

  private:
    std::shared_ptr<const Bvh> bvh_;
    std::vector<const Shape *> shapes_;
    Bounds3 bounds_;
};

}  // namespace phasor
