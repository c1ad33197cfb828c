// SPDX-License-Identifier: Apache-2.0
// phasor — analytic shapes (sphere, disk), intersected in double precision. The shape plug-ins
// in src/shapes/ wrap these with a schema; the accelerator hands them to Embree as user
// geometry.
#pragma once

#include <cmath>
#include <optional>
#include <string>

#include "core/geometry/shape.h"

namespace phasor {

/// A sphere of radius `radius` [m] around `center` [m]. `rotation` orients the (u, v) =
/// (φ/2π, θ/π) parameterisation: local z is the polar axis. Outward normal.
class AnalyticSphere : public Shape {
  public:
    /// Throws phasor::Error if radius is not positive and finite or `rotation` is not a rotation.
    AnalyticSphere(const Vec3 &center, double radius, const Transform &rotation = Transform());
    /// A sphere built from a local sphere (center, radius) mapped by `toWorld`, which must be a
    /// similarity (rotation, uniform scale, translation); throws phasor::Error otherwise.
    static AnalyticSphere FromTransform(const Vec3 &center, double radius, const Transform &toWorld);

    std::optional<double> Intersect(const Ray &ray, double tMin, double tMax) const override;
    SurfaceInteraction Interaction(const Ray &ray, double t, unsigned prim, double b1,
                                   double b2) const override;
    Bounds3 Bounds() const override;
    double Area() const override;
    ShapeSample Sample(const Vec2 &u) const override;  // uniform by area
    std::string ToString() const override;

    const Vec3 &Center() const { return center_; }
    double Radius() const { return radius_; }

  private:
    Vec3 center_;
    double radius_;
    Transform rotation_;  // local (parameterisation) → world orientation
};

/// The disk x² + y² ≤ radius² in the local z = 0 plane, mapped to world space by an affine
/// `toWorld` (a non-uniform scale makes it an ellipse). Outward normal = +z mapped as a normal.
/// (u, v) = (φ/2π, ρ/radius).
class AnalyticDisk : public Shape {
  public:
    /// Throws phasor::Error if radius is not positive and finite or toWorld is singular.
    AnalyticDisk(double radius, const Transform &toWorld);

    std::optional<double> Intersect(const Ray &ray, double tMin, double tMax) const override;
    SurfaceInteraction Interaction(const Ray &ray, double t, unsigned prim, double b1,
                                   double b2) const override;
    Bounds3 Bounds() const override;
    double Area() const override { return area_; }
    ShapeSample Sample(const Vec2 &u) const override;  // uniform by area
    std::string ToString() const override;

    double Radius() const { return radius_; }
    /// The point of the rim at angle φ [rad] (world space).
    Vec3 RimPoint(double phi) const { return toWorld_.Point(Vec3(radius_ * std::cos(phi), radius_ * std::sin(phi), 0)); }
    const Vec3 &Normal() const { return normal_; }
    Vec3 Center() const { return toWorld_.Point(Vec3(0, 0, 0)); }

  private:
    double radius_;
    Transform toWorld_, toLocal_;
    Vec3 normal_;  // unit world normal
    double area_;
};

}  // namespace phasor
