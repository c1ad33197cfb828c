// SPDX-License-Identifier: Apache-2.0
// phasor — the footprint integral of the `aperture` kernel (aperture_integral.h, theory §9).
#include "materials/aperture_integral.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "core/numerics/faddeeva.h"
#include "core/numerics/gauss_legendre.h"
#include "core/render/narrow_pixels.h"

namespace phasor {

namespace {

constexpr double SqrtPi = 1.77245385090551602730;

// ---- Gauss–Legendre orders ------------------------------------------------------------------------

// The orders a panel may use (the rules themselves: core/numerics/gauss_legendre.h).
constexpr int MaxOrder = 64;
static_assert(MaxOrder <= MaxGaussLegendreNodes);
constexpr int Orders[] = {2, 3, 4, 5, 6, 8, 10, 12, 14, 16, 20, 24, 28, 32, 40, 48, 56, 64};

// ---- Quadrature order ------------------------------------------------------------------------------
//
// On a panel mapped to t ∈ [−1, 1] the integrand is modelled by its dominant factors
// exp(c1·t + c2·t²) (one "term" per edge or interior line of the piece; c1, c2 complex). For a
// function analytic inside the Bernstein ellipse E_ρ (semi-axes a = (ρ+1/ρ)/2, b = (ρ−1/ρ)/2) and
// bounded there by M, n-point Gauss–Legendre errs by at most 64·M/(15(ρ²−1)ρ^{2n}) (Trefethen,
// "Is Gauss quadrature better than Clenshaw–Curtis?", SIAM Rev. 50, 2008, Thm 4.5). On E_ρ,
//   Re(c1 t) ≤ √((Re c1·a)² + (Im c1·b)²),  Re(c2 t²) ≤ |Re c2|·b² (Re c2 ≤ 0) or Re c2·a²,
//   plus |Im c2|·a·b,
// and the bound is taken relative to the term's maximum on [−1, 1]. The order is the smallest
// n for which some ρ of a fixed grid gives a relative error ≤ PanelTolerance; the model is checked
// against adaptive brute-force quadrature in tests/materials/aperture_test.cpp.
constexpr double PanelTolerance = 1e-13;

struct Term {
    Complex c1, c2;
};

struct Plan {
    const GaussLegendreRule *rule;
    int panels;
};

struct EllipseGrid {
    static constexpr int N = 10;
    double a[N], b[N], logNum[N], twoLogRho[N];  // logNum = log(64/15) − log(ρ²−1) − log tol
};
const EllipseGrid &Ellipses() {
    static const EllipseGrid g = [] {
        EllipseGrid e{};
        const double rho[EllipseGrid::N] = {1.08, 1.2, 1.4, 1.7, 2.1, 2.8, 4, 6, 10, 20};
        for (int i = 0; i < EllipseGrid::N; ++i) {
            const double r = rho[i];
            e.a[i] = 0.5 * (r + 1 / r);
            e.b[i] = 0.5 * (r - 1 / r);
            e.logNum[i] = std::log(64.0 / 15) - std::log(r * r - 1) - std::log(PanelTolerance);
            e.twoLogRho[i] = 2 * std::log(r);
        }
        return e;
    }();
    return g;
}

// Max of Re(c1 t + c2 t²) over t ∈ [−1, 1] (≥ 0: t = 0).
double RealMax(const Term &t) {
    const double r1 = t.c1.real(), r2 = t.c2.real();
    double m = std::max({0.0, r1 + r2, -r1 + r2});
    if (r2 < 0) {
        const double ts = -r1 / (2 * r2);
        if (ts > -1 && ts < 1) m = std::max(m, -r1 * r1 / (4 * r2));
    }
    return m;
}

// Smallest number of nodes for one panel of the given terms (scaled by 1/p: p panels).
int NodesFor(const Term *terms, int nt, double p) {
    const EllipseGrid &e = Ellipses();
    Term t[4];
    double realMax[4];
    for (int j = 0; j < nt; ++j) {
        t[j] = {terms[j].c1 / p, terms[j].c2 / (p * p)};
        realMax[j] = RealMax(t[j]);
    }
    double best = Infinity;
    for (int i = 0; i < EllipseGrid::N; ++i) {
        double excess = 0;
        for (int j = 0; j < nt; ++j) {
            const double la = t[j].c1.real() * e.a[i], lb = t[j].c1.imag() * e.b[i];
            const double r2 = t[j].c2.real();
            const double quad = (r2 <= 0 ? -r2 * e.b[i] * e.b[i] : r2 * e.a[i] * e.a[i]) +
                                std::abs(t[j].c2.imag()) * e.a[i] * e.b[i];
            excess = std::max(excess, std::sqrt(la * la + lb * lb) + quad - realMax[j]);
        }
        best = std::min(best, (e.logNum[i] + excess) / e.twoLogRho[i]);
    }
    return best < 1e6 ? int(std::ceil(best)) : 1 << 20;  // (also for non-finite input)
}

// At most MaxPanels panels (65 536 nodes) per strip: beyond that the integrand oscillates
// ~10⁴ times over the strip, which only a far-off-lobe direction of a huge footprint does; the
// cost stays bounded and the (tiny) value loses accuracy.
constexpr int MaxPanels = 1024;

Plan PlanFor(const Term *terms, int nt) {
    int panels = 1, n = NodesFor(terms, nt, 1);
    while (n > MaxOrder && panels < MaxPanels) {
        panels *= 2;
        n = NodesFor(terms, nt, panels);
    }
    for (int order : Orders)
        if (order >= n) return {&GaussLegendre(order), panels};
    return {&GaussLegendre(MaxOrder), panels};
}

inline Complex ExpC(double re, double im) {
    const double m = std::exp(re);
    return {m * std::cos(im), m * std::sin(im)};
}

// sin and cos of n arguments (vectorisable): Cody–Waite reduction by π/2 with a three-part
// constant (fdlibm's split; exact quotient for |x| < 2^20·π/2) and Taylor polynomials on
// |r| ≤ π/4 to r¹⁷ / r¹⁸ (truncation < 5·10⁻¹⁷); |error| ≤ 3·10⁻¹⁶ there. Larger arguments fall
// back to libm. About twice as fast as libm's sincos, which dominated the quadrature's cost.
void SinCosBatch(int n, const double *x, double *s, double *c) {
    constexpr double TwoOverPi = 0.63661977236758134308, Magic = 6755399441055744.0;  // 1.5·2⁵²
    constexpr double P1 = 1.57079632673412561417e+00, P2 = 6.07710050630396597660e-11,
                     P3 = 2.02226624879595063154e-21;
    constexpr double Limit = 1.6e6;
    bool small = true;
    for (int i = 0; i < n; ++i) small &= std::abs(x[i]) < Limit;
    if (!small) {
        for (int i = 0; i < n; ++i) s[i] = std::sin(x[i]), c[i] = std::cos(x[i]);
        return;
    }
    for (int i = 0; i < n; ++i) {
        const double q = (x[i] * TwoOverPi + Magic) - Magic;  // nearest integer to 2x/π
        const double r = ((x[i] - q * P1) - q * P2) - q * P3;
        const double r2 = r * r;
        const double sp =
            r + r * r2 *
                    (-1.0 / 6 +
                     r2 * (1.0 / 120 +
                           r2 * (-1.0 / 5040 +
                                 r2 * (1.0 / 362880 + r2 * (-1.0 / 39916800 +
                                                            r2 * (1.0 / 6227020800 +
                                                                  r2 * (-1.0 / 1307674368000 +
                                                                        r2 * (1.0 / 355687428096000))))))));
        const double cp =
            1 + r2 * (-0.5 +
                      r2 * (1.0 / 24 +
                            r2 * (-1.0 / 720 +
                                  r2 * (1.0 / 40320 + r2 * (-1.0 / 3628800 +
                                                            r2 * (1.0 / 479001600 +
                                                                  r2 * (-1.0 / 87178291200 +
                                                                        r2 * (1.0 / 20922789888000 -
                                                                              r2 / 6402373705728000.0))))))));
        // Quadrant m = q mod 4 without branches (so that the loop vectorises).
        const double f = (q * 0.25 + Magic) - Magic;
        const double m0 = q - 4 * f;                                // in {−2, …, 2}
        const double m = m0 + 2 * (1 - std::copysign(1.0, m0));     // in {0, 1, 2, 3}
        const double hi = 0.5 + 0.5 * std::copysign(1.0, m - 1.5);  // m ≥ 2
        const double swap = m - 2 * hi;                             // m odd
        const double signS = 1 - 2 * hi, signC = 1 - 2 * (hi + swap - 2 * hi * swap);
        s[i] = signS * (sp + swap * (cp - sp));
        c[i] = signC * (cp + swap * (sp - cp));
    }
}

// Terms whose exponent has a real part below CutExponent (|integrand| ≤ 1 everywhere, so they
// are < 1e-13 of the integrand's peak) are dropped.
constexpr double CutExponent = -30;

// The short-interval test |Δz|·max(1, |z_l|, |z_h|) < 0.3, in squared norms (no hypot).
inline bool ShortInterval(const Complex &zl, const Complex &zh) {
    return std::norm(zh - zl) * std::max({1.0, std::norm(zl), std::norm(zh)}) < 0.09;
}

// Insertion sort of a few break points (std::sort on a small array trips GCC 12's -Warray-bounds).
void SortSmall(double *v, int n) {
    for (int i = 1; i < n; ++i)
        for (int j = i; j > 0 && v[j] < v[j - 1]; --j) std::swap(v[j], v[j - 1]);
}

// ---- One strip: GL along s, closed form along x -----------------------------------------------------

// The exponent of one piece, c0 − (axx x² + 2axy xy + ayy y²) + i(bx x + by y), in plate
// coordinates relative to the hit point; b and c0 are complex once the beams' evolution along
// their axes is re-expanded about the piece (Expand).
struct Quadratic {
    Complex axx, axy, ayy, bx, by, c0;
};

constexpr Complex I1{0, 1};

// Value, gradient and Hessian of a correction to the exponent at one point.
struct Jet {
    Complex f, g[2], h[2][2];
};

// The traced GR's exact paraxial beam minus its quadratic form at the hit point (PlateGaussian):
// Δf = (ik/2)·T·(1/(q+a) − 1/q) − ln(1 + a/q), a = d·Δ, T = |Δ|² − a² (the Gaussian beam
// ψ ∝ (q/(q+a))·exp(ik a + ikT/(2(q+a))), Siegman, "Lasers", §16.7; q grows along the traced d).
Jet BeamCorrection(const PlateGaussian &g, double x, double y) {
    const double d[2] = {g.d1, g.d2}, p[2] = {x, y};
    const double a = g.d1 * x + g.d2 * y, t = x * x + y * y - a * a;
    const Complex u = g.invQ / (1.0 + a * g.invQ);  // 1/(q + a)
    const Complex w = -a * g.invQ * u;              // 1/(q + a) − 1/q, without cancellation
    const Complex ik2 = 0.5 * g.k * I1;
    Jet j;
    j.f = ik2 * t * w - std::log(1.0 + a * g.invQ);
    double dt[2];
    Complex du[2];
    for (int i = 0; i < 2; ++i) {
        dt[i] = 2 * (p[i] - a * d[i]);
        du[i] = -u * u * d[i];
        j.g[i] = ik2 * (dt[i] * w + t * du[i]) - u * d[i];
    }
    for (int i = 0; i < 2; ++i)
        for (int l = 0; l < 2; ++l) {
            const double ddt = 2 * ((i == l ? 1.0 : 0.0) - d[i] * d[l]);
            const Complex ddu = 2.0 * u * u * u * (d[i] * d[l]);
            j.h[i][l] = ik2 * (ddt * w + dt[i] * du[l] + dt[l] * du[i] + t * ddu) + u * u * (d[i] * d[l]);
        }
    return j;
}

// The exact spherical wave (R/r)·e^{ik(r − R)}, r = |Δ + R s|, minus its quadratic form at the
// hit point ik(a_s + (|Δ|² − a_s²)/(2R)), a_s = s·Δ.
Jet SphereCorrection(const PlateGaussian &g, double x, double y) {
    const double R = g.dist, s[2] = {g.s1, g.s2}, p[2] = {x, y};
    const double as = g.s1 * x + g.s2 * y, p2 = x * x + y * y;
    const double r = std::sqrt(R * R + 2 * R * as + p2), e = (2 * R * as + p2) / (r + R);  // e = r − R
    const double nv[2] = {(R * s[0] + x) / r, (R * s[1] + y) / r};                          // ∇r
    Jet j;
    j.f = I1 * (g.k * (e - as - (p2 - as * as) / (2 * R))) - std::log1p(e / R);
    for (int i = 0; i < 2; ++i) j.g[i] = I1 * (g.k * (nv[i] - s[i] - (p[i] - as * s[i]) / R)) - nv[i] / r;
    for (int i = 0; i < 2; ++i)
        for (int l = 0; l < 2; ++l) {
            const double del = i == l ? 1.0 : 0.0;
            j.h[i][l] = I1 * (g.k * ((del - nv[i] * nv[l]) / r - (del - s[i] * s[l]) / R)) -
                        (del - 2 * nv[i] * nv[l]) / (r * r);
        }
    return j;
}

// An incident Gaussian beam (AddIncidentBeam) relative to its on-axis amplitude at the hit's
// axial position, minus the plane wave e^{ik s·Δ} of the quadratic form: with a = A·Δ (A = the
// axis on the plate), T = |off + Δ|² − a² (the squared distance from the axis) and u = 1/(q + a),
//     Δf = −ln(1 + a/q) + ik a + (ik/2)·T·u − ik s·Δ
// (the beam of GaussianBeamGeometry; q(z) = q + a along the plate).
Jet IncidentBeamCorrection(const PlateGaussian &g, double x, double y) {
    const double A[2] = {g.ba1, g.ba2}, o[2] = {g.bo1, g.bo2}, s[2] = {g.s1, g.s2}, p[2] = {x, y};
    const double a = A[0] * x + A[1] * y;
    const double t = g.bOff2 + 2 * (o[0] * x + o[1] * y) + x * x + y * y - a * a;
    const Complex u = 1.0 / (g.bq + a);
    const Complex ik = I1 * g.k, ik2 = 0.5 * ik;
    Jet j;
    j.f = -std::log(1.0 + a / g.bq) + ik * (a - s[0] * x - s[1] * y) + ik2 * t * u;
    double dt[2];
    Complex du[2];
    for (int i = 0; i < 2; ++i) {
        dt[i] = 2 * (o[i] + p[i] - a * A[i]);
        du[i] = -u * u * A[i];
        j.g[i] = -u * A[i] + ik * (A[i] - s[i]) + ik2 * (dt[i] * u + t * du[i]);
    }
    for (int i = 0; i < 2; ++i)
        for (int l = 0; l < 2; ++l) {
            const double ddt = 2 * ((i == l ? 1.0 : 0.0) - A[i] * A[l]);
            const Complex ddu = 2.0 * u * u * u * (A[i] * A[l]);
            j.h[i][l] = u * u * (A[i] * A[l]) + ik2 * (ddt * u + dt[i] * du[l] + dt[l] * du[i] + t * ddu);
        }
    return j;
}

// Sum of two corrections.
void AddJet(Jet *j, const Jet &b) {
    j->f += b.f;
    for (int i = 0; i < 2; ++i) {
        j->g[i] += b.g[i];
        for (int l = 0; l < 2; ++l) j->h[i][l] += b.h[i][l];
    }
}

// ---- A pixel state's non-paraxial field (PixelWavelet) -------------------------------------------

// Value, gradient and Hessian in the plate coordinates (x, y), forward mode: enough arithmetic to
// write the log-integrand once (WaveletLog) and get its Jet.
struct CJet {
    Complex v, gx, gy, hxx, hxy, hyy;
};
CJet Seed(double v, int axis) {  // the coordinate x (axis 0) or y (axis 1)
    CJet j{v, 0, 0, 0, 0, 0};
    (axis == 0 ? j.gx : j.gy) = 1;
    return j;
}
CJet operator+(const CJet &a, const CJet &b) {
    return {a.v + b.v, a.gx + b.gx, a.gy + b.gy, a.hxx + b.hxx, a.hxy + b.hxy, a.hyy + b.hyy};
}
CJet operator-(const CJet &a, const CJet &b) {
    return {a.v - b.v, a.gx - b.gx, a.gy - b.gy, a.hxx - b.hxx, a.hxy - b.hxy, a.hyy - b.hyy};
}
CJet operator+(const CJet &a, Complex c) { return {a.v + c, a.gx, a.gy, a.hxx, a.hxy, a.hyy}; }
CJet operator+(Complex c, const CJet &a) { return a + c; }
CJet operator-(const CJet &a, Complex c) { return {a.v - c, a.gx, a.gy, a.hxx, a.hxy, a.hyy}; }
CJet operator-(Complex c, const CJet &a) { return {c - a.v, -a.gx, -a.gy, -a.hxx, -a.hxy, -a.hyy}; }
CJet operator*(Complex c, const CJet &a) { return {c * a.v, c * a.gx, c * a.gy, c * a.hxx, c * a.hxy, c * a.hyy}; }
CJet operator*(const CJet &a, const CJet &b) {
    return {a.v * b.v,
            a.gx * b.v + a.v * b.gx,
            a.gy * b.v + a.v * b.gy,
            a.hxx * b.v + 2.0 * a.gx * b.gx + a.v * b.hxx,
            a.hxy * b.v + a.gx * b.gy + a.gy * b.gx + a.v * b.hxy,
            a.hyy * b.v + 2.0 * a.gy * b.gy + a.v * b.hyy};
}
// f(a) for a scalar function with derivatives d1 = f'(a.v), d2 = f''(a.v).
CJet Chain(const CJet &a, Complex f, Complex d1, Complex d2) {
    return {f,
            d1 * a.gx,
            d1 * a.gy,
            d1 * a.hxx + d2 * a.gx * a.gx,
            d1 * a.hxy + d2 * a.gx * a.gy,
            d1 * a.hyy + d2 * a.gy * a.gy};
}
CJet Inverse(const CJet &a) {
    const Complex i = 1.0 / a.v;
    return Chain(a, i, -i * i, 2.0 * i * i * i);
}
CJet operator/(const CJet &a, const CJet &b) { return a * Inverse(b); }
CJet Sqrt(const CJet &a) {
    const Complex r = std::sqrt(a.v);
    return Chain(a, r, 0.5 / r, -0.25 / (r * a.v));
}
CJet Log(const CJet &a) {
    const Complex i = 1.0 / a.v;
    return Chain(a, std::log(a.v), i, -i * i);
}
Complex Inverse(Complex a) { return 1.0 / a; }
Complex Sqrt(Complex a) { return std::sqrt(a); }
Complex Log(Complex a) { return std::log(a); }

// The log of K·H·√w_n of PixelWavelet at the plate offset (x, y) from the hit point, minus
// ik·rRef and w.ref, for T = Complex (a value) or CJet (with derivatives).
template <class T>
T WaveletLog(const PixelWavelet &w, const T &x, const T &y) {
    const Vec3 &e1 = w.e1, &e2 = w.e2;
    // D = dRef + x e1 + y e2; its components along the sensor frame and its length.
    auto along = [&](const Vec3 &a) { return Dot(w.dRef, a) + Complex(Dot(e1, a)) * x + Complex(Dot(e2, a)) * y; };
    const T ds = along(w.sensor.s), dt = along(w.sensor.t), dn = along(w.sensor.n);
    const T dd = Complex(2 * Dot(w.dRef, e1)) * x + Complex(2 * Dot(w.dRef, e2)) * y + x * x + y * y;  // |D|² − r²_ref
    const T r = Sqrt(Complex(w.rRef * w.rRef) + dd);
    const T inv = Inverse(r);
    const T e = dd / (r + Complex(w.rRef));  // r − rRef without cancellation
    const T ws = ds * inv, wt = dt * inv;
    const Complex ik(0, w.k);
    const double c = 0.5 / w.beta2;
    const T kap = Complex(0, -0.5 * w.k) * inv;  // −ik/(2r)
    const T qxx = Complex(c) + kap * (Complex(1) - ws * ws), qxy = Complex(-1) * kap * ws * wt,
            qyy = Complex(c) + kap * (Complex(1) - wt * wt);
    const T det = qxx * qyy - qxy * qxy;
    const T bs = Complex(w.k) * (ws - Complex(w.label.x)), bt = Complex(w.k) * (wt - Complex(w.label.y));
    const T quad = (qyy * bs * bs - Complex(2) * qxy * bs * bt + qxx * bt * bt) / det;
    // log H = ½·log(π/β²) − ½·log det Q − ¼·bᵀQ⁻¹b  (Im det Q < 0 for |w⊥| < 1: no branch cut)
    const T logH = Complex(0.5 * std::log(Pi / w.beta2)) - Complex(0.5) * Log(det) - Complex(0.25) * quad;
    // log K = log(c_p/(2π)) + log(1 − ikr) − 2·log r + ik·r, with D·n_plate constant over the plate.
    const double cpn = std::abs(Dot(w.dRef, w.np));
    const T logK = Complex(std::log(cpn / (2 * Pi))) - Log(r) + Log(Complex(1) - ik * r) - Complex(2) * Log(r) + ik * e;
    // √w_n = √(D·n/r)
    const T logW = Complex(0.5) * (Log(dn) - Log(r));
    return logK + logH + logW + Complex(-w.ref);
}

Jet ToJet(const CJet &c) {
    Jet j;
    j.f = c.v;
    j.g[0] = c.gx, j.g[1] = c.gy;
    j.h[0][0] = c.hxx, j.h[0][1] = j.h[1][0] = c.hxy, j.h[1][1] = c.hyy;
    return j;
}

// The exact incident wave at the plate offset (x, y) from the hit point, relative to its value
// there: e^{ik s·Δ} for a plane wave, the exact spherical wave (R/r)·e^{ik(r−R)} of a source at
// dist, or the Gaussian beam of AddIncidentBeam (theory §9; per unit amplitude at the hit).
Jet IncidentJet(const PlateGaussian &g, double x, double y) {
    const Complex ik(0, g.k);
    const double s[2] = {g.s1, g.s2}, p[2] = {x, y};
    const double as = g.s1 * x + g.s2 * y;
    Jet j;
    j.f = ik * as;
    for (int i = 0; i < 2; ++i) j.g[i] = ik * s[i];
    if (std::isfinite(g.dist) && g.dist > 0) {
        // The quadratic form ik(|Δ|² − a_s²)/(2R) of MakePlateGaussian plus the exact remainder.
        const double R = g.dist;
        j.f += ik * (x * x + y * y - as * as) / (2 * R);
        for (int i = 0; i < 2; ++i) {
            j.g[i] += ik * (p[i] - as * s[i]) / R;
            for (int l = 0; l < 2; ++l) j.h[i][l] += ik * ((i == l ? 1.0 : 0.0) - s[i] * s[l]) / R;
        }
        AddJet(&j, SphereCorrection(g, x, y));
    }
    if (g.beam) AddJet(&j, IncidentBeamCorrection(g, x, y));
    return j;
}

// The whole integrand of a pixel state (incident wave × K·H·√w_n), as a Jet at (x, y) from the hit.
Jet IntegrandJet(const PlateGaussian &g, const PixelWavelet &w, double x, double y) {
    Jet j = ToJet(WaveletLog(w, Seed(x, 0), Seed(y, 1)));
    AddJet(&j, IncidentJet(g, x, y));
    return j;
}
// Its value only.
Complex IntegrandLog(const PlateGaussian &g, const PixelWavelet &w, double x, double y) {
    return WaveletLog(w, Complex(x), Complex(y)) + IncidentJet(g, x, y).f;
}

// The quadratic form plus the correction j (its value, gradient and Hessian at (cx, cy)) as one
// quadratic: the second-order Taylor expansion about (cx, cy) rewritten in p.
Quadratic TaylorAbout(const PlateGaussian &g, const Jet &j, double cx, double cy) {
    const double c[2] = {cx, cy};
    Complex lin[2];  // G − H c
    for (int i = 0; i < 2; ++i) lin[i] = j.g[i] - (j.h[i][0] * c[0] + j.h[i][1] * c[1]);
    Quadratic e;
    e.axx = g.axx - 0.5 * j.h[0][0];
    e.axy = g.axy - 0.25 * (j.h[0][1] + j.h[1][0]);
    e.ayy = g.ayy - 0.5 * j.h[1][1];
    e.bx = g.bx - I1 * lin[0];
    e.by = g.by - I1 * lin[1];
    e.c0 = j.f - (j.g[0] * c[0] + j.g[1] * c[1]) +
           0.5 * (c[0] * (j.h[0][0] * c[0] + j.h[0][1] * c[1]) + c[1] * (j.h[1][0] * c[0] + j.h[1][1] * c[1]));
    return e;
}

// TaylorAbout, or nullopt if that is not a decaying Gaussian.
std::optional<Quadratic> ExpandWith(const PlateGaussian &g, const Jet &j, double cx, double cy, double x0,
                                    double x1, double y0, double y1) {
    const Quadratic e = TaylorAbout(g, j, cx, cy);
    const double rxx = e.axx.real(), rxy = e.axy.real(), ryy = e.ayy.real();
    const bool ok = rxx > 0 && ryy > 0 && rxx * ryy > rxy * rxy && std::isfinite(e.c0.imag()) &&
                    e.c0.real() < 700 && std::isfinite(std::abs(e.bx) + std::abs(e.by));
    if (!ok) return std::nullopt;
    // Every factor of the integrand (unit-amplitude GR, beam relative to its axis) has |·| ≤ 1:
    // an expansion that grows above that inside the box has left its range of validity (a
    // decaying form's maximum over the box is at its peak, clamped, or on the boundary).
    auto re = [&](double x, double y) {
        return e.c0.real() - (e.axx.real() * x * x + 2 * e.axy.real() * x * y + e.ayy.real() * y * y) -
               (e.bx.imag() * x + e.by.imag() * y);
    };
    const double det = rxx * ryy - rxy * rxy;
    const double px = std::clamp((-e.bx.imag() * ryy + e.by.imag() * rxy) / (2 * det), x0, x1);
    const double py = std::clamp((-e.by.imag() * rxx + e.bx.imag() * rxy) / (2 * det), y0, y1);
    double peak = re(px, py);
    for (double x : {x0, x1, px})
        for (double y : {y0, y1, py}) peak = std::max(peak, re(x, y));
    if (!(peak < 1)) return std::nullopt;
    return e;
}

// The exponent for a piece whose (piece ∩ window) is the box [x0, x1] × [y0, y1], centred at
// (cx, cy): the hit point's
// quadratic form plus the second-order Taylor expansion of the corrections about the centre,
// Δf ≈ Δf(c) + G·(p − c) + ½(p − c)ᵀH(p − c) rewritten in p. Falls back to the plain form if the
// expansion would not be a decaying Gaussian (a footprint deeper than the GR's Rayleigh range).
// An incident Gaussian beam is expanded about the piece even when the GR's own evolution is not
// (its amplitude varies across the footprint; dropping it would leave a plane wave).
Quadratic Expand(const PlateGaussian &g, double x0, double x1, double y0, double y1) {
    double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
    if (g.wavelet) {
        // The whole integrand about the centre of (piece ∩ tile); IntegrateWavelet sized the tile
        // so that this holds (the real part need not decay over a finite tile: the closed forms
        // are exact for any complex quadratic there).
        const Jet j = IntegrandJet(g, *g.wavelet, g.shift.x + cx, g.shift.y + cy);
        return TaylorAbout(g, j, cx, cy);
    }
    const Quadratic plain{g.axx, g.axy, g.ayy, g.bx, g.by, 0};
    const bool finite = std::isfinite(cx) && std::isfinite(cy);
    if (!finite || (!g.evolve && !g.beam)) return plain;
    if (g.beam) {
        // Expand where the integrand lives: the peak of |GR × beam|, between the hit (the GR's
        // centre) and the beam's spot on the plate (the point nearest its axis, Δ* =
        // −(I − AAᵀ)⁻¹·off), weighted by their decay rates, clamped to the box. About the box's
        // centre the neglected third-order term k·|A|·δ³/|q|² grows with the spot's distance δ
        // (a tilted beam 200 µm off the hit: tens of per cent).
        const double a2 = g.ba1 * g.ba1 + g.ba2 * g.ba2, ao = g.ba1 * g.bo1 + g.ba2 * g.bo2;
        const double sx = -(g.bo1 + g.ba1 * ao / std::max(1 - a2, 1e-12));
        const double sy = -(g.bo2 + g.ba2 * ao / std::max(1 - a2, 1e-12));
        const double wg = 0.5 * (g.axx.real() + g.ayy.real());  // ≈ 1/(2β²) of the GR on the plate
        const double wb = 0.5 * g.k * (1.0 / (g.bq + (g.ba1 * sx + g.ba2 * sy))).imag();  // 1/(2β_b²)
        if (wb > 0 && wg >= 0) {
            const double t = wb / (wg + wb);
            cx = std::clamp(t * sx, x0, x1);
            cy = std::clamp(t * sy, y0, y1);
        }
    }
    const Jet beam = g.beam ? IncidentBeamCorrection(g, cx, cy) : Jet{};
    if (g.evolve) {
        Jet j = BeamCorrection(g, cx, cy);
        if (std::isfinite(g.dist) && g.dist > 0) AddJet(&j, SphereCorrection(g, cx, cy));
        if (g.beam) AddJet(&j, beam);
        if (auto e = ExpandWith(g, j, cx, cy, x0, x1, y0, y1)) return *e;
    }
    if (!g.beam) return plain;
    // An incident beam is never dropped: without it the integrand would be a plane wave of the
    // axis irradiance everywhere.
    if (auto e = ExpandWith(g, beam, cx, cy, x0, x1, y0, y1)) return *e;
    // Last resort: the plane wave scaled by the beam's amplitude at the centre (bounded by 1).
    Quadratic scaled = plain;
    scaled.c0 = beam.f.real();
    return scaled;
}


// The integrand in the orientation used for a piece: x is the closed-form axis, y the quadrature
// axis; hx = far × the window along x, hy = the window along y.
struct Oriented {
    Complex axx, axy, ayy, bx, by, c0;
    double hx, hy;
    // Derived.
    Complex sa, inv2a, inv4a, k;  // √axx, 1/(2axx), 1/(4axx), √π/(2√axx)
};

Oriented Orient(const Quadratic &q, const PlateGaussian &g, bool transpose) {
    Oriented o;
    if (!transpose) {
        o.axx = q.axx, o.ayy = q.ayy, o.bx = q.bx, o.by = q.by, o.hx = g.far * g.hx, o.hy = g.hy;
    } else {
        o.axx = q.ayy, o.ayy = q.axx, o.bx = q.by, o.by = q.bx, o.hx = g.far * g.hy, o.hy = g.hx;
    }
    o.axy = q.axy;
    o.c0 = q.c0;
    o.sa = std::sqrt(o.axx);  // principal root: Re > 0 since Re axx > 0
    o.inv2a = 0.5 / o.axx;
    o.inv4a = 0.25 / o.axx;
    o.k = SqrtPi / (2.0 * o.sa);
    return o;
}

// Exponent c0 − (axx x² + 2axy xy + ayy y²) + i(bx x + by y).
inline Complex Exponent(const Oriented &o, double x, double y) {
    return o.c0 - (o.axx * (x * x) + o.axy * (2 * x * y) + o.ayy * (y * y)) + I1 * (o.bx * x + o.by * y);
}

// ∂Φ/∂x and ∂Φ/∂y of the exponent at (x, y).
inline Complex DxPhi(const Oriented &o, double x, double y) {
    return I1 * o.bx - 2.0 * (o.axx * x + o.axy * y);
}
inline Complex DyPhi(const Oriented &o, double x, double y) {
    return I1 * o.by - 2.0 * (o.axy * x + o.ayy * y);
}

// Quadrature plan for y ∈ [y0, y1] (y = s) with linear limits x = xl + sl·(y − ym),
// x = xh + sh·(y − ym), ym the midpoint: the exponent along the lines between the limits.
Plan LinearPlan(const Oriented &o, double y0, double y1, double xl, double sl, double xh, double sh) {
    const double mid = 0.5 * (y0 + y1), half = 0.5 * (y1 - y0);
    Term t[3];
    for (int j = 0; j < 3; ++j) {
        const double lam = 0.5 * j, x = (1 - lam) * xl + lam * xh, sg = (1 - lam) * sl + lam * sh;
        t[j].c1 = half * (DxPhi(o, x, mid) * sg + DyPhi(o, x, mid));
        t[j].c2 = -(half * half) * (o.axx * (sg * sg) + o.axy * (2 * sg) + o.ayy);
    }
    return PlanFor(t, 3);
}

// ∫_{s0}^{s1} jac(s) ∫_{xl(s)}^{xh(s)} exp(Exponent(x, y(s))) dx ds; `lim(n, s, y, xl, xh, jac)`
// gives the strip's geometry at n parameter values; `plan` is the quadrature (see PlanFor).
template <typename Limits>
Complex IntegrateStrip(const Oriented &o, double s0, double s1, const Plan &plan, const Limits &lim) {
    if (!(s1 > s0)) return 0;
    const GaussLegendreRule &rule = *plan.rule;
    const GaussLegendreRule &short8 = GaussLegendre(8);  // for very short x-intervals
    constexpr int MaxEdges = 2 * MaxOrder;
    double sv[MaxOrder], yv[MaxOrder], xlv[MaxOrder], xhv[MaxOrder], jv[MaxOrder];
    double zr[MaxEdges], zi[MaxEdges], er[MaxEdges], ei[MaxEdges], coef[MaxEdges], wr[MaxEdges], wi[MaxEdges],
        sn[MaxEdges], cs[MaxEdges];
    double fr[MaxOrder], fi[MaxOrder], fcoef[MaxOrder];
    Complex sumK = 0, sumDirect = 0;  // terms to multiply by √π/(2√axx), and direct ones
    const double panelLen = (s1 - s0) / plan.panels;
    for (int p = 0; p < plan.panels; ++p) {
        const double mid = s0 + (p + 0.5) * panelLen, half = 0.5 * panelLen;
        for (int j = 0; j < rule.n; ++j) sv[j] = mid + half * rule.x[std::size_t(j)];
        lim(rule.n, sv, yv, xlv, xhv, jv);
        int edges = 0, fulls = 0;
        for (int j = 0; j < rule.n; ++j) {
            const double y = yv[j], xl = xlv[j], xh = xhv[j];
            if (!(xh > xl)) continue;
            const double wj = half * rule.w[std::size_t(j)] * jv[j];
            // Inner integral over x: α = axx, β = −2axy y + i bx, m = β/(2α), z = √α(x − m).
            const Complex beta = I1 * o.bx - o.axy * (2 * y);
            const Complex m = beta * o.inv2a;
            const Complex zl = o.sa * (xl - m), zh = o.sa * (xh - m);
            if (ShortInterval(zl, zh)) {
                // Short interval: the two closed-form terms would nearly cancel; the exponent varies
                // by < 0.7 over it, so 8-point Gauss–Legendre is exact to rounding.
                const double c = 0.5 * (xl + xh), h = 0.5 * (xh - xl);
                Complex s = 0;
                for (int i = 0; i < 8; ++i) {
                    const Complex e = Exponent(o, c + h * short8.x[std::size_t(i)], y);
                    s += short8.w[std::size_t(i)] * ExpC(e.real(), e.imag());
                }
                sumDirect += wj * h * s;
                continue;
            }
            const bool posL = zl.real() >= 0, posH = zh.real() >= 0;
            if (!posL && posH) {
                // The stationary point lies inside: the full-line term 2e^{αm²}·e^{y-part}.
                const Complex full = beta * beta * o.inv4a - o.ayy * (y * y) + I1 * (o.by * y) + o.c0;
                if (full.real() > CutExponent) {
                    fr[fulls] = full.real(), fi[fulls] = full.imag(), fcoef[fulls] = 2 * wj;
                    ++fulls;
                }
            }
            // Edge terms s_e·w(σ_e i z_e)·E(x_e), σ_e = sign(Re z_e); (G(xl) − G(xh) of the header).
            const Complex el = Exponent(o, xl, y), eh = Exponent(o, xh, y);
            if (el.real() > CutExponent) {
                const double sg = posL ? 1 : -1;
                zr[edges] = -sg * zl.imag(), zi[edges] = sg * zl.real();  // σ i z
                er[edges] = el.real(), ei[edges] = el.imag(), coef[edges] = sg * wj;
                ++edges;
            }
            if (eh.real() > CutExponent) {
                const double sg = posH ? 1 : -1;
                zr[edges] = -sg * zh.imag(), zi[edges] = sg * zh.real();
                er[edges] = eh.real(), ei[edges] = eh.imag(), coef[edges] = -sg * wj;
                ++edges;
            }
        }
        FaddeevaWUpperBatch(edges, zr, zi, wr, wi);
        SinCosBatch(edges, ei, sn, cs);
        double accR = 0, accI = 0;
        for (int e = 0; e < edges; ++e) {
            const double mag = coef[e] * std::exp(er[e]);
            accR += mag * (wr[e] * cs[e] - wi[e] * sn[e]);
            accI += mag * (wr[e] * sn[e] + wi[e] * cs[e]);
        }
        SinCosBatch(fulls, fi, sn, cs);
        for (int e = 0; e < fulls; ++e) {
            const double mag = fcoef[e] * std::exp(fr[e]);
            accR += mag * cs[e];
            accI += mag * sn[e];
        }
        sumK += Complex(accR, accI);
    }
    return o.k * sumK + sumDirect;
}

// A trapezoid {y ∈ [y0, y1], x ∈ [a0 + a1 y, b0 + b1 y]} (oriented, relative coordinates) ∩ window.
Complex Trapezoid(const Oriented &o, double y0, double y1, double a0, double a1, double b0, double b1) {
    y0 = std::max(y0, -o.hy);
    y1 = std::min(y1, o.hy);
    if (!(y1 > y0)) return 0;
    // Break where a limit crosses the window's x-edges (or the other limit), so that each
    // sub-interval has linear limits.
    double br[8];
    int nb = 0;
    auto add = [&](double y) {
        if (y > y0 && y < y1) br[nb++] = y;
    };
    for (double c : {-o.hx, o.hx}) {
        if (a1 != 0) add((c - a0) / a1);
        if (b1 != 0) add((c - b0) / b1);
    }
    if (a1 != b1) add((b0 - a0) / (a1 - b1));
    SortSmall(br, nb);
    Complex sum = 0;
    double lo = y0;
    for (int i = 0; i <= nb; ++i) {
        const double hi = i < nb ? br[i] : y1;
        if (hi > lo) {
            const double ym = 0.5 * (lo + hi);
            const double xlm = a0 + a1 * ym, xhm = b0 + b1 * ym;
            if (std::min(xhm, o.hx) > std::max(xlm, -o.hx)) {
                // Which limits are the lines (not the window) on this sub-interval.
                const bool lineL = xlm > -o.hx, lineH = xhm < o.hx;
                const Plan plan = LinearPlan(o, lo, hi, std::max(xlm, -o.hx), lineL ? a1 : 0.0,
                                             std::min(xhm, o.hx), lineH ? b1 : 0.0);
                sum += IntegrateStrip(
                    o, lo, hi, plan,
                    [&](int n, const double *s, double *y, double *xl, double *xh, double *jac) {
                        for (int j = 0; j < n; ++j) {
                            y[j] = s[j];
                            xl[j] = std::max(a0 + a1 * s[j], -o.hx);
                            xh[j] = std::min(b0 + b1 * s[j], o.hx);
                            jac[j] = 1;
                        }
                    });
            }
        }
        lo = hi;
    }
    return sum;
}

// Quadrature plan for φ ∈ [p0, p1] of a disc strip: y = cy + r sin φ and the limits are the arcs
// cx ∓ r cos φ or, where the arc lies outside, the constants xmin / xmax (passed as ±Infinity
// when the arc is the limit). The exponent along the lines between the limits is expanded to
// second order in φ about the midpoint.
Plan DiscPlan(const Oriented &o, double cx, double cy, double r, double p0, double p1, double xminConst,
              double xmaxConst) {
    const double pm = 0.5 * (p0 + p1), half = 0.5 * (p1 - p0);
    const double c = r * std::cos(pm), sn = r * std::sin(pm);
    const double y = cy + sn, y1 = c, y2 = -sn;  // y, dy/dφ, d²y/dφ²
    double xl = cx - c, xl1 = sn, xl2 = c, xh = cx + c, xh1 = -sn, xh2 = -c;
    if (std::isfinite(xminConst)) xl = xminConst, xl1 = xl2 = 0;
    if (std::isfinite(xmaxConst)) xh = xmaxConst, xh1 = xh2 = 0;
    Term t[3];
    for (int j = 0; j < 3; ++j) {
        const double lam = 0.5 * j;
        const double x = (1 - lam) * xl + lam * xh, x1 = (1 - lam) * xl1 + lam * xh1,
                     x2 = (1 - lam) * xl2 + lam * xh2;
        const Complex dx = DxPhi(o, x, y), dy = DyPhi(o, x, y);
        t[j].c1 = half * (dx * x1 + dy * y1);
        t[j].c2 = (half * half) * (0.5 * (dx * x2 + dy * y2) -
                                   (o.axx * (x1 * x1) + o.axy * (2 * x1 * y1) + o.ayy * (y1 * y1)));
    }
    return PlanFor(t, 3);
}

// A disc of centre (cx, cy) and radius r clipped to x ∈ [xmin, xmax], y ∈ [y0, y1] (relative
// coordinates, window included). Integrated over φ with y = cy + r sin φ, so the x-limits
// cx ± r cos φ are smooth (no square-root end points).
Complex Disc(const Oriented &o, double cx, double cy, double r, double xmin, double xmax, double y0,
             double y1) {
    xmin = std::max(xmin, -o.hx);
    xmax = std::min(xmax, o.hx);
    y0 = std::max({y0, -o.hy, cy - r});
    y1 = std::min({y1, o.hy, cy + r});
    if (!(y1 > y0) || !(xmax > xmin) || !(r > 0)) return 0;
    const double p0 = std::asin(std::clamp((y0 - cy) / r, -1.0, 1.0));
    const double p1 = std::asin(std::clamp((y1 - cy) / r, -1.0, 1.0));
    double br[4];
    int nb = 0;
    for (double c : {xmin, xmax}) {
        const double q = std::abs(c - cx) / r;
        if (q > 0 && q < 1) {
            const double a = std::acos(q);
            for (double p : {-a, a})
                if (p > p0 && p < p1) br[nb++] = p;
        }
    }
    SortSmall(br, nb);
    Complex sum = 0;
    double lo = p0;
    for (int i = 0; i <= nb; ++i) {
        const double hi = i < nb ? br[i] : p1;
        if (hi > lo) {
            const double pm = 0.5 * (lo + hi), cm = r * std::cos(pm);
            const double xlm = cx - cm, xhm = cx + cm;
            if (std::min(xhm, xmax) > std::max(xlm, xmin)) {
                const bool arcL = xlm > xmin, arcH = xhm < xmax;
                // Panels of at most π/4, on which the exponent's quadratic model in φ holds.
                const int parts = std::max(1, int(std::ceil((hi - lo) / (0.25 * Pi))));
                for (int k = 0; k < parts; ++k) {
                    const double a = lo + (hi - lo) * k / parts, b = lo + (hi - lo) * (k + 1) / parts;
                    const Plan plan =
                        DiscPlan(o, cx, cy, r, a, b, arcL ? Infinity : xmin, arcH ? Infinity : xmax);
                    sum += IntegrateStrip(
                        o, a, b, plan,
                        [&](int n, const double *s, double *y, double *xl, double *xh, double *jac) {
                            SinCosBatch(n, s, y, jac);  // sin φ, cos φ
                            for (int j = 0; j < n; ++j) {
                                const double c = r * jac[j];
                                y[j] = cy + r * y[j];
                                xl[j] = std::max(cx - c, xmin);
                                xh[j] = std::min(cx + c, xmax);
                                jac[j] = c;
                            }
                        });
                }
            }
        }
        lo = hi;
    }
    return sum;
}

// Max over y ∈ [y0, y1] of Re Exponent(x, y) (a concave quadratic in y).
double MaxRealExponent(const Oriented &o, double x, double y0, double y1) {
    auto re = [&](double y) { return Exponent(o, x, y).real(); };
    double m = std::max(re(y0), re(y1));
    const double c = o.ayy.real();
    if (c > 0) {
        // d/dy Re(…) = −2Re(axy)x − 2Re(ayy)y − Im(by) = 0.
        const double ys = -(2 * o.axy.real() * x + o.by.imag()) / (2 * c);
        if (ys > y0 && ys < y1) m = std::max(m, re(ys));
    }
    return m;
}

// A rectangle x ∈ [xl, xh], y ∈ [y0, y1] (oriented, clipped). When both x-edges are negligible
// for every y and the stationary point of the x-integral lies inside for every y, the inner
// integral is the full-line Gaussian √(π/axx)·e^{full(y)} with
// full(y) = −bx²/(4axx) + i(by − bx·axy/axx)·y − (ayy − axy²/axx)·y², so the strip is one more
// closed form (the common case of a slit longer than the footprint). Otherwise quadrature.
Complex RectStrip(const Oriented &o, double xl, double xh, double y0, double y1) {
    auto rez = [&](double x, double y) {
        const Complex m = (I1 * o.bx - o.axy * (2 * y)) * o.inv2a;
        return (o.sa * (x - m)).real();
    };
    if (MaxRealExponent(o, xl, y0, y1) < CutExponent && MaxRealExponent(o, xh, y0, y1) < CutExponent &&
        rez(xl, y0) < 0 && rez(xl, y1) < 0 && rez(xh, y0) >= 0 && rez(xh, y1) >= 0) {
        const Complex r = o.axy / o.axx;
        const Complex alpha = o.ayy - o.axy * r;  // Schur complement: Re > 0
        const Complex beta = I1 * o.by - I1 * o.bx * r;
        const Complex c0 = -o.bx * o.bx * o.inv4a + o.c0;
        return 2.0 * o.k * std::exp(c0) * GaussianSegmentIntegral(alpha, beta, y0, y1);
    }
    const Plan plan = LinearPlan(o, y0, y1, xl, 0, xh, 0);
    return IntegrateStrip(o, y0, y1, plan,
                          [&](int n, const double *s, double *y, double *a, double *b, double *jac) {
                              for (int j = 0; j < n; ++j) y[j] = s[j], a[j] = xl, b[j] = xh, jac[j] = 1;
                          });
}

}  // namespace

PixelWavelet PixelWavelet::Make(const PixelState &p, const Vec3 &hit, const Vec3 &e1, const Vec3 &e2, const Vec3 &np,
                                double k) {
    PixelWavelet w;
    w.dRef = hit - p.centre;
    w.rRef = Length(w.dRef);
    w.e1 = e1, w.e2 = e2, w.np = np;
    w.sensor = p.frame;
    w.k = k;
    w.beta2 = p.beta2;
    w.label = p.label;
    w.labelOnly = p.labelOnly;
    return w;
}

double PixelWavelet::ExpansionError() const {
    const double wt = std::sqrt(std::max(0.0, 1 - Sqr(Dot(dRef, sensor.n) / rRef)));
    return narrow_pixels::ExpansionPhase(k, beta2, rRef, wt);
}

bool PixelWavelet::Preferred() const {
    if (labelOnly || LengthSquared(label) >= 1) return true;
    constexpr double KBeta = narrow_pixels::NonParaxialBelowKBeta;
    return k * k * beta2 < KBeta * KBeta && ExpansionError() <= narrow_pixels::MaxExpansionPhase;
}

namespace {

// The region of the plate (plate coordinates) whose directions from the pixel lie within `radius`
// (sensor-plane direction cosines) of the label; the openings' bounds where it reaches the
// horizon or the plate's plane does not meet every such direction in front.
Bounds2 WaveletWindow(const PixelWavelet &w, const Vec2 &hit, double radius, const Bounds2 &openings) {
    const Vec2 u = w.label;
    if (Length(u) + radius >= 0.999) return openings;
    // The plate point along a direction (sensor direction cosines) from the pixel centre.
    const Vec3 centre = -w.dRef;  // the pixel centre relative to the hit
    const double h = Dot(-centre, w.np);  // the plate's plane: Dot(x − centre, np) = h
    Bounds2 b;
    constexpr int N = 32;
    for (int i = 0; i < N; ++i) {
        const double phi = 2 * Pi * i / N;
        const Vec2 v = u + Vec2(std::cos(phi), std::sin(phi)) * radius;
        const Vec3 dir = w.sensor.s * v.x + w.sensor.t * v.y + w.sensor.n * std::sqrt(1 - LengthSquared(v));
        const double dn = Dot(dir, w.np);
        if (!(std::abs(dn) > 1e-12) || !(h / dn > 0)) return openings;
        const Vec3 x = centre + dir * (h / dn);  // relative to the hit
        b.Extend(hit + Vec2(Dot(x, w.e1), Dot(x, w.e2)));
    }
    // The boundary between the 32 samples bulges by < 1 % of the extent for a smooth convex curve;
    // pad by 5 %.
    const Vec2 pad = (b.hi - b.lo) * 0.05;
    b.lo = b.lo - pad;
    b.hi = b.hi + pad;
    return b.Intersect(openings);
}

// Tiles of IntegrateWavelet: the largest allowed residual of the second-order expansion (rad,
// weighted by the integrand's magnitude; |A|² errs by ~0.2 of it, measured against brute force in
// tests/materials/pixel_wavelet_test.cpp: 1e-3 gave 1.6e-4, 1e-4 gives ≤ 2.8e-5), and the most
// tiles one integral may use.
constexpr double TileTolerance = 1e-4;
constexpr int MaxTiles = 4096;

struct Tiler {
    const PlateGaussian &g;
    const PixelWavelet &w;
    const ApertureMask &mask;
    Vec2 hit;
    int tiles = 0;

    Complex Tile(const Bounds2 &box) {  // plate coordinates
        bool any = false;
        mask.ForEachPiece(box, [&](const MaskPiece &p) { any = any || p.t > 0; });
        if (!any) return 0;
        const Vec2 c = (box.lo + box.hi) * 0.5 - hit, half = (box.hi - box.lo) * 0.5;
        const Jet j = IntegrandJet(g, w, c.x, c.y);
        // The expansion about the centre, T, against the integrand f at the corners and edge
        // midpoints q. Its error grows from the centre like t³ along the segment c + t(q − c),
        // where the integrand's magnitude is |e^T| (normalised to ≲ 1): the estimate is
        // max_t |f(q) − T(q)|·t³·|e^{T(c + t(q − c))}|, which also sees a footprint's peak inside
        // a tile whose corners lie in its tails.
        double residual = 0, peak = j.f.real();
        for (int ix = -1; ix <= 1; ++ix)
            for (int iy = -1; iy <= 1; ++iy) {
                if (ix == 0 && iy == 0) continue;
                const double dx = ix * half.x, dy = iy * half.y;
                const Complex lin = j.g[0] * dx + j.g[1] * dy;
                const Complex quad = 0.5 * (j.h[0][0] * dx * dx + 2.0 * j.h[0][1] * dx * dy + j.h[1][1] * dy * dy);
                const Complex exact = IntegrandLog(g, w, c.x + dx, c.y + dy);
                const double err = std::abs(exact - (j.f + lin + quad));
                peak = std::max(peak, exact.real());
                double weight = 0;
                for (int i = 1; i <= 16; ++i) {
                    const double t = i / 16.0, re = j.f.real() + t * lin.real() + t * t * quad.real();
                    peak = std::max(peak, re);
                    weight = std::max(weight, t * t * t * std::exp(std::min(0.0, re)));
                }
                residual = std::max(residual, err * weight);
            }
        if (peak < CutExponent) return 0;  // negligible everywhere
        if (residual > TileTolerance && tiles < MaxTiles) {
            ++tiles;
            Bounds2 a = box, b = box;
            if (half.x >= half.y) a.hi.x = b.lo.x = 0.5 * (box.lo.x + box.hi.x);
            else a.hi.y = b.lo.y = 0.5 * (box.lo.y + box.hi.y);
            return Tile(a) + Tile(b);
        }
        PlateGaussian t = g;
        t.wavelet = &w;
        t.shift = c;
        t.hx = half.x, t.hy = half.y, t.far = 1;
        t.axx = t.axy = t.ayy = 0;
        t.bx = t.by = 0;
        t.evolve = false;
        Complex sum = 0;
        mask.ForEachPiece(box, [&](const MaskPiece &p) {
            if (p.t > 0) sum += p.t * IntegratePiece(t, p, hit + c);
        });
        return sum;
    }
};

}  // namespace

Complex IntegrateWavelet(const PlateGaussian &g, const PixelWavelet &wIn, const ApertureMask &mask, const Vec2 &hit,
                         double window) {
    PixelWavelet w = wIn;
    const Bounds2 openings = mask.Bounds();
    if (openings.Empty()) return 0;
    const double beta = std::sqrt(w.beta2), fresnel = w.k * w.beta2 / w.rRef;
    const double radius = 2 * window * std::sqrt(1 + fresnel * fresnel) / (w.k * beta);
    Bounds2 box = WaveletWindow(w, hit, radius, openings);
    if (g.beam) {
        // An incident Gaussian beam confines the integrand to its spot, Δ* = −(I − AAᵀ)⁻¹·off
        // from the hit (A = its axis on the plate, off = the hit's offset from the axis), where its
        // amplitude e^{−ρ²/(2β_b²)} falls to e^{−32} at ρ = 8β_b — on the plate the oblique cut
        // of that cylinder; 1.5× for the beam's change of radius along a tilted plate.
        const double a2 = g.ba1 * g.ba1 + g.ba2 * g.ba2, an = 1 - a2;
        if (an > 1e-6) {
            const double ao = g.ba1 * g.bo1 + g.ba2 * g.bo2;
            const Vec2 spot(-(g.bo1 + g.ba1 * ao / an), -(g.bo2 + g.ba2 * ao / an));
            const double wb = 0.5 * g.k * (1.0 / (g.bq + (g.ba1 * spot.x + g.ba2 * spot.y))).imag();  // 1/(2β_b²)
            if (wb > 0) {
                const double reach = 1.5 * 8 / std::sqrt(2 * wb);
                const Vec2 h(reach * std::sqrt(1 + g.ba1 * g.ba1 / an), reach * std::sqrt(1 + g.ba2 * g.ba2 / an));
                box = box.Intersect(Bounds2{hit + spot - h, hit + spot + h});
            }
        }
    }
    if (box.Empty()) return 0;
    // Normalise by the magnitude at the point of the window nearest the label's direction (the
    // hit when the window contains it): |integrand| ≲ 1 there, as CutExponent assumes.
    const Vec2 near(std::clamp(hit.x, box.lo.x, box.hi.x), std::clamp(hit.y, box.lo.y, box.hi.y));
    w.ref = WaveletLog(w, Complex(near.x - hit.x), Complex(near.y - hit.y)).real();
    Tiler tiler{g, w, mask, hit};
    return std::exp(w.ref) * tiler.Tile(box);
}

Complex GaussianSegmentIntegral(Complex alpha, Complex beta, double x0, double x1) {
    if (!(x1 > x0)) return x1 == x0 ? Complex(0) : -GaussianSegmentIntegral(alpha, beta, x1, x0);
    const Complex sa = std::sqrt(alpha);  // principal root: Re > 0
    const Complex m = beta / (2.0 * alpha);
    const Complex z0 = sa * (x0 - m), z1 = sa * (x1 - m);
    auto logE = [&](double x) { return -alpha * (x * x) + beta * x; };
    if (ShortInterval(z0, z1)) {
        const GaussLegendreRule &r = GaussLegendre(8);
        const double c = 0.5 * (x0 + x1), h = 0.5 * (x1 - x0);
        Complex s = 0;
        for (int i = 0; i < 8; ++i) s += r.w[std::size_t(i)] * std::exp(logE(c + h * r.x[std::size_t(i)]));
        return h * s;
    }
    const bool pos0 = z0.real() >= 0, pos1 = z1.real() >= 0;
    Complex sum = 0;
    if (!pos0 && pos1) sum += 2.0 * std::exp(beta * m / 2.0);  // 2e^{αm²}
    const Complex t0 = FaddeevaWUpper(pos0 ? Complex(0, 1) * z0 : Complex(0, -1) * z0) * std::exp(logE(x0));
    const Complex t1 = FaddeevaWUpper(pos1 ? Complex(0, 1) * z1 : Complex(0, -1) * z1) * std::exp(logE(x1));
    sum += (pos0 ? 1.0 : -1.0) * t0 - (pos1 ? 1.0 : -1.0) * t1;
    return SqrtPi / (2.0 * sa) * sum;
}

PlateGaussian MakePlateGaussian(const Vec3 &d, const Vec3 &s, const Vec3 &e1, const Vec3 &e2, const Vec3 &n,
                                double k, double beta2, double rho, double dist, double window) {
    // Theory §9: the traced GR on the plate (GenRay::OnPlane, oblique cut) times the incident
    // wave exp(ik s·Δ + ik|Δ⊥s|²/(2R)), expanded in plate coordinates Δ = x e1 + y e2.
    const double d1 = Dot(d, e1), d2 = Dot(d, e2), dn = Dot(d, n);
    const double s1 = Dot(s, e1), s2 = Dot(s, e2);
    const Complex gamma = Complex(1, -rho) / (2 * beta2);
    const double kr = std::isfinite(dist) && dist > 0 ? k / (2 * dist) : 0.0;
    PlateGaussian g;
    g.axx = gamma * (1 - d1 * d1) - Complex(0, kr * (1 - s1 * s1));
    g.axy = -gamma * (d1 * d2) + Complex(0, kr * s1 * s2);
    g.ayy = gamma * (1 - d2 * d2) - Complex(0, kr * (1 - s2 * s2));
    g.bx = k * (d1 + s1);
    g.by = k * (d2 + s2);
    // The exact beams, re-expanded per piece (IntegratePiece): 1/q = (ρ + i)/(kβ²). Only as a
    // perturbation: when the axial offsets across the window reach 5 % of |q| (footprints of a
    // few wavelengths at oblique incidence) the paraxial beam itself is not accurate there, and the
    // plain quadratic form — exactly unitary, so the kernel keeps flux ≤ 1 — is used instead.
    const double aMax = window * std::sqrt(beta2) *
                        (std::abs(d1) * std::sqrt(1 + d1 * d1 / (dn * dn)) +
                         std::abs(d2) * std::sqrt(1 + d2 * d2 / (dn * dn)));
    g.evolve = aMax * std::abs(Complex(rho, 1) / (k * beta2)) < 0.05;
    g.k = k;
    g.d1 = d1, g.d2 = d2, g.s1 = s1, g.s2 = s2;
    g.invQ = Complex(rho, 1) / (k * beta2);
    g.dist = kr > 0 ? dist : Infinity;
    // The box bounding the oblique cut |Δ⊥d| ≤ ϱ (theory §0 D13).
    const double varrho = window * std::sqrt(beta2);
    g.hx = varrho * std::sqrt(1 + d1 * d1 / (dn * dn));
    g.hy = varrho * std::sqrt(1 + d2 * d2 / (dn * dn));
    return g;
}

void AddIncidentBeam(PlateGaussian *g, const GaussianBeamGeometry &b, const Vec3 &hit, const Vec3 &e1,
                     const Vec3 &e2) {
    const double z = b.Axial(hit);
    const Vec3 off = hit - b.waist - b.axis * z;  // ⊥ the axis
    g->beam = true;
    g->ba1 = Dot(b.axis, e1);
    g->ba2 = Dot(b.axis, e2);
    g->bo1 = Dot(off, e1);
    g->bo2 = Dot(off, e2);
    g->bOff2 = LengthSquared(off);
    g->bq = b.Q(z, g->k);
}

Complex IntegratePiece(const PlateGaussian &g, const MaskPiece &piece, const Vec2 &origin) {
    const double ox = origin.x, oy = origin.y;
    if (piece.circle) {
        // {v ∈ [v0, v1], u ∈ [uMin, uMax], |(u, v) − c| ≤ r}: quadrature along the shorter side
        // of its bounding box inside the window (geometry only, as for rectangles).
        const double cx = piece.cu - ox, cy = piece.cv - oy, r = piece.r;
        const double u0 = std::max({piece.uMin - ox, cx - r, -g.hx}),
                     u1 = std::min({piece.uMax - ox, cx + r, g.hx});
        const double v0 = std::max({piece.v0 - oy, cy - r, -g.hy}),
                     v1 = std::min({piece.v1 - oy, cy + r, g.hy});
        if (!(u1 > u0 && v1 > v0)) return 0;
        const Quadratic q = Expand(g, u0, u1, v0, v1);
        const Oriented ov = Orient(q, g, false), ou = Orient(q, g, true);
        if (v1 - v0 <= u1 - u0)
            return Disc(ov, cx, cy, r, piece.uMin - ox, piece.uMax - ox, piece.v0 - oy, piece.v1 - oy);
        return Disc(ou, cy, cx, r, piece.v0 - oy, piece.v1 - oy, piece.uMin - ox, piece.uMax - ox);
    }
    // Linear limits u = A + B v, in relative coordinates: x = (A − ox + B oy) + B y.
    const double y0 = piece.v0 - oy, y1 = piece.v1 - oy;
    const double a0 = piece.loA - ox + piece.loB * oy, b0 = piece.hiA - ox + piece.hiB * oy;
    if (piece.loB == 0 && piece.hiB == 0) {
        // A rectangle counts if it meets the window box. Gauss–Legendre runs along its shorter
        // side inside the window, the closed form along the other (to far × the window). The
        // choice depends on geometry only, not on the direction (b): for one GR every direction
        // then measures the same truncated wave function, so Parseval and the energy bound hold
        // exactly for the truncated state.
        if (!(std::min(b0, g.hx) > std::max(a0, -g.hx) && std::min(y1, g.hy) > std::max(y0, -g.hy))) return 0;
        const Quadratic q = Expand(g, std::max(a0, -g.hx), std::min(b0, g.hx), std::max(y0, -g.hy),
                                   std::min(y1, g.hy));
        const Oriented ov = Orient(q, g, false), ou = Orient(q, g, true);  // closed form in u / in v
        const double vu0 = std::max(a0, -ov.hx), vu1 = std::min(b0, ov.hx);  // ov: u limits
        const double vv0 = std::max(y0, -ov.hy), vv1 = std::min(y1, ov.hy);  // ov: v range
        const double uv0 = std::max(y0, -ou.hx), uv1 = std::min(y1, ou.hx);  // ou: v limits
        const double uu0 = std::max(a0, -ou.hy), uu1 = std::min(b0, ou.hy);  // ou: u range
        return vv1 - vv0 <= uu1 - uu0 ? RectStrip(ov, vu0, vu1, vv0, vv1) : RectStrip(ou, uv0, uv1, uu0, uu1);
    }
    // The expansion centre: the middle of the piece's bounding box inside the D13 box.
    const double ya = std::max(y0, -g.hy), yb = std::min(y1, g.hy);
    if (!(yb > ya)) return 0;
    const double xa = std::max(std::min(a0 + piece.loB * ya, a0 + piece.loB * yb), -g.hx);
    const double xb = std::min(std::max(b0 + piece.hiB * ya, b0 + piece.hiB * yb), g.hx);
    const Quadratic q = xb > xa ? Expand(g, xa, xb, ya, yb) : Expand(g, 0, 0, ya, yb);
    return Trapezoid(Orient(q, g, false), y0, y1, a0, piece.loB, b0, piece.hiB);
}

Complex IntegrateTrapezoid(const PlateGaussian &g, double y0, double y1, double a0, double a1, double b0,
                           double b1) {
    // The expansion centre: the middle of the trapezoid's bounding box inside the D13 box (as
    // IntegratePiece does for its trapezoids).
    const double ya = std::max(y0, -g.hy), yb = std::min(y1, g.hy);
    if (!(yb > ya)) return 0;
    const double xa = std::max(std::min(a0 + a1 * ya, a0 + a1 * yb), -g.hx);
    const double xb = std::min(std::max(b0 + b1 * ya, b0 + b1 * yb), g.hx);
    const Quadratic q = xb > xa ? Expand(g, xa, xb, ya, yb) : Expand(g, 0, 0, ya, yb);
    return Trapezoid(Orient(q, g, false), y0, y1, a0, a1, b0, b1);
}

}  // namespace phasor
