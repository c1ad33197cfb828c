// SPDX-License-Identifier: Apache-2.0
// phasor — the openings of an opaque planar plate (theory §9 "Geometry"), shared by the
// footprint-aware `aperture` kernel and the forward Rayleigh–Sommerfeld integrator `rs`.
//
// Plate coordinates: (u, v) in metres along the plate's local x and y axes, origin at the shape's
// local origin. The shape's to_world must be a rigid motion (rotation + translation, no scale, so
// that opening sizes are metres as written); `PlateFrame` maps plate coordinates to world space. The plate is opaque (t = 0) except inside
// the openings, where the transmission t(u, v) ∈ [0, 1] is piecewise constant. Openings must not
// overlap (the transmission of an overlap is the larger value; pieces would double-count it).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/math.h"

namespace phasor {

struct Bounds2 {
    Vec2 lo{Infinity, Infinity}, hi{-Infinity, -Infinity};
    bool Empty() const { return !(hi.x > lo.x && hi.y > lo.y); }
    void Extend(const Vec2 &p) {
        lo = Vec2(std::min(lo.x, p.x), std::min(lo.y, p.y));
        hi = Vec2(std::max(hi.x, p.x), std::max(hi.y, p.y));
    }
    Bounds2 Intersect(const Bounds2 &o) const {
        return {Vec2(std::max(lo.x, o.lo.x), std::max(lo.y, o.lo.y)),
                Vec2(std::min(hi.x, o.hi.x), std::min(hi.y, o.hi.y))};
    }
};

/// One piece of the openings ∩ a box: {(u, v): v ∈ [v0, v1], u ∈ [ULo(v), UHi(v)]} with constant
/// transmission t. The u-limits are linear in v (trapezoids: rectangles, polygon slabs, bitmap
/// runs) or, for discs, circle arcs clamped to the box (`circle`; then the limits have square-root
/// end points and a quadrature along v should use v = cv + r·sin φ).
struct MaskPiece {
    double v0 = 0, v1 = 0, t = 1;
    // Linear limits: u = a + b·v.
    double loA = 0, loB = 0, hiA = 0, hiB = 0;
    // Disc (circle = true): centre (cu, cv), radius r; limits clamped to [uMin, uMax].
    bool circle = false;
    double cu = 0, cv = 0, r = 0, uMin = -Infinity, uMax = Infinity;
    double ULo(double v) const;
    double UHi(double v) const;
};

/// A set of openings in plate coordinates.
class ApertureMask {
  public:
    /// Axis-aligned rectangle [lo, hi] with transmission t.
    void AddRect(const Vec2 &lo, const Vec2 &hi, double t = 1);
    /// Disc of centre c and radius r.
    void AddDisc(const Vec2 &c, double r, double t = 1);
    /// Simple polygon (either orientation, ≥ 3 vertices, not self-intersecting; checked).
    /// Throws phasor::Error if it is degenerate or self-intersecting.
    void AddPolygon(const std::vector<Vec2> &vertices, double t = 1);
    /// A bitmap read with OpenImageIO (first channel, or luminance of RGB), covering the rectangle
    /// [lo, hi] (image row 0 at v = hi.y); texel values are clamped to [0, 1] and quantised to
    /// `levels` steps so that runs of equal transmission merge. Throws phasor::Error (file name,
    /// OIIO's reason) if it cannot be read.
    void AddBitmap(const std::string &path, const Vec2 &lo, const Vec2 &hi, int levels = 256);

    /// t(u, v) ∈ [0, 1].
    double Transmission(const Vec2 &p) const;
    /// Bounding box of all openings (empty if there are none).
    Bounds2 Bounds() const { return bounds_; }
    /// Total open area weighted by t, ∫ t dA [m²].
    double OpenArea() const;
    /// Calls f for every piece of (openings ∩ box); pieces do not overlap.
    void ForEachPiece(const Bounds2 &box, const std::function<void(const MaskPiece &)> &f) const;
    /// True if every opening is an axis-aligned rectangle whose extent along v is at least
    /// `minLength` and which shares one v-range with all others (the 2-D mode of `rs`: slits
    /// treated as infinite along v). Fills [v0, v1] with that range.
    bool IsSlitsAlongV(double minLength, double *v0 = nullptr, double *v1 = nullptr) const;
    bool Empty() const { return bounds_.Empty(); }
    std::string ToString() const;

  private:
    struct Rect { Vec2 lo, hi; double t; };
    struct Disc { Vec2 c; double r, t; };
    struct Polygon { std::vector<Vec2> v; double t; Bounds2 b; };
    std::vector<Rect> rects_;  // rectangles and bitmap runs
    std::vector<Disc> discs_;
    std::vector<Polygon> polygons_;
    int userRects_ = 0;        // rectangles added by AddRect (the rest are bitmap runs)
    Bounds2 bounds_;
};

/// The plate's frame in world space: origin and orthonormal axes (e1 = local x, e2 = local y,
/// n = e1 × e2 = local +z).
struct PlateFrame {
    Vec3 origin, e1{1, 0, 0}, e2{0, 1, 0}, n{0, 0, 1};
    /// From an object-to-world transform; throws phasor::Error if it is not a rigid motion
    /// (scale, shear or mirror; tolerance 1e-9).
    static PlateFrame FromTransform(const Transform &toWorld);
    Vec2 ToPlate(const Vec3 &pWorld) const {
        const Vec3 d = pWorld - origin;
        return Vec2(Dot(d, e1), Dot(d, e2));
    }
    Vec3 ToWorld(const Vec2 &uv) const { return origin + e1 * uv.x + e2 * uv.y; }
};

class Material;

/// The facet of a kernel that is an opaque plate with openings (the `aperture` material): what
/// field-based integrators (`rs`) and the scene checks read of it, beside the kernel interface.
class PlateOpenings {
  public:
    /// The openings in plate coordinates.
    virtual const ApertureMask &Openings() const = 0;

  protected:
    ~PlateOpenings() = default;
};
/// m's openings (PlateOpenings), or nullptr for a kernel that is not a plate with openings.
const ApertureMask *OpeningsOf(const Material &m);

}  // namespace phasor
