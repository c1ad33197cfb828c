// SPDX-License-Identifier: Apache-2.0
// phasor — a small line-plot rasteriser (image module, src/core/image/plot.cpp): data series as
// anti-aliased solid/dashed/dotted lines on white, axes with ticks and numeric tick labels, grid,
// legend, title and axis labels, written as an 8-bit sRGB PNG (all or nothing, like image_io.h).
// Text is drawn through OpenImageIO with a TrueType font (DejaVu Sans, Debian package
// fonts-dejavu-core); without the font the plot is still written, without any text.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/image/output_file.h"

namespace phasor {

/// One data series. Points with a non-finite coordinate are skipped and break the line.
struct PlotSeries {
    enum Style { Solid, Dashed, Dotted };
    std::string label;         // legend text; empty = not in the legend
    std::vector<double> x, y;  // data coordinates, same length ≥ 1
    Vec3 rgb{0, 0, 0};         // display-referred sRGB colour, components in [0, 1]
    Style style = Solid;
    double lineWidth = 2.5;  // pixels
};

/// A horizontal bar from x0 to x1 at height y (data units), e.g. one sensor pixel's extent.
struct PlotBar {
    std::string label;  // legend text; empty = not in the legend
    double x0 = 0, x1 = 0, y = 0;
    Vec3 rgb{0, 0.75, 0.9};  // display-referred sRGB (default cyan)
    double thickness = 6;    // pixels
};

struct PlotOptions {
    std::string title, xLabel, yLabel;
    int width = 1000, height = 600;  // pixels, each in [320, 16384] × [200, 16384]
    std::vector<PlotBar> bars;
    bool yIncludesZero = true;  // extend the y range to 0 (intensities)
    /// A fixed x range (data units) when both are finite and xMin < xMax; else fitted to the data.
    double xMin = std::numeric_limits<double>::quiet_NaN(), xMax = std::numeric_limits<double>::quiet_NaN();
    std::string font = "DejaVuSans";  // OpenImageIO font name or a .ttf path
};

/// Where the data lands in the image: the plot rectangle in pixels (pixel edges, y down) and the
/// data range it spans, plus the tick values drawn on each axis (data units).
struct PlotLayout {
    int left = 0, top = 0, right = 0, bottom = 0;  // plot rectangle [left, right] × [top, bottom]
    double xMin = 0, xMax = 1, yMin = 0, yMax = 1;
    std::vector<double> xTicks, yTicks;
    /// Continuous pixel coordinates (pixel (i, j) covers [i, i+1) × [j, j+1)) of a data point.
    double PixelX(double x) const { return left + (x - xMin) / (xMax - xMin) * (right - left); }
    double PixelY(double y) const { return bottom - (y - yMin) / (yMax - yMin) * (bottom - top); }
};

struct PlotResult {
    bool textDrawn = true;    // false when no font could be loaded (the plot has no text)
    std::string textProblem;  // why, when textDrawn is false
};

/// The layout WritePlotPng uses for these inputs. Throws phasor::Error (FileLoc empty) for
/// unusable input: no series, x/y of different lengths, no finite point, a bad size or x range.
PlotLayout ComputePlotLayout(const std::vector<PlotSeries> &series, const PlotOptions &opt = {});

/// Renders the plot and writes it as a PNG to `path` through OutputFiles (core/image/output_file.h:
/// checked writes to a temporary file + rename; on any failure nothing is left behind). Throws
/// phasor::Error naming the file and the reason. A missing font is not an error: the result says
/// so and the caller decides whether to warn. The form taking `OutputFiles &` only stages the
/// file (it appears at files.Commit()).
PlotResult WritePlotPng(const std::string &path, const std::vector<PlotSeries> &series,
                        const PlotOptions &opt = {});
PlotResult WritePlotPng(OutputFiles &files, const std::string &path, const std::vector<PlotSeries> &series,
                        const PlotOptions &opt = {});

/// An 8-bit sRGB image (w × h, packed RGB, top row first) with a labelled vertical colour bar to
/// its right — e.g. a false-colour dB map and its scale. `barColour(t)` is the display colour at
/// t ∈ [0, 1] (bottom to top of the bar); each tick puts its text at its t; `barTitle` goes above
/// the bar. An image less than 256 px tall is enlarged by a whole factor (nearest neighbour; at
/// most 4096 px wide). Staged in `files` (core/image/output_file.h; it appears at files.Commit()) with
/// `description` as the PNG's Description; throws phasor::Error. Text as in WritePlotPng (the bar
/// is drawn without a font, the labels are not).
struct ColourBarTick {
    double t = 0;
    std::string text;
};
PlotResult WriteImageWithColourBarPng(OutputFiles &files, const std::string &path, const std::vector<uint8_t> &rgb,
                                      int w, int h, Vec3 (*barColour)(double t),
                                      const std::vector<ColourBarTick> &ticks, const std::string &barTitle,
                                      const std::string &description, const std::string &font = "DejaVuSans");

}  // namespace phasor
