// SPDX-License-Identifier: Apache-2.0
// SurfaceInteraction::dpdu, dpdv (what textures are evaluated with, TextureEvalContext) for each
// kind of shape: the analytic sphere and disk, and MeshShape (what rectangle, trianglemesh, obj,
// gltf and subdivision build) with given uvs, with the default per-triangle parameterisation and
// from Catmull–Clark subdivision. Check: for two nearby hits, p₂ − p₁ must equal
// dp/du·Δu + dp/dv·Δv to first order (a finite difference of the shape's own positions).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/geometry/analytic.h"
#include "core/geometry/mesh_io.h"
#include "core/geometry/shape.h"
#include "support/stats.h"

namespace phasor {
namespace {

using test::TestRng;

// Relative first-order error |Δp − (dpdu Δu + dpdv Δv)| / |Δp| between hits a and b. For a step ε
// on a surface of curvature radius R the second-order remainder makes it ~ε/R; a wrong factor in
// dp/du or dp/dv (e.g. a missing 2π) makes it O(1).
double FirstOrderError(const SurfaceInteraction &a, const SurfaceInteraction &b) {
    const Vec2 duv = b.uv - a.uv;
    const Vec3 dp = b.p - a.p;
    return Length(dp - (duv.x * a.dpdu + duv.y * a.dpdv)) / Length(dp);
}

// The hit of a ray aimed at `target` from along the normal `n` (analytic shapes).
SurfaceInteraction HitAt(const Shape &s, const Vec3 &target, const Vec3 &n) {
    Ray r{target + 0.5 * n, -n};
    auto t = s.Intersect(r, 0, Infinity);
    EXPECT_TRUE(t.has_value());
    return s.Interaction(r, t.value_or(0.5), 0, 0, 0);
}

// Checks hits near `count` random points of an analytic shape; `point(u)` gives a surface point
// and its normal from two uniform numbers, `scale` the size of the shape [m].
void CheckAnalytic(const Shape &s, double scale, const std::function<std::pair<Vec3, Vec3>(Vec2)> &point) {
    TestRng rng(11);
    const double eps = 1e-6 * scale;
    for (int i = 0; i < 200; ++i) {
        auto [p, n] = point(Vec2(0.05 + 0.9 * rng.Uniform(), 0.05 + 0.9 * rng.Uniform()));
        const SurfaceInteraction a = HitAt(s, p, n);
        const Frame f = Frame::FromNormal(a.n);
        for (double ang : {0.3, 1.9, 3.7, 5.1}) {
            const Vec3 q = a.p + eps * (std::cos(ang) * f.s + std::sin(ang) * f.t);
            const SurfaceInteraction b = HitAt(s, q, a.n);
            if (std::abs(b.uv.x - a.uv.x) > 0.5) continue;  // across the u = 0 / 1 seam
            EXPECT_LT(FirstOrderError(a, b), 1e-4) << "at uv " << a.uv.x << " " << a.uv.y;
        }
    }
}

TEST(Dpdu, Sphere) {
    const Transform rot = Transform::Rotate(0.7, Vec3(1, 2, 3));
    const AnalyticSphere s(Vec3(0.1, -0.2, 0.3), 0.8, rot);
    CheckAnalytic(s, 0.8, [&](Vec2 u) {
        const double z = 1 - 2 * u.x, r = SafeSqrt(1 - z * z), phi = 2 * Pi * u.y;
        // In the sphere's own frame, |cos θ| ≤ 0.9: away from the poles, where u changes fast.
        const Vec3 n = rot.Vector(Vec3(r * std::cos(phi), r * std::sin(phi), z));
        return std::make_pair(s.Center() + s.Radius() * n, n);
    });
}

TEST(Dpdu, Disk) {
    // A non-uniform scale and a rotation: dp/du, dp/dv follow to_world.
    const Transform toWorld = Transform::Translate(Vec3(0.2, 0, -1)) * Transform::Rotate(0.4, Vec3(0, 1, 1)) *
                              Transform::Scale(Vec3(2, 0.5, 1));
    const AnalyticDisk d(0.3, toWorld);
    const Vec3 n = Normalize(toWorld.Normal(Vec3(0, 0, 1)));
    CheckAnalytic(d, 0.3, [&](Vec2 u) {
        const double rho = 0.3 * (0.1 + 0.85 * u.x), phi = 2 * Pi * u.y;
        return std::make_pair(toWorld.Point(Vec3(rho * std::cos(phi), rho * std::sin(phi), 0)), n);
    });
}

// Meshes: pairs of points inside one triangle (the parameterisation is linear there, so the
// first-order relation is exact up to rounding).
void CheckMesh(const MeshShape &m, double tol) {
    const TriangleMesh &mesh = *m.Mesh();
    TestRng rng(5);
    for (std::size_t tri = 0; tri < mesh.TriangleCount(); tri += 1 + mesh.TriangleCount() / 50) {
        const double b1 = 0.1 + 0.3 * rng.Uniform(), b2 = 0.1 + 0.3 * rng.Uniform();
        const SurfaceInteraction a = m.Interaction(Ray{}, 0, unsigned(tri), b1, b2);
        for (auto [d1, d2] : {std::pair{1e-3, 0.0}, {0.0, 1e-3}, {7e-4, -4e-4}}) {
            const SurfaceInteraction b = m.Interaction(Ray{}, 0, unsigned(tri), b1 + d1, b2 + d2);
            EXPECT_LT(FirstOrderError(a, b), tol) << "triangle " << tri;
        }
        EXPECT_GT(Length(a.dpdu), 0);
        EXPECT_GT(Length(a.dpdv), 0);
    }
}

TEST(Dpdu, MeshWithUvs) {
    // A skewed quad with rotated, scaled uvs (as obj/gltf/rectangle give).
    TriangleMesh t;
    t.positions = {{0, 0, 0}, {2, 0.1, 0}, {2.3, 1, 0.5}, {0.2, 1.2, 0.4}};
    t.uvs = {{0.1, 0.2}, {0.9, 0.5}, {0.6, 1.4}, {-0.2, 1.1}};
    t.indices = {0, 1, 2, 0, 2, 3};
    CheckMesh(MeshShape(t), 1e-9);
}

TEST(Dpdu, MeshWithDefaultParameterisation) {
    TriangleMesh t;
    t.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.3}, {0, 1, 0}};
    t.indices = {0, 1, 2, 0, 2, 3};
    CheckMesh(MeshShape(t), 1e-9);
}

TEST(Dpdu, Subdivision) { CheckMesh(MeshShape(SubdivideCatmullClark(CubeCage(), 2)), 1e-9); }

TEST(Dpdu, DegenerateUvsGiveZero) {
    TriangleMesh t;
    t.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    t.uvs = {{0.5, 0.5}, {0.5, 0.5}, {0.5, 0.5}};
    t.indices = {0, 1, 2};
    const SurfaceInteraction si = MeshShape(t).Interaction(Ray{}, 0, 0, 0.3, 0.3);
    EXPECT_EQ(si.dpdu, Vec3(0, 0, 0));
    EXPECT_EQ(si.dpdv, Vec3(0, 0, 0));
}

}  // namespace
}  // namespace phasor
