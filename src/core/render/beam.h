// SPDX-License-Identifier: Apache-2.0
// phasor — the PLT beam of sample-solve (theory §5.2–5.3, §4.9, §0 D5, D9): what `sample_solve`
// carries forward from a light to the detector along a sampled path.
//
// State:
//   * one Stokes vector (S0..S3) per carried wavelength, relative to the path's scalar estimate
//     (sources emit unpolarised light, S = (1, 0, 0, 0); theory §4.9);
//   * the reference frame: the unit direction of travel d̂ and the Stokes x axis t̂ ⊥ d̂; the
//     basis is (t̂, d̂ × t̂), right-handed with d̂ like the s/p basis of core/polarization.h, so a
//     lobe's Mueller matrix applies once t̂ is its s axis;
//   * the coherence: K, the 2×2 covariance of the ensemble's transverse wavevector divided by
//     k₀² = (2π/λ)² in the same (t̂, d̂ × t̂) coordinates [rad²] — the angular covariance Ω of D5
//     in vacuum (in a medium of index n the angles are K/n², and k²Ω = k₀²K is what enters μ);
//     mutual coherence between transverse points separated by v: μ(v) = exp(−½k₀²·vᵀKv) (D5);
//     Θ = (k₀²K)⁻¹ is PLT's shape matrix (theory §2.3);
//   * the distance travelled from the source [m].
// Operations: Source, Propagate, Interact (frame rotation into the lobe's s/p frame, its Mueller
// response, deformation of K), MutualCoherence, Measure (rotation into the detector's frame and an
// optional ideal linear polariser).
//
// What K is and when it changes (docs/sample_solve.md): K is the angular spread of the ensemble a
// measurement integrates analytically — a `distant` source measured in closed form keeps its profile's
// Ω; a source point or direction that the path sampled is one coherent mode (K = 0). Light at
// infinity does not change its coherence with distance, and a mode is coherent at every distance,
// so Propagate only adds the distance. At a near-delta lobe the tangential wavevector is conserved:
// the in-plane transverse spread scales by cosθ_in/cosθ_out (the anamorphic factor of refraction and
// of grating orders; 1 for reflection), the s component is unchanged (D ← UᵀDU with U = I for
// reflection, theory §5.3).
#pragma once

#include <array>
#include <optional>

#include "core/math.h"
#include "core/polarization.h"
#include "core/spectrum/spectrum.h"

namespace phasor {

/// A symmetric 2×2 matrix [[xx, xy], [xy, yy]].
struct Sym2 {
    double xx = 0, xy = 0, yy = 0;
    static Sym2 Isotropic(double v) { return {v, 0, v}; }
    /// vᵀ M v.
    double Quadratic(double vx, double vy) const { return xx * vx * vx + 2 * xy * vx * vy + yy * vy * vy; }
    bool IsZero() const { return xx == 0 && xy == 0 && yy == 0; }
};

/// An ideal linear polariser whose transmission axis is at `angle` [rad] from the x axis of the
/// Stokes frame (towards y): M = ½[[1, c, s, 0], [c, c², cs, 0], [s, cs, s², 0], [0, 0, 0, 0]],
/// c = cos 2·angle, s = sin 2·angle. Malus: linear light at angle a transmits cos²(a − angle).
Mueller LinearPolarizer(double angle);

/// The Mueller matrix of the reverse path through a reciprocal element whose matrix is M, each wave
/// in its basis (ŝ, k̂ × ŝ): P·Mᵀ·P with P = diag(1, 1, −1, 1), the Mueller matrix of D·Jᵀ·D,
/// D = diag(1, −1) (reciprocity transposes the Jones matrix; reversing k̂ flips p̂). Kernels state
/// their response for the backward tracer's direction (light arriving along −wi); `sample_solve`
/// sends light the other way. A diagonal (interface) response is its own reverse.
Mueller ReciprocalMueller(const Mueller &m);

/// The angle ψ [rad] about the unit axis `d` that turns the unit vector `from` into `to` (both ⊥ d).
double AngleAbout(const Vec3 &from, const Vec3 &to, const Vec3 &d);
/// The Stokes vector S given in the basis (from, d × from) re-expressed in (to, d × to):
/// Mueller::Rotation(−ψ)·S with ψ = AngleAbout(from, to, d).
Stokes RotateStokesFrame(const Stokes &s, const Vec3 &from, const Vec3 &to, const Vec3 &d);
/// A unit vector ⊥ d near `hint` (its projection), or any unit vector ⊥ d if the projection vanishes.
Vec3 PerpendicularTo(const Vec3 &d, const Vec3 &hint);

struct PltBeam {
    int count = 1;                           // carried wavelengths in use
    std::array<Stokes, NumWavelengths> S{};  // relative Stokes vectors, one per carried wavelength
    Vec3 d{0, 0, 1};                         // unit direction of travel (world)
    Vec3 t{1, 0, 0};                         // Stokes and coherence x axis, unit, ⊥ d
    Sym2 K;                                  // transverse-wavevector covariance / k₀² in (t, d × t) [rad²]
    double dist = 0;                         // travelled distance [m]
    /// Per carried wavelength, the share of K the measurement integrates: Ω_w/(Ω + Ω_w) when the
    /// closed form saw the source's profile (isotropic Ω) through a Gaussian angular window of
    /// variance Ω_w (SetWindow), 1 without a window. μ uses K times this share.
    std::array<double, NumWavelengths> share = [] { std::array<double, NumWavelengths> a; a.fill(1.0); return a; }();

    /// A beam leaving a source along `travel`: unpolarised, S = (1, 0, 0, 0) at each of `count`
    /// wavelengths; isotropic coherence K = omega·I (omega [rad²], D5; 0: a coherent mode).
    static PltBeam Source(const Vec3 &travel, int count, double omega);

    /// Travel `length` [m] along d (finite; coherence unchanged, see the top of the file).
    void Propagate(double length);
    /// Re-expresses the Stokes vectors and K in the basis whose x axis is `newT` (⊥ d).
    void RotateFrame(const Vec3 &newT);
    /// The measurement saw the source through an isotropic Gaussian angular window of variance
    /// `windowVariance` [rad²] at carried wavelength i (a GR's σ_k²/k², D14; Infinity: none). The
    /// ensemble it integrates is the source's profile times that window, whose covariance is
    /// (Ω⁻¹ + Ω_w⁻¹)⁻¹ = Ω·Ω_w/(Ω + Ω_w) for the source's isotropic Ω = K.xx (call right after Source):
    /// a camera pixel narrower than the source sees a narrow, nearly coherent part of it.
    void SetWindow(int i, double windowVariance);
    /// μ(v) = exp(−½k₀²·share[i]·v⊥ᵀKv⊥) at vacuum wavenumber k0 [rad/m] of carried wavelength i, for
    /// a world displacement v projected onto the plane ⊥ d (theory §0 D5).
    double MutualCoherence(const Vec3 &v, double k0, int i) const;

    /// An interaction with a lobe whose s axis is `s` (world, ⊥ to d and to `out`): rotates into
    /// the lobe's frame, applies per wavelength i < count the Mueller matrix m[i] (expressed in
    /// (s, d × s) → (s, out × s)), and continues along `out` with t = s. `inPlaneScale` multiplies
    /// the in-plane (d × s) component of the transverse spread (cosθ_in/cosθ_out for a near-delta
    /// lobe); `resetCoherence` makes the beam a coherent mode (K = 0: a sampled continuous lobe).
    void Interact(const Vec3 &s, const Vec3 &out, const std::array<Mueller, NumWavelengths> &m, double inPlaneScale,
                  bool resetCoherence);

    /// The Stokes vector of wavelength i in the basis (x, d × x) (x ⊥ d), after an ideal linear
    /// polariser whose axis is at `polarizer` [rad] from x, if one is given.
    Stokes Measure(int i, const Vec3 &x, const std::optional<double> &polarizer) const;
};

}  // namespace phasor
