// SPDX-License-Identifier: Apache-2.0
// phasor — the footprint integral of the `aperture` kernel (theory §9, docs/aperture.md).
//
// A generalized ray (GR) meets a planar mask. Its traced wave function on the plate (the oblique
// cut of theory §6.3 step 3), the mask transmission t and an incident plane or spherical wave
// combine into one Gaussian integrand in plate coordinates (x, y) relative to the hit point:
//
//     A = C · ∫∫ t(x, y) · exp(−(axx x² + 2 axy x y + ayy y²) + i (bx x + by y)) dx dy,
//
// restricted to the locality window |x| ≤ hx, |y| ≤ hy (theory §0 D13). Re[[axx, axy], [axy, ayy]]
// is positive definite. Over each mask piece (core/render/aperture.h: a trapezoid with linear limits or a
// clipped disc) one axis is integrated in closed form with the Faddeeva function w and the other
// with Gauss–Legendre quadrature whose order follows from the integrand's variation over the
// interval (see IntegratePiece). docs/aperture.md describes the whole chain.
#pragma once

#include "core/render/aperture.h"
#include "core/render/genray.h"
#include "core/math.h"

namespace phasor {

/// ∫_{x0}^{x1} exp(−αx² + βx) dx for Re α > 0, in a closed form that neither overflows nor
/// cancels: with m = β/(2α), z(x) = √α(x − m) and E(x) = exp(−αx² + βx), the antiderivative is
/// F(x) = −(√π/(2√α))·erfc(z)·e^{αm²}, where erfc(z)e^{αm²} = w(iz)·E(x) if Re z ≥ 0 and
/// 2e^{αm²} − w(−iz)·E(x) otherwise (so w is only needed in the upper half-plane, where the
/// fast FaddeevaWUpper of core/numerics/faddeeva.h serves).
Complex GaussianSegmentIntegral(Complex alpha, Complex beta, double x0, double x1);

/// The integrand of one wavelength in plate coordinates relative to the hit point (see above).
///
/// With `evolve` (set by MakePlateGaussian) the quadratic form is only the integrand's expansion
/// at the hit point; the integrand itself is the GR's exact paraxial beam, which evolves along its
/// own axis, times the exact spherical incident wave (theory §9; docs/aperture.md):
///     ψ ∝ (q/(q+a))·exp(ik a + ik T/(2(q+a))),  a = d1 x + d2 y,  T = x² + y² − a²,
/// 1/q = (ρ + i)/(kβ²) (so ik/(2q) = −γ), and U_inc ∝ (R/r)·e^{ik(r − R)}, r = |Δ + R s|.
/// IntegratePiece re-expands that exponent to second order about the centre of each
/// (piece ∩ window), so the closed forms get per-piece complex coefficients. At oblique
/// incidence the axial offset a reaches ±β·window·tanθ and changes the curvature radius by a
/// relative a/|q|: a phase error odd in the offset (a fringe shift) if ignored.
struct PixelWavelet;

struct PlateGaussian {
    Complex axx, axy, ayy;                // [1/m²]
    double bx = 0, by = 0;                // [rad/m]
    double hx = Infinity, hy = Infinity;  // window half-widths [m]
    bool evolve = false;                  // add the beams' evolution along their axes (see above)
    double k = 0;                         // wavenumber [rad/m]
    double d1 = 0, d2 = 0;                // the traced GR's direction on the plate axes
    Complex invQ;                         // 1/q of the traced GR at the hit point [1/m]
    double s1 = 0, s2 = 0;                // the incident wave's direction on the plate axes
    double dist = Infinity;               // its wavefront radius at the hit point [m]
    /// An incident TEM₀₀ Gaussian beam (AddIncidentBeam) in place of the plane wave along s: its
    /// field relative to its on-axis amplitude at the hit's axial position, times e^{−ik s·Δ},
    /// enters every piece as an exact-to-second-order correction about the piece (the beam is
    /// Gaussian across its axis; only the slow change of q along the axis is expanded).
    bool beam = false;
    double ba1 = 0, ba2 = 0;              // the beam's axis on the plate axes
    double bo1 = 0, bo2 = 0, bOff2 = 0;   // the hit's offset from the axis: on e1, e2; squared [m²]
    Complex bq;                           // q = z − i·z_R of the beam at the hit's axial position [m]
    /// The window truncates the quadrature axis of a piece at hx (or hy) and its closed-form axis
    /// at far·hx (far·hy): truncating there saves nothing, and at 2× the D13 window the GR's
    /// amplitude is < e^{−2·window²} (e^{−32} for window = 4), so a slit longer than the
    /// footprint costs one closed form. far = 1 gives the plain box (used by tests).
    double far = 2;
    /// A sensor pixel's state in place of the traced GR (PixelWavelet, IntegrateWavelet): the
    /// quadratic form above is then zero and the whole integrand — the incident wave and the
    /// state's non-paraxial field — is expanded about each piece of a tile whose centre lies at
    /// `shift` from the hit point (the piece's coordinates are relative to that centre).
    const PixelWavelet *wavelet = nullptr;
    Vec2 shift;
};

/// The coefficients of theory §9 for the traced GR at the hit point — unit mean direction d
/// (world, pointing into the plate), wavenumber k [rad/m], β² [m²], ρ (traced convention, ρ > 0
/// diverging along d) — measured against an incident wave travelling along the unit vector s
/// (world, direction of light flow) whose wavefront has radius `dist` [m] (Infinity: a plane
/// wave). (e1, e2, n) are the plate's axes; `window` is the locality radius in units of β.
/// With γ = (1−iρ)/(2β²), κ = k/(2·dist) and dᵢ = d·eᵢ, sᵢ = s·eᵢ, d_n = d·n:
///   axx = γ(1−d1²) − iκ(1−s1²),  axy = −γ d1 d2 + iκ s1 s2,  ayy = γ(1−d2²) − iκ(1−s2²),
///   bx = k(d1+s1),  by = k(d2+s2),  hx = ϱ√(1 + d1²/d_n²),  hy = ϱ√(1 + d2²/d_n²), ϱ = window·β
/// (the box bounding the oblique cut |Δ⊥d| ≤ ϱ). Requires d_n ≠ 0. Sets `evolve` and its data.
PlateGaussian MakePlateGaussian(const Vec3 &d, const Vec3 &s, const Vec3 &e1, const Vec3 &e2, const Vec3 &n,
                                double k, double beta2, double rho, double dist, double window);

/// Replaces g's incident plane wave (direction s of MakePlateGaussian) by the Gaussian beam `b`
/// (core/render/genray.h) at wavenumber g.k; `hit` is the hit point (world), (e1, e2) the plate axes. The
/// integral is then per unit on-axis amplitude of the beam at the hit's axial position.
void AddIncidentBeam(PlateGaussian *g, const GaussianBeamGeometry &b, const Vec3 &hit, const Vec3 &e1,
                     const Vec3 &e2);

/// A sensor pixel's detection state (core/render/genray.h PixelState) meeting the plate, for one
/// wavenumber k (docs/narrow_pixels.md). Its exchange with the field U₀ = t·U_inc just behind the
/// plate is, exactly for the Kirchhoff boundary values (theory §6.2) and to second order in the
/// pixel's extent over its distance (the error is k·|w⊥|·(3β)³/(2r²) + k(3β)⁴/(8r³) rad),
///     A = ∫ t·U_inc(x')·K(x')·H(x')·√(w_n) d²x',
/// where, with D = x' − x_p (x_p the pixel centre), r = |D|, w = D/r and w⊥ = (w·s, w·t) its
/// sensor-plane direction cosines:
///   * K = (c_p/(2π))·(1/r − ik)·e^{ikr}/r is the Rayleigh–Sommerfeld kernel from x' to the pixel
///     centre (c_p = |D·n_plate|/r);
///   * H = ∫ g(δ)·e^{ik u·δ}·e^{ik(R − r)} d²δ = (πβ²)^{−1/2}·(π/√det Q)·exp(−bᵀQ⁻¹b/4) is the
///     pixel's Gaussian g (β² = 2σ²) against the wavelet from x' expanded to second order in the
///     offset δ on the sensor, R − r = −w⊥·δ + (|δ|² − (w⊥·δ)²)/(2r): b = k(w⊥ − u),
///     Q = I/(2β²) − (ik/(2r))(I − w⊥w⊥ᵀ) — the state's field on the plate at any angle, with
///     no paraxial approximation (in the near zone of a wide pixel it is the Gaussian beam);
///   * √w_n (w_n = w·n_sensor) makes |A|² integrated over the labels the flux through the
///     sensor plane rather than |U|² (see IntegrateWavelet).
/// Summed over labels, ∫|A|² d²u/λ² is the flux weighted by the pixel's Gaussian N(0, σ²).
struct PixelWavelet {
    Vec3 dRef;          // hit point − pixel centre (world) [m]
    double rRef = 0;    // |dRef|
    Vec3 e1, e2, np;    // the plate's axes (world)
    Frame sensor;       // s, t span the sensor plane, n its front normal
    double k = 0;       // wavenumber [rad/m]
    double beta2 = 0;   // β_D² [m²]
    Vec2 label;         // u
    bool labelOnly = false;  // PixelState::labelOnly: the GR's ray is not along the label
    double ref = 0;     // subtracted from the log-integrand (keeps |integrand| ≲ 1; IntegrateWavelet)
    /// From the pixel state, the hit point and the plate axes.
    static PixelWavelet Make(const PixelState &p, const Vec3 &hit, const Vec3 &e1, const Vec3 &e2,
                             const Vec3 &np, double k);
    /// Whether the second-order expansion in the pixel's extent holds at this distance: the
    /// neglected phase k·|w⊥|·(3β)³/(2r²) + k(3β)⁴/(8r³) at the hit, in radians.
    double ExpansionError() const;
    /// Whether the aperture kernel evaluates the pixel's state this way rather than through the
    /// paraxial GR it was traced as: for pixels with kβ < 63 (σ_pix < 7.1 λ), where the paraxial GR
    /// errs by more than ≈ 2/(kβ)² = 5e-4 of the pixel (docs/narrow_pixels.md), as long as
    /// ExpansionError() ≤ narrow_pixels::MaxExpansionPhase (0.02 rad); and always for a GR whose
    /// ray is not along its label (labelOnly: the paraxial GR has no such state). Wider pixels keep the paraxial GR, which
    /// is as accurate there and ~100× cheaper (one closed form per slit instead of tiles).
    bool Preferred() const;
};

/// A = ∫ t·U_inc·K·H·√w_n d²x' of PixelWavelet over the openings of `mask`, for the incident wave
/// of `g` (MakePlateGaussian's s, dist, and AddIncidentBeam; its quadratic form and window are
/// not used) and the pixel state `w`; `hit` is the hit point in plate coordinates. The window is
/// the region of the plate whose directions from the pixel lie within 2·window·√(1 + F²)/(kβ) of
/// the label u (F = kβ²/r, the pixel's Fresnel number: where |H| falls to e^{−2·window²}), or
/// the openings' bounds where that region reaches the horizon (and, for an incident Gaussian beam,
/// the oblique cut of the beam within 12 radii of its axis). It is cut into tiles, halved until
/// the integrand's second-order expansion about each tile's centre errs by ≤ 1e-4 rad (weighted
/// by the integrand's magnitude along the segments from the centre to the corners and edge
/// midpoints); each tile's pieces are then done by IntegratePiece with the expansion about the
/// piece. Returns A [m].
Complex IntegrateWavelet(const PlateGaussian &g, const PixelWavelet &w, const ApertureMask &mask, const Vec2 &hit,
                         double window);

/// ∫∫ over (piece ∩ window) of exp(−(axx x² + 2axy xy + ayy y²) + i(bx x + by y)) dx dy, where
/// the piece is given in plate coordinates and `origin` is the hit point's plate position (so
/// x = u − origin.x, y = v − origin.y); the window is the box of PlateGaussian (see `far`). The
/// piece's transmission is not applied. Rectangles and discs put the quadrature along the shorter
/// side of their part inside the window (a choice that depends on geometry only, so that every
/// direction of one GR measures the same truncated state); trapezoids are done in closed form
/// along x. A rectangle longer than the footprint along its closed-form axis collapses to one
/// more closed form. The Gauss–Legendre order follows a quadratic model of the exponent and the
/// Bernstein-ellipse error bound (see the .cpp), for an error ≲ 1e-10 of ∫|integrand| over the
/// piece (checked against adaptive brute force in tests/materials/aperture_test.cpp). With
/// g.evolve the exact beams are re-expanded about the centre of (piece ∩ D13 box) first (see
/// PlateGaussian); the residual is their third-order term over the piece.
Complex IntegratePiece(const PlateGaussian &g, const MaskPiece &piece, const Vec2 &origin);

/// The same integrand over the trapezoid {y ∈ [y0, y1], x ∈ [a0 + a1·y, b0 + b1·y]} (coordinates
/// relative to the hit point) ∩ the window, always in closed form along x (to far × hx) and by
/// Gauss–Legendre along y (to hy) — also for rectangles, so that complementary sets of trapezoids
/// (a region and the rest of the box, used by free-space diffraction, docs/fsd.md) are cut by the
/// same window and their integrals add up to the box's exactly.
Complex IntegrateTrapezoid(const PlateGaussian &g, double y0, double y1, double a0, double a1, double b0, double b1);

}  // namespace phasor
