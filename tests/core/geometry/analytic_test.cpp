// SPDX-License-Identifier: Apache-2.0
// Analytic sphere and disk: double-precision intersection against long-double references,
// interactions, and χ² tests of uniform area sampling.
#include "core/geometry/analytic.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/diagnostics.h"
#include "geometry_test_util.h"
#include "support/stats.h"

namespace phasor {
namespace {

using test::TestRng;

Vec3 RandomInBall(TestRng &rng) {
    for (;;) {
        Vec3 v(2 * rng.Uniform() - 1, 2 * rng.Uniform() - 1, 2 * rng.Uniform() - 1);
        if (LengthSquared(v) <= 1) return v;
    }
}
Vec3 RandomDirection(TestRng &rng) {
    double z = 1 - 2 * rng.Uniform(), phi = 2 * Pi * rng.Uniform(), r = SafeSqrt(1 - z * z);
    return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

// Rays aimed within 0.95 r of the centre: √disc ≥ 0.31 r, so the root's condition number is
// ≤ |o−c|/√disc ≈ 70 and double precision gives ≲ 1e-14 relative error. 1e-12 leaves margin
// while a float computation (~1e-7) would fail.
TEST(Sphere, IntersectMatchesLongDoubleReference) {
    TestRng rng(7);
    for (int i = 0; i < 20000; ++i) {
        Vec3 c = (i % 2 ? 100.0 : 10.0) * RandomInBall(rng);
        double r = 0.1 + 5 * rng.Uniform();
        AnalyticSphere s(c, r);
        Vec3 o = c + (2 + 18 * rng.Uniform()) * r * RandomDirection(rng);
        Vec3 target = c + 0.95 * r * RandomInBall(rng);
        Ray ray{o, Normalize(target - o)};
        auto t = s.Intersect(ray, 0, Infinity);
        auto ref = test::RefSphere(ray, c, r, 0, Infinity);
        ASSERT_TRUE(t && ref) << i;
        EXPECT_NEAR(*t, double(*ref), 1e-12 * double(*ref)) << i;
        // From inside (origin at the centre) the far root is the radius.
        auto inside = s.Intersect(Ray{c, ray.d}, 0, Infinity);
        ASSERT_TRUE(inside);
        EXPECT_NEAR(*inside, r, 1e-12 * r);
    }
}

TEST(Sphere, IntervalAndMisses) {
    AnalyticSphere s(Vec3(0, 0, 0), 1);
    Ray ray{Vec3(0, 0, -5), Vec3(0, 0, 1)};
    EXPECT_DOUBLE_EQ(*s.Intersect(ray, 0, Infinity), 4);
    EXPECT_DOUBLE_EQ(*s.Intersect(ray, 4.5, Infinity), 6);  // near root excluded by tMin
    EXPECT_FALSE(s.Intersect(ray, 0, 3.9));                 // both beyond tMax
    EXPECT_FALSE(s.Intersect(ray, 6.5, Infinity));          // both before tMin
    EXPECT_FALSE(s.Intersect(Ray{Vec3(0, 1.0001, -5), Vec3(0, 0, 1)}, 0, Infinity));
    EXPECT_FALSE(s.Intersect(Ray{Vec3(0, 0, -5), Vec3(0, 0, -1)}, 0, Infinity));
}

TEST(Sphere, InteractionAndFrame) {
    AnalyticSphere s(Vec3(1, 2, 3), 2);
    Ray ray{Vec3(1, 2, 10), Vec3(0, 0, -1)};
    auto t = s.Intersect(ray, 0, Infinity);
    ASSERT_TRUE(t);
    SurfaceInteraction si = s.Interaction(ray, *t, 0, 0, 0);
    EXPECT_NEAR(si.p.z, 5, 1e-14);
    EXPECT_NEAR(si.n.z, 1, 1e-15);
    EXPECT_NEAR(si.uv.y, 0, 1e-12);  // north pole: θ = 0
    EXPECT_EQ(si.shape, &s);
    // Equator, +y: φ = π/2 → u = 1/4, v = 1/2; dp/du along −x.
    Ray r2{Vec3(1, 10, 3), Vec3(0, -1, 0)};
    si = s.Interaction(r2, *s.Intersect(r2, 0, Infinity), 0, 0, 0);
    EXPECT_NEAR(si.uv.x, 0.25, 1e-12);
    EXPECT_NEAR(si.uv.y, 0.5, 1e-12);
    EXPECT_NEAR(si.shading.s.x, -1, 1e-12);
    EXPECT_NEAR(Dot(si.shading.n, si.n), 1, 1e-12);
    EXPECT_NEAR(Dot(si.shading.s, si.shading.n), 0, 1e-12);
}

TEST(Sphere, FromTransformRequiresSimilarity) {
    Transform t = Transform::Translate(Vec3(1, 0, 0)) * Transform::Rotate(0.3, Vec3(1, 1, 0)) *
                  Transform::Scale(Vec3(2, 2, 2));
    AnalyticSphere s = AnalyticSphere::FromTransform(Vec3(0, 0, 1), 0.5, t);
    EXPECT_NEAR(s.Radius(), 1, 1e-12);
    Vec3 c = t.Point(Vec3(0, 0, 1));
    EXPECT_NEAR(Length(s.Center() - c), 0, 1e-12);
    EXPECT_THROW(AnalyticSphere::FromTransform(Vec3(), 1, Transform::Scale(Vec3(1, 2, 1))), Error);
    EXPECT_THROW(AnalyticSphere(Vec3(), -1), Error);
}

// Uniform area sampling: z = n·ẑ is uniform on [−1, 1] and φ uniform (Archimedes); χ² on a
// 10 × 20 grid of equal-area cells in (z, φ).
TEST(Sphere, SamplingIsUniformByArea) {
    AnalyticSphere s(Vec3(0, 1, 0), 3);
    TestRng rng(11);
    const int nz = 10, nphi = 20, n = 200000;
    std::vector<double> obs(nz * nphi, 0), expct(nz * nphi, double(n) / (nz * nphi));
    for (int i = 0; i < n; ++i) {
        ShapeSample ss = s.Sample(Vec2(rng.Uniform(), rng.Uniform()));
        ASSERT_NEAR(Length(ss.p - Vec3(0, 1, 0)), 3, 1e-12);
        ASSERT_NEAR(Dot(ss.n, (ss.p - Vec3(0, 1, 0)) / 3), 1, 1e-12);
        ASSERT_DOUBLE_EQ(ss.pdfArea, 1 / (4 * Pi * 9));
        double phi = std::atan2(ss.n.y, ss.n.x) + Pi;
        int iz = std::min(nz - 1, int((ss.n.z + 1) / 2 * nz));
        int ip = std::min(nphi - 1, int(phi / (2 * Pi) * nphi));
        obs[iz * nphi + ip] += 1;
    }
    auto res = test::Chi2Test(obs, expct);
    EXPECT_GT(res.pValue, 0.001) << res.ToString();
}

TEST(Disk, IntersectionAreaAndSampling) {
    Transform t = Transform::Translate(Vec3(0, 0, 2)) * Transform::Rotate(Radians(40), Vec3(1, 0, 0)) *
                  Transform::Scale(Vec3(2, 1, 1));
    AnalyticDisk d(0.5, t);
    // Ellipse with semi-axes 1 and 0.5.
    EXPECT_NEAR(d.Area(), Pi * 0.5, 1e-14);
    // The ray through the world image of a local point hits at that point, within 1e-12.
    TestRng rng(3);
    for (int i = 0; i < 2000; ++i) {
        double rho = 0.5 * std::sqrt(rng.Uniform()), phi = 2 * Pi * rng.Uniform();
        Vec3 target = t.Point(Vec3(rho * std::cos(phi), rho * std::sin(phi), 0));
        Vec3 o = target + 3 * RandomDirection(rng);
        Ray ray{o, Normalize(target - o)};
        auto hit = d.Intersect(ray, 0, Infinity);
        ASSERT_TRUE(hit) << i;
        EXPECT_NEAR(*hit, Length(target - o), 1e-12 * Length(target - o));
        SurfaceInteraction si = d.Interaction(ray, *hit, 0, 0, 0);
        EXPECT_NEAR(Length(si.p - target), 0, 1e-12);
        EXPECT_NEAR(si.uv.y, rho / 0.5, 1e-9);
    }
    // Outside the rim: miss.
    Vec3 outside = t.Point(Vec3(0.51, 0, 0));
    EXPECT_FALSE(d.Intersect(Ray{outside + Vec3(0, 0, 1), Vec3(0, 0, -1)}, 0, Infinity));
    // Normal: +z mapped as a normal.
    Vec3 n = Normalize(t.Normal(Vec3(0, 0, 1)));
    ShapeSample ss = d.Sample(Vec2(0.3, 0.7));
    EXPECT_NEAR(Dot(ss.n, n), 1, 1e-14);
    EXPECT_DOUBLE_EQ(ss.pdfArea, 1 / d.Area());
    // Bounds contain samples and are tight in x (semi-axis 1 along x).
    Bounds3 b = d.Bounds();
    EXPECT_NEAR(b.hi.x, 1, 1e-14);
    EXPECT_NEAR(b.lo.x, -1, 1e-14);
}

// Uniform by area on the ellipse: in local coordinates the samples must be uniform on the disk:
// χ² over 8 rings of equal area × 16 sectors.
TEST(Disk, SamplingIsUniformByArea) {
    Transform t = Transform::Rotate(0.7, Vec3(0, 1, 1)) * Transform::Scale(Vec3(3, 1, 1));
    AnalyticDisk d(2, t);
    Transform inv = t.Inverse();
    TestRng rng(5);
    const int nr = 8, ns = 16, n = 100000;
    std::vector<double> obs(nr * ns, 0), expct(nr * ns, double(n) / (nr * ns));
    for (int i = 0; i < n; ++i) {
        Vec3 l = inv.Point(d.Sample(Vec2(rng.Uniform(), rng.Uniform())).p);
        ASSERT_NEAR(l.z, 0, 1e-12);
        double r2 = (l.x * l.x + l.y * l.y) / 4, phi = std::atan2(l.y, l.x) + Pi;
        obs[std::min(nr - 1, int(r2 * nr)) * ns + std::min(ns - 1, int(phi / (2 * Pi) * ns))] += 1;
    }
    auto res = test::Chi2Test(obs, expct);
    EXPECT_GT(res.pValue, 0.001) << res.ToString();
}

}  // namespace
}  // namespace phasor
