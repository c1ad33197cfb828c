// SPDX-License-Identifier: Apache-2.0
// The Embree accelerator: hits recomputed in double precision must match long-double references
// for spheres, disks and triangles; Occluded must agree with Intersect; spawned rays must not
// re-hit their own surface at real scale; queries are thread-safe.
#include "core/geometry/accel.h"

#include <gtest/gtest.h>

#include <chrono>
#include <set>
#include <cstdlib>
#include <thread>

#include "core/diagnostics.h"
#include "core/geometry/analytic.h"
#include "core/geometry/mesh_io.h"
#include "geometry_test_util.h"
#include "support/stats.h"

namespace phasor {
namespace {

using test::LD;
using test::TestRng;

Vec3 RandomDirection(TestRng &rng) {
    double z = 1 - 2 * rng.Uniform(), phi = 2 * Pi * rng.Uniform(), r = SafeSqrt(1 - z * z);
    return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}
Vec3 RandomInBox(TestRng &rng, const Vec3 &lo, const Vec3 &hi) {
    return Vec3(Lerp(rng.Uniform(), lo.x, hi.x), Lerp(rng.Uniform(), lo.y, hi.y),
                Lerp(rng.Uniform(), lo.z, hi.z));
}

/// A test scene: shape 0 a soup of random triangles, shapes 1…nSpheres spheres, then a disk.
/// Everything is offset by `offset` and has sizes of about a metre (real scale).
struct TestScene {
    std::vector<std::unique_ptr<Shape>> owned;
    std::vector<const Shape *> shapes;
    TriangleMesh mesh;
    std::vector<std::pair<Vec3, double>> spheres;
    Transform diskToWorld;
    double diskRadius = 0.4;
    Vec3 offset;

    TestScene(const Vec3 &off, int nTriangles, int nSpheres, uint64_t seed) : offset(off) {
        TestRng rng(seed);
        for (int i = 0; i < nTriangles; ++i) {
            Vec3 c = off + RandomInBox(rng, Vec3(-3, -3, -3), Vec3(3, 3, 3));
            for (int k = 0; k < 3; ++k) {
                mesh.positions.push_back(c + 0.6 * RandomDirection(rng));
                mesh.indices.push_back(uint32_t(mesh.positions.size() - 1));
            }
        }
        owned.push_back(std::make_unique<MeshShape>(mesh));
        for (int i = 0; i < nSpheres; ++i) {
            Vec3 c = off + RandomInBox(rng, Vec3(-3, -3, -3), Vec3(3, 3, 3));
            double r = 0.1 + 0.5 * rng.Uniform();
            spheres.push_back({c, r});
            owned.push_back(std::make_unique<AnalyticSphere>(c, r));
        }
        diskToWorld =
            Transform::Translate(off + Vec3(0.5, -0.5, 0.2)) * Transform::Rotate(0.8, Vec3(1, 2, 0));
        owned.push_back(std::make_unique<AnalyticDisk>(diskRadius, diskToWorld));
        for (auto &s : owned) shapes.push_back(s.get());
    }

    /// A ray from a random origin in a larger box towards a random point of a random shape.
    Ray RandomRay(TestRng &rng) const {
        Vec3 o = offset + RandomInBox(rng, Vec3(-6, -6, -6), Vec3(6, 6, 6));
        Vec3 target;
        std::size_t s = std::min<std::size_t>(shapes.size() - 1, std::size_t(rng.Uniform() * shapes.size()));
        if (s == 0) {
            std::size_t tri = std::min<std::size_t>(mesh.TriangleCount() - 1,
                                                    std::size_t(rng.Uniform() * mesh.TriangleCount()));
            double b1 = rng.Uniform(), b2 = rng.Uniform();
            if (b1 + b2 > 1) {
                b1 = 1 - b1;
                b2 = 1 - b2;
            }
            target = (1 - b1 - b2) * mesh.positions[3 * tri] + b1 * mesh.positions[3 * tri + 1] +
                     b2 * mesh.positions[3 * tri + 2];
        } else if (s <= spheres.size()) {
            target =
                spheres[s - 1].first + 0.95 * spheres[s - 1].second * RandomDirection(rng) * rng.Uniform();
        } else {
            double rho = diskRadius * std::sqrt(rng.Uniform()), phi = 2 * Pi * rng.Uniform();
            target = diskToWorld.Point(Vec3(rho * std::cos(phi), rho * std::sin(phi), 0));
        }
        return Ray{o, Normalize(target - o)};
    }

    /// Long-double reference: every intersection in (tMin, tMax) sorted by t, with a flag for
    /// hits that are numerically ambiguous (near an edge or grazing).
    struct RefHit {
        LD t;
        unsigned shape, prim;
        LD b1, b2;
        bool ambiguous;
    };
    std::vector<RefHit> Reference(const Ray &ray, LD tMin, LD tMax) const {
        std::vector<RefHit> hits;
        const LD edgeEps = 1e-6L;
        for (std::size_t i = 0; i < mesh.TriangleCount(); ++i) {
            const Vec3 &p0 = mesh.positions[3 * i], &p1 = mesh.positions[3 * i + 1],
                       &p2 = mesh.positions[3 * i + 2];
            // Plane hit including slightly outside the triangle, to flag edge cases.
            test::LVec e1 = test::Sub(test::L(p1), test::L(p0)), e2 = test::Sub(test::L(p2), test::L(p0));
            test::LVec d = test::L(ray.d), s = test::Sub(test::L(ray.o), test::L(p0)), md{-d.x, -d.y, -d.z};
            LD det = test::LDot(md, test::LCross(e1, e2));
            if (det == 0) continue;
            LD t = test::LDot(s, test::LCross(e1, e2)) / det;
            LD b1 = test::LDot(md, test::LCross(s, e2)) / det, b2 = test::LDot(md, test::LCross(e1, s)) / det;
            LD b0 = 1 - b1 - b2;
            bool inside = b0 >= 0 && b1 >= 0 && b2 >= 0;
            bool nearEdge = std::min({fabsl(b0), fabsl(b1), fabsl(b2)}) < edgeEps;
            if (!(t > tMin && t < tMax)) continue;
            if (inside || nearEdge) hits.push_back({t, 0, unsigned(i), b1, b2, nearEdge || !inside});
        }
        for (std::size_t k = 0; k < spheres.size(); ++k) {
            auto [c, r] = spheres[k];
            test::LVec oc = test::Sub(test::L(ray.o), test::L(c)), d = test::L(ray.d);
            LD b = test::LDot(oc, d), cc = test::LDot(oc, oc) - LD(r) * r,
               disc = b * b - test::LDot(d, d) * cc;
            bool grazing = fabsl(disc) < 1e-6L * r * r;
            if (disc < 0 && !grazing) continue;
            LD sq = sqrtl(std::max<LD>(disc, 0));
            for (LD t : {(-b - sq), (-b + sq)})
                if (t > tMin && t < tMax) hits.push_back({t, unsigned(k + 1), 0, 0, 0, grazing});
        }
        {
            Transform inv = diskToWorld.Inverse();
            Vec3 o = inv.Point(ray.o), d = inv.Vector(ray.d);
            if (d.z != 0) {
                LD t = -LD(o.z) / d.z;
                LD x = o.x + t * d.x, y = o.y + t * d.y, rr = sqrtl(x * x + y * y);
                bool nearRim = fabsl(rr - diskRadius) < 1e-6L;
                if (t > tMin && t < tMax && (rr <= diskRadius || nearRim))
                    hits.push_back({t, unsigned(spheres.size() + 1), 0, 0, 0, nearRim});
            }
        }
        std::sort(hits.begin(), hits.end(), [](const RefHit &a, const RefHit &b) { return a.t < b.t; });
        return hits;
    }
};

/// True when the nearest reference hit is unambiguous: not near an edge, not grazing, and not
/// within 1e-6 (relative) of the next hit on another shape or triangle.
bool Unambiguous(const std::vector<TestScene::RefHit> &h) {
    if (h.empty()) return true;
    if (h[0].ambiguous) return false;
    if (h.size() > 1 && (h[1].ambiguous || h[1].t - h[0].t < 1e-6L * h[0].t)) return false;
    return true;
}

// Embree picks the primitive in float; t, b1, b2 are recomputed in double. Tolerance 1e-9
// relative: the double Möller–Trumbore / quadratic errors are ~1e-15·κ with κ ≲ 1e3 for these
// non-grazing rays, while float results (relative error ~3e-8) would fail — checked below.
void CheckAgainstReference(const Vec3 &offset, uint64_t seed) {
    TestScene scene(offset, 300, 12, seed);
    Accel accel(scene.shapes);
    TestRng rng(seed + 1);
    int compared = 0, skipped = 0, floatWouldFail = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        Ray ray = scene.RandomRay(rng);
        auto ref = scene.Reference(ray, 0, Infinity);
        if (!Unambiguous(ref)) {
            ++skipped;
            continue;
        }
        auto hit = accel.Intersect(ray);
        ASSERT_EQ(hit.has_value(), !ref.empty()) << "ray " << i;
        if (!hit) continue;
        ++compared;
        double t = double(ref[0].t);
        ASSERT_EQ(hit->shapeIndex, ref[0].shape) << "ray " << i;
        ASSERT_NEAR(hit->t, t, 1e-9 * t) << "ray " << i << " shape " << hit->shapeIndex;
        if (std::abs(double(float(t)) - t) > 1e-9 * t) ++floatWouldFail;
        if (hit->shapeIndex == 0) {
            ASSERT_EQ(hit->prim, ref[0].prim) << "ray " << i;
            ASSERT_NEAR(hit->b1, double(ref[0].b1), 1e-9) << "ray " << i;
            ASSERT_NEAR(hit->b2, double(ref[0].b2), 1e-9) << "ray " << i;
        }
        // IntersectSurface returns the same surface point.
        auto si = accel.IntersectSurface(ray);
        ASSERT_TRUE(si);
        ASSERT_LT(Length(si->p - ray.At(t)), 1e-9 * (1 + Length(ray.o)));
    }
    EXPECT_LT(skipped, n / 50) << "too many ambiguous rays";
    EXPECT_GT(compared, n / 2);
    EXPECT_GT(floatWouldFail, compared / 2) << "the tolerance must be able to reject float results";
}

TEST(Accel, HitsMatchDoublePrecisionReferenceNearOrigin) { CheckAgainstReference(Vec3(0, 0, 0), 101); }
TEST(Accel, HitsMatchDoublePrecisionReferenceFarFromOrigin) {
    CheckAgainstReference(Vec3(120, -40, 75), 202);
}

TEST(Accel, OccludedAgreesWithIntersect) {
    TestScene scene(Vec3(3, 1, -2), 200, 8, 303);
    Accel accel(scene.shapes);
    TestRng rng(304);
    int agreeHit = 0, agreeMiss = 0;
    for (int i = 0; i < 20000; ++i) {
        Ray ray = scene.RandomRay(rng);
        double tMin = rng.Uniform() < 0.5 ? 0 : 3 * rng.Uniform();
        double tMax = tMin + 12 * rng.Uniform();
        auto ref = scene.Reference(ray, tMin, tMax);
        auto hit = accel.Intersect(ray, tMin, tMax);
        bool occ = accel.Occluded(ray, tMin, tMax);
        ASSERT_EQ(occ, hit.has_value()) << "ray " << i;
        if (Unambiguous(ref) && (ref.empty() || (ref[0].t - tMin > 1e-6L && tMax - ref[0].t > 1e-6L))) {
            ASSERT_EQ(occ, !ref.empty()) << "ray " << i;
            if (occ) {
                ASSERT_NEAR(hit->t, double(ref[0].t), 1e-9 * double(ref[0].t));
            }
        }
        (occ ? agreeHit : agreeMiss)++;
    }
    EXPECT_GT(agreeHit, 2000);
    EXPECT_GT(agreeMiss, 2000);
}

// Rays spawned from hits at real scale (100 m from the origin, metre-sized shapes) leave the
// surface cleanly: a triangle is planar, so a spawned ray can never legitimately hit the same
// triangle; a ray leaving a sphere outwards can never hit it again, inwards only at the chord.
TEST(Accel, SpawnedRaysDoNotSelfIntersect) {
    TestScene scene(Vec3(100, 30, -60), 300, 12, 505);
    Accel accel(scene.shapes);
    TestRng rng(506);
    int spawned = 0;
    for (int i = 0; i < 20000; ++i) {
        Ray ray = scene.RandomRay(rng);
        auto hit = accel.Intersect(ray);
        if (!hit) continue;
        const Shape *shape = scene.shapes[hit->shapeIndex];
        SurfaceInteraction si = shape->Interaction(ray, hit->t, hit->prim, hit->b1, hit->b2);
        bool isSphere = hit->shapeIndex >= 1 && hit->shapeIndex <= scene.spheres.size();
        for (int side = 0; side < 2; ++side) {
            Vec3 w = RandomDirection(rng);
            if ((Dot(w, si.n) > 0) != (side == 0)) w = -w;
            Ray r{si.SpawnOrigin(w), w};
            ++spawned;
            auto h = accel.Intersect(r);
            if (!h || h->shapeIndex != hit->shapeIndex) continue;
            if (shape->Mesh()) {
                ASSERT_NE(h->prim, hit->prim) << "triangle self-intersection at t = " << h->t;
            } else {
                ASSERT_TRUE(isSphere && side == 1) << "re-hit its own surface at t = " << h->t;
                // The chord of an inward ray is 2r|cos θ| (a little more, from the offset origin).
                double chord = 2 * scene.spheres[hit->shapeIndex - 1].second * std::abs(Dot(w, si.n));
                ASSERT_GT(h->t, 0.5 * chord) << "inward ray re-hit the sphere at its origin";
            }
        }
    }
    EXPECT_GT(spawned, 20000);
}

TEST(Accel, ThreadSafeQueries) {
    TestScene scene(Vec3(0, 0, 0), 300, 10, 606);
    Accel accel(scene.shapes);
    TestRng rng(607);
    std::vector<Ray> rays;
    for (int i = 0; i < 20000; ++i) rays.push_back(scene.RandomRay(rng));
    std::vector<double> serial(rays.size()), parallel(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        auto h = accel.Intersect(rays[i]);
        serial[i] = h ? h->t : -1;
    }
    auto work = [&](std::size_t begin) {
        for (std::size_t i = begin; i < rays.size(); i += 2) {
            auto h = accel.Intersect(rays[i]);
            parallel[i] = h ? h->t : -1;
        }
    };
    std::thread a(work, 0), b(work, 1);
    a.join();
    b.join();
    EXPECT_EQ(serial, parallel);
    std::size_t hits = 0;
    for (double t : serial) hits += t >= 0;
    EXPECT_EQ(accel.RawIntersectCount(rays), hits);
}

TEST(Accel, EmptySceneAndBounds) {
    Accel empty({});
    EXPECT_FALSE(empty.Intersect(Ray{Vec3(), Vec3(0, 0, 1)}));
    EXPECT_FALSE(empty.Occluded(Ray{Vec3(), Vec3(0, 0, 1)}, 0, Infinity));
    AnalyticSphere s(Vec3(1, 2, 3), 0.5);
    Accel one({&s});
    EXPECT_EQ(one.Bounds().lo, Vec3(0.5, 1.5, 2.5));
    // tMin beyond the near root: the far root, in double precision.
    Ray ray{Vec3(1, 2, 0), Vec3(0, 0, 1)};
    EXPECT_DOUBLE_EQ(one.Intersect(ray)->t, 2.5);
    EXPECT_DOUBLE_EQ(one.Intersect(ray, 2.6)->t, 3.5);
    EXPECT_FALSE(one.Intersect(ray, 3.6));
    EXPECT_FALSE(one.Occluded(ray, 0, 2.4));
    EXPECT_TRUE(one.Occluded(ray, 0, 2.6));
}

// A subdivision surface (15 360 triangles): Embree agrees with the brute-force double-precision
// Shape::Intersect on every ray.
TEST(Accel, SubdivisionMeshAgreesWithBruteForce) {
    MeshShape shape(SubdivideCatmullClark(LoadObjPolygons(test::AssetPath("jack_cage.obj")), 4));
    ASSERT_EQ(shape.Mesh()->TriangleCount(), 30u * 256 * 2);
    Accel accel({&shape});
    TestRng rng(707);
    int hits = 0;
    for (int i = 0; i < 400; ++i) {
        Vec3 o = 5 * RandomDirection(rng);
        Ray ray{o, Normalize(1.2 * RandomDirection(rng) * rng.Uniform() - o)};
        auto bf = shape.Intersect(ray, 0, Infinity);
        auto h = accel.Intersect(ray);
        ASSERT_EQ(bf.has_value(), h.has_value()) << i;
        if (!h) continue;
        ++hits;
        EXPECT_NEAR(h->t, *bf, 1e-9 * *bf);
    }
    EXPECT_GT(hits, 100);
}

// ≥ 1M triangles (subdivision level 8 of the 30-quad jack cage: 3.9M triangles). Slow (a few
// seconds), so it runs only when PHASOR_LARGE_TESTS is set.
TEST(Accel, LargeMeshBuild) {
    if (!std::getenv("PHASOR_LARGE_TESTS")) GTEST_SKIP() << "set PHASOR_LARGE_TESTS=1 to run";
    auto t0 = std::chrono::steady_clock::now();
    MeshShape shape(SubdivideCatmullClark(LoadObjPolygons(test::AssetPath("jack_cage.obj")), 8));
    auto t1 = std::chrono::steady_clock::now();
    Accel accel({&shape});
    auto t2 = std::chrono::steady_clock::now();
    EXPECT_EQ(shape.Mesh()->TriangleCount(), 30u * 65536 * 2);
    TestRng rng(808);
    std::vector<Ray> rays;
    for (int i = 0; i < 1000000; ++i) {
        Vec3 o = 5 * RandomDirection(rng);
        rays.push_back(Ray{o, Normalize(RandomDirection(rng) * rng.Uniform() - o)});
    }
    auto t3 = std::chrono::steady_clock::now();
    std::size_t hits = accel.RawIntersectCount(rays);
    auto t4 = std::chrono::steady_clock::now();
    using S = std::chrono::duration<double>;
    std::printf("subdivide %.2f s, BVH build %.2f s, %.2f Mrays/s (1 thread, %zu hits)\n", S(t1 - t0).count(),
                S(t2 - t1).count(), rays.size() / S(t4 - t3).count() / 1e6, hits);
    EXPECT_GT(hits, rays.size() / 2);
}

}  // namespace
}  // namespace phasor

namespace phasor {
namespace {

// Distance from p to triangle (a, b, c), brute force on a barycentric grid refined by projection
// (enough to decide whether the triangle meets a ball whose radius is not within 1e-3 of it).
double PointTriangleDistance(const Vec3 &p, const Vec3 &a, const Vec3 &b, const Vec3 &c) {
    double best = Infinity;
    const int n = 200;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; i + j <= n; ++j) {
            const double u = double(i) / n, v = double(j) / n;
            best = std::min(best, Length(a + (b - a) * u + (c - a) * v - p));
        }
    return best;
}

TEST(Accel, BallQueryFindsEveryPrimitiveWithinTheRadius) {
    // ForEachNear is conservative: every triangle and analytic shape that meets the ball is
    // reported (it may report more); a ball far from everything reports nothing.
    TestScene sc(Vec3(0, 0, 0), 60, 4, 17);
    Accel accel(sc.shapes);
    TestRng rng(5);
    for (int q = 0; q < 40; ++q) {
        const Vec3 c = RandomInBox(rng, Vec3(-3, -3, -3), Vec3(3, 3, 3));
        const double r = 0.2 + 1.2 * rng.Uniform();
        std::set<std::pair<unsigned, unsigned>> found;
        accel.ForEachNear(c, r, [&](unsigned s, unsigned p) { found.insert({s, p}); });
        for (std::size_t t = 0; t < sc.mesh.TriangleCount(); ++t) {
            const double d = PointTriangleDistance(c, sc.mesh.positions[3 * t], sc.mesh.positions[3 * t + 1],
                                                   sc.mesh.positions[3 * t + 2]);
            if (d < r * (1 - 1e-3)) {
                EXPECT_TRUE(found.count({0u, unsigned(t)})) << "triangle " << t;
            }
        }
        for (std::size_t k = 0; k < sc.spheres.size(); ++k) {
            const double d = Length(sc.spheres[k].first - c) - sc.spheres[k].second;
            if (d < r * (1 - 1e-3)) {
                EXPECT_TRUE(found.count({unsigned(k + 1), 0u})) << "sphere " << k;
            }
        }
    }
    int far = 0;
    accel.ForEachNear(Vec3(100, 100, 100), 1, [&](unsigned, unsigned) { ++far; });
    EXPECT_EQ(far, 0);
}

}  // namespace
}  // namespace phasor
