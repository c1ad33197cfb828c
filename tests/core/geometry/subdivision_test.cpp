// SPDX-License-Identifier: Apache-2.0
// Catmull–Clark subdivision through OpenSubdiv: topology counts, convergence of the refined
// control points to the limit surface, limit normals, face-varying uvs, and cage errors.
#include <gtest/gtest.h>

#include <cmath>

#include "core/diagnostics.h"
#include "core/geometry/mesh_io.h"
#include "geometry_test_util.h"

namespace phasor {
namespace {

double MaxAbsX(const TriangleMesh &m) {
    double v = 0;
    for (const Vec3 &p : m.positions) v = std::max(v, std::abs(p.x));
    return v;
}

// A closed quad mesh of genus 0 refined L times has F = 6·4^L quads, E = 2F edges and, by
// Euler's formula V − E + F = 2, V = 6·4^L + 2 vertices: 8, 26, 98, 386.
TEST(Subdivision, CubeCountsPerLevel) {
    const std::size_t verts[] = {8, 26, 98, 386};
    for (int level = 0; level <= 3; ++level) {
        TriangleMesh m = SubdivideCatmullClark(CubeCage(), level);
        EXPECT_EQ(m.positions.size(), verts[level]) << level;
        EXPECT_EQ(m.TriangleCount(), 12u << (2 * level)) << level;
        EXPECT_EQ(m.normals.size(), m.positions.size());
    }
}

// The limit surface of the cube cage [−1,1]³ reaches x = 68/81 at the face centres: after one
// step the face point (1,0,0) is a regular vertex with edge neighbours x = 3/4 and diagonal
// neighbours x = 5/9 (the new corner points), and the regular Catmull–Clark limit mask
// (16·v + 4·Σe + Σd)/36 gives (16 + 12 + 20/9)/36 = 68/81. The control points approach the
// limit from outside; in a regular region the distance shrinks by 1/4 per level.
TEST(Subdivision, CubeBoundsConvergeToLimit) {
    const double limit = 68.0 / 81.0;
    double prevExtent = 2, prevErr = 1;
    for (int level = 0; level <= 6; ++level) {
        TriangleMesh m = SubdivideCatmullClark(CubeCage(), level);
        Bounds3 b = m.Bounds();
        double ext = MaxAbsX(m);
        EXPECT_NEAR(b.hi.y, ext, 1e-14);  // cubic symmetry
        EXPECT_NEAR(-b.lo.z, ext, 1e-14);
        EXPECT_LE(ext, prevExtent + 1e-15) << "bounds must not grow, level " << level;
        EXPECT_GT(ext, limit - 1e-14) << "control points lie outside the limit surface";
        double err = ext - limit;
        if (level >= 3) {
            EXPECT_LT(err, 0.3 * prevErr) << "level " << level;  // ratio → 1/4
            EXPECT_GT(err, 0.2 * prevErr) << "level " << level;
        }
        prevExtent = ext;
        prevErr = err;
    }
    EXPECT_LT(prevErr, 1e-3);
}

TEST(Subdivision, LimitNormalsAreUnitOutwardAndSymmetric) {
    TriangleMesh m = SubdivideCatmullClark(CubeCage(), 3);
    std::size_t faceCentre = 0;
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        ASSERT_NEAR(Length(m.normals[i]), 1, 1e-12);
        ASSERT_GT(Dot(m.normals[i], m.positions[i]), 0) << "inward normal at vertex " << i;
        if (m.positions[i].x > m.positions[faceCentre].x) faceCentre = i;
    }
    // The face centre of +x: position (ext, 0, 0), limit normal exactly +x by symmetry.
    EXPECT_NEAR(m.positions[faceCentre].y, 0, 1e-14);
    EXPECT_NEAR(m.normals[faceCentre].x, 1, 1e-12);
    // Every triangle is wound counter-clockwise seen from outside (agrees with the normals).
    for (std::size_t t = 0; t < m.TriangleCount(); ++t) {
        const Vec3 &a = m.positions[m.indices[3 * t]], &b = m.positions[m.indices[3 * t + 1]],
                   &c = m.positions[m.indices[3 * t + 2]];
        ASSERT_GT(Dot(Cross(b - a, c - a), m.normals[m.indices[3 * t]]), 0) << "triangle " << t;
    }
}

TEST(Subdivision, JackCageIsClosedAndManifold) {
    PolyMesh cage = LoadObjPolygons(test::AssetPath("jack_cage.obj"));
    EXPECT_EQ(cage.positions.size(), 32u);
    EXPECT_EQ(cage.faceSizes.size(), 30u);
    for (int level : {1, 3}) {
        TriangleMesh m = SubdivideCatmullClark(cage, level);
        std::size_t f = 30u << (2 * level);
        // Closed genus-0 surface: V = F + 2 for quads.
        EXPECT_EQ(m.positions.size(), f + 2);
        EXPECT_EQ(m.TriangleCount(), 2 * f);
    }
}

TEST(Subdivision, OpenCageKeepsCornersAndTriangleCagesWork) {
    PolyMesh quad;
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    quad.faceSizes = {4};
    quad.faceIndices = {0, 1, 2, 3};
    TriangleMesh m = SubdivideCatmullClark(quad, 2);
    EXPECT_EQ(m.positions.size(), 25u);  // (2^L + 1)²
    for (const Vec3 &c : quad.positions) {
        bool found = false;
        for (const Vec3 &p : m.positions) found |= Length(p - c) < 1e-14;
        EXPECT_TRUE(found) << "corner " << ToString(c) << " moved";  // EDGE_AND_CORNER rule
    }
    for (const Vec3 &n : m.normals) EXPECT_NEAR(n.z, 1, 1e-12);

    PolyMesh tet;
    tet.positions = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    tet.faceSizes = {3, 3, 3, 3};
    tet.faceIndices = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};
    EXPECT_EQ(SubdivideCatmullClark(tet, 0).TriangleCount(), 4u);
    EXPECT_EQ(SubdivideCatmullClark(tet, 1).TriangleCount(), 24u);  // 12 quads
}

// A flat n×n grid of quads whose uvs are an affine function of position: Catmull–Clark refines
// positions and face-varying uvs with the same stencils inside a chart and the same B-spline rule
// along its boundary (VTX_BOUNDARY_EDGE_AND_CORNER for positions, FVAR_LINEAR_CORNERS_ONLY for
// uvs), so every refined vertex keeps uv = A·(x, y) + b exactly (up to rounding). A uv paired
// with the wrong vertex, or interpolated with other weights, breaks it by O(1/n).
TEST(Subdivision, UvsFollowAnAffineMapOfAFlatGrid) {
    const int n = 3;
    auto uvOf = [](double x, double y) { return Vec2(0.3 + 0.5 * x - 0.2 * y, -0.1 + 0.25 * x + 0.7 * y); };
    PolyMesh grid;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const double x = i + 0.2 * j, y = j + 0.1 * i * i;  // a sheared, bent grid in z = 0
            grid.positions.push_back(Vec3(x, y, 0));
            grid.uvs.push_back(uvOf(x, y));
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            grid.faceSizes.push_back(4);
            for (int v : {j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i}) {
                grid.faceIndices.push_back(v);
                grid.faceUvIndices.push_back(v);
            }
        }
    for (int level : {0, 1, 3}) {
        TriangleMesh m = SubdivideCatmullClark(grid, level);
        ASSERT_EQ(m.uvs.size(), m.positions.size());
        EXPECT_EQ(m.positions.size(), std::size_t((n << level) + 1) * std::size_t((n << level) + 1));  // no seam
        for (std::size_t i = 0; i < m.positions.size(); ++i) {
            const Vec2 want = uvOf(m.positions[i].x, m.positions[i].y);
            ASSERT_NEAR(m.uvs[i].x, want.x, 1e-12) << "level " << level << ", vertex " << i;
            ASSERT_NEAR(m.uvs[i].y, want.y, 1e-12) << "level " << level << ", vertex " << i;
        }
    }
}

// A closed tube (a ring of 8 quads around x, 4 segments long, capped) with u along the axis and v
// around it, the seam at v = 0 ≡ 1: the refined mesh has the geometry of the cage without uvs,
// repeats exactly the seam's vertices, never interpolates across the seam, and dp/du follows the
// axis on the side wall away from the ends (what a grating's groove direction is measured from).
TEST(Subdivision, TubeUvSeamIsKept) {
    const int ring = 8, segs = 4;
    PolyMesh tube;
    for (int i = 0; i <= segs; ++i)
        for (int k = 0; k < ring; ++k) {
            const double a = 2 * Pi * k / ring;
            tube.positions.push_back(Vec3(i, std::cos(a), std::sin(a)));
        }
    for (int i = 0; i <= segs; ++i)
        for (int k = 0; k <= ring; ++k) tube.uvs.push_back(Vec2(double(i) / segs, double(k) / ring));
    const int capUv = int(tube.uvs.size());
    tube.uvs.push_back(Vec2(0.5, 0.5));  // the caps: one uv (a degenerate chart)
    auto vid = [&](int i, int k) { return i * ring + k % ring; };
    auto tid = [&](int i, int k) { return i * (ring + 1) + k; };  // k = ring: the seam's other side
    for (int i = 0; i < segs; ++i)
        for (int k = 0; k < ring; ++k) {
            tube.faceSizes.push_back(4);
            for (auto [a, b] : {std::pair{i, k}, {i, k + 1}, {i + 1, k + 1}, {i + 1, k}}) {
                tube.faceIndices.push_back(vid(a, b));
                tube.faceUvIndices.push_back(tid(a, b));
            }
        }
    for (int end : {0, segs}) {
        tube.faceSizes.push_back(ring);
        for (int k = 0; k < ring; ++k) {
            tube.faceIndices.push_back(vid(end, end == 0 ? ring - k : k));
            tube.faceUvIndices.push_back(capUv);
        }
    }
    PolyMesh plain = tube;
    plain.uvs.clear();
    plain.faceUvIndices.clear();
    const int level = 3;
    TriangleMesh m = SubdivideCatmullClark(tube, level), g = SubdivideCatmullClark(plain, level);
    ASSERT_EQ(m.uvs.size(), m.positions.size());
    EXPECT_EQ(m.TriangleCount(), g.TriangleCount());
    // Same surface: every triangle of m has the positions of g's triangle of the same index.
    for (std::size_t i = 0; i < m.indices.size(); ++i) {
        ASSERT_EQ(m.positions[m.indices[i]], g.positions[g.indices[i]]) << i;
        ASSERT_EQ(m.normals[m.indices[i]], g.normals[g.indices[i]]) << i;
    }
    // Copies: the side wall's seam column (segs·2^L + 1 vertices) once more, and the cap
    // boundaries, which belong to the cap chart and the wall chart (2·ring·2^L vertices).
    const std::size_t seam = std::size_t(segs << level) + 1, capRims = 2 * std::size_t(ring << level);
    EXPECT_EQ(m.positions.size(), g.positions.size() + seam + capRims);
    MeshShape shape(m);
    std::size_t wall = 0;
    for (std::size_t t = 0; t < m.TriangleCount(); ++t) {
        const Vec2 &a = m.uvs[m.indices[3 * t]], &b = m.uvs[m.indices[3 * t + 1]], &c = m.uvs[m.indices[3 * t + 2]];
        EXPECT_LT(std::max({std::abs(a.y - b.y), std::abs(b.y - c.y), std::abs(a.y - c.y)}), 0.25) << t;
        const SurfaceInteraction si = shape.Interaction(Ray{}, 0, unsigned(t), 1.0 / 3, 1.0 / 3);
        if (Length(si.dpdu) == 0) continue;  // a cap: one uv, no parameterisation
        ++wall;
        if (std::abs(si.p.x - 0.5 * segs) > 1) continue;  // near the ends the wall turns into the caps
        const Vec3 radial = Normalize(Vec3(0, si.p.y, si.p.z));
        EXPECT_GT(Normalize(si.dpdu).x, 0.9) << "triangle " << t;  // along +x
        EXPECT_LT(std::abs(Dot(Normalize(si.dpdv), radial)), 0.35) << "triangle " << t;  // around
    }
    EXPECT_GT(wall, m.TriangleCount() / 2);
}

TEST(Subdivision, BadCagesThrow) {
    PolyMesh c = CubeCage();
    c.faceIndices[5] = 99;
    EXPECT_THROW(SubdivideCatmullClark(c, 1), Error);
    c = CubeCage();
    c.faceSizes[0] = 2;
    EXPECT_THROW(SubdivideCatmullClark(c, 1), Error);
    EXPECT_THROW(SubdivideCatmullClark(CubeCage(), -1), Error);
    EXPECT_THROW(SubdivideCatmullClark(CubeCage(), 11), Error);
    EXPECT_THROW(SubdivideCatmullClark(PolyMesh{}, 1), Error);
    c = CubeCage();
    c.uvs = {Vec2(0, 0)};
    c.faceUvIndices.assign(c.faceIndices.size() - 1, 0);  // one corner short
    EXPECT_THROW(SubdivideCatmullClark(c, 1), Error);
    c.faceUvIndices.push_back(1);  // out of range
    EXPECT_THROW(SubdivideCatmullClark(c, 1), Error);
}

}  // namespace
}  // namespace phasor
