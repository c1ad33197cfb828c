// SPDX-License-Identifier: Apache-2.0
// The union of polygons cut into trapezoids (core/geometry/polygon_union.h): areas and covered
// points against brute force, overlaps counted once, holes, cancelling shared edges.
#include "core/geometry/polygon_union.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace phasor {
namespace {

void AddPolygon(std::vector<OrientedSegment> &segs, const std::vector<Vec2> &v) {
    for (std::size_t i = 0; i < v.size(); ++i) segs.push_back({v[i], v[(i + 1) % v.size()], int(segs.size())});
}

// True if p lies in one of the trapezoids (strictly inside, away from limits by tol).
bool Inside(const std::vector<Trapezoid> &ts, const Vec2 &p) {
    for (const Trapezoid &t : ts)
        if (p.y > t.v0 && p.y < t.v1 && p.x > t.Lo(p.y) && p.x < t.Hi(p.y)) return true;
    return false;
}

double Area(const std::vector<Trapezoid> &ts) {
    double a = 0;
    for (const Trapezoid &t : ts) a += t.Area();
    return a;
}

TEST(PolygonUnion, OneSquareInsideTheBox) {
    std::vector<OrientedSegment> segs;
    AddPolygon(segs, {{-0.5, -0.25}, {0.5, -0.25}, {0.5, 0.25}, {-0.5, 0.25}});
    const UnionDecomposition d = DecomposeUnion(segs, 2, 1);
    EXPECT_NEAR(Area(d.covered), 0.5, 1e-14);
    EXPECT_NEAR(Area(d.open), 8 - 0.5, 1e-13);
    ASSERT_EQ(d.covered.size(), 1u);  // the slabs above and below merge nothing into it
    EXPECT_EQ(d.covered[0].loSeg, 3);  // bounded by the left and right edges
    EXPECT_EQ(d.covered[0].hiSeg, 1);
}

TEST(PolygonUnion, OverlapsCountOnceAndHolesStayOpen) {
    std::vector<OrientedSegment> segs;
    // Two overlapping squares (the front and back faces of a box seen along its axis: the same
    // square twice) and a third one shifted.
    AddPolygon(segs, {{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}});
    AddPolygon(segs, {{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}});
    AddPolygon(segs, {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
    UnionDecomposition d = DecomposeUnion(segs, 3, 3);
    EXPECT_NEAR(Area(d.covered), 1 + 1 - 0.25, 1e-13);
    EXPECT_NEAR(Area(d.covered) + Area(d.open), 36, 1e-12);
    // A plate with a square hole: outline counter-clockwise, hole clockwise.
    segs.clear();
    AddPolygon(segs, {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}});
    AddPolygon(segs, {{-0.25, -0.25}, {-0.25, 0.25}, {0.25, 0.25}, {0.25, -0.25}});
    d = DecomposeUnion(segs, 3, 3);
    EXPECT_NEAR(Area(d.covered), 4 - 0.25, 1e-13);
    EXPECT_FALSE(Inside(d.covered, {0.1, -0.05}));
    EXPECT_TRUE(Inside(d.open, {0.1, -0.05}));
    EXPECT_TRUE(Inside(d.covered, {0.5, 0.7}));
}

TEST(PolygonUnion, SharedEdgesOfOppositeSidesCancel) {
    // A square as two triangles sharing the diagonal (once each way): no boundary on the diagonal.
    std::vector<OrientedSegment> segs;
    AddPolygon(segs, {{0, 0}, {1, 0}, {1, 1}});
    AddPolygon(segs, {{0, 0}, {1, 1}, {0, 1}});
    const UnionDecomposition d = DecomposeUnion(segs, 2, 2);
    EXPECT_NEAR(Area(d.covered), 1, 1e-14);
    for (const Trapezoid &t : d.covered) {  // no interval ends on the diagonal (segments 2 and 3)
        EXPECT_NE(t.loSeg, 2);
        EXPECT_NE(t.hiSeg, 2);
        EXPECT_NE(t.loSeg, 3);
        EXPECT_NE(t.hiSeg, 3);
    }
}

TEST(PolygonUnion, OutlinesLeftOfTheBoxStillCover) {
    // A polygon much wider than the box: it covers the box completely.
    std::vector<OrientedSegment> segs;
    AddPolygon(segs, {{-10, -10}, {10, -10}, {10, 0.5}, {-10, 0.5}});
    const UnionDecomposition d = DecomposeUnion(segs, 1, 1);
    EXPECT_NEAR(Area(d.covered), 2 * 1.5, 1e-13);
    EXPECT_NEAR(Area(d.open), 2 * 0.5, 1e-13);
}

TEST(PolygonUnion, RandomTrianglesMatchBruteForce) {
    // Random counter-clockwise triangles (overlapping, crossing the box): the covered area and
    // membership agree with the winding number on a fine grid; covered + open tile the box.
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> U(-1.6, 1.6);
    for (int trial = 0; trial < 20; ++trial) {
        std::vector<OrientedSegment> segs;
        const int n = 2 + trial % 7;
        for (int k = 0; k < n; ++k) {
            Vec2 a(U(rng), U(rng)), b(U(rng), U(rng)), c(U(rng), U(rng));
            const double cross = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
            if (cross < 0) std::swap(b, c);
            AddPolygon(segs, {a, b, c});
        }
        const double hu = 1.2, hv = 0.9;
        const UnionDecomposition d = DecomposeUnion(segs, hu, hv);
        EXPECT_NEAR(Area(d.covered) + Area(d.open), 4 * hu * hv, 1e-12);
        const int N = 300;
        double covered = 0;
        int mismatches = 0;
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < N; ++j) {
                const Vec2 p(-hu + (i + 0.5) * 2 * hu / N, -hv + (j + 0.5) * 2 * hv / N);
                const bool in = WindingNumber(segs, p) >= 1;
                covered += in;
                // Points within 1e-9 of a limit may go either way; the grid avoids them.
                if (in != Inside(d.covered, p) || in == Inside(d.open, p)) ++mismatches;
            }
        EXPECT_EQ(mismatches, 0) << "trial " << trial;
        // The grid's area estimate has an error of order perimeter × cell size.
        EXPECT_NEAR(Area(d.covered), covered * 4 * hu * hv / (N * N), 0.02) << "trial " << trial;
    }
}

}  // namespace
}  // namespace phasor
