// SPDX-License-Identifier: Apache-2.0
// phasor — images for people (image module, src/core/image/sheet.cpp): values tone-mapped through
// a colour map (dB false colour of sensor images, signed differences), and sheets that put 8-bit
// images side by side with labels and a colour bar — boxes, lines and text drawn by OpenImageIO
// (ImageBufAlgo; text through FreeType with DejaVu Sans, Debian package fonts-dejavu-core).
// Plots (axes, curves) are matplotlib's: src/app/plot.h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/image/output_file.h"

namespace phasor {

/// An 8-bit display-referred sRGB image, packed RGB, top row first.
struct Rgb8Image {
    int width = 0, height = 0;
    std::vector<uint8_t> rgb;
};

enum class ColourMap {
    /// viridis (van der Walt & Smith 2015, matplotlib's default): dark purple → yellow.
    Viridis,
    /// ColorBrewer RdBu reversed (Brewer 2002): blue (t = 0) → white (½) → red (1), for signed
    /// values around zero.
    Diverging,
};
/// The display sRGB colour in [0, 1]³ of `map` at t (clamped to [0, 1]).
Vec3 ColourAt(ColourMap map, double t);

/// `values` (width × height, top row first) mapped linearly from `lo` (t = 0) to `hi` (t = 1),
/// clamped to the map's ends; +Inf maps to t = 1, NaN and −Inf to t = 0. Requires lo < hi.
Rgb8Image MapColours(const std::vector<double> &values, int width, int height, ColourMap map, double lo, double hi);

/// A colour bar: `map` from t = 0 (bottom) to 1 (top), a label at each tick, a title above.
struct ColourBarTick {
    double t = 0;
    std::string text;
};
struct ColourBar {
    ColourMap map = ColourMap::Viridis;
    std::vector<ColourBarTick> ticks;
    std::string title;
};

/// Levels in dB against a reference level: 10·log10(v / zeroDb) (v is power-like: intensity,
/// irradiance), below −rangeDb (and v ≤ 0, NaN) → −rangeDb. The bar of that scale: 0 dB at the
/// top, labelled every 10 dB (5 dB below a 20 dB range).
std::vector<double> DecibelLevels(const std::vector<double> &values, double zeroDb, double rangeDb);
ColourBar DecibelBar(double rangeDb, const std::string &title);

/// One image of a sheet and the text above it (empty: none).
struct SheetTile {
    Rgb8Image image;
    std::string label;
};

struct SheetResult {
    bool textDrawn = true;    // false when no font could be loaded (the sheet has no text)
    std::string textProblem;  // why, when textDrawn is false
};

/// The whole-number factor by which a sheet enlarges its tiles (nearest neighbour): the tallest
/// tile to at least 256 px, the widest to at most max(its width, 1024) px.
int SheetScale(const std::vector<SheetTile> &tiles);

/// Where StageSheetPng puts things (pixels, y down): each tile's enlarged image (the label band,
/// `labelBand` px, above it) and the colour bar (w = h = 0 without one). Throws phasor::Error (no
/// FileLoc) for no tiles, an empty or inconsistent tile, or a sheet over 2·10⁸ pixels.
struct SheetLayout {
    struct Rect {
        int x = 0, y = 0, w = 0, h = 0;
    };
    int width = 0, height = 0, scale = 1, labelBand = 0;
    std::vector<Rect> tiles;
    Rect bar;
};
SheetLayout LayoutSheet(const std::vector<SheetTile> &tiles, const ColourBar *bar, int columns = 0);

/// Stages in `files` (core/image/output_file.h; it appears at files.Commit()) a PNG of `tiles` on
/// white in `columns` columns (≤ 0: one row of up to 4 tiles, one column when the tiles are
/// more than 3× wider than tall), each enlarged by SheetScale and labelled above, and `bar` (when
/// not null) to their right, as tall as the tiles. `description` becomes the PNG's Description.
/// Throws phasor::Error ("cannot write 'PATH': …") for empty or inconsistent tiles or a failed
/// write. A missing font is not an error: the result says so, the sheet has no text.
SheetResult StageSheetPng(OutputFiles &files, const std::string &path, const std::vector<SheetTile> &tiles,
                          const ColourBar *bar, const std::string &description, int columns = 0,
                          const std::string &font = "DejaVuSans");

}  // namespace phasor
