// SPDX-License-Identifier: Apache-2.0
// The field of the forward Rayleigh–Sommerfeld integrator `rs` (rs/rs.cpp): the RS-I field behind
// one opaque plate with openings, lit by one coherent wave (theory §6.2), by Gauss–Legendre
// panels over the openings (rs/propagator.cpp, docs/rs.md §2). Exposed for the integrator's tests.
#pragma once

#include <memory>
#include <vector>

#include "core/render/aperture.h"
#include "core/render/coherent_source.h"
#include "core/math.h"

namespace phasor::rs {

struct NodeRule;

/// Tunables of the aperture quadrature (Gauss–Legendre panels, rs/propagator.cpp header).
struct QuadratureRule {
    /// Upper bound of the phase change over one panel [rad] (from |∇φ| bounds × panel length).
    double maxPanelPhase = 6 * Pi;
    /// Per-panel error target of the node-count rule (relative, for a linear phase).
    double tolerance = 1e-14;
    int minNodes = 6, maxNodes = 20;
    /// Panels are at most this fraction of the distance to the field point (and to a point
    /// source), so that the 1/R amplitudes are resolved in the near field.
    double maxPanelOverDistance = 0.5;
    /// c of the sensor grid's spacing h ≤ 2π/(kΔ + c/σ): the trapezoid rule's aliasing under the
    /// Gaussian pixel weight is then ≈ e^{−c²/2} of the local intensity.
    double gridMargin = 5;

    /// The rule for a target accuracy (largest pixel error relative to the row's peak) of the
    /// integrator's `accuracy` parameter: per-panel tolerance accuracy·1e-3 (panel integrals
    /// cancel: their magnitudes sum to ~10²× |U| on long slits) and e^{−c²/2} = accuracy/10.
    /// The defaults above (1e-14 per panel, c = 5) are the strict rule the unit tests use.
    static QuadratureRule ForAccuracy(double accuracy);
};

/// The field U [√(W/m²)] and its derivative along a unit vector m, ∂U/∂m = m·∇U [√(W/m²)/m].
struct FieldValue {
    Complex u, dudm;
};

/// RS-I propagation (theory §6.2) from the openings of one plate, with Kirchhoff boundary values
/// U₀ = t·U_inc, to points on the far side of the plate. U_inc is any coherent source's field at
/// one wavelength (core/render/coherent_source.h: |U_inc|² = irradiance normal to the local
/// direction of travel), read over the plate through its PlaneField. Phases are relative to a
/// per-point reference (only |U|², and U*·∂U, are meaningful).
class Propagator {
  public:
    /// The field of `source` at vacuum wavelength `lambda` [m].
    /// `flip`: the sensor lies on the −n side of `plate` (local z is then measured along −n).
    /// `twoD`: openings are slits infinite along the plate's v axis (e2) and the wave is a plane
    /// wave with no component along e2 — the 2-D form of theory §6.2 with H₁⁽¹⁾.
    /// Throws phasor::Error if the wave does not reach the plate from the other side.
    Propagator(const PlateFrame &plate, const ApertureMask &mask, const CoherentSource &source, double lambda,
               bool flip, bool twoD, QuadratureRule rule = {});

    /// U and ∂U/∂m at world point p (which must lie in front of the plate, on the sensor side).
    FieldValue Field(const Vec3 &p, const Vec3 &m) const;
    /// Power per unit area crossing a surface at p with front normal `front` from its front side,
    /// −Im(U*·∂U/∂front)/k [W/m²] (S = Im(U*∇U)/k).
    double Flux(const Vec3 &p, const Vec3 &front) const;
    /// |U(p)|² [W/m²].
    double Intensity(const Vec3 &p) const;

    /// An upper bound of the spread (max − min) of the component along unit `axis` of the unit
    /// directions from the openings' bounding box (in 2-D mode: the slits' u range, in the plane
    /// normal to the slits) to any point of the parallelogram corner + a·es + b·et, a, b ∈ [0, 1]
    /// (es = et = 0: one point), from interval bounds (never below the true spread). Times k it
    /// bounds the band of the intensity along `axis` there.
    double DirectionSpread(const Vec3 &corner, const Vec3 &es, const Vec3 &et, const Vec3 &axis) const;
    /// The openings' bounding box in plate coordinates [m].
    const Bounds2 &OpeningBounds() const { return bounds_; }
    /// Signed distance of p from the plate, positive on the sensor side [m].
    double Height(const Vec3 &p) const;

    double K() const { return k_; }
    const QuadratureRule &Rule() const { return rule_; }
    bool TwoD() const { return twoD_; }
    const PlateFrame &Plate() const { return plate_; }

    struct Local;  // a field point in plate coordinates (rs/propagator.cpp)

  private:
    void Field3D(const Local &p, double acc[4]) const;
    void Field2D(const Local &p, double acc[4]) const;

    PlateFrame plate_;
    double zSign_;
    bool twoD_;
    QuadratureRule rule_;
    std::shared_ptr<const NodeRule> nodes_;  // panel phase → Gauss–Legendre node count
    std::vector<MaskPiece> pieces_;
    Bounds2 bounds_;            // the openings' box within the incident field's support
    std::shared_ptr<const PlaneField> incident_;  // U_inc over the plate
    double panelLimit_ = Infinity;               // the incident amplitude's panel limit over bounds_
    double k_;
};

}  // namespace phasor::rs
