// SPDX-License-Identifier: Apache-2.0
// phasor — free-space diffraction: event search and the shadow mask (fsd_geometry.h).
#include "integrators/fsd/fsd_geometry.h"

#include <algorithm>
#include <cmath>

#include "core/geometry/analytic.h"
#include "core/geometry/intersect.h"
#include "core/numerics/gauss_legendre.h"

namespace phasor::fsd {

std::vector<ParamSpec> Params() {
    return {P::Bool("fsd",
                    "free-space diffraction at the edges of opaque geometry inside a generalized ray's "
                    "footprint (theory §4.8, docs/fsd.md); off: edges shadow sharply")
                .Default(Value::Bool(false)),
            P::Number("fsd_window", "FSD integration radius in units of the GR's footprint β (D13)")
                .Default(Value::Number(4))
                .Min(1),
            P::Length("fsd_radius",
                      "a constant FSD integration radius instead of fsd_window·β (0: the footprint's); "
                      "for comparisons only: too small is wrong, too large is slow (docs/fsd.md §6)")
                .Default(Value::Number(0, Dim::Length()))
                .Min(0)};
}

Settings SettingsFromParams(const ParamDict &d) {
    Settings s;
    s.enabled = d.GetBool("fsd");
    s.window = d.GetNumber("fsd_window");
    s.radius = d.GetNumber("fsd_radius");
    return s;
}

namespace {

// A kernel transmits if, for light from either side, one of its lobes (near-delta or sampled)
// leaves on the far side with a non-zero weight; probed in the ray-optics limit at 550 nm over a
// few incidence angles (kernels are not textured by direction).
bool Transmits(const Material &m) {
    SampledWavelengths wl;
    wl.lambda.fill(550e-9);
    wl.pdf.fill(1);
    wl.delta = true;
    for (double z : {1.0, 0.6, 0.2, -1.0, -0.6, -0.2}) {
        ScatterQuery q;
        q.wi = Normalize(Vec3(std::sqrt(std::max(0.0, 1 - z * z)), 0, z));
        q.wl = &wl;
        q.rayOptics = true;
        q.tex = TextureEvalContext::AtUV(Vec2(0.5, 0.5));
        ScratchBuffer scratch;
        const PreparedKernel &k = m.Prepare(q, scratch);
        for (const NearDeltaLobe &l : k.ListNearDelta())
            if ((l.flags & ScatterTransmission) && l.Weight().Max() > 0) return true;
        for (int i = 0; i < 16; ++i) {
            const double u = (i + 0.5) / 16;
            auto s = k.Sample(u, Vec2(std::fmod(u * 7.31, 1.0), std::fmod(u * 3.77, 1.0)));
            if (s && (s->flags & ScatterTransmission) && s->weight.Max() > 0) return true;
        }
    }
    return false;
}

// Closest points of the segments p0 + s·(p1 − p0) and q0 + t·(q1 − q0), s, t ∈ [0, 1]
// (Ericson, "Real-Time Collision Detection", 2005, §5.1.9).
double SegmentSegment(const Vec3 &p0, const Vec3 &p1, const Vec3 &q0, const Vec3 &q1, double *s, double *t) {
    const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const double a = Dot(d1, d1), e = Dot(d2, d2), f = Dot(d2, r);
    if (a <= 0 && e <= 0) {
        *s = *t = 0;
        return Length(p0 - q0);
    }
    if (a <= 0) {
        *s = 0;
        *t = std::clamp(f / e, 0.0, 1.0);
    } else {
        const double c = Dot(d1, r);
        if (e <= 0) {
            *t = 0;
            *s = std::clamp(-c / a, 0.0, 1.0);
        } else {
            const double b = Dot(d1, d2), den = a * e - b * b;
            *s = den > 0 ? std::clamp((b * f - c * e) / den, 0.0, 1.0) : 0.0;
            *t = (b * *s + f) / e;
            if (*t < 0) {
                *t = 0;
                *s = std::clamp(-c / a, 0.0, 1.0);
            } else if (*t > 1) {
                *t = 1;
                *s = std::clamp((b - c) / a, 0.0, 1.0);
            }
        }
    }
    return Length((p0 + d1 * *s) - (q0 + d2 * *t));
}

// Closest point of triangle (a, b, c) to p (Ericson §5.1.5).
Vec3 ClosestOnTriangle(const Vec3 &p, const Vec3 &a, const Vec3 &b, const Vec3 &c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = Dot(ab, ap), d2 = Dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const Vec3 bp = p - b;
    const double d3 = Dot(ab, bp), d4 = Dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
    const Vec3 cp = p - c;
    const double d5 = Dot(ab, cp), d6 = Dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const double den = 1 / (va + vb + vc);
    return a + ab * (vb * den) + ac * (vc * den);
}

// Distance between the axis segment o + τd, τ ∈ [t0, t1], and a triangle; *tau gets the axis
// parameter of the closest approach.
double AxisTriangle(const Vec3 &o, const Vec3 &d, double t0, double t1, const Vec3 &a, const Vec3 &b,
                    const Vec3 &c, double *tau) {
    if (auto h = RayTriangle(Ray{o, d}, a, b, c, t0, t1)) {
        *tau = h->t;
        return 0;
    }
    const Vec3 p0 = o + d * t0, p1 = o + d * t1;
    double best = Infinity;
    for (double t : {t0, t1}) {
        const Vec3 p = o + d * t;
        const double dist = Length(ClosestOnTriangle(p, a, b, c) - p);
        if (dist < best) best = dist, *tau = t;
    }
    const Vec3 v[3] = {a, b, c};
    for (int i = 0; i < 3; ++i) {
        double s, t;
        const double dist = SegmentSegment(p0, p1, v[i], v[(i + 1) % 3], &s, &t);
        if (dist < best) best = dist, *tau = t0 + s * (t1 - t0);
    }
    return best;
}

// Number of polygon vertices for a circle of radius r [m] with a sagitta below tol.
int CircleVertices(double r, double tol) {
    const double n = Pi * std::sqrt(std::max(r, 0.0) / (2 * std::max(tol, 1e-300)));
    return int(std::clamp(std::ceil(n), 16.0, 512.0));
}

// The largest depth along the ray r of a point of the bounds b (≤ 0: all behind its origin).
double FarthestDepth(const Bounds3 &b, const Ray &r) {
    double best = -Infinity;
    for (int i = 0; i < 8; ++i) {
        const Vec3 c(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z);
        best = std::max(best, Dot(c - r.o, r.d));
    }
    return best;
}

}  // namespace

Occluders::Occluders(const Scene &scene) {
    const auto &shapes = scene.GetAccel().Shapes();
    occluder_.assign(shapes.size(), 0);
    for (std::size_t i = 0; i < shapes.size(); ++i) {
        const Material *m = shapes[i]->material;
        const bool opaque = !m || (!m->IsFootprintAware() && !Transmits(*m));
        occluder_[i] = opaque ? 1 : 0;
        any_ = any_ || opaque;
    }
}

double IntegrationRadius(const SpectralGenRay &g, double t, const Settings &s) {
    if (s.radius > 0) return s.radius;
    double b2 = 0;
    for (int i = 0; i < g.count; ++i) b2 = std::max(b2, Beta2At(g.k[i], g.beta2[i], g.rho[i], t));
    return s.window * std::sqrt(b2);
}

double GaussianMass(const Trapezoid &tr, double beta2) {
    // ∫ N(v)·½[erf(hi(v)/β) − erf(lo(v)/β)] dv, N(v) = e^{−v²/β²}/(√π β): panels of ≤ β/2,
    // 8 Gauss–Legendre nodes each (the integrand is smooth on the scale β).
    const double beta = std::sqrt(beta2);
    if (!(beta > 0) || !(tr.v1 > tr.v0)) return 0;
    const double v0 = std::max(tr.v0, -8 * beta), v1 = std::min(tr.v1, 8 * beta);
    if (!(v1 > v0)) return 0;
    const int panels = std::max(1, int(std::ceil((v1 - v0) / (0.5 * beta))));
    const double inv = 1 / beta;
    const double m = IntegrateGaussLegendre(
        [&](double v) {
            const double lo = tr.Lo(v), hi = tr.Hi(v);
            if (!(hi > lo)) return 0.0;
            return std::exp(-v * v * inv * inv) * inv / std::sqrt(Pi) * 0.5 *
                   (std::erf(hi * inv) - std::erf(lo * inv));
        },
        v0, v1, 8, panels);
    return std::max(0.0, m);
}

void BuildMask(const Scene &scene, const Occluders &occ, const SpectralGenRay &g, double t, const Shape *exclude,
               const Settings &s, Event *ev, SearchCost *cost, double tEnd) {
    ev->t = t;
    ev->p = g.o + g.d * t;
    ev->frame = Frame::FromNormal(g.d);
    ev->halfWidth = IntegrationRadius(g, t, s);
    // The ball around the box [−2ϱ, 2ϱ] × [−ϱ, ϱ]: every triangle that meets the box is gathered,
    // so the union is exact inside it.
    ev->gatherRadius = std::sqrt(5.0) * ev->halfWidth * (1 + 1e-9);
    ev->heroBeta2 = Beta2At(g.k[0], g.beta2[0], g.rho[0], t);
    ev->edges.clear();
    ev->beyond = 0;
    auto reach = [&](double d) { ev->beyond = std::clamp(std::max(ev->beyond, d - t), 0.0, ev->gatherRadius); };
    const Frame &f = ev->frame;
    const double rho = ev->halfWidth;
    auto toPlane = [&](const Vec3 &x) {
        const Vec3 r = x - ev->p;
        return Vec2(Dot(r, f.s), Dot(r, f.t));
    };
    // Depth from the segment's origin: geometry behind the GR's origin or beyond the segment's end
    // (the hit, a source) is not in its way.
    const double eps = 1e-9 * (rho + t);
    const double far = tEnd;
    auto depth = [&](const Vec3 &x) { return Dot(x - g.o, g.d); };

    // Gather: every opaque primitive within gatherRadius of p.
    struct Tri {
        unsigned shape, prim;
    };
    std::vector<Tri> tris;
    std::vector<unsigned> analytic;
    const Accel &accel = scene.GetAccel();
    const auto &shapes = accel.Shapes();
    accel.ForEachNear(ev->p, ev->gatherRadius, [&](unsigned shape, unsigned prim) {
        if (!occ.Contains(shape) || shapes[shape] == exclude) return;
        if (shapes[shape]->Mesh()) tris.push_back({shape, prim});
        else if (std::find(analytic.begin(), analytic.end(), shape) == analytic.end()) analytic.push_back(shape);
    });
    if (cost) {
        ++cost->ballQueries;
        cost->primitives += int(tris.size() + analytic.size());
    }

    // Triangles: projected, oriented counter-clockwise in the plane; each edge keyed by its
    // mesh vertices so that shared edges can be found.
    struct EdgeRec {
        unsigned shape;
        uint32_t lo, hi;  // mesh vertex indices, lo < hi (the key)
        bool forward;     // the oriented edge runs lo → hi
        OrientedSegment seg;
        bool keyed;       // false for edges of clipped triangles (never cancelled)
    };
    std::vector<EdgeRec> recs;
    const double r2 = ev->gatherRadius * ev->gatherRadius;
    for (const Tri &tr : tris) {
        const TriangleMesh &mesh = *shapes[tr.shape]->Mesh();
        const uint32_t *idx = &mesh.indices[3 * std::size_t(tr.prim)];
        const Vec3 P[3] = {mesh.positions[idx[0]], mesh.positions[idx[1]], mesh.positions[idx[2]]};
        // Exact test: the triangle meets the gather ball.
        if (LengthSquared(ClosestOnTriangle(ev->p, P[0], P[1], P[2]) - ev->p) > r2) continue;
        const double dep[3] = {depth(P[0]), depth(P[1]), depth(P[2])};
        // Only the part between the GR's origin and the segment's end is in its way.
        if (std::max({dep[0], dep[1], dep[2]}) <= eps || std::min({dep[0], dep[1], dep[2]}) >= far) continue;
        const bool clipped = std::min({dep[0], dep[1], dep[2]}) <= eps || std::max({dep[0], dep[1], dep[2]}) >= far;
        reach(std::min(std::max({dep[0], dep[1], dep[2]}), far));
        // The polygon (3-D points with the triangle vertex each is, −1 if made by a clip), clipped
        // to eps < depth < far (Sutherland–Hodgman, one plane after the other).
        std::vector<std::pair<Vec3, int>> pts = {{P[0], 0}, {P[1], 1}, {P[2], 2}};
        if (clipped) {
            for (int side = 0; side < 2; ++side) {
                auto inside = [&](const Vec3 &x) { return side == 0 ? depth(x) > eps : depth(x) < far; };
                const double bound = side == 0 ? eps : far;
                std::vector<std::pair<Vec3, int>> out;
                for (std::size_t i = 0; i < pts.size(); ++i) {
                    const auto &a = pts[i], &b = pts[(i + 1) % pts.size()];
                    if (inside(a.first)) out.push_back(a);
                    if (inside(a.first) != inside(b.first)) {
                        const double da = depth(a.first), db = depth(b.first);
                        out.push_back({a.first + (b.first - a.first) * ((bound - da) / (db - da)), -1});
                    }
                }
                pts.swap(out);
            }
        }
        std::vector<Vec2> poly;
        std::vector<int> from;
        for (const auto &[x, i] : pts) poly.push_back(toPlane(x)), from.push_back(i);
        if (poly.size() < 3) continue;
        double area2 = 0, size2 = 0;
        for (std::size_t i = 0; i < poly.size(); ++i) {
            const Vec2 &a = poly[i], &b = poly[(i + 1) % poly.size()];
            area2 += a.x * b.y - b.x * a.y;
            size2 = std::max(size2, LengthSquared(b - a));
        }
        if (!(std::abs(area2) > 1e-12 * size2)) continue;  // seen edge-on: no area
        const bool ccw = area2 > 0;
        const std::size_t n = poly.size();
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t j = (i + 1) % n;
            EdgeRec e;
            e.shape = tr.shape;
            e.seg = ccw ? OrientedSegment{poly[i], poly[j], -1} : OrientedSegment{poly[j], poly[i], -1};
            e.keyed = !clipped && from[i] >= 0 && from[j] >= 0;
            if (e.keyed) {
                const uint32_t a = idx[from[i]], b = idx[from[j]];
                // Direction of the oriented edge in mesh vertices.
                const uint32_t ta = ccw ? a : b, tb = ccw ? b : a;
                e.lo = std::min(a, b);
                e.hi = std::max(a, b);
                e.forward = ta < tb;
            } else {
                e.lo = e.hi = 0;
                e.forward = true;
            }
            recs.push_back(e);
        }
    }
    // The edge detector: an edge shared by two gathered triangles whose projections lie on
    // opposite sides of it (the two oriented copies run opposite ways) is inside the shadow and
    // cancels; what remains are silhouette edges (both faces on one side: one faces the GR, one
    // faces away), open boundaries and edges shared with triangles outside the ball.
    std::vector<std::size_t> order(recs.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        const EdgeRec &x = recs[a], &y = recs[b];
        if (x.keyed != y.keyed) return x.keyed < y.keyed;
        if (x.shape != y.shape) return x.shape < y.shape;
        if (x.lo != y.lo) return x.lo < y.lo;
        return x.hi < y.hi;
    });
    for (std::size_t i = 0; i < order.size();) {
        const EdgeRec &e = recs[order[i]];
        std::size_t j = i + 1;
        if (e.keyed)
            while (j < order.size() && recs[order[j]].keyed && recs[order[j]].shape == e.shape &&
                   recs[order[j]].lo == e.lo && recs[order[j]].hi == e.hi)
                ++j;
        if (j - i == 2 && recs[order[i]].forward != recs[order[i + 1]].forward) {
            i = j;  // interior: the two copies cancel
            continue;
        }
        for (std::size_t k = i; k < j; ++k) ev->edges.push_back(recs[order[k]].seg);
        i = j;
    }

    // Analytic shapes: a sphere's outline is a circle of its radius around its projected centre;
    // a disk's rim projects to an ellipse. Both as polygons (sagitta ≤ 10⁻³ ϱ).
    for (unsigned si : analytic) {
        const Shape *shape = shapes[si];
        std::vector<Vec2> poly;
        if (const auto *sphere = dynamic_cast<const AnalyticSphere *>(shape)) {
            if (depth(sphere->Center()) <= eps) continue;
            if (LengthSquared(g.o - sphere->Center()) < sphere->Radius() * sphere->Radius()) continue;  // a room
            const Vec2 c = toPlane(sphere->Center());
            const double r = sphere->Radius();
            if (Length(c) > r + 2 * ev->gatherRadius) continue;
            reach(depth(sphere->Center()) + r);
            const int nv = CircleVertices(r, 1e-3 * rho);
            // Equal-area polygon: radius r·√(2π/(n sin(2π/n))).
            const double rp = r * std::sqrt(2 * Pi / (nv * std::sin(2 * Pi / nv)));
            for (int k = 0; k < nv; ++k) {
                const double phi = 2 * Pi * k / nv;
                poly.push_back(c + Vec2(std::cos(phi), std::sin(phi)) * rp);
            }
        } else if (const auto *disk = dynamic_cast<const AnalyticDisk *>(shape)) {
            if (depth(disk->Center()) <= eps) continue;
            double rmax = 0;
            for (int k = 0; k < 4; ++k) rmax = std::max(rmax, Length(disk->RimPoint(0.5 * Pi * k) - disk->Center()));
            const int nv = CircleVertices(rmax, 1e-3 * rho);
            const double scale = std::sqrt(2 * Pi / (nv * std::sin(2 * Pi / nv)));
            const Vec2 c = toPlane(disk->Center());
            reach(depth(disk->Center()) + rmax);
            for (int k = 0; k < nv; ++k) poly.push_back(c + (toPlane(disk->RimPoint(2 * Pi * k / nv)) - c) * scale);
        } else {
            continue;  // an analytic shape without a known outline casts no FSD shadow
        }
        double area2 = 0;
        for (std::size_t i = 0; i < poly.size(); ++i) {
            const Vec2 &a = poly[i], &b = poly[(i + 1) % poly.size()];
            area2 += a.x * b.y - b.x * a.y;
        }
        if (!(std::abs(area2) > 0)) continue;
        for (std::size_t i = 0; i < poly.size(); ++i) {
            const std::size_t j = (i + 1) % poly.size();
            ev->edges.push_back(area2 > 0 ? OrientedSegment{poly[i], poly[j], -1}
                                          : OrientedSegment{poly[j], poly[i], -1});
        }
    }
    for (std::size_t i = 0; i < ev->edges.size(); ++i) ev->edges[i].id = int(i);

    ev->mask = DecomposeUnion(ev->edges, 2 * rho, rho);
    ev->coveredMass.clear();
    ev->coveredFraction = 0;
    for (const Trapezoid &tr : ev->mask.covered) {
        ev->coveredMass.push_back(GaussianMass(tr, ev->heroBeta2));
        ev->coveredFraction += ev->coveredMass.back();
    }
}

Search FindEvent(const Scene &scene, const Occluders &occ, const SpectralGenRay &g, double tEnd, const Shape *exclude,
                 const Settings &s, Event *ev, SearchCost *cost, double source) {
    if (!occ.Any()) return Search::None;
    const Accel &accel = scene.GetAccel();
    const auto &shapes = accel.Shapes();
    const Ray axis{g.o, g.d};
    // Walk the mean ray to its hit or to the farthest depth of the scene's bounds (every point of
    // the scene is nearest to the axis at a depth ≤ that; the balls cover the footprint around it,
    // so the axis may miss the bounds while the footprint meets them). Events lie on this part:
    // geometry beyond the surface the mean ray hits is behind it.
    const double tStop = std::min(tEnd, FarthestDepth(scene.Bounds(), axis));
    if (!(tStop > 0) || !std::isfinite(tStop)) return Search::None;
    constexpr int MaxBalls = 256;
    double t = 0;
    // Balls at least this long keep the count ≤ MaxBalls.
    const double minStep = tStop / MaxBalls;
    for (int n = 0; t < tStop && n < 4 * MaxBalls; ++n) {
        const double step = std::max(2 * IntegrationRadius(g, t, s), minStep);
        const double t1 = std::min(t + step, tStop);
        const double rEnd = IntegrationRadius(g, t1, s);
        const Vec3 c = g.o + g.d * (0.5 * (t + t1));
        const double radius = std::sqrt(0.25 * (t1 - t) * (t1 - t) + rEnd * rEnd);
        // The primitives this ball holds, each at its nearest approach to the rest of the axis
        // [t, tStop] (a sphere met by the ball's end is nearest at its equator, further on).
        double bestDist = Infinity, bestTau = 0;
        accel.ForEachNear(c, radius, [&](unsigned si, unsigned prim) {
            if (!occ.Contains(si) || shapes[si] == exclude) return;
            const Shape *shape = shapes[si];
            double tau = t, dist = Infinity;
            if (const TriangleMesh *mesh = shape->Mesh()) {
                const uint32_t *idx = &mesh->indices[3 * std::size_t(prim)];
                dist = AxisTriangle(g.o, g.d, t, tStop, mesh->positions[idx[0]], mesh->positions[idx[1]],
                                    mesh->positions[idx[2]], &tau);
            } else if (const auto *sphere = dynamic_cast<const AnalyticSphere *>(shape)) {
                // A sphere around the GR's origin (a room) has no outline in its way: its inside
                // is met only where the mean ray hits it.
                if (LengthSquared(g.o - sphere->Center()) < sphere->Radius() * sphere->Radius()) return;
                tau = std::clamp(Dot(sphere->Center() - g.o, g.d), t, tStop);
                dist = std::max(0.0, Length(g.o + g.d * tau - sphere->Center()) - sphere->Radius());
            } else if (const auto *disk = dynamic_cast<const AnalyticDisk *>(shape)) {
                if (auto h = disk->Intersect(axis, t, tStop)) {
                    tau = *h;
                    dist = 0;
                } else {
                    for (int k = 0; k < 64; ++k) {
                        double ss, tt;
                        const double dd = SegmentSegment(g.o + g.d * t, g.o + g.d * tStop,
                                                          disk->RimPoint(2 * Pi * k / 64),
                                                          disk->RimPoint(2 * Pi * (k + 1) / 64), &ss, &tt);
                        if (dd < dist) dist = dd, tau = t + ss * (tStop - t);
                    }
                }
            }
            if (cost) ++cost->primitives;
            // Within the footprint at its depth; the nearest to the axis, and among equally near
            // ones (a face and its edge, both faces of a thin plate), the first along the GR.
            const double r = IntegrationRadius(g, tau, s);
            if (!(dist <= r)) return;
            const double tol = 1e-9 * r;
            if (dist < bestDist - tol || (dist <= bestDist + tol && tau < bestTau)) bestDist = dist, bestTau = tau;
        });
        if (cost) ++cost->ballQueries;
        if (std::isfinite(bestDist)) {
            BuildMask(scene, occ, g, bestTau, exclude, s, ev, cost, source);
            if (ev->coveredFraction > 1 - 1e-5) return Search::Blocked;
            if (ev->coveredFraction >= 1e-5) return Search::Event;
            // Negligible (geometry at the rim of the footprint): walk on past it.
            t = std::max(t1, bestTau + ev->halfWidth);
            continue;
        }
        t = t1;
    }
    return Search::None;
}

}  // namespace phasor::fsd
