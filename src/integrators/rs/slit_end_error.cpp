// SPDX-License-Identifier: Apache-2.0
// The slit-end error model of `rs` (rs/slit_end_error.h; docs/rs.md "2-D mode selection"):
// `mode = "auto"` takes the 2-D mode only where SlitEndError — the Fresnel factor of the finite
// slit length averaged over each pixel — predicts at most `auto_2d_tolerance` (default 2e-4 of
// the local intensity; 1.3e-4 for the paper's 4000 µm slits).
#include "integrators/rs/slit_end_error.h"

#include <algorithm>
#include <cmath>

#include "core/numerics/faddeeva.h"
#include "integrators/rs/sensor_quadrature.h"

namespace phasor {
namespace rs {

namespace {

/// erf(a·s) for a = (√π/2)(1 − i): with E = C + iS the Fresnel integrals, E(s) = ((1 + i)/2)·erf(a·s).
/// Through the Faddeeva function, erf(z) = 1 − e^{−z²}·w(iz), where e^{−z²} = e^{iπs²/2} and iz lies
/// on the first quadrant's diagonal for s ≥ 0 (odd in s).
Complex ErfDiagonal(double s) {
    const double as = std::abs(s), c = 0.5 * std::sqrt(Pi) * as;
    const Complex e = Complex(1, 0) - std::polar(1.0, 0.5 * Pi * as * as) * FaddeevaW(Complex(c, c));
    return s < 0 ? -e : e;
}

}  // namespace

Complex SlitLengthFactor(double y, double v0, double v1, double k, double r) {
    const double f = std::sqrt(k / (Pi * r));
    return 0.5 * (ErfDiagonal(f * (v1 - y)) - ErfDiagonal(f * (v0 - y)));
}

double SlitEndError(const PlateFrame &plate, const Bounds2 &slits, const SensorPlaneGeometry &g, double k) {
    const Vec3 e2 = plate.e2;
    const bool alongT = std::abs(Dot(g.frame.t, e2)) >= 1 - 1e-9;
    const double pitch = alongT ? g.pitchY : g.pitchX, ext = WindowHalfWidth(g, pitch);
    const int nAlong = alongT ? g.ny : g.nx, nAcross = alongT ? g.nx : g.ny;
    // In-plane (⊥ slits) distances between the slits' u range and the window: the extremes of a
    // segment-to-segment distance lie at end points.
    auto inPlane = [&](const Vec3 &p) {  // (u, height) of p
        const Vec3 d = p - plate.origin;
        return Vec2(Dot(d, plate.e1), std::abs(Dot(d, plate.n)));
    };
    auto centre = [&](int along, int across) {
        const Vec2 c = alongT ? g.PixelCenter(across, along) : g.PixelCenter(along, across);
        return g.origin + g.frame.s * c.x + g.frame.t * c.y;
    };
    const Vec3 acrossDir = alongT ? g.frame.s : g.frame.t;
    const Vec2 w0 = inPlane(centre(0, 0) - acrossDir * ext), w1 = inPlane(centre(0, nAcross - 1) + acrossDir * ext);
    auto pointToSlit = [&](Vec2 w) { return std::hypot(std::max({0.0, slits.lo.x - w.x, w.x - slits.hi.x}), w.y); };
    auto pointToWindow = [&](double u) {  // distance from (u, 0) to the segment w0–w1
        const Vec2 d = w1 - w0, q = Vec2(u - w0.x, -w0.y);
        const double t = Dot(d, d) > 0 ? std::clamp(Dot(q, d) / Dot(d, d), 0.0, 1.0) : 0.0;
        return Length(q - d * t);
    };
    const double rMin = std::min({pointToSlit(w0), pointToSlit(w1), pointToWindow(slits.lo.x), pointToWindow(slits.hi.x)});
    const double rMax = std::max({std::hypot(w0.x - slits.lo.x, w0.y), std::hypot(w0.x - slits.hi.x, w0.y),
                                  std::hypot(w1.x - slits.lo.x, w1.y), std::hypot(w1.x - slits.hi.x, w1.y)});
    if (!(rMin > 0)) return Infinity;
    const double v0 = slits.lo.y, v1 = slits.hi.y;
    double worst = 0;
    for (int j = 0; j < nAlong; ++j) {
        const double yc = Dot(centre(j, 0) - plate.origin, e2);
        // |G|² − 1 oscillates at k·|y − v_end|/R; resolve it with 8 nodes a period (and σ/4).
        const double far = std::max(std::abs(yc - v0), std::abs(yc - v1)) + ext;
        const double h = std::min(g.sigma / 4, 2 * Pi / (k * far / rMin) / 8);
        const int n = int(std::ceil(ext / h));
        for (double r : {rMin, rMax}) {
            double e;
            if (n <= 20000) {  // the pixel-averaged error (trapezoid rule under the pixel weight)
                double acc = 0;
                for (int a = -n; a <= n; ++a) {
                    const double d = a * ext / n;
                    acc += PixelWeight(d, g.sigma, pitch, g.gaussianPixel) *
                           (std::norm(SlitLengthFactor(yc + d, v0, v1, k, r)) - 1);
                }
                e = std::abs(acc * ext / n);
            } else {  // too many fringes to average: bound |G|² − 1 by the edge tails at the window
                const double f = std::sqrt(k / (Pi * r));
                const double s0 = f * (yc - ext - v0), s1 = f * (v1 - yc - ext);
                if (s0 <= 0 || s1 <= 0) return Infinity;
                const double t = 0.5 * (std::abs(1.0 - ErfDiagonal(s0)) + std::abs(1.0 - ErfDiagonal(s1)));
                e = 2 * t + t * t;
            }
            worst = std::max(worst, e);
        }
    }
    return worst;
}


}  // namespace rs
}  // namespace phasor
