// SPDX-License-Identifier: Apache-2.0
// The numerical core of the forward Rayleigh–Sommerfeld integrator `rs` (rs.cpp): the RS-I field
// behind one opaque plate with openings, lit by one coherent wave, and its integral over the
// pixels of a sensor plane. Exposed for the integrator's tests; the quadrature rules are
// documented in rs.cpp and docs/rs.md.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <vector>

#include "core/aperture.h"
#include "core/detector.h"
#include "core/light.h"
#include "core/math.h"

namespace phasor::rs {

struct NodeRule;

/// Tunables of the aperture quadrature (Gauss–Legendre panels, rs.cpp header).
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
/// U₀ = t·U_inc, to points on the far side of the plate. Amplitude convention: |U_inc|² =
/// irradiance normal to the local direction of travel (CoherentWave). Phases are relative to a
/// per-point reference (only |U|², and U*·∂U, are meaningful).
class Propagator {
  public:
    /// `flip`: the sensor lies on the −n side of `plate` (local z is then measured along −n).
    /// `twoD`: openings are slits infinite along the plate's v axis (e2) and the wave is a plane
    /// wave with no component along e2 — the 2-D form of theory §6.2 with H₁⁽¹⁾.
    /// Throws phasor::Error if the wave does not reach the plate from the other side.
    Propagator(const PlateFrame &plate, const ApertureMask &mask, const CoherentWave &wave, bool flip,
               bool twoD, QuadratureRule rule = {});

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

    struct Local;  // a field point in plate coordinates (rs.cpp)

  private:
    void Field3D(const Local &p, double acc[4]) const;
    void Field2D(const Local &p, double acc[4]) const;

    PlateFrame plate_;
    double zSign_;
    bool twoD_;
    QuadratureRule rule_;
    std::shared_ptr<const NodeRule> nodes_;  // panel phase → Gauss–Legendre node count
    std::vector<MaskPiece> pieces_;
    Bounds2 bounds_;
    /// Gaussian beams: an upper bound, over the plate box [ua, ub] × [va, vb], of how far the
    /// beam's phase gradient along either plate axis departs from k times its axis' component
    /// (curvature, the change of curvature along the axis and the Gouy phase) [rad/m].
    double BeamSlopeBound(double ua, double ub, double va, double vb) const;

    // Incident wave in plate coordinates (local z towards the sensor).
    bool spherical_;
    bool beam_ = false;                 // a Gaussian beam (du_, dv_: its axis on e1, e2)
    GaussianBeamGeometry beamGeo_;
    double beamZRef_ = 0;               // axial position of the plate origin (phase reference)
    double beamPanel_ = Infinity;       // panel length limit: the beam's smallest β on the openings
    double k_, amp_;
    double du_ = 0, dv_ = 0;           // plane: direction cosines along e1, e2
    double su_ = 0, sv_ = 0, sz_ = 0;  // spherical: source at (su, sv), distance sz > 0 behind
};

enum class Quantity { Flux, Intensity };

/// The uniform grid on which the field is evaluated (rs.cpp header, "sensor quadrature"): nodes
/// xs × ys in sensor-plane coordinates; a collapsed axis has one node of weight 1 (2-D mode,
/// the field is constant along it).
struct SensorGrid {
    std::vector<double> xs, ys;
    double hx = 0, hy = 0;
    bool collapseX = false, collapseY = false;
    std::size_t Nodes() const { return xs.size() * ys.size(); }
};

/// Chooses the grid for `sensor` and the field of `prop`. In 2-D mode the axis along the slits
/// is collapsed (it must be parallel to the plate's e2; checked by the caller).
SensorGrid MakeGrid(const SensorPlaneGeometry &sensor, const Propagator &prop);

/// Pixel values, row-major (j·nx + i), of the quantity integrated against each pixel's
/// sensitivity [W/m²] (not divided by the reference irradiance). The grid nodes are evaluated in
/// ProgressUnits(grid) equal batches; `batchDone(batches)` is called from the calling thread after
/// every batch with the number done so far; returning false cancels. `cancel`, when set, is also
/// checked before every node, so a stop request ends the current batch early. A cancelled call
/// returns an empty vector. Parallel over grid nodes (TBB), deterministic.
std::vector<double> IntegrateSensor(const SensorPlaneGeometry &sensor, const Propagator &prop,
                                    const SensorGrid &grid, Quantity q,
                                    const std::function<bool(int)> &batchDone = {},
                                    const std::atomic<bool> *cancel = nullptr);
/// Number of progress units (batches of at least 64 grid nodes, at most 1000 batches) that
/// IntegrateSensor reports for `grid`.
int ProgressUnits(const SensorGrid &grid);

/// The factor by which a slit's finite length [v0, v1] (plate y axis) multiplies the field of the
/// infinite slit at plate height y and in-plane distance r [m] (Fresnel approximation along the
/// slit, where the 3-D field factorises): G = ½[erf(a·s₁) − erf(a·s₀)], s_j = √(k/(πr))·(v_j − y),
/// a = (√π/2)(1 − i) — the Fresnel integrals C + iS. G → 1 for an infinite slit.
Complex SlitLengthFactor(double y, double v0, double v1, double k, double r);
/// Predicted error of the 2-D mode for slits spanning `slits` (plate coordinates: u range × the
/// common v range) seen by `sensor`, one of whose axes is parallel to the slits: the largest
/// |∫ w(y − y_p)·(|G(y)|² − 1) dy| over the pixel rows along the slits (w = the pixel's
/// sensitivity along them), at the smallest and largest in-plane distance between the slits and
/// the window — relative to the local 2-D intensity, hence ≥ the error relative to the peak.
double SlitEndError(const PlateFrame &plate, const Bounds2 &slits, const SensorPlaneGeometry &sensor, double k);

/// H₀⁽¹⁾(x) and H₁⁽¹⁾(x) for x > 0 (asymptotic series for x ≥ 25, std::cyl_bessel_j /
/// cyl_neumann below).
void Hankel01(double x, Complex *h0, Complex *h1);

}  // namespace phasor::rs
