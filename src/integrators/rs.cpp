// SPDX-License-Identifier: Apache-2.0
// `rs`: the forward Rayleigh–Sommerfeld reference (theory §6.2, §9; design.md §4.3). Coherent,
// monochromatic sources (`plane_wave` with a line spectrum at any incidence, isotropic `point`
// with a line spectrum, `gaussian_beam` with a line spectrum: its exact paraxial TEM₀₀ field,
// GaussianBeamGeometry, with the waist anywhere) shine on ONE planar aperture plate — the scene's only shape, whose
// material has openings (Material::Openings, e.g. `aperture`) — and the scalar field behind it is
// computed in double precision on the `virtual_plane` sensor:
//   Kirchhoff boundary values U₀ = t·U_inc on the openings (the plate is infinite and opaque
//   elsewhere), RS of the first kind
//     U(r) = (1/2π) ∫∫ U₀(r') (z/R)(1/R − ik) e^{ikR}/R dA'                              (3-D)
//     U(x, z) = (ikz/2) ∫ U₀(x') H₁⁽¹⁾(kR)/R dx'                                          (2-D)
//   and ∇U from the analytic derivative of the same kernels. Amplitude convention: |U_inc|² =
//   irradiance normal to the direction of travel. Pixels report FLUX through the sensor plane per
//   unit area, F = −Im(U*·∂U/∂n_s)/k (n_s = front normal; S = Im(U*∇U)/k), integrated against
//   the pixel sensitivity of theory §0 D2 (Gaussian N(0, σ²I) or box ⊛ Gaussian) and divided by
//   the sensor's reference irradiance. Several lights add incoherently (intensities add).
//   In the double-slit set-up F differs from |U|² by 2.8e-5 of peak (measured in rs_test.cpp).
//
// Quadrature (docs/rs.md; `accuracy`, default 1e-4 of peak, sets the tolerances below through
// QuadratureRule::ForAccuracy; measured errors are far smaller, see docs/rs.md §4):
//  * Aperture integral, per field point, per mask piece {v ∈ [v0, v1], u ∈ [ULo(v), UHi(v)]}:
//    Gauss–Legendre panels along v, and for each v node along u. Panels are marched so that
//    (bound of |∂φ/∂u| or |∂φ/∂v| over the panel's box) × length ≤ 6π, φ = kR + incident phase;
//    the bound is exact interval arithmetic on the direction cosines (monotone in the offsets),
//    plus |slope|·|∂φ/∂u| for the moving limits of trapezoids. Panels are at most half the distance
//    to the field point (and to a point source) so the 1/R amplitudes are resolved. Nodes per
//    panel: the fewest n ∈ [6, 20] whose Gauss–Legendre error for a linear phase Φ,
//    Φ^{2n}(n!)⁴/((2n+1)((2n)!)³) (A&S 25.4.30), is below the per-panel tolerance (accuracy·1e-3;
//    n = 12 at Φ = 6π for the default). Discs are integrated in ψ, v = c_v + r·sin ψ (smooth
//    chord limits), with the ψ bound of docs/rs.md §2.
//  * 2-D mode: only the u integral (slits infinite along v), same panels; H₀, H₁ by their
//    asymptotic series for kR ≥ 25 (error < 1e-16), std::cyl_bessel_j / cyl_neumann below.
//  * Sensor: the field on a uniform grid over all pixel centres ± 6σ (± pitch/2 + 6σ for box
//    pixels), spacing h ≤ 2π/(k·Δ + c/σ) per axis, Δ = an interval bound, tile by tile over the
//    window, of the spread of the direction components along that axis from the openings' box to
//    any one point (the band limit of the intensity); nodes no pixel window reaches are skipped (a
//    one-row sensor evaluates only its row's nodes). Each pixel is Σ w(node)·F(node)·h_x·h_y: the
//    trapezoid rule on a band-limited integrand times a Gaussian, aliasing ≈ e^{−c²/2} of the
//    local intensity (e^{−c²/2} = accuracy/10).
//  * 2-D mode (`mode = "2d"`, or `auto` when every opening is a rectangle with one common v range,
//    the light is a plane wave with no component along v, a sensor axis is parallel to the slits,
//    and SlitEndError — the Fresnel factor of the finite slit length averaged over each pixel —
//    predicts at most `auto_2d_tolerance`, default 2e-4 of the local intensity; 1.3e-4 for the
//    paper's 4000 µm slits): the field is constant along the slits, so the pixel sensitivity
//    along them integrates to 1 and that grid axis collapses to one node.
// Parallel over grid nodes with TBB; every node and every pixel sum is computed in a fixed
// order, so the result does not depend on the thread count.
#include "integrators/rs.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <thread>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "core/integrator.h"
#include "core/material.h"
#include "core/registry.h"
#include "core/scene.h"
#include "core/numerics/faddeeva.h"

namespace phasor {
namespace rs {

namespace {

// Gaussian beams: openings farther than this many β(z) from the beam's axis are not integrated.
constexpr double BeamCutoff = 8;

// ---- Gauss–Legendre rules ------------------------------------------------------------------------

constexpr int MaxGaussNodes = 32;

struct GaussTable {
    std::array<std::vector<double>, MaxGaussNodes + 1> x, w;  // nodes and weights on [−1, 1]
};

const GaussTable &Gauss() {
    static const GaussTable table = [] {
        GaussTable t;
        for (int n = 1; n <= MaxGaussNodes; ++n) {
            t.x[n].resize(n);
            t.w[n].resize(n);
            for (int i = 0; i < n; ++i) {
                // Newton's method on P_n from Tricomi's initial guess (Abramowitz & Stegun 22.16).
                double x = std::cos(Pi * (i + 0.75) / (n + 0.5)), dp = 1;
                for (int it = 0; it < 100; ++it) {
                    double p0 = 1, p1 = x;
                    for (int j = 2; j <= n; ++j) {
                        const double p2 = ((2 * j - 1) * x * p1 - (j - 1) * p0) / j;
                        p0 = p1;
                        p1 = p2;
                    }
                    dp = n * (x * p1 - p0) / (x * x - 1);
                    const double dx = p1 / dp;
                    x -= dx;
                    if (std::abs(dx) < 1e-16) break;
                }
                double p0 = 1, p1 = x;  // derivative at the converged node
                for (int j = 2; j <= n; ++j) {
                    const double p2 = ((2 * j - 1) * x * p1 - (j - 1) * p0) / j;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n * (x * p1 - p0) / (x * x - 1);
                t.x[n][i] = x;
                t.w[n][i] = 2 / ((1 - x * x) * dp * dp);  // A&S 25.4.29
            }
        }
        return t;
    }();
    return table;
}

/// Largest panel phase Φ_n [rad] that n Gauss–Legendre nodes integrate with a relative error
/// below `tol` for e^{iΦt/2}, t ∈ [−1, 1]: the remainder f^{(2n)}·L^{2n+1}(n!)⁴/((2n+1)((2n)!)³)
/// (A&S 25.4.30) with |f^{(2n)}| = (Φ/L)^{2n}.
double MaxPhaseForNodes(int n, double tol) {
    const double logErrPerPhase =
        4 * std::lgamma(n + 1.0) - std::log(2 * n + 1.0) - 3 * std::lgamma(2 * n + 1.0);
    return std::exp((std::log(tol) - logErrPerPhase) / (2 * n));
}

// ---- Hankel functions -----------------------------------------------------------------------------

constexpr int HankelTerms = 48;
constexpr double HankelAsymptoticMin = 25;

struct HankelCoefficients {
    std::array<double, HankelTerms> a0, a1;  // a_m(ν) of DLMF 10.17.1 for ν = 0, 1
};

const HankelCoefficients &HankelCoeffs() {
    static const HankelCoefficients c = [] {
        HankelCoefficients h;
        h.a0[0] = h.a1[0] = 1;
        for (int m = 1; m < HankelTerms; ++m) {
            const double odd = (2.0 * m - 1) * (2.0 * m - 1);
            h.a0[m] = h.a0[m - 1] * (0 - odd) / (8.0 * m);
            h.a1[m] = h.a1[m - 1] * (4 - odd) / (8.0 * m);
        }
        return h;
    }();
    return c;
}

/// The slowly varying factors P_ν(x) = Σ i^m a_m(ν)/x^m of H_ν⁽¹⁾(x) = √(2/(πx))·e^{i(x − νπ/2 −
/// π/4)}·P_ν(x) (DLMF 10.17.5), for ν = 0 and 1; x ≥ 25, summed until the terms drop below 1e-17
/// (the remainder is bounded by the first neglected term, DLMF 10.17(iii)).
void HankelSeries(double x, Complex *p0, Complex *p1) {
    const HankelCoefficients &c = HankelCoeffs();
    double r0 = 1, i0 = 0, r1 = 1, i1 = 0, xm = 1;
    for (int m = 1; m < HankelTerms; ++m) {
        xm /= x;
        const double t0 = c.a0[m] * xm, t1 = c.a1[m] * xm;
        switch (m & 3) {  // i^m
            case 0: r0 += t0, r1 += t1; break;
            case 1: i0 += t0, i1 += t1; break;
            case 2: r0 -= t0, r1 -= t1; break;
            default: i0 -= t0, i1 -= t1; break;
        }
        if (std::abs(t0) < 1e-17 && std::abs(t1) < 1e-17) break;
    }
    *p0 = Complex(r0, i0);
    *p1 = Complex(r1, i1);
}

// ---- Interval bounds of phase gradients -----------------------------------------------------------

/// Range of a/√(a² + p²) over a ∈ [aLo, aHi], p ∈ [pLo, pHi] (p ≥ 0): increasing in a, and |·|
/// decreasing in p.
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

/// Marches panels over [a, b]: each is at most lmax long and has bound(x0, x1)·(x1 − x0) ≤ phiMax
/// (bound: an upper bound of |φ'| on [x0, x1], monotone under inclusion). Calls emit(x0, x1, Φ)
/// with Φ = that product.
template <class Bound, class Emit>
void MarchPanels(double a, double b, double lmax, double phiMax, Bound &&bound, Emit &&emit) {
    double x = a;
    const double tiny = 1e-12 * (b - a);
    int guard = 0;
    while (b - x > tiny && guard++ < 50000000) {
        const double rem = b - x, cap = std::min(rem, lmax);
        double len = cap, g = bound(x, x + len);
        if (g * len > phiMax) {
            len = phiMax / g;  // valid: the bound over a sub-interval is no larger
            g = bound(x, x + len);
            for (int it = 0; it < 3; ++it) {  // grow while the tighter bound allows it
                const double trial = std::min(cap, phiMax / g);
                if (!(trial > len * 1.02)) break;
                const double gt = bound(x, x + trial);
                if (gt * trial > phiMax) break;
                len = trial;
                g = gt;
            }
        }
        double end = x + len;
        if (b - end <= tiny) end = b;
        emit(x, end, g * (end - x));
        x = end;
    }
}

}  // namespace

void Hankel01(double x, Complex *h0, Complex *h1) {
    if (x >= HankelAsymptoticMin) {
        Complex p0, p1;
        HankelSeries(x, &p0, &p1);
        const double amp = std::sqrt(2 / (Pi * x));
        *h0 = amp * std::polar(1.0, x - Pi / 4) * p0;
        *h1 = amp * std::polar(1.0, x - 3 * Pi / 4) * p1;
        return;
    }
    *h0 = Complex(std::cyl_bessel_j(0.0, x), std::cyl_neumann(0.0, x));
    *h1 = Complex(std::cyl_bessel_j(1.0, x), std::cyl_neumann(1.0, x));
}

// ---- Propagator -------------------------------------------------------------------------------------

QuadratureRule QuadratureRule::ForAccuracy(double accuracy) {
    QuadratureRule r;
    const double a = std::clamp(accuracy, 1e-12, 0.1);
    r.tolerance = std::max(1e-15, 1e-3 * a);
    r.gridMargin = std::sqrt(2 * std::log(10 / a));
    return r;
}

/// A field point in plate coordinates: (X, Y) along e1, e2, Z > 0 towards the sensor; m the
/// derivative direction in the same coordinates.
struct Propagator::Local {
    double x, y, z, mu, mv, mn;
};

/// Node counts per panel phase for a rule (index n → largest Φ).
struct NodeRule {
    std::array<double, MaxGaussNodes + 1> maxPhase{};
    int minNodes, maxNodes;
    explicit NodeRule(const QuadratureRule &r)
        : minNodes(std::clamp(r.minNodes, 1, MaxGaussNodes)),
          maxNodes(std::clamp(r.maxNodes, 1, MaxGaussNodes)) {
        for (int n = 1; n <= MaxGaussNodes; ++n) maxPhase[n] = MaxPhaseForNodes(n, r.tolerance);
    }
    int Nodes(double phase) const {
        int n = minNodes;
        while (n < maxNodes && maxPhase[n] < phase) ++n;
        return n;
    }
};

Propagator::Propagator(const PlateFrame &plate, const ApertureMask &mask, const CoherentWave &wave, bool flip,
                       bool twoD, QuadratureRule rule)
    : plate_(plate),
      zSign_(flip ? -1.0 : 1.0),
      twoD_(twoD),
      rule_(rule),
      nodes_(std::make_shared<const NodeRule>(rule)) {
    if (!(wave.lambda > 0) || !(wave.strength >= 0))
        throw Error("rs: the coherent wave has no valid wavelength");
    k_ = 2 * Pi / wave.lambda;
    amp_ = std::sqrt(wave.strength);
    spherical_ = wave.kind == CoherentWave::Kind::Spherical;
    beam_ = wave.kind == CoherentWave::Kind::GaussianBeam;
    if (beam_) {
        if (!(wave.beta2 > 0)) throw Error("rs: the Gaussian beam has no waist");
        beamGeo_ = GaussianBeamGeometry{wave.pos, Normalize(wave.dir), wave.beta2};
        beamZRef_ = beamGeo_.Axial(plate.origin);
    }
    if (spherical_) {
        const Vec3 d = wave.pos - plate.origin;
        su_ = Dot(d, plate.e1);
        sv_ = Dot(d, plate.e2);
        sz_ = -zSign_ * Dot(d, plate.n);
        if (!(sz_ > 0)) throw Error("the point source is not on the far side of the plate from the sensor");
    } else {
        const Vec3 d = Normalize(wave.dir);
        du_ = Dot(d, plate.e1);
        dv_ = Dot(d, plate.e2);
        if (!(zSign_ * Dot(d, plate.n) > 0))
            throw Error(std::string(beam_ ? "the Gaussian beam" : "the plane wave") +
                        " does not travel towards the sensor side of the plate");
    }
    bounds_ = mask.Bounds();
    Bounds2 beamBox;
    if (beam_ && !bounds_.Empty()) {
        // Only the beam's footprint on the plate carries light: clip the openings to the box of
        // the points within BeamCutoff·β(z) of its axis (amplitude e^{−32} of the axis value
        // there), which also keeps the panels from resolving the wavefront's phase where there is
        // no amplitude. β at the farthest z of the box bounds the footprint (one refinement).
        const double cn = std::abs(Dot(beamGeo_.axis, plate.n));
        if (!(cn > 1e-6)) throw Error("the Gaussian beam runs parallel to the aperture plate");
        const double t = Dot(plate.origin - beamGeo_.waist, plate.n) / Dot(beamGeo_.axis, plate.n);
        const Vec3 hit = beamGeo_.waist + beamGeo_.axis * t;  // the axis meets the plate here
        const Vec2 c(Dot(hit - plate.origin, plate.e1), Dot(hit - plate.origin, plate.e2));
        double half = BeamCutoff * std::sqrt(beamGeo_.Beta2At(t, k_)) / cn;
        const double slope = std::sqrt(std::max(0.0, 1 - cn * cn));  // |dz/ds| along the plate
        half = BeamCutoff * std::sqrt(beamGeo_.Beta2At(std::abs(t) + half * slope, k_)) / cn;
        beamBox = Bounds2{c - Vec2(half, half), c + Vec2(half, half)};
        bounds_ = bounds_.Intersect(beamBox);
    }
    if (beam_ && !bounds_.Empty()) {
        // Panels no longer than the beam's radius β(z) anywhere on the openings' box, so that
        // Gauss–Legendre resolves its Gaussian envelope (β(z) is smallest at the z nearest 0).
        double zLo = Infinity, zHi = -Infinity;
        for (int c = 0; c < 4; ++c) {
            const double z = beamGeo_.Axial(
                plate.ToWorld(Vec2((c & 1) ? bounds_.hi.x : bounds_.lo.x, (c & 2) ? bounds_.hi.y : bounds_.lo.y)));
            zLo = std::min(zLo, z);
            zHi = std::max(zHi, z);
        }
        const double zNear = (zLo <= 0 && zHi >= 0) ? 0.0 : std::min(std::abs(zLo), std::abs(zHi));
        beamPanel_ = std::sqrt(beamGeo_.Beta2At(zNear, k_));
    }
    if (!bounds_.Empty()) {
        Bounds2 box = bounds_;
        const Vec2 pad = 0.01 * (box.hi - box.lo);
        box.lo = box.lo - pad;
        box.hi = box.hi + pad;
        if (beam_) box = box.Intersect(beamBox);
        mask.ForEachPiece(box, [&](const MaskPiece &p) {
            if (p.t > 0 && p.v1 > p.v0) pieces_.push_back(p);
        });
    }
    if (twoD_) {
        if (spherical_ || beam_ || std::abs(dv_) > 1e-9)
            throw Error(
                "the 2-D mode needs a plane wave with no component along the slits (the plate's y axis)");
        if (!mask.IsSlitsAlongV(0))
            throw Error("the 2-D mode needs openings that are rectangles sharing one v range");
    }
}

double Propagator::BeamSlopeBound(double ua, double ub, double va, double vb) const {
    // φ = k z + k r² z/(2(z² + z_R²)) − atan(z/z_R) (GaussianBeamGeometry); along a plate axis
    // |∂r/∂u| ≤ 1 and |∂z/∂u| ≤ a (the axis' largest component on the plate), so beyond k·∂z/∂u
    // the gradient is at most k·r·max|z|/(z² + z_R²) + a·(k r²/(2 z_R²) + 1/z_R). r (distance from the axis, convex) and z
    // (linear) take their extremes over the box at its corners.
    const double zr = k_ * beamGeo_.beta2;
    const double a = std::max(std::abs(du_), std::abs(dv_));  // |∂z/∂u|, |∂z/∂v| ≤ a
    double rMax = 0, zLo = Infinity, zHi = -Infinity;
    for (int c = 0; c < 4; ++c) {
        const Vec3 p = plate_.ToWorld(Vec2((c & 1) ? ub : ua, (c & 2) ? vb : va));
        const double z = beamGeo_.Axial(p);
        rMax = std::max(rMax, std::sqrt(std::max(0.0, LengthSquared(p - beamGeo_.waist) - z * z)));
        zLo = std::min(zLo, z);
        zHi = std::max(zHi, z);
    }
    auto f = [&](double z) { return std::abs(z) / (z * z + zr * zr); };
    double fMax = std::max(f(zLo), f(zHi));
    if (zLo <= zr && zHi >= zr) fMax = std::max(fMax, f(zr));
    if (zLo <= -zr && zHi >= -zr) fMax = std::max(fMax, f(-zr));
    return k_ * rMax * fMax + a * (k_ * rMax * rMax / (2 * zr * zr) + 1 / zr);
}

double Propagator::Height(const Vec3 &p) const { return zSign_ * Dot(p - plate_.origin, plate_.n); }

FieldValue Propagator::Field(const Vec3 &p, const Vec3 &m) const {
    const Vec3 d = p - plate_.origin;
    Local l{Dot(d, plate_.e1), Dot(d, plate_.e2), zSign_ * Dot(d, plate_.n),
            Dot(m, plate_.e1), Dot(m, plate_.e2), zSign_ * Dot(m, plate_.n)};
    if (!(l.z > 0)) return {};
    double acc[4] = {0, 0, 0, 0};  // Re U, Im U, Re ∂U, Im ∂U (before the kernel's constant)
    if (twoD_) {
        Field2D(l, acc);
        // × ik/2 (theory §6.2, 2-D form)
        const double h = 0.5 * k_;
        return {Complex(-h * acc[1], h * acc[0]), Complex(-h * acc[3], h * acc[2])};
    }
    Field3D(l, acc);
    const double c = 1 / (2 * Pi);  // theory §6.2, 3-D form
    return {Complex(c * acc[0], c * acc[1]), Complex(c * acc[2], c * acc[3])};
}

double Propagator::Flux(const Vec3 &p, const Vec3 &front) const {
    const FieldValue f = Field(p, front);
    // S = Im(U*∇U)/k; power arriving at the front side crosses along −front.
    return -(f.u.real() * f.dudm.imag() - f.u.imag() * f.dudm.real()) / k_;
}

double Propagator::Intensity(const Vec3 &p) const { return std::norm(Field(p, plate_.n).u); }

void Propagator::Field3D(const Local &p, double acc[4]) const {
    const GaussTable &gl = Gauss();
    const NodeRule &nodes = *nodes_;
    const double k = k_, X = p.x, Y = p.y, Z = p.z, Z2 = Z * Z;
    const double lmax =
        std::min(rule_.maxPanelOverDistance * (spherical_ ? std::min(Z, sz_) : Z), beamPanel_);
    const double phiMax = rule_.maxPanelPhase;
    double ur = 0, ui = 0, dr = 0, di = 0;

    // Bounds of |∂φ/∂u| and |∂φ/∂v| over a box, φ = k(R − Z) + φ_inc.
    // Bound on |∂(kR + phase of U_inc)/∂a| over the panel [a0, a1] × [b0, b1], for the axis a
    // (field point coordinate A along it, B across; source point (sa, sb); plane-wave slope da).
    auto gradAlong = [&](double A, double B, double a0, double a1, double b0, double b1, double sa, double sb,
                         double da, double beamExtra) {
        double pLo, pHi, lo, hi;
        DistanceRange(B, b0, b1, &pLo, &pHi);
        CosineRange(A - a1, A - a0, std::sqrt(pLo * pLo + Z2), std::sqrt(pHi * pHi + Z2), &lo, &hi);
        double gLo = -hi, gHi = -lo;  // ∂R/∂a = −(A − a)/R
        if (spherical_) {
            double qLo, qHi, sLo, sHi;
            DistanceRange(sb, b0, b1, &qLo, &qHi);
            CosineRange(a0 - sa, a1 - sa, std::sqrt(qLo * qLo + sz_ * sz_), std::sqrt(qHi * qHi + sz_ * sz_),
                        &sLo, &sHi);
            gLo += sLo;
            gHi += sHi;
        } else {
            gLo += da;
            gHi += da;
        }
        return k * std::max(std::abs(gLo), std::abs(gHi)) + beamExtra;
    };
    auto gradU = [&](double ua, double ub, double va, double vb) {
        return gradAlong(X, Y, ua, ub, va, vb, su_, sv_, du_, beam_ ? BeamSlopeBound(ua, ub, va, vb) : 0.0);
    };
    auto gradV = [&](double ua, double ub, double va, double vb) {
        return gradAlong(Y, X, va, vb, ua, ub, sv_, su_, dv_, beam_ ? BeamSlopeBound(ua, ub, va, vb) : 0.0);
    };

    // One line v = const of a piece: the u integral, weight wv (outer node weight × Jacobian).
    auto line = [&](double v, double wv, double uLo, double uHi, double t) {
        const double dy = Y - v, dy2z2 = dy * dy + Z2;
        const double mvw = p.mv * dy + p.mn * Z;
        // Incident wave along this line (plane: linear phase; point: spherical).
        const double phiV = spherical_ ? 0.0 : k * dv_ * v;
        const double dsv = v - sv_;
        MarchPanels(
            uLo, uHi, lmax, phiMax, [&](double ua, double ub) { return gradU(ua, ub, v, v); },
            [&](double ua, double ub, double phaseU) {
                const int nu = nodes.Nodes(phaseU);
                const std::vector<double> &hx = gl.x[nu], &hw = gl.w[nu];
                const double half = 0.5 * (ub - ua), mid = 0.5 * (ua + ub);
                for (int iu = 0; iu < nu; ++iu) {
                    const double u = mid + half * hx[iu];
                    double a = amp_ * t * wv * half * hw[iu], phi;
                    if (spherical_) {
                        // U_inc = √I e^{ikρ}/ρ, phase relative to kρ₀ (ρ₀ = sz).
                        const double dsu = u - su_, q = dsu * dsu + dsv * dsv;
                        const double rho = std::sqrt(q + sz_ * sz_);
                        a /= rho;
                        phi = k * q / (rho + sz_);
                    } else if (beam_) {
                        // U_inc = √P·ψ (GaussianBeamGeometry), phase relative to k·z(origin).
                        const Complex psi = beamGeo_.Field(plate_.ToWorld(Vec2(u, v)), k, beamZRef_);
                        a *= std::abs(psi);
                        phi = std::arg(psi);
                    } else {
                        phi = k * du_ * u + phiV;
                    }
                    const double dx = X - u, q = dx * dx + dy * dy;
                    const double r2 = dx * dx + dy2z2, r = std::sqrt(r2), ir = 1 / r, ir2 = ir * ir;
                    const double ir3 = ir2 * ir;
                    phi += k * q / (r + Z);  // k(R − Z), without cancellation
                    double sn, cs;
                    ::sincos(phi, &sn, &cs);
                    const double er = a * cs, ei = a * sn;
                    // Kernel (1 − ikR)/R³ and its derivative (k²R² + 3ikR − 3)/R⁵ (rs.h).
                    const double ar = ir3, ai = -k * ir2;
                    const double br = (k * k * r2 - 3) * ir3 * ir2, bi = 3 * k * ir2 * ir2;
                    const double mw = p.mu * dx + mvw;
                    // U: Z·A; ∂U/∂m: m_n·A + Z·(m·w)·B.
                    const double tur = Z * ar, tui = Z * ai;
                    const double tdr = p.mn * ar + Z * mw * br, tdi = p.mn * ai + Z * mw * bi;
                    ur += er * tur - ei * tui;
                    ui += er * tui + ei * tur;
                    dr += er * tdr - ei * tdi;
                    di += er * tdi + ei * tdr;
                }
            });
    };

    for (const MaskPiece &piece : pieces_) {
        const double t = piece.t;
        if (piece.circle) {
            // Discs: v = c_v + r·sin ψ makes the chord limits smooth, dv = r cos ψ dψ. Panels in ψ:
            // per unit ψ the phase changes by at most r·|cos ψ|·|∂φ/∂v| inside the chord and
            // r·(|sin ψ|·|∂φ/∂u| + |cos ψ|·|∂φ/∂v|) at its ends (bounded over the arcs' boxes), and
            // the chord length × Jacobian ∝ cos²ψ adds a frequency of 2.
            const double r = piece.r, uA = std::max(piece.cu - r, piece.uMin),
                         uB = std::min(piece.cu + r, piece.uMax);
            if (!(uB > uA)) continue;
            const double psi0 = std::asin(std::clamp((piece.v0 - piece.cv) / r, -1.0, 1.0));
            const double psi1 = std::asin(std::clamp((piece.v1 - piece.cv) / r, -1.0, 1.0));
            MarchPanels(
                psi0, psi1, lmax / r, phiMax,
                [&](double pa, double pb) {
                    const double va = piece.cv + r * std::sin(pa), vb = piece.cv + r * std::sin(pb);
                    const double sinMax = std::max(std::abs(std::sin(pa)), std::abs(std::sin(pb)));
                    const double cosMin = std::min(std::cos(pa), std::cos(pb));
                    const double cosMax = (pa <= 0 && pb >= 0) ? 1.0 : std::max(std::cos(pa), std::cos(pb));
                    // Boxes of the two arcs swept by the chord ends (clamped to the piece's u range).
                    const double lo0 = std::clamp(piece.cu - r * cosMax, uA, uB),
                                 lo1 = std::clamp(piece.cu - r * cosMin, uA, uB);
                    const double hi0 = std::clamp(piece.cu + r * cosMin, uA, uB),
                                 hi1 = std::clamp(piece.cu + r * cosMax, uA, uB);
                    const double gEnds = std::max(gradU(lo0, lo1, va, vb), gradU(hi0, hi1, va, vb));
                    const double gEndsV = std::max(gradV(lo0, lo1, va, vb), gradV(hi0, hi1, va, vb));
                    const double interior = cosMax * gradV(lo0, hi1, va, vb);
                    return r * std::max(interior, sinMax * gEnds + cosMax * gEndsV) + 2.0;
                },
                [&](double pa, double pb, double phase) {
                    const int n = nodes.Nodes(phase);
                    const std::vector<double> &gx = gl.x[n], &gw = gl.w[n];
                    for (int i = 0; i < n; ++i) {
                        const double psi = 0.5 * (pa + pb) + 0.5 * (pb - pa) * gx[i];
                        const double v = piece.cv + r * std::sin(psi),
                                     wv = 0.5 * (pb - pa) * gw[i] * r * std::cos(psi);
                        const double uLo = piece.ULo(v), uHi = piece.UHi(v);
                        if (uHi > uLo && wv > 0) line(v, wv, uLo, uHi, t);
                    }
                });
        } else {
            // Trapezoids: the u limits move by |slope| per unit v, so the phase at a limit changes
            // by up to |∂φ/∂v| + |slope|·|∂φ/∂u| per unit v.
            const double uA = std::min(piece.ULo(piece.v0), piece.ULo(piece.v1));
            const double uB = std::max(piece.UHi(piece.v0), piece.UHi(piece.v1));
            if (!(uB > uA)) continue;
            const double slope = std::max(std::abs(piece.loB), std::abs(piece.hiB));
            MarchPanels(
                piece.v0, piece.v1, lmax, phiMax,
                [&](double va, double vb) {
                    return gradV(uA, uB, va, vb) + (slope > 0 ? slope * gradU(uA, uB, va, vb) : 0.0);
                },
                [&](double va, double vb, double phase) {
                    const int n = nodes.Nodes(phase);
                    const std::vector<double> &gx = gl.x[n], &gw = gl.w[n];
                    for (int i = 0; i < n; ++i) {
                        const double v = 0.5 * (va + vb) + 0.5 * (vb - va) * gx[i],
                                     wv = 0.5 * (vb - va) * gw[i];
                        const double uLo = piece.ULo(v), uHi = piece.UHi(v);
                        if (uHi > uLo) line(v, wv, uLo, uHi, t);
                    }
                });
        }
    }
    acc[0] = ur;
    acc[1] = ui;
    acc[2] = dr;
    acc[3] = di;
}

void Propagator::Field2D(const Local &p, double acc[4]) const {
    const GaussTable &gl = Gauss();
    const NodeRule &nodes = *nodes_;
    const double k = k_, X = p.x, Z = p.z, Z2 = Z * Z;
    const double lmax = rule_.maxPanelOverDistance * Z;
    // The reference phase kZ − 3π/4 is dropped from every node (rs.h: phases are relative).
    const Complex refPhase = std::polar(1.0, -(k * Z - 3 * Pi / 4));
    double ur = 0, ui = 0, dr = 0, di = 0;
    auto gradU = [&](double ua, double ub) {
        double lo, hi;
        CosineRange(X - ub, X - ua, Z, Z, &lo, &hi);
        return k * std::max(std::abs(du_ - hi), std::abs(du_ - lo));
    };
    for (const MaskPiece &piece : pieces_) {
        const double vm = 0.5 * (piece.v0 + piece.v1);
        const double uLo = piece.ULo(vm), uHi = piece.UHi(vm);
        if (!(uHi > uLo)) continue;
        MarchPanels(uLo, uHi, lmax, rule_.maxPanelPhase, gradU, [&](double ua, double ub, double phase) {
            const int n = nodes.Nodes(phase);
            const std::vector<double> &gx = gl.x[n], &gw = gl.w[n];
            const double half = 0.5 * (ub - ua), mid = 0.5 * (ua + ub);
            for (int i = 0; i < n; ++i) {
                const double u = mid + half * gx[i];
                const double a = amp_ * piece.t * half * gw[i];
                const double dx = X - u, r2 = dx * dx + Z2, r = std::sqrt(r2), x = k * r;
                const double phiInc = k * du_ * u;
                // h0, h1 = H₀⁽¹⁾(kR), H₁⁽¹⁾(kR) without the common factor e^{i(kZ − 3π/4)}.
                Complex h0, h1;
                if (x >= HankelAsymptoticMin) {
                    Complex p0, p1;
                    HankelSeries(x, &p0, &p1);
                    const Complex e = std::polar(std::sqrt(2 / (Pi * x)), k * dx * dx / (r + Z));
                    h1 = e * p1;
                    h0 = Complex(0, 1) * e * p0;  // e^{−iπ/4} = i·e^{−3iπ/4}
                } else {
                    Hankel01(x, &h0, &h1);
                    h0 *= refPhase;
                    h1 *= refPhase;
                }
                const Complex e = a * std::polar(1.0, phiInc);
                // F = H₁(kR)/R, F' = (kR·H₀ − 2H₁)/R² (H₁' = H₀ − H₁/x); U ∝ Z·F,
                // ∂U/∂m ∝ m_n·F + Z·F'·(m_u·dx + m_n·Z)/R.
                const Complex f = h1 / r, fp = (x * h0 - 2.0 * h1) / r2;
                const Complex tu = Z * f, td = p.mn * f + Z * fp * ((p.mu * dx + p.mn * Z) / r);
                const Complex cu = e * tu, cd = e * td;
                ur += cu.real();
                ui += cu.imag();
                dr += cd.real();
                di += cd.imag();
            }
        });
    }
    acc[0] = ur;
    acc[1] = ui;
    acc[2] = dr;
    acc[3] = di;
}

double Propagator::DirectionSpread(const Vec3 &corner, const Vec3 &es, const Vec3 &et, const Vec3 &axis) const {
    if (bounds_.Empty()) return 0;
    // The difference vectors w = p − q (p in the region, q on the openings' box) form a convex
    // polytope whose vertices are differences of vertices, so the box of their projections onto
    // a frame (axis, fb, fc) contains them all. c = w_a/√(w_a² + ρ²), ρ² = w_b² + w_c², grows with
    // w_a and, for w_a > 0, falls with ρ (rises for w_a < 0): its extremes over that box are at
    // (max w_a, ρ_min or ρ_max) and (min w_a, ρ_max or ρ_min).
    const Frame f = Frame::FromNormal(axis);
    const Vec3 fb = f.s, fc = f.t;
    const Vec3 region[4] = {corner, corner + es, corner + et, corner + es + et};
    // The box's corners (2-D mode: the slits' u range; components along the slits do not enter).
    const int nBox = twoD_ ? 2 : 4;
    Vec3 box[4];
    for (int c = 0; c < nBox; ++c)
        box[c] = plate_.ToWorld(Vec2((c & 1) ? bounds_.hi.x : bounds_.lo.x, (c & 2) ? bounds_.hi.y : bounds_.lo.y));
    double lo[3] = {Infinity, Infinity, Infinity}, hi[3] = {-Infinity, -Infinity, -Infinity};
    for (const Vec3 &p : region)
        for (int j = 0; j < nBox; ++j) {
            Vec3 w = p - box[j];
            if (twoD_) w = w - plate_.e2 * Dot(w, plate_.e2);
            const double c[3] = {Dot(w, axis), Dot(w, fb), Dot(w, fc)};
            for (int i = 0; i < 3; ++i) {
                lo[i] = std::min(lo[i], c[i]);
                hi[i] = std::max(hi[i], c[i]);
            }
        }
    auto nearest = [](double l, double h) { return l > 0 ? l : (h < 0 ? -h : 0.0); };
    const double rhoMin = std::hypot(nearest(lo[1], hi[1]), nearest(lo[2], hi[2]));
    const double rhoMax = std::hypot(std::max(std::abs(lo[1]), std::abs(hi[1])), std::max(std::abs(lo[2]), std::abs(hi[2])));
    auto cosine = [](double a, double rho) {
        const double n = std::hypot(a, rho);
        return n > 0 ? a / n : 0.0;
    };
    const double cMax = cosine(hi[0], hi[0] >= 0 ? rhoMin : rhoMax);
    const double cMin = cosine(lo[0], lo[0] >= 0 ? rhoMax : rhoMin);
    return cMax - cMin;
}

// ---- Sensor quadrature ----------------------------------------------------------------------------

namespace {

/// Pixel sensitivity along one axis at offset d from the pixel centre (theory §0 D2), with unit
/// integral: Gaussian N(0, σ²) or box ⊛ Gaussian.
double PixelWeight(double d, double sigma, double pitch, bool gaussian) {
    if (gaussian) return std::exp(-0.5 * d * d / (sigma * sigma)) / (std::sqrt(2 * Pi) * sigma);
    const double s = 1 / (std::sqrt(2.0) * sigma);
    return 0.5 * (std::erf((d + 0.5 * pitch) * s) - std::erf((d - 0.5 * pitch) * s)) / pitch;
}

double WindowHalfWidth(const SensorPlaneGeometry &g, double pitch) {
    return 6 * g.sigma + (g.gaussianPixel ? 0.0 : 0.5 * pitch);
}

/// Uniform nodes over [lo, hi] with spacing ≤ hMax, keeping those within `ext` of a pixel centre
/// c0 + i·pitch (i < n).
std::vector<double> AxisNodes(double lo, double hi, double hMax, double c0, double pitch, int n, double ext,
                              double *h) {
    const long long intervals = std::max(1LL, (long long)std::ceil((hi - lo) / hMax));
    if (intervals > 50000000) throw Error("rs: the sensor grid would need more than 5e7 nodes along an axis");
    *h = (hi - lo) / intervals;
    std::vector<double> out;
    for (long long a = 0; a <= intervals; ++a) {
        const double x = lo + a * *h;
        const double i = std::clamp(std::round((x - c0) / pitch), 0.0, double(n - 1));
        if (std::abs(x - (c0 + i * pitch)) <= ext) out.push_back(x);
    }
    return out;
}

}  // namespace

SensorGrid MakeGrid(const SensorPlaneGeometry &g, const Propagator &prop) {
    SensorGrid grid;
    if (!(g.sigma > 0) || g.nx < 1 || g.ny < 1) throw Error("rs: the sensor plane has no valid pixels");
    const double extX = WindowHalfWidth(g, g.pitchX), extY = WindowHalfWidth(g, g.pitchY);
    const Vec2 c00 = g.PixelCenter(0, 0), c11 = g.PixelCenter(g.nx - 1, g.ny - 1);
    const double xLo = c00.x - extX, xHi = c11.x + extX;  // x grows with i, y falls with j
    const double yLo = c11.y - extY, yHi = c00.y + extY;
    if (prop.TwoD()) {
        const Vec3 e2 = prop.Plate().e2;
        if (std::abs(Dot(g.frame.t, e2)) >= 1 - 1e-9)
            grid.collapseY = true;
        else if (std::abs(Dot(g.frame.s, e2)) >= 1 - 1e-9)
            grid.collapseX = true;
        else
            throw Error("the 2-D mode needs a sensor axis parallel to the slits (the plate's y axis)");
    }
    // Band limit of the intensity along each axis (rs.cpp header): the largest direction spread
    // seen from any point of the window, bounded tile by tile. A tile of size T overestimates the
    // spread by at most ~T/distance, so tiles a quarter of the openings' extent (at most 256 per
    // axis) keep the grid within ~25 % of the spacing the exact maximum would allow.
    const Bounds2 ob = prop.OpeningBounds();
    const double tileMin = ob.Empty() ? Infinity : 0.25 * std::max(ob.hi.x - ob.lo.x, ob.hi.y - ob.lo.y);
    auto tiles = [&](double lo, double hi, bool collapsed) {
        if (collapsed) return 1;
        const double n = std::ceil((hi - lo) / std::max(tileMin, (hi - lo) / 256));
        return std::clamp(int(n), 1, 256);
    };
    const int ns = tiles(xLo, xHi, grid.collapseX), nt = tiles(yLo, yHi, grid.collapseY);
    const double tx = grid.collapseX ? 0 : (xHi - xLo) / ns, ty = grid.collapseY ? 0 : (yHi - yLo) / nt;
    const double x0 = grid.collapseX ? 0.5 * (xLo + xHi) : xLo, y0 = grid.collapseY ? 0.5 * (yLo + yHi) : yLo;
    double spreadS = 0, spreadT = 0;
    for (int a = 0; a < ns; ++a)
        for (int b = 0; b < nt; ++b) {
            const Vec3 corner = g.origin + g.frame.s * (x0 + a * tx) + g.frame.t * (y0 + b * ty);
            const Vec3 es = g.frame.s * tx, et = g.frame.t * ty;
            if (!grid.collapseX) spreadS = std::max(spreadS, prop.DirectionSpread(corner, es, et, g.frame.s));
            if (!grid.collapseY) spreadT = std::max(spreadT, prop.DirectionSpread(corner, es, et, g.frame.t));
        }
    const double k = prop.K();
    if (grid.collapseX) {
        grid.xs = {0.5 * (xLo + xHi)};
        grid.hx = 1;
    } else {
        const double hMax = 2 * Pi / (k * spreadS + prop.Rule().gridMargin / g.sigma);
        grid.xs = AxisNodes(xLo, xHi, hMax, c00.x, g.pitchX, g.nx, extX, &grid.hx);
    }
    if (grid.collapseY) {
        grid.ys = {0.5 * (yLo + yHi)};
        grid.hy = 1;
    } else {
        const double hMax = 2 * Pi / (k * spreadT + prop.Rule().gridMargin / g.sigma);
        // Pixel centres along y run downwards from c00.y; reuse AxisNodes on the reversed axis.
        grid.ys = AxisNodes(yLo, yHi, hMax, c11.y, g.pitchY, g.ny, extY, &grid.hy);
    }
    return grid;
}

int ProgressUnits(const SensorGrid &grid) {
    return int(std::clamp<std::size_t>(grid.Nodes() / 64, 1, 1000));
}

std::vector<double> IntegrateSensor(const SensorPlaneGeometry &g, const Propagator &prop,
                                    const SensorGrid &grid, Quantity q,
                                    const std::function<bool(int)> &batchDone,
                                    const std::atomic<bool> *cancel) {
    const std::size_t nxg = grid.xs.size(), nyg = grid.ys.size(), total = nxg * nyg;
    std::vector<double> field(total, 0.0);
    const int units = ProgressUnits(grid);
    auto cancelled = [&] { return cancel && cancel->load(std::memory_order_relaxed); };
    for (int u = 0; u < units; ++u) {
        const std::size_t begin = total * u / units, end = total * (u + 1) / units;
        tbb::parallel_for(
            tbb::blocked_range<std::size_t>(begin, end, 1), [&](const tbb::blocked_range<std::size_t> &r) {
                for (std::size_t idx = r.begin(); idx < r.end(); ++idx) {
                    if (cancelled()) return;
                    const double x = grid.xs[idx % nxg], y = grid.ys[idx / nxg];
                    const Vec3 p = g.origin + g.frame.s * x + g.frame.t * y;
                    field[idx] = q == Quantity::Flux ? prop.Flux(p, g.frame.n) : prop.Intensity(p);
                }
            });
        if (cancelled() || (batchDone && !batchDone(u + 1))) return {};
    }
    // Separable pixel sums: G(b, i) = Σ_a w_x(x_a − x_i)·F(a, b)·h_x, then Σ_b w_y·G·h_y, over the
    // nodes within each pixel's window (the node lists are sorted).
    struct Taps {
        std::size_t first = 0;
        std::vector<double> w;  // quadrature weights w(node − centre)·h of nodes first, first + 1, …
    };
    auto taps = [&](const std::vector<double> &nodes, double centre, double pitch, double h) {
        const double ext = WindowHalfWidth(g, pitch);
        Taps t;
        t.first = std::size_t(std::lower_bound(nodes.begin(), nodes.end(), centre - ext) - nodes.begin());
        for (std::size_t a = t.first; a < nodes.size() && nodes[a] <= centre + ext; ++a)
            t.w.push_back(PixelWeight(nodes[a] - centre, g.sigma, pitch, g.gaussianPixel) * h);
        return t;
    };
    std::vector<Taps> tapsX(g.nx), tapsY(g.ny);
    if (!grid.collapseX)
        for (int i = 0; i < g.nx; ++i) tapsX[i] = taps(grid.xs, g.PixelCenter(i, 0).x, g.pitchX, grid.hx);
    if (!grid.collapseY)
        for (int j = 0; j < g.ny; ++j) tapsY[j] = taps(grid.ys, g.PixelCenter(0, j).y, g.pitchY, grid.hy);
    std::vector<double> rowSums(nyg * std::size_t(g.nx), 0.0);
    tbb::parallel_for(std::size_t(0), nyg, [&](std::size_t b) {
        for (int i = 0; i < g.nx; ++i) {
            double s = 0;
            if (grid.collapseX) {
                s = field[b * nxg];
            } else {
                const Taps &t = tapsX[i];
                for (std::size_t a = 0; a < t.w.size(); ++a) s += t.w[a] * field[b * nxg + t.first + a];
            }
            rowSums[b * g.nx + i] = s;
        }
    });
    std::vector<double> pixels(std::size_t(g.nx) * g.ny, 0.0);
    tbb::parallel_for(0, g.ny, [&](int j) {
        for (int i = 0; i < g.nx; ++i) {
            double s = 0;
            if (grid.collapseY) {
                s = rowSums[i];
            } else {
                const Taps &t = tapsY[j];
                for (std::size_t b = 0; b < t.w.size(); ++b) s += t.w[b] * rowSums[(t.first + b) * g.nx + i];
            }
            pixels[std::size_t(j) * g.nx + i] = s;
        }
    });
    return pixels;
}

// ---- Slit-end error of the 2-D mode -----------------------------------------------------------------

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

// ---- The integrator ---------------------------------------------------------------------------------

class RsIntegrator final : public Integrator {
  public:
    enum class Mode { Auto, TwoD, ThreeD };
    RsIntegrator(Mode mode, double auto2dTolerance, double accuracy)
        : mode_(mode), auto2dTolerance_(auto2dTolerance), accuracy_(accuracy) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "integrator",
            "rs",
            "Forward Rayleigh-Sommerfeld reference: coherent plane waves / point sources through one "
            "aperture plate onto a virtual_plane (double precision, pixel-integrated flux).",
            {P::String("mode",
                       "2d: slits infinite along the plate's y axis; 3d: full surface integral; auto: 2d "
                       "where it applies (slits, a plane wave without a y component, a sensor axis along "
                       "the slits) and the slit ends' predicted effect is within auto_2d_tolerance")
                 .Default(Value::String("auto"))
                 .Choices({"auto", "2d", "3d"}),
             P::Number("auto_2d_tolerance",
                       "largest predicted error (relative to the local intensity) of ignoring the slit ends "
                       "that `auto` accepts for the 2-D mode")
                 .Default(Value::Number(2e-4))
                 .Min(0),
             P::Number("accuracy",
                       "target accuracy of the quadratures: largest pixel error relative to the row's peak "
                       "(sets the Gauss-Legendre node rule and the sensor grid; docs/rs.md)")
                 .Default(Value::Number(1e-4))
                 .Min(1e-12)
                 .Max(0.1)}};
        return s;
    }
    static std::unique_ptr<Integrator> Create(const ParamDict &d, BuildContext &) {
        const std::string m = d.GetString("mode");
        const Mode mode = m == "2d" ? Mode::TwoD : (m == "3d" ? Mode::ThreeD : Mode::Auto);
        return std::make_unique<RsIntegrator>(mode, d.GetNumber("auto_2d_tolerance"), d.GetNumber("accuracy"));
    }

    RenderStats Render(const Scene &scene, Film &film, const RenderOptions &opt) const override {
        const auto start = std::chrono::steady_clock::now();
        std::unique_ptr<tbb::global_control> threads;
        if (opt.threads > 0)
            threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                            opt.threads);

        // ---- Checks (every unsupported scene is a clear error naming the object) -------------
        const Detector &det = scene.GetDetector();
        const SensorPlaneGeometry *sensor = det.SensorPlane();
        if (!sensor)
            throw Error(scene.Where(&det),
                        "integrator 'rs' needs a virtual_plane detector (a sensor plane); detector '" +
                        det.name + "' is not one");
        if (scene.Lights().empty())
            throw Error(scene.Where(this), "integrator 'rs' needs at least one coherent light; the scene has none");
        for (const Light *light : scene.Lights())
            if (!light->CoherentField())
                throw Error(
                    scene.Where(light),
                    "light '" + light->name +
                    "' has no coherent field: integrator 'rs' needs monochromatic (line-spectrum) plane "
                    "waves, isotropic point lights or Gaussian beams");
        const auto &shapes = scene.Shapes();
        if (shapes.empty())
            throw Error(
                scene.Where(this),
                "integrator 'rs' needs exactly one shape, a planar aperture plate (material with openings, "
                "e.g. 'aperture') between the source and the sensor; the scene has none");
        if (shapes.size() > 1) {
            std::string names;
            for (std::size_t i = 0; i < shapes.size() && i < 6; ++i)
                names += (i ? ", '" : "'") + shapes[i]->name + "'";
            throw Error(
                scene.Where(shapes[1].get()),
                "integrator 'rs' handles exactly one planar aperture plate between source and sensor; the "
                "scene has " +
                std::to_string(shapes.size()) + " shapes (" + names + (shapes.size() > 6 ? ", …" : "") + ")");
        }
        const Shape &shape = *shapes[0];
        const ApertureMask *mask = shape.material ? shape.material->Openings() : nullptr;
        if (!mask)
            throw Error(scene.Where(&shape), "integrator 'rs' needs an aperture plate: shape '" + shape.name +
                        "' has no material with openings (use the 'aperture' material)");
        if (!shape.IsPlanar())
            throw Error(scene.Where(&shape), "integrator 'rs': the aperture plate '" + shape.name + "' is not planar");
        PlateFrame plate;
        try {
            plate = PlateFrame::FromTransform(shape.objectToWorld);
        } catch (const Error &e) {
            throw Error(scene.Where(&shape), "aperture plate '" + shape.name + "': " + e.Message());
        }

        // Sensor side: the whole evaluation window must lie strictly on one side, ≥ 1 λ away.
        const double extX = 6 * sensor->sigma + 0.5 * sensor->pitchX,
                     extY = 6 * sensor->sigma + 0.5 * sensor->pitchY;
        const Vec2 c00 = sensor->PixelCenter(0, 0), c11 = sensor->PixelCenter(sensor->nx - 1, sensor->ny - 1);
        double hMin = Infinity, hMax = -Infinity;
        for (int c = 0; c < 4; ++c) {
            const double x = (c & 1) ? c11.x + extX : c00.x - extX, y = (c & 2) ? c00.y + extY : c11.y - extY;
            const double h =
                Dot(sensor->origin + sensor->frame.s * x + sensor->frame.t * y - plate.origin, plate.n);
            hMin = std::min(hMin, h);
            hMax = std::max(hMax, h);
        }
        if (!(hMin > 0) && !(hMax < 0))
            throw Error(scene.Where(&det), "sensor '" + det.name + "' is not in front of the aperture plate '" + shape.name +
                        "': it reaches the plate's plane");
        const bool flip = hMax < 0;
        const Vec3 towardsSensor = flip ? -plate.n : plate.n;
        if (!(Dot(sensor->frame.n, towardsSensor) < 0))
            throw Error(scene.Where(&det), "sensor '" + det.name + "' is not in front of the aperture plate '" + shape.name +
                        "': its front side (+z) faces away from the plate");

        struct Job {
            const Light *light;
            CoherentWave wave;
            std::unique_ptr<rs::Propagator> prop;
            rs::SensorGrid grid;
        };
        std::vector<Job> jobs;
        int totalUnits = 0;
        for (const Light *light : scene.Lights()) {
            const auto wave = light->CoherentField();
            const double minHeight = std::min(std::abs(hMin), std::abs(hMax));
            if (minHeight < wave->lambda)
                throw Error(scene.Where(&det), "sensor '" + det.name +
                            "' is closer than one wavelength to the aperture plate '" + shape.name +
                            "' (Kirchhoff boundary values need a distant sensor)");
            const bool sameSide = wave->kind != CoherentWave::Kind::Spherical
                                      ? !(Dot(Normalize(wave->dir), towardsSensor) > 0)
                                      : !(Dot(wave->pos - plate.origin, towardsSensor) < 0);
            if (sameSide)
                throw Error(scene.Where(light), "light '" + light->name + "' and sensor '" + det.name +
                            "' are on the same side of the aperture plate '" + shape.name +
                            "' (rs propagates from the source through the plate to the sensor)");
            const bool twoD = Choose2d(scene, *mask, plate, *wave, *sensor, light->name);
            Job job{light, *wave, std::make_unique<rs::Propagator>(plate, *mask, *wave, flip, twoD,
                                                                  rs::QuadratureRule::ForAccuracy(accuracy_)),
                    {}};
            try {
                job.grid = rs::MakeGrid(*sensor, *job.prop);
            } catch (const Error &e) {
                throw Error(scene.Where(&det), "sensor '" + det.name + "': " + e.Message());
            }
            totalUnits += rs::ProgressUnits(job.grid);
            jobs.push_back(std::move(job));
        }

        // Work estimate before the long part: a few field evaluations timed (≤ ~0.5 s per light)
        // times the grid's nodes, on all threads.
        if (opt.warn) {
            double seconds = 0, nodes = 0, perNode = 0;
            for (const Job &job : jobs) {
                const rs::SensorGrid &gr = job.grid;
                const auto t0 = std::chrono::steady_clock::now();
                double elapsed = 0, sink = 0;
                int n = 0;
                for (; n < 8 && (n == 0 || elapsed < 0.5); ++n) {
                    const double x = gr.xs[(n * gr.xs.size()) / 8], y = gr.ys[(n * gr.ys.size()) / 8];
                    sink += job.prop->Flux(sensor->origin + sensor->frame.s * x + sensor->frame.t * y, sensor->frame.n);
                    elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                }
                (void)sink;
                nodes += double(gr.Nodes());
                perNode = std::max(perNode, elapsed / n);
                seconds += elapsed / n * double(gr.Nodes());
            }
            const int threads =
                opt.threads > 0 ? opt.threads : int(std::max(1u, std::thread::hardware_concurrency()));
            char what[160];
            std::snprintf(what, sizeof what, "%.3g field nodes on the sensor grid at %.3g ms each on %d threads",
                          nodes, perNode * 1e3, threads);
            const std::string msg =
                WorkWarning(seconds / threads, what,
                            "the sensor grid and the quadrature over the openings follow the wavelength; a "
                            "longer wavelength (the light's spectrum, e.g. the scene's `lambda`), a smaller sensor "
                            "'extent', shorter openings or mode = \"2d\" for long slits reduce it");
            if (!msg.empty()) opt.warn(msg);
        }

        // ---- Field and pixel integrals, one light at a time (intensities add) ------------------
        RenderStats stats;
        const int nx = sensor->nx, ny = sensor->ny;
        std::size_t fieldPoints = 0;
        std::string modes;
        for (const Job &job : jobs) {
            fieldPoints += job.grid.Nodes();
            const std::string m = job.prop->TwoD() ? "2d" : "3d";
            if (modes.find(m) == std::string::npos) modes += (modes.empty() ? "" : ",") + m;
        }
        std::vector<Vec3> channels(std::size_t(nx) * ny);
        std::vector<double> intensity(std::size_t(nx) * ny, 0.0);
        int unitsDone = 0;
        const double eRef = sensor->referenceIrradiance > 0 ? sensor->referenceIrradiance : 1.0;
        for (const Job &job : jobs) {
            const int base = unitsDone;
            auto onBatch = [&](int done) {
                unitsDone = base + done;
                if (opt.progress) opt.progress(unitsDone, totalUnits);
                return true;
            };
            std::vector<double> flux =
                rs::IntegrateSensor(*sensor, *job.prop, job.grid, rs::Quantity::Flux, onBatch, opt.cancel);
            if (flux.empty()) {
                // Every pixel needs the field over its whole window, so a partial field gives no
                // honest pixel: nothing is written (docs/rs.md "Cancellation").
                stats.cancelled = true;
                stats.hasImage = false;
                stats.work = "stopped after " + std::to_string(unitsDone) + " of " + std::to_string(totalUnits) +
                             " steps of its field integral";
                stats.seconds =
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                return stats;
            }
            const Vec3 wc = film.Response().Channels(job.wave.lambda);
            const double wi = film.Response().Intensity(job.wave.lambda);
            for (std::size_t p = 0; p < flux.size(); ++p) {
                const double v = flux[p] / eRef;
                channels[p] += wc * v;
                intensity[p] += wi * v;
            }
        }
        // Round-off can leave tiny negative sums in dark pixels: those are clamped to 0. A pixel
        // more negative than round-off, or one the film cannot hold (NaN, beyond float), is an
        // invalid sample (counted, written as 0).
        double peak = 0;
        for (double v : intensity) peak = std::max(peak, v);
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const std::size_t p = std::size_t(j) * nx + i;
                Vec3 c = channels[p];
                double v = intensity[p];
                if (v < -1e-9 * peak) {
                    film.AddInvalidSample(i, j);
                    continue;
                }
                c = Vec3(std::max(c.x, 0.0), std::max(c.y, 0.0), std::max(c.z, 0.0));
                film.AddReduced(i, j, c, std::max(v, 0.0));
            }
        // rs evaluates the field deterministically on a grid and integrates it over each pixel: it
        // takes no samples, so it reports its own work, never an spp.
        stats.work = "solved " + std::to_string(std::size_t(nx) * ny) + " pixels (" + std::to_string(nx) + "x" +
                     std::to_string(ny) + ", " + modes + ") from " + std::to_string(fieldPoints) +
                     " field points";
        stats.metadata["phasor:rs_field_points"] = std::to_string(fieldPoints);
        stats.metadata["phasor:rs_mode"] = modes;
        stats.invalidSamples = film.InvalidSampleCount();
        stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return stats;
    }

    bool Deterministic() const override { return true; }

    std::string ToString() const override {
        const char *m = mode_ == Mode::TwoD ? "2d" : (mode_ == Mode::ThreeD ? "3d" : "auto");
        return std::string("rs { mode = ") + m + ", auto_2d_tolerance = " + std::to_string(auto2dTolerance_) +
               ", accuracy = " + std::to_string(accuracy_) + " }";
    }

  private:
    /// Whether the 2-D mode applies (rs.cpp header); throws for `mode = "2d"` when it cannot.
    bool Choose2d(const Scene &scene, const ApertureMask &mask, const PlateFrame &plate, const CoherentWave &wave,
                  const SensorPlaneGeometry &sensor, const std::string &lightName) const {
        if (mode_ == Mode::ThreeD) return false;
        const bool forced = mode_ == Mode::TwoD;
        auto fail = [&](const std::string &why) {
            if (forced) throw Error(scene.Where(this), "integrator 'rs' with mode = \"2d\": " + why);
            return false;
        };
        double v0 = 0, v1 = 0;
        if (!mask.IsSlitsAlongV(0, &v0, &v1))
            return fail(
                "the openings must be rectangles that share one range along the plate's y axis (slits)");
        if (wave.kind != CoherentWave::Kind::Plane || std::abs(Dot(Normalize(wave.dir), plate.e2)) > 1e-9)
            return fail("light '" + lightName + "' must be a plane wave with no component along the slits");
        const bool alongT = std::abs(Dot(sensor.frame.t, plate.e2)) >= 1 - 1e-9;
        const bool alongS = std::abs(Dot(sensor.frame.s, plate.e2)) >= 1 - 1e-9;
        if (!alongT && !alongS)
            return fail("a sensor axis must be parallel to the slits (the plate's y axis)");
        if (forced) return true;
        // auto: the slit ends' predicted effect on every pixel (docs/rs.md "2-D mode selection").
        Bounds2 slits = mask.Bounds();
        slits.lo.y = v0;
        slits.hi.y = v1;
        return rs::SlitEndError(plate, slits, sensor, 2 * Pi / wave.lambda) <= auto2dTolerance_;
    }

    Mode mode_;
    double auto2dTolerance_, accuracy_;
};

PHASOR_EXPORT_PLUGIN(Integrator, RsIntegrator)

}  // namespace phasor
