// SPDX-License-Identifier: Apache-2.0
// The false-colour dB PNG of sensor planes carries a colour bar: the map's pixels unchanged at the
// left (enlarged by a whole factor when small), the viridis scale beside them from 0 dB (top) to
// −range (bottom), and its labels drawn with the plot font.

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "core/image/image_io.h"
#include "core/image/plot.h"
#include "support/temp_dir.h"

namespace phasor {
namespace {

class ColourBarTest : public test::TempDirTest {
  protected:
    ColourBarTest() : TempDirTest("phasor_colour_bar") {}
};

Vec3 At(const Image &img, int i, int j) { return Vec3(img.At(i, j, 0), img.At(i, j, 1), img.At(i, j, 2)) * 255.0; }

TEST_F(ColourBarTest, FalseColourPngHasALabelledBar) {
    // A 64×64 ramp: the left column at the maximum, the right one 40 dB below.
    Image img;
    img.width = img.height = 64;
    img.channels = {"intensity"};
    for (int j = 0; j < 64; ++j)
        for (int i = 0; i < 64; ++i) img.data.push_back(float(std::pow(10.0, -4.0 * i / 63)));
    WriteFalseColorPng(Path("map.png"), img, "intensity", 40);
    const Image png = ReadImage(Path("map.png"));
    // Enlarged 4× (to 256 px) with the bar and its labels to the right.
    ASSERT_EQ(png.height, 32 + 256 + 12);
    ASSERT_GT(png.width, 256 + 20 + 24);
    const int top = 32, barX = 256 + 20;
    // The map: 0 dB is viridis' yellow (#FDE725), −40 dB its purple (#440154).
    const Vec3 hot = At(png, 1, top + 100), cold = At(png, 254, top + 100);
    EXPECT_NEAR(hot.x, 0xFD, 1);
    EXPECT_NEAR(hot.z, 0x25, 1);
    EXPECT_NEAR(cold.x, 0x44, 1);
    EXPECT_NEAR(cold.z, 0x54, 1);
    // The bar: yellow at the top, purple at the bottom.
    // (rows sample t at their centres: within 1/256 of the ends, i.e. a few codes off).
    const Vec3 barTop = At(png, barX + 12, top + 1), barBottom = At(png, barX + 12, top + 254);
    EXPECT_NEAR(barTop.x, 0xFD, 8);
    EXPECT_NEAR(barBottom.x, 0x44, 8);
    // Labels: dark text pixels right of the bar (the plot's font is installed with the project).
    int dark = 0;
    for (int j = 0; j < png.height; ++j)
        for (int i = barX + 24 + 8; i < png.width; ++i) dark += At(png, i, j).y < 100;
    EXPECT_GT(dark, 50) << "no labels drawn";
}

}  // namespace
}  // namespace phasor
