// SPDX-License-Identifier: Apache-2.0
// phasor — colour maps and image sheets (sheet.h). A sheet is composed in a float sRGB buffer
// wrapped by an OIIO::ImageBuf: tiles are copied in (nearest-neighbour enlargement by a whole
// factor), the colour bar's rows filled, frames and ticks drawn with ImageBufAlgo::render_box /
// render_line, text with ImageBufAlgo::render_text; then quantised to 8 bits and staged through
// the all-or-nothing writer (oiio_write.h).

#include "core/image/sheet.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "core/diagnostics.h"
#include "core/image/oiio_write.h"

namespace phasor {
namespace {

namespace IBA = OIIO::ImageBufAlgo;

// viridis (van der Walt & Smith 2015, matplotlib's default colour map): its published sRGB colours
// at t = 0, 1/9, …, 1; interpolated linearly in between.
constexpr uint8_t Viridis[10][3] = {{0x44, 0x01, 0x54}, {0x48, 0x28, 0x78}, {0x3E, 0x4A, 0x89}, {0x31, 0x68, 0x8E},
                                    {0x26, 0x82, 0x8E}, {0x1F, 0x9E, 0x89}, {0x35, 0xB7, 0x79}, {0x6D, 0xCD, 0x59},
                                    {0xB4, 0xDE, 0x2C}, {0xFD, 0xE7, 0x25}};
// ColorBrewer RdBu, 11 classes (Cynthia Brewer, colorbrewer2.org, Apache 2.0), reversed: blue for
// negative values, white at zero, red for positive ones.
constexpr uint8_t Diverging[11][3] = {{0x05, 0x30, 0x61}, {0x21, 0x66, 0xAC}, {0x43, 0x93, 0xC3}, {0x92, 0xC5, 0xDE},
                                      {0xD1, 0xE5, 0xF0}, {0xF7, 0xF7, 0xF7}, {0xFD, 0xDB, 0xC7}, {0xF4, 0xA5, 0x82},
                                      {0xD6, 0x60, 0x4D}, {0xB2, 0x18, 0x2B}, {0x67, 0x00, 0x1F}};

template <std::size_t N>
void Interpolate(const uint8_t (&table)[N][3], double t, uint8_t out[3]) {
    t = (std::isfinite(t) ? Clamp(t, 0, 1) : 0) * (N - 1);
    const int i = std::min(int(t), int(N) - 2);
    const double f = t - i;
    for (int c = 0; c < 3; ++c) out[c] = uint8_t(std::lround(Lerp(f, table[i][c], table[i + 1][c])));
}

void Colour8(ColourMap map, double t, uint8_t out[3]) {
    if (map == ColourMap::Diverging)
        Interpolate(Diverging, t, out);
    else
        Interpolate(Viridis, t, out);
}

// Layout constants (pixels).
constexpr int Margin = 10, LabelBand = 26, LabelLine = 19, Gap = 12, BarGap = 18, BarWidth = 24, BarLabels = 92,
              TitleBand = 40;
constexpr int TickLength = 6, FontSize = 15, LabelFontSize = 16;

}  // namespace

Vec3 ColourAt(ColourMap map, double t) {
    uint8_t c[3];
    Colour8(map, t, c);
    return Vec3(c[0], c[1], c[2]) / 255.0;
}

Rgb8Image MapColours(const std::vector<double> &values, int width, int height, ColourMap map, double lo, double hi) {
    if (!(lo < hi)) throw Error("MapColours: empty range");
    Rgb8Image out;
    out.width = width;
    out.height = height;
    out.rgb.resize(values.size() * 3);
    for (std::size_t i = 0; i < values.size(); ++i) {
        const double v = values[i];
        const double t = v == Infinity ? 1 : std::isfinite(v) ? (v - lo) / (hi - lo) : 0;
        Colour8(map, t, &out.rgb[3 * i]);
    }
    return out;
}

std::vector<double> DecibelLevels(const std::vector<double> &values, double zeroDb, double rangeDb) {
    std::vector<double> db(values.size(), -rangeDb);
    for (std::size_t i = 0; i < values.size(); ++i) {
        const double v = values[i];
        if (v == Infinity)
            db[i] = 0;
        else if (zeroDb > 0 && v > 0 && std::isfinite(v))
            db[i] = std::max(-rangeDb, 10 * std::log10(v / zeroDb));
    }
    return db;
}

ColourBar DecibelBar(double rangeDb, const std::string &title) {
    ColourBar bar;
    bar.map = ColourMap::Viridis;
    bar.title = title;
    const double step = rangeDb >= 20 ? 10 : 5;
    for (double db = 0; db <= rangeDb * (1 + 1e-9); db += step) {
        char label[32];
        std::snprintf(label, sizeof label, "%g dB", db > 0 ? -db : 0.0);  // "0 dB", not "-0 dB"
        bar.ticks.push_back({1 - db / rangeDb, label});
    }
    return bar;
}

int SheetScale(const std::vector<SheetTile> &tiles) {
    int w = 1, h = 1;
    for (const SheetTile &t : tiles) {
        w = std::max(w, t.image.width);
        h = std::max(h, t.image.height);
    }
    return std::clamp(int(std::ceil(256.0 / h)), 1, std::max(1, 1024 / w));
}

SheetLayout LayoutSheet(const std::vector<SheetTile> &tiles, const ColourBar *bar, int columns) {
    if (tiles.empty()) throw Error("no image to show");
    int tileW = 0, tileH = 0, labelLines = 0;
    for (const SheetTile &t : tiles) {
        if (t.image.width <= 0 || t.image.height <= 0 ||
            t.image.rgb.size() != std::size_t(t.image.width) * t.image.height * 3)
            throw Error("an image is empty or its size is inconsistent");
        tileW = std::max(tileW, t.image.width);
        tileH = std::max(tileH, t.image.height);
        // Labels: one or more lines ('\n') above each tile.
        if (!t.label.empty())
            labelLines = std::max(labelLines, 1 + int(std::count(t.label.begin(), t.label.end(), '\n')));
    }
    SheetLayout L;
    L.scale = SheetScale(tiles);
    tileW *= L.scale;
    tileH *= L.scale;
    const int n = int(tiles.size());
    if (columns <= 0) columns = tileW > 3 * tileH ? 1 : std::min(n, 4);
    columns = std::min(columns, n);
    const int rows = (n + columns - 1) / columns;
    L.labelBand = labelLines > 0 ? LabelBand + (labelLines - 1) * LabelLine : 0;
    const int top = bar && !bar->title.empty() ? TitleBand : Margin;
    const int gridW = columns * tileW + (columns - 1) * Gap, gridH = rows * (L.labelBand + tileH) + (rows - 1) * Gap;
    for (int k = 0; k < n; ++k) {
        const int x0 = Margin + (k % columns) * (tileW + Gap),
                  y0 = top + (k / columns) * (L.labelBand + tileH + Gap) + L.labelBand;
        L.tiles.push_back({x0, y0, tiles[k].image.width * L.scale, tiles[k].image.height * L.scale});
    }
    if (bar) {
        L.bar = {Margin + gridW + BarGap, top + L.labelBand, BarWidth, std::max(gridH - L.labelBand, 160)};
        L.width = L.bar.x + BarWidth + BarLabels;
        L.height = std::max(top + gridH, L.bar.y + L.bar.h) + Margin;
    } else {
        L.width = Margin + gridW + Margin;
        L.height = top + gridH + Margin;
    }
    if (double(L.width) * L.height > 2e8)
        throw Error("the sheet would be " + std::to_string(L.width) + "x" + std::to_string(L.height) + " pixels");
    return L;
}

SheetResult StageSheetPng(OutputFiles &files, const std::string &path, const std::vector<SheetTile> &tiles,
                          const ColourBar *bar, const std::string &description, int columns, const std::string &font) {
    SheetLayout L;
    try {
        L = LayoutSheet(tiles, bar, columns);
    } catch (const Error &e) {
        throw Error(FileLoc{path}, "cannot write '" + path + "': " + e.Message());
    }
    const int width = L.width, height = L.height, scale = L.scale, n = int(tiles.size());
    const int barX = L.bar.x, barY = L.bar.y, barH = L.bar.h;
    std::vector<float> canvas(std::size_t(width) * height * 3, 1.0f);
    OIIO::ImageBuf buf(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT), canvas.data());
    const float black[3] = {0, 0, 0};

    // Tiles, enlarged by a whole factor.
    for (int k = 0; k < n; ++k) {
        const Rgb8Image &img = tiles[k].image;
        const int x0 = L.tiles[k].x, y0 = L.tiles[k].y;
        for (int j = 0; j < img.height * scale; ++j)
            for (int i = 0; i < img.width * scale; ++i) {
                const uint8_t *src = &img.rgb[(std::size_t(j / scale) * img.width + i / scale) * 3];
                float *dst = &canvas[(std::size_t(y0 + j) * width + x0 + i) * 3];
                for (int c = 0; c < 3; ++c) dst[c] = src[c] / 255.0f;
            }
    }
    // The colour bar: one colour per row, a frame, ticks.
    if (bar) {
        for (int j = 0; j < barH; ++j) {
            const Vec3 c = ColourAt(bar->map, 1 - (j + 0.5) / barH);
            const float rgb[3] = {float(c.x), float(c.y), float(c.z)};
            IBA::fill(buf, rgb, OIIO::ROI(barX, barX + BarWidth, barY + j, barY + j + 1));
        }
        IBA::render_box(buf, barX, barY, barX + BarWidth - 1, barY + barH - 1, black);
        for (const ColourBarTick &t : bar->ticks) {
            const int y = barY + int(std::lround((1 - Clamp(t.t, 0, 1)) * (barH - 1)));
            IBA::render_line(buf, barX + BarWidth, y, barX + BarWidth + TickLength, y, black);
        }
    }

    // Text. A font that cannot be loaded leaves the sheet without text (and says so).
    SheetResult result;
    const OIIO::ROI probe = IBA::text_size("0", FontSize, font);
    OIIO::geterror();  // drop any message of a failed font look-up
    if (!probe.defined()) {
        result.textDrawn = false;
        result.textProblem = "OpenImageIO found no font '" + font +
                             "' (install the Debian package fonts-dejavu-core, or set $OPENIMAGEIO_FONTS)";
    }
    auto text = [&](int x, int y, const std::string &s, int size, IBA::TextAlignX ax, IBA::TextAlignY ay) {
        if (!result.textDrawn || s.empty()) return;
        if (!IBA::render_text(buf, x, y, s, size, font, black, ax, ay, 0, {}, 1)) {
            result.textDrawn = false;
            result.textProblem = "OpenImageIO could not render text with font '" + font + "': " + buf.geterror();
        }
    };
    for (int k = 0; k < n; ++k) {
        const int x0 = L.tiles[k].x, y0 = L.tiles[k].y - L.labelBand, tileW = L.tiles[k].w;
        std::size_t start = 0;
        for (int line = 0; start <= tiles[k].label.size(); ++line) {
            const std::size_t end = std::min(tiles[k].label.find('\n', start), tiles[k].label.size());
            const std::string s = tiles[k].label.substr(start, end - start);
            // The largest size (down to 10 px) at which the line fits above its tile.
            int size = LabelFontSize;
            while (size > 10 && result.textDrawn) {
                const OIIO::ROI r = IBA::text_size(s, size, font);
                if (!r.defined() || r.xend - std::min(0, r.xbegin) <= tileW - 4) break;
                --size;
            }
            text(x0 + 2, y0 + 4 + LabelLine * line + LabelLine / 2, s, size, IBA::TextAlignX::Left,
                 IBA::TextAlignY::Center);
            start = end + 1;
        }
    }
    if (bar) {
        for (const ColourBarTick &t : bar->ticks) {
            const int y = barY + int(std::lround((1 - Clamp(t.t, 0, 1)) * (barH - 1)));
            text(barX + BarWidth + TickLength + 4, y, t.text, FontSize - 2, IBA::TextAlignX::Left,
                 IBA::TextAlignY::Center);
        }
        text(width - 6, 16, bar->title, FontSize - 1, IBA::TextAlignX::Right, IBA::TextAlignY::Center);
    }

    std::vector<uint8_t> bytes(canvas.size());
    for (std::size_t k = 0; k < bytes.size(); ++k) bytes[k] = uint8_t(std::lround(Clamp(canvas[k], 0, 1) * 255.0));
    OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    if (!description.empty()) spec.attribute("Description", description);
    detail::StageImage(files, path, "png", spec, OIIO::TypeDesc::UINT8, bytes.data());
    return result;
}

}  // namespace phasor
