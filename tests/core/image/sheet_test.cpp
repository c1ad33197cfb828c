// SPDX-License-Identifier: Apache-2.0
// Images for people (core/image/sheet.h): the colour maps at their published colours, dB levels,
// sheets of labelled tiles with a colour bar drawn by OpenImageIO (tiles land where the layout
// says, enlarged by a whole factor; labels and bar text with the default font, none without one),
// the false-colour PNG of sensor images, and all-or-nothing writes.

#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "core/diagnostics.h"
#include "core/image/image_io.h"
#include "core/image/sheet.h"
#include "support/temp_dir.h"

namespace phasor {
namespace {

class SheetTest : public test::TempDirTest {
  protected:
    SheetTest() : TempDirTest("phasor_sheet") {}
};

// A pixel of an 8-bit PNG read back, in codes 0..255.
Vec3 At(const Image &img, int i, int j) { return Vec3(img.At(i, j, 0), img.At(i, j, 1), img.At(i, j, 2)) * 255.0; }
void ExpectCode(const Vec3 &got, int r, int g, int b, double tol = 0.5) {
    EXPECT_NEAR(got.x, r, tol);
    EXPECT_NEAR(got.y, g, tol);
    EXPECT_NEAR(got.z, b, tol);
}

Rgb8Image Solid(int w, int h, uint8_t r, uint8_t g, uint8_t b) {
    Rgb8Image img;
    img.width = w;
    img.height = h;
    for (int i = 0; i < w * h; ++i) img.rgb.insert(img.rgb.end(), {r, g, b});
    return img;
}

// Dark pixels (text) in a rectangle.
int Ink(const Image &img, int x0, int y0, int x1, int y1) {
    int ink = 0;
    for (int j = std::max(0, y0); j < std::min(img.height, y1); ++j)
        for (int i = std::max(0, x0); i < std::min(img.width, x1); ++i) ink += At(img, i, j).y < 128;
    return ink;
}

TEST(ColourMaps, EndsAndMiddleAreThePublishedColours) {
    // viridis: #440154 at 0, #FDE725 at 1; RdBu reversed: #053061 at 0, #F7F7F7 at ½, #67001F at 1.
    auto code = [](ColourMap m, double t) { return ColourAt(m, t) * 255.0; };
    ExpectCode(code(ColourMap::Viridis, 0), 0x44, 0x01, 0x54);
    ExpectCode(code(ColourMap::Viridis, 1), 0xFD, 0xE7, 0x25);
    ExpectCode(code(ColourMap::Diverging, 0), 0x05, 0x30, 0x61);
    ExpectCode(code(ColourMap::Diverging, 0.5), 0xF7, 0xF7, 0xF7);
    ExpectCode(code(ColourMap::Diverging, 1), 0x67, 0x00, 0x1F);
    // Clamped outside [0, 1]; NaN at the bottom.
    ExpectCode(code(ColourMap::Viridis, 7), 0xFD, 0xE7, 0x25);
    ExpectCode(code(ColourMap::Viridis, std::nan("")), 0x44, 0x01, 0x54);

    // MapColours: lo → t = 0, hi → 1, +Inf → 1, NaN and −Inf → 0.
    const double inf = std::numeric_limits<double>::infinity();
    const Rgb8Image m = MapColours({-2, 0, 2, inf, std::nan(""), -inf}, 6, 1, ColourMap::Diverging, -2, 2);
    const uint8_t expected[6][3] = {{0x05, 0x30, 0x61}, {0xF7, 0xF7, 0xF7}, {0x67, 0x00, 0x1F},
                                    {0x67, 0x00, 0x1F}, {0x05, 0x30, 0x61}, {0x05, 0x30, 0x61}};
    for (int i = 0; i < 6; ++i)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(m.rgb[3 * i + c], expected[i][c]) << "value " << i;
    EXPECT_THROW(MapColours({1}, 1, 1, ColourMap::Viridis, 1, 1), Error);
}

TEST(ColourMaps, DecibelLevelsAgainstAReference) {
    const std::vector<double> db = DecibelLevels({2, 0.2, 2e-3, 2e-9, 0, -1, std::nan(""), 20}, 2, 40);
    const std::vector<double> expected = {0, -10, -30, -40, -40, -40, -40, 10};
    ASSERT_EQ(db.size(), expected.size());
    for (std::size_t i = 0; i < db.size(); ++i) EXPECT_NEAR(db[i], expected[i], 1e-12) << i;
    // The bar: 0 dB on top, every 10 dB down to −40 dB.
    const ColourBar bar = DecibelBar(40, "t");
    ASSERT_EQ(bar.ticks.size(), 5u);
    EXPECT_EQ(bar.ticks[0].text, "0 dB");
    EXPECT_DOUBLE_EQ(bar.ticks[0].t, 1);
    EXPECT_EQ(bar.ticks[4].text, "-40 dB");
    EXPECT_DOUBLE_EQ(bar.ticks[4].t, 0);
}

TEST_F(SheetTest, TilesLandWhereTheLayoutSaysWithLabelsAndABar) {
    // Two 40×30 tiles, enlarged 9× (to ≥ 256 px tall), side by side, a diverging bar to the right.
    const std::vector<SheetTile> tiles = {{Solid(40, 30, 200, 30, 30), "first\nsecond line"},
                                          {Solid(40, 30, 30, 30, 200), "other"}};
    ColourBar bar;
    bar.map = ColourMap::Diverging;
    bar.title = "(I - R) / max(R)";
    bar.ticks = {{0, "-1"}, {0.5, "0"}, {1, "+1"}};
    const SheetLayout L = LayoutSheet(tiles, &bar);
    EXPECT_EQ(L.scale, 9);
    ASSERT_EQ(L.tiles.size(), 2u);
    EXPECT_EQ(L.tiles[0].y, L.tiles[1].y);  // one row
    EXPECT_GT(L.tiles[1].x, L.tiles[0].x + L.tiles[0].w);
    EXPECT_EQ(L.tiles[0].w, 360);
    EXPECT_GT(L.bar.x, L.tiles[1].x + L.tiles[1].w);

    OutputFiles files;
    const SheetResult r = StageSheetPng(files, Path("sheet.png"), tiles, &bar, "test");
    files.Commit();
    EXPECT_TRUE(r.textDrawn) << r.textProblem;  // DejaVu Sans is installed with the project
    const Image png = ReadImage(Path("sheet.png"));
    ASSERT_EQ(png.width, L.width);
    ASSERT_EQ(png.height, L.height);
    // Each tile's pixels, corners included, and white between them.
    for (int k = 0; k < 2; ++k) {
        const auto &t = L.tiles[k];
        const Vec3 want = k == 0 ? Vec3(200, 30, 30) : Vec3(30, 30, 200);
        for (auto [i, j] : {std::pair{t.x, t.y}, {t.x + t.w - 1, t.y + t.h - 1}, {t.x + t.w / 2, t.y + t.h / 2}})
            ExpectCode(At(png, i, j), int(want.x), int(want.y), int(want.z));
    }
    ExpectCode(At(png, L.tiles[0].x + L.tiles[0].w + 2, L.tiles[0].y + 10), 255, 255, 255);
    // The bar: blue at the bottom, white in the middle, red at the top (rows sample t at their centres:
    // one row from an end is a few codes off).
    const int bx = L.bar.x + L.bar.w / 2;
    ExpectCode(At(png, bx, L.bar.y + L.bar.h - 2), 0x05, 0x30, 0x61, 8);
    ExpectCode(At(png, bx, L.bar.y + L.bar.h / 2), 0xF7, 0xF7, 0xF7, 3);
    ExpectCode(At(png, bx, L.bar.y + 1), 0x67, 0x00, 0x1F, 8);
    // Text: both lines of the first label, the second label, the bar's labels and title.
    const int band = L.labelBand;
    EXPECT_GT(Ink(png, L.tiles[0].x, L.tiles[0].y - band, L.tiles[0].x + 200, L.tiles[0].y - band / 2), 30);
    EXPECT_GT(Ink(png, L.tiles[0].x, L.tiles[0].y - band / 2, L.tiles[0].x + 200, L.tiles[0].y), 30);
    EXPECT_GT(Ink(png, L.tiles[1].x, L.tiles[1].y - band, L.tiles[1].x + 200, L.tiles[1].y), 30);
    EXPECT_GT(Ink(png, L.bar.x + L.bar.w + 8, L.bar.y, png.width, L.bar.y + L.bar.h), 30);
    EXPECT_GT(Ink(png, L.bar.x - 100, 0, png.width, 28), 30);

    // Without the font the sheet is written all the same, without any text.
    OutputFiles more;
    const SheetResult none = StageSheetPng(more, Path("plain.png"), tiles, &bar, "", 0, "no-such-font-phasor");
    more.Commit();
    EXPECT_FALSE(none.textDrawn);
    EXPECT_NE(none.textProblem.find("no-such-font-phasor"), std::string::npos) << none.textProblem;
    const Image plain = ReadImage(Path("plain.png"));
    EXPECT_EQ(Ink(plain, L.tiles[0].x, L.tiles[0].y - band, L.tiles[1].x + 300, L.tiles[0].y), 0);
    ExpectCode(At(plain, L.tiles[1].x + 5, L.tiles[1].y + 5), 30, 30, 200);
}

TEST_F(SheetTest, WideTilesAreStackedAndOneRowImagesAreEnlarged) {
    // A one-row sensor (48×1) is enlarged by 21 (1008 px wide); such strips stack in one column.
    const std::vector<SheetTile> tiles = {{Solid(48, 1, 0, 0, 0), "a"}, {Solid(48, 1, 0, 0, 0), "b"}};
    const SheetLayout L = LayoutSheet(tiles, nullptr);
    EXPECT_EQ(L.scale, 21);
    EXPECT_EQ(L.tiles[0].x, L.tiles[1].x);
    EXPECT_GT(L.tiles[1].y, L.tiles[0].y + L.tiles[0].h);
}

TEST_F(SheetTest, FalseColourPngHasALabelledBar) {
    // A 64×64 ramp: the left column at the maximum, the right one 40 dB below.
    Image img;
    img.width = img.height = 64;
    img.channels = {"intensity"};
    for (int j = 0; j < 64; ++j)
        for (int i = 0; i < 64; ++i) img.data.push_back(float(std::pow(10.0, -4.0 * i / 63)));
    const SheetResult r = WriteFalseColorPng(Path("map.png"), img, "intensity", 40);
    EXPECT_TRUE(r.textDrawn) << r.textProblem;
    const Image png = ReadImage(Path("map.png"));
    ColourBar bar = DecibelBar(40, "intensity, 0 dB = 1");
    const SheetLayout L = LayoutSheet({SheetTile{Solid(64, 64, 0, 0, 0), ""}}, &bar);
    ASSERT_EQ(png.width, L.width);
    ASSERT_EQ(png.height, L.height);
    EXPECT_EQ(L.scale, 4);  // enlarged to 256 px
    const auto &t = L.tiles[0];
    // The map: 0 dB is viridis' yellow (#FDE725), −40 dB its purple (#440154).
    ExpectCode(At(png, t.x + 1, t.y + 100), 0xFD, 0xE7, 0x25, 1);
    ExpectCode(At(png, t.x + t.w - 2, t.y + 100), 0x44, 0x01, 0x54, 1);
    // The bar: yellow at the top, purple at the bottom; its labels to the right.
    EXPECT_NEAR(At(png, L.bar.x + 12, L.bar.y + 1).x, 0xFD, 8);
    EXPECT_NEAR(At(png, L.bar.x + 12, L.bar.y + L.bar.h - 2).x, 0x44, 8);
    EXPECT_GT(Ink(png, L.bar.x + L.bar.w + 8, L.bar.y, png.width, L.bar.y + L.bar.h), 50) << "no labels drawn";

    // 0 dB may be set from outside (one scale for several images): against 10, the maximum of 1
    // is −10 dB, the colour at t = 0.75.
    WriteFalseColorPng(Path("scaled.png"), img, "intensity", 40, 10);
    const Vec3 want = ColourAt(ColourMap::Viridis, 0.75) * 255.0;
    ExpectCode(At(ReadImage(Path("scaled.png")), t.x + 1, t.y + 100), int(std::lround(want.x)),
               int(std::lround(want.y)), int(std::lround(want.z)), 1);
}

TEST_F(SheetTest, BadInputLeavesNothingBehind) {
    OutputFiles files;
    EXPECT_THROW(StageSheetPng(files, Path("none.png"), {}, nullptr, ""), Error);
    Rgb8Image bad = Solid(4, 4, 0, 0, 0);
    bad.rgb.pop_back();
    try {
        StageSheetPng(files, Path("bad.png"), {SheetTile{bad, ""}}, nullptr, "");
        ADD_FAILURE() << "no error for an inconsistent tile";
    } catch (const Error &e) {
        EXPECT_NE(e.Message().find("cannot write '" + Path("bad.png") + "'"), std::string::npos) << e.Message();
    }
    EXPECT_THROW(StageSheetPng(files, Path("no_such_dir/x.png"), {SheetTile{Solid(4, 4, 0, 0, 0), ""}}, nullptr, ""),
                 Error);
    files.Commit();
    EXPECT_TRUE(Listing().empty());
}

}  // namespace
}  // namespace phasor
