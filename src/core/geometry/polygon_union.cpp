// SPDX-License-Identifier: Apache-2.0
// phasor — the union of planar polygons cut into trapezoids (polygon_union.h).
#include "core/geometry/polygon_union.h"

#include <algorithm>
#include <cmath>

namespace phasor {

namespace {

// A segment prepared for the sweep: v-range, u at a given v, winding step.
struct Seg {
    double v0, v1;  // v0 < v1
    double uAt0;    // u at v0
    double slope;   // du/dv
    double u0, u1;  // u-range
    int step;       // winding change when crossed towards +u
    int index;      // in the caller's span
    double U(double v) const { return uAt0 + slope * (v - v0); }
};

// Proper crossing of two segments strictly inside both v-ranges: its v, or NaN.
double CrossingV(const Seg &p, const Seg &q) {
    const double lo = std::max(p.v0, q.v0), hi = std::min(p.v1, q.v1);
    if (!(hi > lo)) return NAN;
    const double dLo = p.U(lo) - q.U(lo), dHi = p.U(hi) - q.U(hi);
    if (!((dLo < 0 && dHi > 0) || (dLo > 0 && dHi < 0))) return NAN;
    return lo + (hi - lo) * dLo / (dLo - dHi);
}

// Where the segment meets the vertical line u = c strictly inside its v-range, or NaN.
double SideV(const Seg &s, double c) {
    if (s.slope == 0) return NAN;
    const double v = s.v0 + (c - s.uAt0) / s.slope;
    return v > s.v0 && v < s.v1 ? v : NAN;
}

// One limit of an interval inside a slab: a segment (seg ≥ 0) or the constant u = c.
struct Limit {
    int seg = -1;
    double c = 0;
};

// An interval of one slab, keyed by its two limits (merged with the next slab's when equal).
struct Piece {
    Limit lo, hi;
    double v0, v1;
};

bool SameLimit(const Limit &a, const Limit &b) { return a.seg == b.seg && (a.seg >= 0 || a.c == b.c); }

Trapezoid ToTrapezoid(const Piece &p, const std::vector<Seg> &segs) {
    Trapezoid t;
    t.v0 = p.v0;
    t.v1 = p.v1;
    auto set = [&](const Limit &l, double *a, double *b, int *idx) {
        if (l.seg >= 0) {
            const Seg &s = segs[std::size_t(l.seg)];
            *b = s.slope;
            *a = s.uAt0 - s.slope * s.v0;
            *idx = s.index;
        } else {
            *a = l.c;
            *b = 0;
            *idx = -1;
        }
    };
    set(p.lo, &t.loA, &t.loB, &t.loSeg);
    set(p.hi, &t.hiA, &t.hiB, &t.hiSeg);
    return t;
}

}  // namespace

double Trapezoid::Area() const {
    const double vm = 0.5 * (v0 + v1);
    return std::max(0.0, Hi(vm) - Lo(vm)) * (v1 - v0);
}

int WindingNumber(std::span<const OrientedSegment> segments, const Vec2 &p) {
    int w = 0;
    for (const OrientedSegment &s : segments) {
        const double dv = s.b.y - s.a.y;
        if (dv == 0) continue;
        const double lo = std::min(s.a.y, s.b.y), hi = std::max(s.a.y, s.b.y);
        // Half-open in v so that a vertex shared by two segments counts once.
        if (!(p.y >= lo && p.y < hi)) continue;
        const double u = s.a.x + (s.b.x - s.a.x) * (p.y - s.a.y) / dv;
        if (u < p.x) w += dv > 0 ? -1 : 1;
    }
    return w;
}

UnionDecomposition DecomposeUnion(std::span<const OrientedSegment> segments, double halfU, double halfV) {
    UnionDecomposition out;
    if (!(halfU > 0 && halfV > 0)) return out;
    // Prepared segments crossing the box's v-range.
    std::vector<Seg> segs;
    segs.reserve(segments.size());
    double scale = std::max(halfU, halfV);
    for (std::size_t i = 0; i < segments.size(); ++i) {
        const OrientedSegment &o = segments[i];
        if (!(std::isfinite(o.a.x) && std::isfinite(o.a.y) && std::isfinite(o.b.x) && std::isfinite(o.b.y)))
            continue;
        const double dv = o.b.y - o.a.y;
        if (dv == 0) continue;
        const bool up = dv > 0;
        const Vec2 &lo = up ? o.a : o.b, &hi = up ? o.b : o.a;
        if (hi.y <= -halfV || lo.y >= halfV) continue;
        Seg s;
        s.v0 = lo.y;
        s.v1 = hi.y;
        s.uAt0 = lo.x;
        s.slope = (hi.x - lo.x) / (hi.y - lo.y);
        s.u0 = std::min(lo.x, hi.x);
        s.u1 = std::max(lo.x, hi.x);
        s.step = up ? -1 : 1;
        s.index = int(i);
        segs.push_back(s);
    }
    // Slab boundaries: the box, every end point, every crossing and every crossing of the box's
    // sides (so that inside a slab each segment is wholly inside or outside the box).
    std::vector<double> ev{-halfV, halfV};
    auto add = [&](double v) {
        if (v > -halfV && v < halfV) ev.push_back(v);
    };
    for (const Seg &s : segs) {
        add(s.v0);
        add(s.v1);
        add(SideV(s, -halfU));
        add(SideV(s, halfU));
    }
    for (std::size_t i = 0; i < segs.size(); ++i)
        for (std::size_t j = i + 1; j < segs.size(); ++j) {
            const Seg &p = segs[i], &q = segs[j];
            if (p.u1 < q.u0 || q.u1 < p.u0 || p.v1 <= q.v0 || q.v1 <= p.v0) continue;
            add(CrossingV(p, q));
        }
    std::sort(ev.begin(), ev.end());
    const double tol = 1e-13 * scale;
    std::vector<double> v;
    for (double e : ev)
        if (v.empty() || e - v.back() > tol) v.push_back(e);
    if (v.back() < halfV) v.back() = halfV;

    // Sweep each slab. Open pieces of the previous slab wait in `prevCov`/`prevOpen` to be extended.
    std::vector<Piece> prevCov, prevOpen, curCov, curOpen;
    struct Active {
        double u;
        int seg;
    };
    std::vector<Active> act;
    auto flush = [&](std::vector<Piece> &prev, std::vector<Piece> &cur, std::vector<Trapezoid> &dst) {
        // Pieces of `prev` not continued in `cur` are finished.
        for (const Piece &p : prev) {
            bool continued = false;
            for (Piece &c : cur)
                if (SameLimit(c.lo, p.lo) && SameLimit(c.hi, p.hi) && c.v0 == p.v1) {
                    c.v0 = p.v0;
                    continued = true;
                    break;
                }
            if (!continued) dst.push_back(ToTrapezoid(p, segs));
        }
        prev.swap(cur);
        cur.clear();
    };
    for (std::size_t k = 0; k + 1 < v.size(); ++k) {
        const double v0 = v[k], v1 = v[k + 1];
        const double vm = 0.5 * (v0 + v1);
        act.clear();
        for (std::size_t i = 0; i < segs.size(); ++i)
            if (segs[i].v0 < vm && segs[i].v1 > vm) act.push_back({segs[i].U(vm), int(i)});
        std::sort(act.begin(), act.end(), [](const Active &a, const Active &b) { return a.u < b.u; });
        // Walk from u = −∞: W changes at each active segment; intervals clipped to [−halfU, halfU].
        int w = 0;
        Limit lo{-1, -halfU};
        double uLo = -Infinity;
        auto emit = [&](int winding, const Limit &l, double ul, const Limit &h, double uh) {
            // Clip the interval [ul, uh] (limits l, h) to the box.
            Limit cl = l, ch = h;
            if (ul < -halfU) cl = Limit{-1, -halfU}, ul = -halfU;
            if (uh > halfU) ch = Limit{-1, halfU}, uh = halfU;
            if (!(uh > ul)) return;
            Piece p{cl, ch, v0, v1};
            (winding >= 1 ? curCov : curOpen).push_back(p);
        };
        for (const Active &a : act) {
            emit(w, lo, uLo, Limit{a.seg, 0}, a.u);
            w += segs[std::size_t(a.seg)].step;
            lo = Limit{a.seg, 0};
            uLo = a.u;
        }
        emit(w, lo, uLo, Limit{-1, halfU}, Infinity);
        // Merge touching intervals of the same kind (a segment pair with W 1 → 2 → 1 inside).
        for (std::vector<Piece> *list : {&curCov, &curOpen}) {
            std::vector<Piece> merged;
            for (const Piece &p : *list) {
                if (!merged.empty()) {
                    Piece &m = merged.back();
                    const double mh = m.hi.seg >= 0 ? segs[std::size_t(m.hi.seg)].U(vm) : m.hi.c;
                    const double pl = p.lo.seg >= 0 ? segs[std::size_t(p.lo.seg)].U(vm) : p.lo.c;
                    if (mh >= pl) {
                        m.hi = p.hi;
                        continue;
                    }
                }
                merged.push_back(p);
            }
            list->swap(merged);
        }
        flush(prevCov, curCov, out.covered);
        flush(prevOpen, curOpen, out.open);
    }
    for (const Piece &p : prevCov) out.covered.push_back(ToTrapezoid(p, segs));
    for (const Piece &p : prevOpen) out.open.push_back(ToTrapezoid(p, segs));
    return out;
}

}  // namespace phasor
