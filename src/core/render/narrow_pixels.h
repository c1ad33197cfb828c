// SPDX-License-Identifier: Apache-2.0
// When a sensor pixel's detection state is measured non-paraxially at an aperture plate, and how
// close to the plate that measurement holds (theory §2.6, D16; docs/narrow_pixels.md). Shared by
// the aperture kernel (materials/aperture_integral.cpp, PixelWavelet) and the scene's check of a
// sensor plane against its plates (core/render/scene_checks.cpp), so that both use one criterion.
#pragma once

#include <algorithm>
#include <cmath>

namespace phasor::narrow_pixels {

/// Pixels with k·β_D below this (σ_pix < 7.1 λ) are measured by their exact state: the paraxial
/// GR errs by ≈ 2/(kβ)² of the pixel there (8e-5, 3e-4, 1.3e-3, 5e-3 measured at kβ = 157, 81,
/// 41, 21), so 63 keeps it ≤ 5e-4.
inline constexpr double NonParaxialBelowKBeta = 63;

/// The largest phase [rad] the state's second-order expansion in the pixel's extent may neglect
/// (0.1 left 2.6e-3 of peak at the distance it allowed for pitch 5λ; 0.02 leaves ≤ 1.7e-3 beyond it).
inline constexpr double MaxExpansionPhase = 0.02;

/// The phase [rad] neglected by expanding the wavelet from a plate point at distance r to second
/// order in the offset δ on the sensor (|δ| ≤ 3β): the third- and fourth-order terms of R − r,
/// k·wt·(3β)³/(2r²) + k·(3β)⁴/(8r³), where wt is the sine of the point's direction from the
/// sensor's normal. beta2 = β_D² [m²], k [rad/m], r [m].
inline double ExpansionPhase(double k, double beta2, double r, double wt) {
    const double d = 3 * std::sqrt(beta2);
    return k * (wt * d * d * d / (2 * r * r) + d * d * d * d / (8 * r * r * r));
}

/// The least distance [m] of the plate's plane from the sensor (measured along the normal) at
/// which ExpansionPhase ≤ MaxExpansionPhase for every plate point in front: a point at angle θ
/// from the normal lies at r = h/cosθ with wt = sinθ, and sinθ·cos²θ ≤ 2/(3√3), cos³θ ≤ 1.
inline double MinPlateDistance(double k, double beta2) {
    const double worstSin = 2 / (3 * std::sqrt(3.0));
    auto phase = [&](double h) {
        const double d = 3 * std::sqrt(beta2);
        return k * (worstSin * d * d * d / (2 * h * h) + d * d * d * d / (8 * h * h * h));
    };
    double lo = 0, hi = 3 * std::sqrt(beta2);
    while (phase(hi) > MaxExpansionPhase) hi *= 2;
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (phase(mid) > MaxExpansionPhase ? lo : hi) = mid;
    }
    return hi;
}

}  // namespace phasor::narrow_pixels
