// SPDX-License-Identifier: Apache-2.0
// Image files: exact EXR round trips with names and metadata, atomic writes that leave nothing
// behind on failure, 8-bit PNG through the display transform, false-colour dB PNGs.

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "core/diagnostics.h"
#include "core/image/image_io.h"
#include "support/stats.h"
#include "support/temp_dir.h"

namespace phasor {
namespace {

namespace fs = std::filesystem;

// A fresh, empty directory per test, removed afterwards.
class ImageIoTest : public test::TempDirTest {
  protected:
    ImageIoTest() : TempDirTest("phasor_image_io") {}
    void SetUp() override {
        TempDirTest::SetUp();
        unsetenv("OCIO");  // these tests use the built-in OCIO config
    }
};

uint32_t Bits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}
float FromBits(uint32_t u) {
    float f;
    std::memcpy(&f, &u, sizeof f);
    return f;
}

TEST_F(ImageIoTest, ExrRoundTripIsBitExact) {
    Image img;
    img.width = 37;
    img.height = 23;
    img.channels = {"variance", "R", "zeta", "G", "intensity"};
    img.metadata = {{"phasor:samples_per_pixel", "64"},
                    {"phasor:note", "a string with spaces, = and : signs"},
                    {"phasor:integrator", "plt"}};
    test::TestRng rng(20240607);
    img.data.resize(std::size_t(img.width) * img.height * img.channels.size());
    for (float &v : img.data) {
        // Arbitrary finite bit patterns: all exponents, including denormals and huge values.
        do v = FromBits(rng.NextU32());
        while (!std::isfinite(v));
    }
    const float special[] = {std::numeric_limits<float>::denorm_min(),
                             -std::numeric_limits<float>::denorm_min(),
                             std::numeric_limits<float>::min() / 3,
                             std::numeric_limits<float>::max(),
                             -std::numeric_limits<float>::max(),
                             -0.0f,
                             0.0f,
                             1e30f};
    for (std::size_t i = 0; i < std::size(special); ++i) img.data[i * 7] = special[i];
    int denormals = 0;
    for (float v : img.data) denormals += (v != 0 && std::fpclassify(v) == FP_SUBNORMAL);
    ASSERT_GT(denormals, 3);

    const std::string path = Path("roundtrip.exr");
    WriteExr(path, img);
    Image back = ReadImage(path);
    ASSERT_EQ(back.width, img.width);
    ASSERT_EQ(back.height, img.height);
    ASSERT_EQ(back.channels.size(), img.channels.size());
    long long mismatches = 0;
    for (std::size_t c = 0; c < img.channels.size(); ++c) {
        int cb = back.ChannelIndex(img.channels[c]);
        ASSERT_GE(cb, 0) << "channel '" << img.channels[c] << "' lost";
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x)
                mismatches += Bits(img.At(x, y, int(c))) != Bits(back.At(x, y, cb));
    }
    EXPECT_EQ(mismatches, 0);
    for (const auto &[key, value] : img.metadata) {
        auto it = back.metadata.find(key);
        ASSERT_NE(it, back.metadata.end()) << "metadata '" << key << "' lost";
        EXPECT_EQ(it->second, value);
    }
    EXPECT_EQ(Listing(), std::vector<std::string>{"roundtrip.exr"});  // no temporary left
}

TEST_F(ImageIoTest, ExrOverwriteReplacesTheFile) {
    Image img{2, 1, {"intensity"}, {1.0f, 2.0f}, {}};
    const std::string path = Path("a.exr");
    WriteExr(path, img);
    img.data = {3.0f, 4.0f};
    WriteExr(path, img);
    Image back = ReadImage(path);
    ASSERT_EQ(back.data.size(), 2u);
    EXPECT_EQ(back.data[0], 3.0f);
    EXPECT_EQ(back.data[1], 4.0f);
    EXPECT_EQ(Listing(), std::vector<std::string>{"a.exr"});
}

TEST_F(ImageIoTest, WriteIntoMissingDirectoryThrowsAndLeavesNothing) {
    Image img{2, 2, {"R", "G", "B"}, std::vector<float>(12, 0.5f), {}};
    const std::string path = Path("missing/out.exr");
    try {
        WriteExr(path, img);
        FAIL() << "expected phasor::Error";
    } catch (const Error &e) {
        EXPECT_EQ(e.Message().rfind("cannot write '" + path + "': ", 0), 0u) << e.Message();
    }
    EXPECT_THROW(WritePng(Path("missing/out.png"), img), Error);
    EXPECT_FALSE(fs::exists(dir_ / "missing"));
    EXPECT_TRUE(Listing().empty());
}

TEST_F(ImageIoTest, FailedRenameRemovesTheTemporaryFile) {
    // The target is an existing directory: the temporary file is written, the rename fails.
    fs::create_directory(dir_ / "taken.exr");
    Image img{2, 2, {"R", "G", "B"}, std::vector<float>(12, 0.5f), {}};
    EXPECT_THROW(WriteExr(Path("taken.exr"), img), Error);
    EXPECT_THROW(WritePng(Path("taken.exr"), img), Error);
    EXPECT_EQ(Listing(), std::vector<std::string>{"taken.exr"});
    EXPECT_TRUE(fs::is_empty(dir_ / "taken.exr"));
}

TEST_F(ImageIoTest, InconsistentImageThrows) {
    Image img{4, 4, {"R", "G", "B"}, std::vector<float>(10, 0.0f), {}};
    EXPECT_THROW(WriteExr(Path("bad.exr"), img), Error);
    EXPECT_TRUE(Listing().empty());
}

TEST_F(ImageIoTest, ReadingAMissingFileThrowsNamingIt) {
    const std::string path = Path("nothing.exr");
    try {
        ReadImage(path);
        FAIL() << "expected phasor::Error";
    } catch (const Error &e) {
        EXPECT_NE(e.Message().find(path), std::string::npos) << e.Message();
    }
}

// A truncated PNG: one error, the exception's, on one line — libpng's own "libpng error: …" on
// stderr used to repeat it (issue 10 §4).
TEST_F(ImageIoTest, ATruncatedPngIsOneErrorAndNothingOnStderr) {
    Image img{64, 64, {"R", "G", "B"}, std::vector<float>(64 * 64 * 3), {}};
    test::TestRng rng(3);
    for (float &v : img.data) v = float(rng.Uniform());
    WritePng(Path("full.png"), img);
    const std::string bytes = [&] {
        std::ifstream f(Path("full.png"), std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(f), {});
    }();
    std::ofstream(Path("cut.png"), std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    testing::internal::CaptureStderr();
    std::string message;
    try {
        ReadImage(Path("cut.png"));
    } catch (const Error &e) {
        message = e.Message();
    }
    const std::string printed = testing::internal::GetCapturedStderr();
    EXPECT_EQ(printed, "");
    EXPECT_EQ(message.rfind("cannot read '" + Path("cut.png") + "': ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

// IEC 61966-2-1 sRGB encoding.
double SrgbEncode(double x) {
    return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
}

TEST_F(ImageIoTest, PngHasExpected8BitValuesForKnownColours) {
    const std::vector<Vec3> colours = {{0, 0, 0},     {1, 1, 1},         {0.18, 0.5, 0.02},
                                       {2, -1, 0.75}, {0.001, 0.3, 0.9}, {0.0004, 0.06, 0.7}};
    Image img;
    img.width = int(colours.size());
    img.height = 2;
    img.channels = {"R", "G", "B", "intensity"};
    for (int y = 0; y < img.height; ++y)
        for (const Vec3 &c : colours)
            img.data.insert(img.data.end(), {float(c.x), float(c.y), float(c.z), 7.0f});
    const std::string path = Path("colours.png");
    WritePng(path, img);
    Image back = ReadImage(path);
    ASSERT_EQ(back.width, img.width);
    ASSERT_EQ(back.height, img.height);
    ASSERT_EQ(back.channels, (std::vector<std::string>{"R", "G", "B"}));
    for (int y = 0; y < img.height; ++y) {
        for (int x = 0; x < img.width; ++x) {
            for (int c = 0; c < 3; ++c) {
                double lin = double(float(colours[x][c]));
                double code = 255 * Clamp(SrgbEncode(Clamp(lin, 0, 1)), 0, 1);
                // The chosen colours sit well away from rounding ties.
                ASSERT_GT(std::abs(code - std::floor(code) - 0.5), 0.01) << lin;
                long expected = std::lround(code);
                long got = std::lround(back.At(x, y, c) * 255.0);
                EXPECT_EQ(got, expected) << "pixel " << x << " channel " << c << " linear " << lin;
            }
        }
    }
    EXPECT_EQ(Listing(), std::vector<std::string>{"colours.png"});
}

TEST_F(ImageIoTest, FalseColourMapsTheDbRangeOntoViridis) {
    // Published viridis colours at t = k/9 (k = 0 … 9), van der Walt & Smith.
    const int viridis[10][3] = {{68, 1, 84},    {72, 40, 120},  {62, 74, 137},  {49, 104, 142},
                                {38, 130, 142}, {31, 158, 137}, {53, 183, 121}, {109, 205, 89},
                                {180, 222, 44}, {253, 231, 37}};
    const double rangeDb = 30;
    Image img;
    img.width = 14;
    img.height = 1;
    img.channels = {"R", "intensity"};
    for (int k = 0; k < 10; ++k) {
        // 10·log10(v / vmax) = −rangeDb·(1 − k/9), with vmax = 2.
        double v = 2 * std::pow(10.0, -rangeDb * (1 - k / 9.0) / 10);
        img.data.insert(img.data.end(), {-1.0f, float(v)});
    }
    // Below the range, zero, negative and NaN all map to the bottom colour.
    for (float v : {1e-9f, 0.0f, -3.0f, std::numeric_limits<float>::quiet_NaN()})
        img.data.insert(img.data.end(), {5.0f, v});
    const std::string path = Path("false.png");
    WriteFalseColorPng(path, img, "intensity", rangeDb);
    Image back = ReadImage(path);
    // The map is enlarged by a whole factor (core/image/sheet.h LayoutSheet) with its colour bar to
    // the right.
    ColourBar bar = DecibelBar(rangeDb, "intensity, 0 dB = 2");
    const SheetLayout L = LayoutSheet({SheetTile{ToFalseColourDb(img, "intensity", rangeDb), ""}}, &bar);
    const int scale = L.scale, left = L.tiles[0].x, top = L.tiles[0].y;
    ASSERT_EQ(back.width, L.width);
    ASSERT_EQ(back.channels.size(), 3u);
    for (int x = 0; x < img.width; ++x) {
        int k = x < 10 ? x : 0;
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(std::lround(back.At(left + x * scale + scale / 2, top + scale / 2, c) * 255.0), viridis[k][c])
                << "pixel " << x;
    }
    EXPECT_THROW(WriteFalseColorPng(Path("x.png"), img, "phase"), Error);
    EXPECT_FALSE(fs::exists(dir_ / "x.png"));
}

}  // namespace
}  // namespace phasor
