// SPDX-License-Identifier: Apache-2.0
// Catmull–Clark subdivision through OpenSubdiv: topology counts, convergence of the refined
// control points to the limit surface, limit normals, and cage errors.
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
}

}  // namespace
}  // namespace phasor
