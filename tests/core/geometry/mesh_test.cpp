// SPDX-License-Identifier: Apache-2.0
// TriangleMesh, MeshShape and SurfaceInteraction::SpawnOrigin.
#include <gtest/gtest.h>

#include <cmath>

#include "core/diagnostics.h"
#include "core/geometry/shape.h"
#include "geometry_test_util.h"
#include "support/stats.h"

namespace phasor {
namespace {

TriangleMesh UnitQuad() {
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

TEST(TriangleMesh, BoundsAreaValidate) {
    TriangleMesh m = UnitQuad();
    EXPECT_DOUBLE_EQ(m.Area(), 1);
    EXPECT_EQ(m.Bounds().hi, Vec3(1, 1, 0));
    EXPECT_NO_THROW(m.Validate("quad"));
    TriangleMesh bad = m;
    bad.indices.push_back(0);
    EXPECT_THROW(bad.Validate("quad"), Error);
    bad = m;
    bad.indices[4] = 4;
    try {
        bad.Validate("quad.obj");
        FAIL();
    } catch (const Error &e) {
        EXPECT_NE(std::string(e.what()).find("quad.obj"), std::string::npos) << e.what();
    }
    bad = m;
    bad.normals = {{0, 0, 1}};
    EXPECT_THROW(bad.Validate("quad"), Error);
    bad = m;
    bad.positions[2].x = NAN;
    EXPECT_THROW(bad.Validate("quad"), Error);
}

TEST(TriangleMesh, MirroringTransformKeepsWindingConsistent) {
    TriangleMesh m = UnitQuad();
    m.normals.assign(4, Vec3(0, 0, 1));
    m.Transform(Transform::Scale(Vec3(-1, 2, 1)));
    EXPECT_EQ(m.positions[1], Vec3(-1, 0, 0));
    const Vec3 &p0 = m.positions[m.indices[0]], &p1 = m.positions[m.indices[1]],
               &p2 = m.positions[m.indices[2]];
    Vec3 ng = Cross(p1 - p0, p2 - p0);
    EXPECT_GT(Dot(ng, m.normals[0]), 0);
    EXPECT_NEAR(Length(m.normals[0]), 1, 1e-15);
}

TEST(MeshShape, InteractionInterpolates) {
    TriangleMesh m = UnitQuad();
    // Normals tilted towards +x at vertices 1 and 2, uvs scaled by 2 along u.
    m.normals = {{0, 0, 1}, Normalize(Vec3(1, 0, 1)), Normalize(Vec3(1, 0, 1)), {0, 0, 1}};
    m.uvs = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
    MeshShape s(m);
    EXPECT_DOUBLE_EQ(s.Area(), 1);
    Ray ray{Vec3(0.75, 0.25, 1), Vec3(0, 0, -1)};
    // Triangle 0 = (0, 1, 2): p = b0 p0 + b1 p1 + b2 p2 → b1 = 0.5, b2 = 0.25.
    SurfaceInteraction si = s.Interaction(ray, 1, 0, 0.5, 0.25);
    EXPECT_NEAR(Length(si.p - Vec3(0.75, 0.25, 0)), 0, 1e-15);
    EXPECT_NEAR(si.uv.x, 1.5, 1e-15);
    EXPECT_NEAR(si.uv.y, 0.25, 1e-15);
    EXPECT_EQ(si.n, Vec3(0, 0, 1));
    Vec3 expectN = Normalize(0.25 * Vec3(0, 0, 1) + 0.75 * Normalize(Vec3(1, 0, 1)));
    EXPECT_NEAR(Dot(si.shading.n, expectN), 1, 1e-14);
    // dp/du = (0.5, 0, 0): the shading tangent is +x projected onto the shading plane.
    EXPECT_GT(si.shading.s.x, 0.5);
    EXPECT_NEAR(Dot(si.shading.s, si.shading.n), 0, 1e-14);
    EXPECT_NEAR(Dot(si.shading.t, Cross(si.shading.n, si.shading.s)), 1, 1e-14);
    EXPECT_EQ(si.shape, &s);
}

TEST(MeshShape, GeometricNormalFollowsVertexNormals) {
    TriangleMesh m = UnitQuad();
    m.normals.assign(4, Vec3(0, 0, -1));  // winding says +z, normals say −z
    MeshShape s(m);
    SurfaceInteraction si = s.Interaction(Ray{}, 0, 1, 0.2, 0.2);
    EXPECT_EQ(si.n, Vec3(0, 0, -1));
    EXPECT_NEAR(si.shading.n.z, -1, 1e-15);
}

TEST(MeshShape, DefaultIntersectIsBruteForce) {
    MeshShape s(UnitQuad());
    auto t = s.Intersect(Ray{Vec3(0.3, 0.6, 2), Vec3(0, 0, -1)}, 0, Infinity);
    ASSERT_TRUE(t);
    EXPECT_DOUBLE_EQ(*t, 2);
    EXPECT_FALSE(s.Intersect(Ray{Vec3(1.3, 0.6, 2), Vec3(0, 0, -1)}, 0, Infinity));
    EXPECT_FALSE(s.Intersect(Ray{Vec3(0.3, 0.6, 2), Vec3(0, 0, -1)}, 0, 1.5));
}

// A 4 × 1 rectangle covered by five triangles of areas 0.5, 1, 1, 1, 0.5: area-uniform sampling
// must be uniform over the rectangle. χ² over 16 × 4 equal cells.
TEST(MeshShape, SamplingIsUniformByArea) {
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {3, 0, 0}, {4, 0, 0}, {0, 1, 0}, {2, 1, 0}, {4, 1, 0}};
    m.indices = {0, 1, 4, 1, 5, 4, 1, 2, 5, 2, 6, 5, 2, 3, 6};
    MeshShape s(m);
    ASSERT_DOUBLE_EQ(s.Area(), 4);
    test::TestRng rng(17);
    const int nx = 16, ny = 4, n = 128000;
    std::vector<double> obs(nx * ny, 0), expct(nx * ny, double(n) / (nx * ny));
    for (int i = 0; i < n; ++i) {
        ShapeSample ss = s.Sample(Vec2(rng.Uniform(), rng.Uniform()));
        ASSERT_DOUBLE_EQ(ss.pdfArea, 0.25);
        ASSERT_EQ(ss.n, Vec3(0, 0, 1));
        ASSERT_TRUE(ss.p.x > -1e-12 && ss.p.x < 4 + 1e-12 && ss.p.y > -1e-12 && ss.p.y < 1 + 1e-12);
        ASSERT_EQ(ss.p.z, 0);
        obs[std::min(ny - 1, int(ss.p.y * ny)) * nx + std::min(nx - 1, int(ss.p.x / 4 * nx))] += 1;
    }
    auto res = test::Chi2Test(obs, expct);
    EXPECT_GT(res.pValue, 0.001) << res.ToString();
    // u = (1, 1) must not pick a zero-area triangle or leave the mesh.
    ShapeSample edge = s.Sample(Vec2(1, 1));
    EXPECT_LE(edge.p.x, 4 + 1e-12);
}

TEST(SpawnOrigin, OffsetsTowardsTheSideOfW) {
    MeshShape s(UnitQuad());
    SurfaceInteraction si = s.Interaction(Ray{}, 0, 0, 0.25, 0.25);
    Vec3 up = si.SpawnOrigin(Vec3(0.3, 0, 1)), down = si.SpawnOrigin(Vec3(0, 0.3, -1));
    EXPECT_GT(up.z, 0);
    EXPECT_LT(down.z, 0);
    // At least 4 float ulps of the largest coordinate (1), at most a few micro-metres.
    EXPECT_GE(up.z, 4 * std::ldexp(1.0, -23));
    EXPECT_LT(up.z, 1e-6);
    // Scales with magnitude: the same quad 1 km away.
    TriangleMesh far = UnitQuad();
    far.Transform(Transform::Translate(Vec3(1000, 0, 0)));
    MeshShape sf(far);
    SurfaceInteraction sif = sf.Interaction(Ray{}, 0, 0, 0.25, 0.25);
    EXPECT_GE(sif.SpawnOrigin(Vec3(0, 0, 1)).z, 4 * std::ldexp(1000.0, -23));
}

}  // namespace
}  // namespace phasor
