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

class Accel {
  public:
    /// Builds the BVH over `shapes` (pointers must outlive the Accel). Throws phasor::Error if
    /// Embree cannot be initialised.
    explicit Accel(std::vector<const Shape *> shapes);
    ~Accel();
    Accel(const Accel &) = delete;
    Accel &operator=(const Accel &) = delete;

    /// Nearest hit with t in (tMin, tMax). Thread-safe.
    std::optional<Hit> Intersect(const Ray &ray, double tMin = 0, double tMax = Infinity) const;
    /// True if anything is hit with t in (tMin, tMax). Thread-safe.
    bool Occluded(const Ray &ray, double tMin, double tMax) const;
    /// Calls f(shapeIndex, prim) for every primitive whose bounding box Embree finds within
    /// `radius` [m] of `center` (an rtcPointQuery ball query; analytic shapes count as one
    /// primitive, 0). Conservative: the caller tests the primitive itself. Thread-safe.
    void ForEachNear(const Vec3 &center, double radius,
                     const std::function<void(unsigned shapeIndex, unsigned prim)> &f) const;
    /// Intersect + Shape::Interaction.
    std::optional<SurfaceInteraction> IntersectSurface(const Ray &ray, double tMin = 0,
                                                       double tMax = Infinity) const;
    Bounds3 Bounds() const { return bounds_; }
    const std::vector<const Shape *> &Shapes() const { return shapes_; }

    /// Raw Embree throughput probe for benchmarks: intersects `rays` with rtcIntersect1 and
    /// nothing else; returns the number of hits.
    std::size_t RawIntersectCount(const std::vector<Ray> &rays) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    std::vector<const Shape *> shapes_;
    Bounds3 bounds_;
};

}  // namespace phasor
