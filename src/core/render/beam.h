// SPDX-License-Identifier: Apache-2.0
// phasor — the PLT beam of sample-solve (theory §5.2–5.3, §4.9, §0 D9, D15): what `sample_solve`
// carries forward from a light to the detector along a sampled path.
//
// State:
//   * one Stokes vector (S0..S3) per carried wavelength, relative to the path's scalar estimate
//     (sources emit unpolarised light, S = (1, 0, 0, 0); theory §4.9);
//   * the reference frame: the unit direction of travel d̂ and the Stokes x axis t̂ ⊥ d̂; the
//     basis is (t̂, d̂ × t̂), right-handed with d̂ like the s/p basis of core/polarization.h, so a
//     lobe's Mueller matrix applies once t̂ is its s axis;
//   * the distance travelled from the source [m].
// Operations: Source, Propagate, Interact (frame rotation into the lobe's s/p frame and its Mueller
// response), Measure (rotation into the detector's frame and an optional ideal linear polariser).
//
// Partial coherence is not a state of the beam: the plane waves a measurement integrates (a light's
// angular profile through the GR's angular spectrum) enter through each lobe's Mueller matrix
// averaged over them (theory §0 D15, core/render/lobe_average.h), which sample_solve.cpp applies.
#pragma once

#include <array>
#include <optional>

#include "core/math.h"
#include "core/polarization.h"
#include "core/spectrum/spectrum.h"

namespace phasor {

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
    Vec3 t{1, 0, 0};                         // Stokes x axis, unit, ⊥ d
    double dist = 0;                         // travelled distance [m]

    /// A beam leaving a source along `travel`: unpolarised, S = (1, 0, 0, 0) at each of `count`
    /// wavelengths.
    static PltBeam Source(const Vec3 &travel, int count);

    /// Travel `length` [m] along d (finite).
    void Propagate(double length);
    /// Re-expresses the Stokes vectors in the basis whose x axis is `newT` (⊥ d).
    void RotateFrame(const Vec3 &newT);

    /// An interaction with a lobe whose s axis is `s` (world, ⊥ to d and to `out`): rotates into
    /// the lobe's frame, applies per wavelength i < count the Mueller matrix m[i] (expressed in
    /// (s, d × s) → (s, out × s)), and continues along `out` with t = s.
    void Interact(const Vec3 &s, const Vec3 &out, const std::array<Mueller, NumWavelengths> &m);

    /// The Stokes vector of wavelength i in the basis (x, d × x) (x ⊥ d), after an ideal linear
    /// polariser whose axis is at `polarizer` [rad] from x, if one is given.
    Stokes Measure(int i, const Vec3 &x, const std::optional<double> &polarizer) const;
};

}  // namespace phasor
