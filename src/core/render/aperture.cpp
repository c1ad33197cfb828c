// SPDX-License-Identifier: Apache-2.0
// phasor — openings of an opaque plate (core/render/aperture.h): decomposition of (openings ∩ box) into
// pieces with linear or circular u-limits, transmission lookup, bitmap masks and the plate frame.
#include "core/render/aperture.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/diagnostics.h"
#include "core/image/image_io.h"
#include "core/render/material.h"

namespace phasor {

namespace {

double Cross2(const Vec2 &a, const Vec2 &b) { return a.x * b.y - a.y * b.x; }

/// True if the closed segments pq and rs intersect.
bool SegmentsIntersect(const Vec2 &p, const Vec2 &q, const Vec2 &r, const Vec2 &s) {
    const double d1 = Cross2(q - p, r - p), d2 = Cross2(q - p, s - p);
    const double d3 = Cross2(s - r, p - r), d4 = Cross2(s - r, q - r);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
    auto onSeg = [](const Vec2 &a, const Vec2 &b, const Vec2 &c, double cr) {
        return cr == 0 && std::min(a.x, b.x) <= c.x && c.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= c.y &&
               c.y <= std::max(a.y, b.y);
    };
    return onSeg(p, q, r, d1) || onSeg(p, q, s, d2) || onSeg(r, s, p, d3) || onSeg(r, s, q, d4);
}

/// Sorted, de-duplicated values of `v` inside [lo, hi], with lo and hi themselves.
std::vector<double> SplitPoints(std::vector<double> v, double lo, double hi) {
    v.push_back(lo);
    v.push_back(hi);
    std::vector<double> out;
    for (double x : v)
        if (x >= lo && x <= hi) out.push_back(x);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

}  // namespace

double MaskPiece::ULo(double v) const {
    if (!circle) return loA + loB * v;
    const double h2 = r * r - (v - cv) * (v - cv);
    return std::max(cu - std::sqrt(std::max(0.0, h2)), uMin);
}

double MaskPiece::UHi(double v) const {
    if (!circle) return hiA + hiB * v;
    const double h2 = r * r - (v - cv) * (v - cv);
    return std::min(cu + std::sqrt(std::max(0.0, h2)), uMax);
}

void ApertureMask::AddRect(const Vec2 &lo, const Vec2 &hi, double t) {
    if (!(hi.x > lo.x && hi.y > lo.y)) throw Error("a rectangle opening needs u0 < u1 and v0 < v1");
    rects_.push_back(Rect{lo, hi, std::clamp(t, 0.0, 1.0)});
    ++userRects_;
    bounds_.Extend(lo);
    bounds_.Extend(hi);
}

void ApertureMask::AddDisc(const Vec2 &c, double r, double t) {
    if (!(r > 0)) throw Error("a disc opening needs a positive radius");
    discs_.push_back(Disc{c, r, std::clamp(t, 0.0, 1.0)});
    bounds_.Extend(c - Vec2(r, r));
    bounds_.Extend(c + Vec2(r, r));
}

void ApertureMask::AddPolygon(const std::vector<Vec2> &v, double t) {
    const std::size_t n = v.size();
    if (n < 3) throw Error("a polygon opening needs at least 3 vertices");
    double area2 = 0;
    Bounds2 b;
    for (std::size_t i = 0; i < n; ++i) {
        area2 += Cross2(v[i], v[(i + 1) % n]);
        b.Extend(v[i]);
    }
    const double scale = std::max(b.hi.x - b.lo.x, b.hi.y - b.lo.y);
    if (!(std::abs(area2) > 1e-12 * scale * scale)) throw Error("the polygon opening has zero area");
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j) {
            if (j == i + 1 || (i == 0 && j == n - 1)) continue;  // adjacent edges share a vertex
            if (SegmentsIntersect(v[i], v[(i + 1) % n], v[j], v[(j + 1) % n]))
                throw Error("the polygon opening intersects itself (edges " + std::to_string(i) + " and " +
                            std::to_string(j) + ")");
        }
    polygons_.push_back(Polygon{v, std::clamp(t, 0.0, 1.0), b});
    bounds_.Extend(b.lo);
    bounds_.Extend(b.hi);
}

void ApertureMask::AddBitmap(const std::string &path, const Vec2 &lo, const Vec2 &hi, int levels) {
    if (!(hi.x > lo.x && hi.y > lo.y)) throw Error("the mask extent needs u0 < u1 and v0 < v1");
    const Image img = ReadImage(path);
    if (img.width <= 0 || img.height <= 0 || img.channels.empty()) throw Error(path + ": the mask image is empty");
    const int nc = int(img.channels.size());
    const double du = (hi.x - lo.x) / img.width, dv = (hi.y - lo.y) / img.height;
    const int q = std::max(1, levels - 1);
    auto texel = [&](int x, int y) {
        double value = img.At(x, y, 0);
        if (nc >= 3) value = 0.2126 * img.At(x, y, 0) + 0.7152 * img.At(x, y, 1) + 0.0722 * img.At(x, y, 2);
        if (!std::isfinite(value)) value = 0;
        return std::round(std::clamp(value, 0.0, 1.0) * q) / q;  // quantised so runs merge
    };
    for (int y = 0; y < img.height; ++y) {
        const double v1 = hi.y - y * dv, v0 = hi.y - (y + 1) * dv;
        for (int x = 0; x < img.width;) {
            const double t = texel(x, y);
            int e = x + 1;
            while (e < img.width && texel(e, y) == t) ++e;
            if (t > 0) rects_.push_back(Rect{Vec2(lo.x + x * du, v0), Vec2(lo.x + e * du, v1), t});
            x = e;
        }
    }
    bounds_.Extend(lo);
    bounds_.Extend(hi);
}

double ApertureMask::Transmission(const Vec2 &p) const {
    double t = 0;
    for (const Rect &r : rects_)
        if (p.x >= r.lo.x && p.x <= r.hi.x && p.y >= r.lo.y && p.y <= r.hi.y) t = std::max(t, r.t);
    for (const Disc &d : discs_)
        if (LengthSquared(p - d.c) <= d.r * d.r) t = std::max(t, d.t);
    for (const Polygon &poly : polygons_) {
        if (p.x < poly.b.lo.x || p.x > poly.b.hi.x || p.y < poly.b.lo.y || p.y > poly.b.hi.y) continue;
        bool inside = false;  // even–odd crossing test
        for (std::size_t i = 0, j = poly.v.size() - 1; i < poly.v.size(); j = i++) {
            const Vec2 &a = poly.v[i], &b = poly.v[j];
            if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) inside = !inside;
        }
        if (inside) t = std::max(t, poly.t);
    }
    return t;
}

double ApertureMask::OpenArea() const {
    double a = 0;
    for (const Rect &r : rects_) a += r.t * (r.hi.x - r.lo.x) * (r.hi.y - r.lo.y);
    for (const Disc &d : discs_) a += d.t * Pi * d.r * d.r;
    for (const Polygon &p : polygons_) {
        double a2 = 0;
        for (std::size_t i = 0; i < p.v.size(); ++i) a2 += Cross2(p.v[i], p.v[(i + 1) % p.v.size()]);
        a += p.t * 0.5 * std::abs(a2);
    }
    return a;
}

void ApertureMask::ForEachPiece(const Bounds2 &box, const std::function<void(const MaskPiece &)> &f) const {
    if (box.Empty() || bounds_.Intersect(box).Empty()) return;
    for (const Rect &r : rects_) {
        const Bounds2 c = Bounds2{r.lo, r.hi}.Intersect(box);
        if (c.Empty()) continue;
        MaskPiece p;
        p.v0 = c.lo.y;
        p.v1 = c.hi.y;
        p.t = r.t;
        p.loA = c.lo.x;
        p.hiA = c.hi.x;
        f(p);
    }
    for (const Disc &d : discs_) {
        const double v0 = std::max(d.c.y - d.r, box.lo.y), v1 = std::min(d.c.y + d.r, box.hi.y);
        if (!(v1 > v0)) continue;
        // Split where the circle crosses the box's u-limits, so each piece's limits are smooth.
        std::vector<double> cuts;
        for (double ub : {box.lo.x, box.hi.x}) {
            const double du = ub - d.c.x;
            if (std::abs(du) < d.r) {
                const double h = std::sqrt(d.r * d.r - du * du);
                cuts.push_back(d.c.y - h);
                cuts.push_back(d.c.y + h);
            }
        }
        const std::vector<double> vs = SplitPoints(cuts, v0, v1);
        for (std::size_t i = 0; i + 1 < vs.size(); ++i) {
            MaskPiece p;
            p.circle = true;
            p.cu = d.c.x;
            p.cv = d.c.y;
            p.r = d.r;
            p.uMin = box.lo.x;
            p.uMax = box.hi.x;
            p.v0 = vs[i];
            p.v1 = vs[i + 1];
            p.t = d.t;
            const double vm = 0.5 * (p.v0 + p.v1);
            if (p.v1 > p.v0 && p.UHi(vm) > p.ULo(vm)) f(p);
        }
    }
    for (const Polygon &poly : polygons_) {
        const Bounds2 c = poly.b.Intersect(box);
        if (c.Empty()) continue;
        const std::size_t n = poly.v.size();
        // Slabs between vertex heights and the heights where an edge crosses the box's u-limits.
        std::vector<double> cuts;
        for (std::size_t i = 0; i < n; ++i) {
            const Vec2 &a = poly.v[i], &b = poly.v[(i + 1) % n];
            cuts.push_back(a.y);
            for (double ub : {box.lo.x, box.hi.x})
                if ((a.x - ub) * (b.x - ub) < 0) cuts.push_back(a.y + (b.y - a.y) * (ub - a.x) / (b.x - a.x));
        }
        const std::vector<double> vs = SplitPoints(cuts, c.lo.y, c.hi.y);
        for (std::size_t s = 0; s + 1 < vs.size(); ++s) {
            const double va = vs[s], vb = vs[s + 1], vm = 0.5 * (va + vb);
            if (!(vb > va)) continue;
            struct Edge { double a, b, um; };  // u = a + b·v
            std::vector<Edge> edges;
            for (std::size_t i = 0; i < n; ++i) {
                const Vec2 &p0 = poly.v[i], &p1 = poly.v[(i + 1) % n];
                if ((p0.y > vm) == (p1.y > vm)) continue;  // does not span the slab
                const double slope = (p1.x - p0.x) / (p1.y - p0.y);
                const double a = p0.x - slope * p0.y;
                edges.push_back(Edge{a, slope, a + slope * vm});
            }
            std::sort(edges.begin(), edges.end(), [](const Edge &x, const Edge &y) { return x.um < y.um; });
            for (std::size_t e = 0; e + 1 < edges.size(); e += 2) {  // even–odd pairs
                // Clamp each limit to the box: in a slab an edge is wholly left, inside or right.
                auto clampEdge = [&](const Edge &ed, double *a, double *b) {
                    if (ed.um < box.lo.x) *a = box.lo.x, *b = 0;
                    else if (ed.um > box.hi.x) *a = box.hi.x, *b = 0;
                    else *a = ed.a, *b = ed.b;
                };
                MaskPiece p;
                p.v0 = va;
                p.v1 = vb;
                p.t = poly.t;
                clampEdge(edges[e], &p.loA, &p.loB);
                clampEdge(edges[e + 1], &p.hiA, &p.hiB);
                if (p.UHi(vm) > p.ULo(vm)) f(p);
            }
        }
    }
}

bool ApertureMask::IsSlitsAlongV(double minLength, double *v0, double *v1) const {
    if (rects_.empty() || !discs_.empty() || !polygons_.empty() || userRects_ != int(rects_.size())) return false;
    const double a = rects_[0].lo.y, b = rects_[0].hi.y;
    const double tol = 1e-12 * std::max(std::abs(a), std::abs(b)) + 1e-18;
    for (const Rect &r : rects_)
        if (std::abs(r.lo.y - a) > tol || std::abs(r.hi.y - b) > tol) return false;
    if (!(b - a >= minLength)) return false;
    if (v0) *v0 = a;
    if (v1) *v1 = b;
    return true;
}

std::string ApertureMask::ToString() const {
    std::ostringstream os;
    os << userRects_ << " rectangles, " << discs_.size() << " discs, " << polygons_.size() << " polygons, "
       << (rects_.size() - userRects_) << " bitmap runs, open area " << OpenArea() << " m²";
    return os.str();
}

PlateFrame PlateFrame::FromTransform(const Transform &toWorld) {
    PlateFrame f;
    f.origin = toWorld.Point(Vec3(0, 0, 0));
    const Vec3 a1 = toWorld.Vector(Vec3(1, 0, 0)), a2 = toWorld.Vector(Vec3(0, 1, 0)),
               a3 = toWorld.Vector(Vec3(0, 0, 1));
    const double tol = 1e-9;
    if (std::abs(Length(a1) - 1) > tol || std::abs(Length(a2) - 1) > tol || std::abs(Length(a3) - 1) > tol)
        throw Error("the plate's to_world scales it; give opening sizes in metres and place the plate with "
                    "rotations and translations only");
    if (std::abs(Dot(a1, a2)) > tol || std::abs(Dot(a1, a3)) > tol || std::abs(Dot(a2, a3)) > tol)
        throw Error("the plate's to_world shears it; use rotations and translations only");
    if (Dot(Cross(a1, a2), a3) < 0) throw Error("the plate's to_world mirrors it; use rotations and translations only");
    f.e1 = a1;
    f.e2 = a2;
    f.n = a3;
    return f;
}

const ApertureMask *OpeningsOf(const Material &m) {
    const auto *p = dynamic_cast<const PlateOpenings *>(&m);
    return p ? &p->Openings() : nullptr;
}

}  // namespace phasor
