// SPDX-License-Identifier: Apache-2.0
// The slit-end error model of `rs`'s 2-D mode (rs/slit_end_error.cpp, docs/rs.md "2-D mode
// selection"): how much the finite length of slits changes the pixels of the infinite-slit field.
#pragma once

#include "core/render/aperture.h"
#include "core/render/detector.h"
#include "core/math.h"

namespace phasor::rs {

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

}  // namespace phasor::rs
