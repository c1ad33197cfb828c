// SPDX-License-Identifier: Apache-2.0
// The line-plot rasteriser (core/image/plot.h): strokes land on the pixels the layout maps the data to,
// dashes have gaps, non-finite points break a line, axes and ticks are drawn, nice tick values,
// text with the default font and a text-less plot without one, atomic writes.

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "core/diagnostics.h"
#include "core/image/image_io.h"
#include "core/image/plot.h"
#include "support/temp_dir.h"

namespace phasor {
namespace {

namespace fs = std::filesystem;

class PlotTest : public test::TempDirTest {
  protected:
    PlotTest() : TempDirTest("phasor_plot") {}
};

Vec3 Pixel(const Image &img, int i, int j) {
    return {img.At(i, j, 0), img.At(i, j, 1), img.At(i, j, 2)};
}
bool IsColour(const Vec3 &p, const Vec3 &c) {
    return p.x == c.x && p.y == c.y && p.z == c.z;
}
bool IsWhite(const Vec3 &p) {
    return IsColour(p, {1, 1, 1});
}

PlotSeries Line(std::vector<double> x, std::vector<double> y, Vec3 rgb,
                PlotSeries::Style style = PlotSeries::Solid) {
    PlotSeries s;
    s.x = std::move(x);
    s.y = std::move(y);
    s.rgb = rgb;
    s.style = style;
    return s;
}

const Vec3 kRed{1, 0, 0}, kBlue{0, 0, 1};

TEST_F(PlotTest, SolidLineCoversThePixelsItMapsTo) {
    // A diagonal through the data range; no labels, so no legend covers anything.
    std::vector<PlotSeries> series{Line({0, 1}, {0, 1}, kRed)};
    PlotOptions opt;
    const PlotLayout L = ComputePlotLayout(series, opt);
    WritePlotPng(Path("line.png"), series, opt);
    const Image img = ReadImage(Path("line.png"));
    ASSERT_EQ(img.width, 1000);
    ASSERT_EQ(img.height, 600);
    int checked = 0;
    for (double t = 0.05; t <= 0.95; t += 0.01) {
        // Every point of the line is within √2/2 px of the centre of the pixel containing it, so a
        // 2.5 px stroke covers that pixel fully: exactly the series colour.
        const double px = L.PixelX(t), py = L.PixelY(t);
        EXPECT_TRUE(IsColour(Pixel(img, int(px), int(py)), kRed)) << "t = " << t;
        // 20 px straight below the line (≥ 10 px from it): untouched by the stroke.
        const Vec3 below = Pixel(img, int(px), int(py) + 20);
        EXPECT_EQ(below.y, below.x) << "red tint 20 px below the line at t = " << t;
        ++checked;
    }
    EXPECT_GT(checked, 80);
}

TEST_F(PlotTest, DashesAndDotsHaveGapsAndSolidLinesDoNot) {
    const double y = 0.537;  // not on a grid line
    for (auto style : {PlotSeries::Solid, PlotSeries::Dashed, PlotSeries::Dotted}) {
        std::vector<PlotSeries> series{Line({0, 1}, {y, y}, kBlue, style)};
        PlotOptions opt;
        const PlotLayout L = ComputePlotLayout(series, opt);
        WritePlotPng(Path("dash.png"), series, opt);
        const Image img = ReadImage(Path("dash.png"));
        const int row = int(L.PixelY(y));
        // Dashed (2.5 px wide): on 13.25 px of every 21.5; dotted: 1.5 px of every 7.5. Over a
        // whole number of periods (two periods are a whole number of pixels), the mean coverage
        // along the line's row is the on fraction: the ramps at the dash ends are symmetric.
        const double on = style == PlotSeries::Dashed ? 13.25 : style == PlotSeries::Dotted ? 1.5 : 1;
        const double period = style == PlotSeries::Dashed ? 21.5 : style == PlotSeries::Dotted ? 7.5 : 1;
        const int window = int(800 / (2 * period)) * int(2 * period);
        int exact = 0, off = 0;
        double coverage = 0;
        for (int i = L.left + 20; i < L.left + 20 + window; ++i) {
            const Vec3 p = Pixel(img, i, row);
            exact += IsColour(p, kBlue);
            coverage += 1 - p.x;  // blue over white: x = 1 − coverage
            off += p.x > 0.85;    // background (white, or a grid line's grey 0.88)
        }
        if (style == PlotSeries::Solid) {
            EXPECT_EQ(exact, window);
        } else {
            EXPECT_GT(off, window / 3) << "style " << style;
            EXPECT_NEAR(coverage / window, on / period, 0.002) << "style " << style;
        }
    }
}

TEST_F(PlotTest, NonFinitePointsBreakTheLine) {
    const double nan = std::nan("");
    std::vector<PlotSeries> series{Line({0, 0.4, 0.5, 0.6, 1}, {0.5, 0.5, nan, 0.5, 0.5}, kRed)};
    const PlotLayout L = ComputePlotLayout(series);
    WritePlotPng(Path("gap.png"), series);
    const Image img = ReadImage(Path("gap.png"));
    const int row = int(L.PixelY(0.5));
    EXPECT_TRUE(IsColour(Pixel(img, int(L.PixelX(0.2)), row), kRed));
    EXPECT_TRUE(IsColour(Pixel(img, int(L.PixelX(0.8)), row), kRed));
    const Vec3 mid = Pixel(img, int(L.PixelX(0.5)), row);
    EXPECT_EQ(mid.y, mid.x) << "the line continues across the NaN point";
}

TEST_F(PlotTest, AxesFrameAndTicksAreDrawnAtNiceValues) {
    std::vector<PlotSeries> series{Line({-3.2e-6, 7.9e-6}, {0.1, 13.7}, kRed)};
    PlotOptions opt;
    const PlotLayout L = ComputePlotLayout(series, opt);
    WritePlotPng(Path("axes.png"), series, opt);
    const Image img = ReadImage(Path("axes.png"));
    const Vec3 black{0, 0, 0};
    // The frame: 2 px centred on the plot rectangle's edges.
    for (int j = L.top + 1; j < L.bottom; j += 7) {
        EXPECT_TRUE(IsColour(Pixel(img, L.left - 1, j), black)) << j;
        EXPECT_TRUE(IsColour(Pixel(img, L.left, j), black)) << j;
    }
    for (int i = L.left + 1; i < L.right; i += 7) EXPECT_TRUE(IsColour(Pixel(img, i, L.bottom), black)) << i;
    // y starts at 0 (yIncludesZero), and the data fit inside the range.
    EXPECT_EQ(L.yMin, 0);
    EXPECT_GE(L.yMax, 13.7);
    EXPECT_LE(L.xMin, -3.2e-6);
    EXPECT_GE(L.xMax, 7.9e-6);
    // Ticks: 1, 2 or 5 × 10^k apart, inside the range, each with an outward tick mark.
    for (const std::vector<double> *ticks : {&L.xTicks, &L.yTicks}) {
        ASSERT_GE(ticks->size(), 3u);
        const double step = (*ticks)[1] - (*ticks)[0];
        const double mantissa = step / std::pow(10.0, std::floor(std::log10(step)));
        EXPECT_TRUE(std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 ||
                    std::abs(mantissa - 5) < 1e-9)
            << "step " << step;
        for (std::size_t k = 1; k < ticks->size(); ++k)
            EXPECT_NEAR((*ticks)[k] - (*ticks)[k - 1], step, 1e-9 * step);
    }
    EXPECT_GE(L.xTicks.front(), L.xMin);
    EXPECT_LE(L.xTicks.back(), L.xMax);
    for (double t : L.xTicks)
        for (int j = L.bottom + 1; j <= L.bottom + 5; ++j)
            EXPECT_TRUE(IsColour(Pixel(img, int(L.PixelX(t)), j), black)) << "x tick " << t << " row " << j;
    for (double t : L.yTicks)
        for (int i = L.left - 5; i <= L.left - 2; ++i)
            EXPECT_TRUE(IsColour(Pixel(img, i, int(L.PixelY(t))), black))
                << "y tick " << t << " column " << i;
    // Outside the frame, between the ticks, the margin is white.
    EXPECT_TRUE(IsWhite(Pixel(img, L.left - 30, (L.top + L.bottom) / 2 + 3)));
}

TEST_F(PlotTest, BarsAreDrawnWithTheirExtent) {
    std::vector<PlotSeries> series{Line({0, 10}, {0, 1}, kRed)};
    PlotOptions opt;
    PlotBar bar;
    bar.x0 = 4;
    bar.x1 = 6;
    bar.y = 0.9;
    bar.rgb = {0, 1, 1};
    opt.bars.push_back(bar);
    const PlotLayout L = ComputePlotLayout(series, opt);
    WritePlotPng(Path("bar.png"), series, opt);
    const Image img = ReadImage(Path("bar.png"));
    const int row = int(L.PixelY(0.9));
    EXPECT_TRUE(IsColour(Pixel(img, int(L.PixelX(4.1)), row), bar.rgb));
    EXPECT_TRUE(IsColour(Pixel(img, int(L.PixelX(5.9)), row), bar.rgb));
    EXPECT_FALSE(IsColour(Pixel(img, int(L.PixelX(3.8)), row), bar.rgb));
    EXPECT_FALSE(IsColour(Pixel(img, int(L.PixelX(6.2)), row), bar.rgb));
}

// Counts non-white pixels in the title band (above the plot rectangle, around the centre).
int TitleInk(const Image &img, const PlotLayout &L) {
    int ink = 0;
    for (int j = 5; j < L.top - 30; ++j)
        for (int i = img.width / 2 - 150; i < img.width / 2 + 150; ++i) ink += !IsWhite(Pixel(img, i, j));
    return ink;
}

TEST_F(PlotTest, TextIsDrawnWithTheDefaultFontAndOmittedWithoutOne) {
    std::vector<PlotSeries> series{Line({0, 1}, {0, 1}, kRed)};
    series[0].label = "grt";
    PlotOptions opt;
    opt.title = "intensity, row 0";
    opt.xLabel = "x (um)";
    const PlotLayout L = ComputePlotLayout(series, opt);

    // The default font is DejaVu Sans (Debian: fonts-dejavu-core, installed by scripts/install-deps.sh).
    PlotResult r = WritePlotPng(Path("text.png"), series, opt);
    EXPECT_TRUE(r.textDrawn) << r.textProblem;
    EXPECT_GT(TitleInk(ReadImage(Path("text.png")), L), 50);

    opt.font = "no-such-font-phasor";
    r = WritePlotPng(Path("notext.png"), series, opt);
    EXPECT_FALSE(r.textDrawn);
    EXPECT_NE(r.textProblem.find("no-such-font-phasor"), std::string::npos) << r.textProblem;
    const Image img = ReadImage(Path("notext.png"));
    EXPECT_EQ(TitleInk(img, L), 0);
    // The data are still there.
    EXPECT_TRUE(IsColour(Pixel(img, int(L.PixelX(0.3)), int(L.PixelY(0.3))), kRed));
}

TEST_F(PlotTest, BadInputOrAnUnwritablePathLeavesNothingBehind) {
    auto throwsNaming = [&](const std::string &path, const std::vector<PlotSeries> &series,
                            const PlotOptions &opt, const std::string &reason) {
        try {
            WritePlotPng(path, series, opt);
            ADD_FAILURE() << "no error for " << reason;
        } catch (const Error &e) {
            EXPECT_NE(e.Message().find("cannot write '" + path + "'"), std::string::npos) << e.Message();
            EXPECT_NE(e.Message().find(reason), std::string::npos) << e.Message();
        }
    };
    const std::vector<PlotSeries> good{Line({0, 1}, {0, 1}, kRed)};
    throwsNaming(Path("empty.png"), {}, {}, "no data series");
    throwsNaming(Path("sizes.png"), {Line({0, 1, 2}, {0, 1}, kRed)}, {}, "3 x values but 2 y values");
    throwsNaming(Path("nan.png"), {Line({std::nan("")}, {1}, kRed)}, {}, "no series has a finite point");
    PlotOptions tiny;
    tiny.width = 10;
    throwsNaming(Path("tiny.png"), good, tiny, "plot size");
    throwsNaming(Path("no_such_dir/plot.png"), good, {}, "does not exist");
    EXPECT_TRUE(Listing().empty()) << Listing().front();

    // A successful write replaces an existing file and leaves no temporary file.
    WritePlotPng(Path("ok.png"), good);
    WritePlotPng(Path("ok.png"), good);
    EXPECT_EQ(Listing(), std::vector<std::string>{"ok.png"});
}

}  // namespace
}  // namespace phasor
