// SPDX-License-Identifier: Apache-2.0
// `rs`'s propagator (rs/propagator.h): the RS-I field and its gradient behind one plate with
// openings (theory §6.2; docs/rs.md §2). Quadrature (`accuracy` sets the tolerances below through
// QuadratureRule::ForAccuracy; measured errors are far smaller, see docs/rs.md §4):
//  * Aperture integral, per field point, per mask piece {v ∈ [v0, v1], u ∈ [ULo(v), UHi(v)]}:
//    Gauss–Legendre panels along v, and for each v node along u. Panels are marched so that
//    (bound of |∂φ/∂u| or |∂φ/∂v| over the panel's box) × length ≤ 6π, φ = kR + incident phase;
//    the bound is exact interval arithmetic on the direction cosines (monotone in the offsets)
//    plus the incident field's own bound (PlaneField::Slope), plus |slope|·|∂φ/∂u| for the moving
//    limits of trapezoids. Panels are at most half the distance to the field point, and no longer
//    than the incident field's PanelLimit (half a point source's distance, a beam's width), so the
//    amplitudes are resolved; openings outside the field's Support (a beam's footprint) are left
//    out. The incident field is any CoherentSource's (core/render/coherent_source.h). Nodes per
//    panel: the fewest n ∈ [6, 20] whose Gauss–Legendre error for a linear phase Φ,
//    Φ^{2n}(n!)⁴/((2n+1)((2n)!)³) (A&S 25.4.30, GaussLegendreMaxPhase), is below the per-panel
//    tolerance (accuracy·1e-3; n = 12 at Φ = 6π for the default). Discs are integrated in ψ,
//    v = c_v + r·sin ψ (smooth chord limits), with the ψ bound of docs/rs.md §2.
//  * 2-D mode: only the u integral (slits infinite along v), same panels; H₀, H₁ by their
//    asymptotic series for kR ≥ 25 (error < 1e-16), std::cyl_bessel_j / cyl_neumann below
//    (core/numerics/bessel.h).
#include "integrators/rs/propagator.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/diagnostics.h"
#include "core/numerics/bessel.h"
#include "core/numerics/gauss_legendre.h"

namespace phasor {
namespace rs {

namespace {

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
/// Node counts per panel phase for a rule (index n → largest Φ).
struct NodeRule {
    std::array<double, MaxGaussLegendreNodes + 1> maxPhase{};
    int minNodes, maxNodes;
    explicit NodeRule(const QuadratureRule &r)
        : minNodes(std::clamp(r.minNodes, 1, MaxGaussLegendreNodes)),
          maxNodes(std::clamp(r.maxNodes, 1, MaxGaussLegendreNodes)) {
        for (int n = 1; n <= MaxGaussLegendreNodes; ++n) maxPhase[n] = GaussLegendreMaxPhase(n, r.tolerance);
    }
    int Nodes(double phase) const {
        int n = minNodes;
        while (n < maxNodes && maxPhase[n] < phase) ++n;
        return n;
    }
};

Propagator::Propagator(const PlateFrame &plate, const ApertureMask &mask, const CoherentSource &source,
                       double lambda, bool flip, bool twoD, QuadratureRule rule)
    : plate_(plate),
      zSign_(flip ? -1.0 : 1.0),
      twoD_(twoD),
      rule_(rule),
      nodes_(std::make_shared<const NodeRule>(rule)) {
    if (!(lambda > 0)) throw Error("rs: the coherent wave has no valid wavelength");
    k_ = 2 * Pi / lambda;
    // The wave must cross the plate towards the sensor (its direction of travel at the plate).
    if (!(zSign_ * Dot(source.Travel(plate.origin, lambda), plate.n) > 0))
        throw Error("the light does not travel through the plate towards the sensor side");
    incident_ = source.OnPlane(plate, lambda);
    bounds_ = mask.Bounds();
    const Bounds2 support = incident_->Support();
    bounds_ = bounds_.Intersect(support);
    if (!bounds_.Empty()) {
        panelLimit_ = incident_->PanelLimit(bounds_);
        Bounds2 box = bounds_;
        const Vec2 pad = 0.01 * (box.hi - box.lo);
        box.lo = box.lo - pad;
        box.hi = box.hi + pad;
        box = box.Intersect(support);
        mask.ForEachPiece(box, [&](const MaskPiece &p) {
            if (p.t > 0 && p.v1 > p.v0) pieces_.push_back(p);
        });
    }
    if (twoD_) {
        const std::optional<Vec3> dir = source.PlaneWaveDirection();
        if (!dir || std::abs(Dot(Normalize(*dir), plate.e2)) > 1e-9)
            throw Error(
                "the 2-D mode needs a plane wave with no component along the slits (the plate's y axis)");
        if (!mask.IsSlitsAlongV(0))
            throw Error("the 2-D mode needs openings that are rectangles sharing one v range");
    }
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
    const NodeRule &nodes = *nodes_;
    const double k = k_, X = p.x, Y = p.y, Z = p.z, Z2 = Z * Z;
    const double lmax = std::min(rule_.maxPanelOverDistance * Z, panelLimit_);
    const double phiMax = rule_.maxPanelPhase;
    double ur = 0, ui = 0, dr = 0, di = 0;

    // Bounds of |∂φ/∂u| and |∂φ/∂v| over a box, φ = k(R − Z) + φ_inc.
    // Bound on |∂(kR + phase of U_inc)/∂a| over the panel [a0, a1] × [b0, b1], for the axis a
    // (field point coordinate A along it, B across): the interval of −∂R/∂a plus the incident
    // field's (PlaneField::Slope, in units of k, and its slack).
    auto gradAlong = [&](int axis, double A, double B, double ua, double ub, double va, double vb) {
        const double a0 = axis == 0 ? ua : va, a1 = axis == 0 ? ub : vb;
        const double b0 = axis == 0 ? va : ua, b1 = axis == 0 ? vb : ub;
        double pLo, pHi, lo, hi;
        DistanceRange(B, b0, b1, &pLo, &pHi);
        CosineRange(A - a1, A - a0, std::sqrt(pLo * pLo + Z2), std::sqrt(pHi * pHi + Z2), &lo, &hi);
        const PhaseSlope inc = incident_->Slope(axis, Bounds2{Vec2(ua, va), Vec2(ub, vb)});
        const double gLo = -hi + inc.lo, gHi = -lo + inc.hi;  // ∂R/∂a = −(A − a)/R
        return k * std::max(std::abs(gLo), std::abs(gHi)) + inc.slack;
    };
    auto gradU = [&](double ua, double ub, double va, double vb) { return gradAlong(0, X, Y, ua, ub, va, vb); };
    auto gradV = [&](double ua, double ub, double va, double vb) { return gradAlong(1, Y, X, ua, ub, va, vb); };

    // One line v = const of a piece: the u integral, weight wv (outer node weight × Jacobian).
    auto line = [&](double v, double wv, double uLo, double uHi, double t) {
        const double dy = Y - v, dy2z2 = dy * dy + Z2;
        const double mvw = p.mv * dy + p.mn * Z;
        MarchPanels(
            uLo, uHi, lmax, phiMax, [&](double ua, double ub) { return gradU(ua, ub, v, v); },
            [&](double ua, double ub, double phaseU) {
                const int nu = nodes.Nodes(phaseU);
                const GaussLegendreRule &ru = GaussLegendre(nu);
                const double *hx = ru.x, *hw = ru.w;
                const double half = 0.5 * (ub - ua), mid = 0.5 * (ua + ub);
                for (int iu = 0; iu < nu; ++iu) {
                    const double u = mid + half * hx[iu];
                    double a, phi;  // U_inc's amplitude and phase
                    incident_->At(u, v, &a, &phi);
                    a *= t * wv * half * hw[iu];
                    const double dx = X - u, q = dx * dx + dy * dy;
                    const double r2 = dx * dx + dy2z2, r = std::sqrt(r2), ir = 1 / r, ir2 = ir * ir;
                    const double ir3 = ir2 * ir;
                    phi += k * q / (r + Z);  // k(R − Z), without cancellation
                    double sn, cs;
                    ::sincos(phi, &sn, &cs);
                    const double er = a * cs, ei = a * sn;
                    // Kernel (1 − ikR)/R³ and its derivative (k²R² + 3ikR − 3)/R⁵ (propagator.h).
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
                    const GaussLegendreRule &rule = GaussLegendre(n);
                    const double *gx = rule.x, *gw = rule.w;
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
                    const GaussLegendreRule &rule = GaussLegendre(n);
                    const double *gx = rule.x, *gw = rule.w;
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
    const NodeRule &nodes = *nodes_;
    const double k = k_, X = p.x, Z = p.z, Z2 = Z * Z;
    const double lmax = rule_.maxPanelOverDistance * Z;
    // The reference phase kZ − 3π/4 is dropped from every node (propagator.h: phases are relative).
    const Complex refPhase = std::polar(1.0, -(k * Z - 3 * Pi / 4));
    double ur = 0, ui = 0, dr = 0, di = 0;
    // The incident field is a plane wave with no component along the slits (checked at
    // construction): it is read on the line v = 0.
    auto gradU = [&](double ua, double ub) {
        double lo, hi;
        CosineRange(X - ub, X - ua, Z, Z, &lo, &hi);
        const PhaseSlope inc = incident_->Slope(0, Bounds2{Vec2(ua, 0), Vec2(ub, 0)});
        return k * std::max(std::abs(inc.lo - hi), std::abs(inc.hi - lo)) + inc.slack;
    };
    for (const MaskPiece &piece : pieces_) {
        const double vm = 0.5 * (piece.v0 + piece.v1);
        const double uLo = piece.ULo(vm), uHi = piece.UHi(vm);
        if (!(uHi > uLo)) continue;
        MarchPanels(uLo, uHi, lmax, rule_.maxPanelPhase, gradU, [&](double ua, double ub, double phase) {
            const int n = nodes.Nodes(phase);
            const GaussLegendreRule &rule = GaussLegendre(n);
            const double *gx = rule.x, *gw = rule.w;
            const double half = 0.5 * (ub - ua), mid = 0.5 * (ua + ub);
            for (int i = 0; i < n; ++i) {
                const double u = mid + half * gx[i];
                double a, phiInc;  // U_inc's amplitude and phase
                incident_->At(u, 0.0, &a, &phiInc);
                a *= piece.t * half * gw[i];
                const double dx = X - u, r2 = dx * dx + Z2, r = std::sqrt(r2), x = k * r;
                // h0, h1 = H₀⁽¹⁾(kR), H₁⁽¹⁾(kR) without the common factor e^{i(kZ − 3π/4)}.
                Complex h0, h1;
                if (x >= HankelAsymptoticMin) {
                    Complex p0, p1;
                    HankelAsymptoticFactors(x, &p0, &p1);
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

}  // namespace rs
}  // namespace phasor
