// SPDX-License-Identifier: Apache-2.0
// phasor — the field of a coherent light (theory §6.2): what integrators that propagate fields
// (`rs`) ask of a source. A light that implements CoherentSource and returns it from
// Light::Coherent() is propagated by `rs` without any change outside its own file
// (tests/lights/toy_focus_test.cpp proves it with a converging wave).
//
// Amplitude convention: |U(x, λ)|² is the spectral irradiance normal to the local direction of
// travel [W/m²/m]; for a line spectrum (theory §0 D10) the line's irradiance [W/m²]. Phases are
// relative to a reference the source picks (only differences across a surface are meaningful).
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "core/math.h"
#include "core/render/aperture.h"

namespace phasor {

/// A bound of the derivative of a phase along one axis over a region: it lies in
/// k·[lo, hi] ± slack, with k = 2π/λ (so lo, hi are direction cosines for a wave whose phase is
/// k times a path length) and slack [rad/m] what does not scale with k (a beam's Gouy phase).
struct PhaseSlope {
    double lo = 0, hi = 0;
    double slack = 0;
};

/// A source's field over one plane at one wavelength, in the plane's coordinates (u, v) [m] along
/// its axes e1, e2 (PlateFrame): what a quadrature over the plane needs (`rs`'s Kirchhoff boundary
/// values on an aperture plate, rs/propagator.cpp).
class PlaneField {
  public:
    virtual ~PlaneField() = default;
    /// |U| and the phase of U [rad] at plane point (u, v). The phase is relative to a reference
    /// the source picks for this plane, kept small near the plane's origin (double precision).
    virtual void At(double u, double v, double *amplitude, double *phase) const = 0;
    /// Where the phase's derivative along `axis` (0: u, 1: v) lies anywhere in `box` (never an
    /// underestimate: a quadrature sizes its panels by it).
    virtual PhaseSlope Slope(int axis, const Bounds2 &box) const = 0;
    /// The longest panel [m] over which a Gauss–Legendre rule resolves |U| anywhere in `box` (a
    /// spherical wave: half its distance to the plane; a beam: its width); Infinity if |U| is
    /// constant.
    virtual double PanelLimit(const Bounds2 &box) const {
        (void)box;
        return Infinity;
    }
    /// The part of the plane outside which |U| is negligible (below e^{−32} of its peak: a beam's
    /// footprint); the whole plane by default.
    virtual Bounds2 Support() const { return Bounds2{Vec2(-Infinity, -Infinity), Vec2(Infinity, Infinity)}; }
};

/// A coherent source's field (Light::Coherent()).
class CoherentSource {
  public:
    virtual ~CoherentSource() = default;
    /// U(x, λ) at world point x for vacuum wavelength λ [m] (amplitude convention above).
    virtual Complex Field(const Vec3 &x, double lambda) const = 0;
    /// The unit direction in which the light of wavelength λ travels at x (the direction of U's
    /// phase gradient).
    virtual Vec3 Travel(const Vec3 &x, double lambda) const = 0;
    /// The field at λ over `plane`. Throws phasor::Error if the source cannot light the plane
    /// (a beam running parallel to it).
    virtual std::unique_ptr<PlaneField> OnPlane(const PlateFrame &plane, double lambda) const = 0;
    /// A plane wave's direction of travel (U = A·e^{ik d·x}, A constant), for integrators that
    /// reduce slits to a 2-D problem (`rs`'s 2-D mode); nullopt for every other field.
    virtual std::optional<Vec3> PlaneWaveDirection() const { return std::nullopt; }
};

// ---- Interval bounds for PlaneField::Slope ---------------------------------------------------------

/// Range of a/√(a² + p²) over a ∈ [aLo, aHi], p ∈ [pLo, pHi] (p ≥ 0): increasing in a, and |·|
/// decreasing in p. The direction cosine along an axis of the line from a point to a box.
inline void CosineRange(double aLo, double aHi, double pLo, double pHi, double *lo, double *hi) {
    const double pa = aHi > 0 ? pLo : pHi, pb = aLo < 0 ? pLo : pHi;
    *hi = aHi / std::sqrt(aHi * aHi + pa * pa);
    *lo = aLo / std::sqrt(aLo * aLo + pb * pb);
}

/// Distance range from y to the points of [a, b].
inline void DistanceRange(double y, double a, double b, double *lo, double *hi) {
    *lo = y < a ? a - y : (y > b ? y - b : 0.0);
    *hi = std::max(std::abs(y - a), std::abs(y - b));
}

/// The range of ∂ρ/∂a = (a − s_a)/ρ over a box of a plane, ρ the distance from a point at plane
/// coordinates `s` and distance `dist` > 0 from the plane: a spherical wave's phase slope along
/// `axis` (0: u, 1: v) in units of k (diverging from the point; a wave converging on it has the
/// negated range).
inline PhaseSlope SphericalSlope(int axis, const Bounds2 &box, const Vec2 &s, double dist) {
    const double a0 = axis == 0 ? box.lo.x : box.lo.y, a1 = axis == 0 ? box.hi.x : box.hi.y;
    const double b0 = axis == 0 ? box.lo.y : box.lo.x, b1 = axis == 0 ? box.hi.y : box.hi.x;
    const double sa = axis == 0 ? s.x : s.y, sb = axis == 0 ? s.y : s.x;
    double qLo, qHi, lo, hi;
    DistanceRange(sb, b0, b1, &qLo, &qHi);
    CosineRange(a0 - sa, a1 - sa, std::sqrt(qLo * qLo + dist * dist), std::sqrt(qHi * qHi + dist * dist), &lo, &hi);
    return {lo, hi, 0};
}

}  // namespace phasor
