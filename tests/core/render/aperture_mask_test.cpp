// SPDX-License-Identifier: Apache-2.0
// Aperture openings (core/render/aperture.h): pieces tile (openings ∩ box) exactly, transmission lookup,
// polygon validation, bitmap masks, the plate frame.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/render/aperture.h"
#include "core/diagnostics.h"
#include "core/image/image_io.h"

namespace phasor {
namespace {

/// ∫∫ t du dv over the pieces by Gauss–Legendre along v (circle pieces via v = cv + r sin φ).
double PieceArea(const ApertureMask &m, const Bounds2 &box) {
    static const double x[5] = {-0.9061798459386640, -0.5384693101056831, 0, 0.5384693101056831,
                                0.9061798459386640};
    static const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                0.4786286704993665, 0.2369268850561891};
    double area = 0;
    m.ForEachPiece(box, [&](const MaskPiece &p) {
        EXPECT_LE(p.v0, p.v1);
        EXPECT_GE(p.v0, box.lo.y - 1e-15);
        EXPECT_LE(p.v1, box.hi.y + 1e-15);
        const int panels = 64;
        if (p.circle) {
            const double f0 = std::asin(std::clamp((p.v0 - p.cv) / p.r, -1.0, 1.0));
            const double f1 = std::asin(std::clamp((p.v1 - p.cv) / p.r, -1.0, 1.0));
            for (int k = 0; k < panels; ++k)
                for (int i = 0; i < 5; ++i) {
                    const double h = (f1 - f0) / panels, f = f0 + h * (k + 0.5 + 0.5 * x[i]);
                    const double v = p.cv + p.r * std::sin(f);
                    area += p.t * 0.5 * h * w[i] * p.r * std::cos(f) * std::max(0.0, p.UHi(v) - p.ULo(v));
                }
        } else {
            for (int i = 0; i < 5; ++i) {
                const double v = 0.5 * (p.v0 + p.v1) + 0.5 * (p.v1 - p.v0) * x[i];
                EXPECT_GE(p.ULo(v), box.lo.x - 1e-12);
                EXPECT_LE(p.UHi(v), box.hi.x + 1e-12);
                area += p.t * 0.5 * (p.v1 - p.v0) * w[i] * (p.UHi(v) - p.ULo(v));
            }
        }
    });
    return area;
}

/// The same area by brute-force point sampling of Transmission on a fine grid (midpoint rule).
double GridArea(const ApertureMask &m, const Bounds2 &box, int n) {
    const double du = (box.hi.x - box.lo.x) / n, dv = (box.hi.y - box.lo.y) / n;
    double a = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) a += m.Transmission(Vec2(box.lo.x + (i + 0.5) * du, box.lo.y + (j + 0.5) * dv));
    return a * du * dv;
}

TEST(ApertureMask, PiecesTileTheOpeningsInsideABox) {
    ApertureMask m;
    m.AddRect(Vec2(-3, -1), Vec2(-1, 2), 1);
    m.AddDisc(Vec2(2, 0.5), 1.2, 0.5);
    m.AddPolygon({{-2, -4}, {1, -3.5}, {0.5, -1.5}, {-0.5, -2.2}, {-1.8, -1.6}}, 1);  // non-convex
    const Bounds2 all{Vec2(-5, -5), Vec2(5, 5)};
    EXPECT_NEAR(PieceArea(m, all), m.OpenArea(), 1e-9 * m.OpenArea());
    // A box cutting through every opening: compare with the point-sampled transmission.
    const Bounds2 cut{Vec2(-2.2, -2.9), Vec2(2.4, 1.1)};
    const double exact = PieceArea(m, cut), grid = GridArea(m, cut, 2000);
    EXPECT_NEAR(exact, grid, 4e-3 * grid);  // midpoint rule on a discontinuous t: O(h)
}

TEST(ApertureMask, TransmissionAndSlits) {
    ApertureMask m;
    m.AddRect(Vec2(-70e-6, -2e-3), Vec2(-30e-6, 2e-3));
    m.AddRect(Vec2(30e-6, -2e-3), Vec2(70e-6, 2e-3));
    EXPECT_EQ(m.Transmission(Vec2(-50e-6, 0)), 1);
    EXPECT_EQ(m.Transmission(Vec2(0, 0)), 0);
    double v0 = 0, v1 = 0;
    EXPECT_TRUE(m.IsSlitsAlongV(1e-3, &v0, &v1));
    EXPECT_DOUBLE_EQ(v1 - v0, 4e-3);
    EXPECT_FALSE(m.IsSlitsAlongV(5e-3));
    m.AddDisc(Vec2(0, 0), 1e-6);
    EXPECT_FALSE(m.IsSlitsAlongV(1e-3));
}

TEST(ApertureMask, RejectsBadPolygons) {
    ApertureMask m;
    EXPECT_THROW(m.AddPolygon({{0, 0}, {1, 0}}), Error);
    EXPECT_THROW(m.AddPolygon({{0, 0}, {1, 0}, {2, 0}}), Error);              // zero area
    EXPECT_THROW(m.AddPolygon({{0, 0}, {1, 1}, {1, 0}, {0, 1}}), Error);      // bow tie
    EXPECT_THROW(m.AddRect(Vec2(1, 0), Vec2(0, 1)), Error);
    EXPECT_THROW(m.AddDisc(Vec2(0, 0), 0), Error);
}

TEST(ApertureMask, BitmapRunsFollowTheImage) {
    Image img;
    img.width = 4;
    img.height = 2;
    img.channels = {"Y"};
    img.data = {0, 1, 1, 0,      // top row (v in [0.5, 1])
                0.5, 0.5, 0, 1}; // bottom row
    const std::string path = (std::filesystem::temp_directory_path() / "phasor_mask_test.exr").string();
    WriteExr(path, img);
    ApertureMask m;
    m.AddBitmap(path, Vec2(0, 0), Vec2(2, 1), 3);  // levels 0, ½, 1
    std::filesystem::remove(path);
    EXPECT_EQ(m.Transmission(Vec2(0.75, 0.75)), 1);
    EXPECT_EQ(m.Transmission(Vec2(0.25, 0.75)), 0);
    EXPECT_EQ(m.Transmission(Vec2(0.25, 0.25)), 0.5);
    EXPECT_NEAR(m.OpenArea(), 0.25 * (2 + 0.5 + 0.5 + 1), 1e-12);
    EXPECT_NEAR(PieceArea(m, Bounds2{Vec2(-1, -1), Vec2(3, 3)}), m.OpenArea(), 1e-12);
    EXPECT_THROW(m.AddBitmap("no-such-mask.png", Vec2(0, 0), Vec2(1, 1)), Error);
}

TEST(PlateFrame, RigidMotionsOnly) {
    const Transform t = Transform::Translate(Vec3(1, 2, 3)) * Transform::Rotate(0.3, Vec3(1, 1, 0));
    const PlateFrame f = PlateFrame::FromTransform(t);
    const Vec3 p = t.Point(Vec3(0.4, -0.2, 0));
    const Vec2 uv = f.ToPlate(p);
    EXPECT_NEAR(uv.x, 0.4, 1e-12);
    EXPECT_NEAR(uv.y, -0.2, 1e-12);
    EXPECT_NEAR(Length(f.ToWorld(uv) - p), 0, 1e-12);
    EXPECT_THROW(PlateFrame::FromTransform(Transform::Scale(Vec3(2, 2, 2))), Error);
    EXPECT_THROW(PlateFrame::FromTransform(Transform::Scale(Vec3(1, -1, 1))), Error);
}

}  // namespace
}  // namespace phasor
