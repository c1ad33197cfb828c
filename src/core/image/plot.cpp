// SPDX-License-Identifier: Apache-2.0
// phasor — the line-plot rasteriser of plot.h. Everything is drawn into a float sRGB canvas:
// strokes are anti-aliased by exact pixel-centre distance to each segment (coverage =
// clamp(w/2 + 1/2 − d, 0, 1), a one-pixel linear ramp), accumulated per series as the maximum
// coverage so that joints and overlapping segments of one series are not darkened twice; text
// goes through OpenImageIO's FreeType renderer; the result is quantised to 8 bits and written
// through the atomic writer of image_io.cpp.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "core/diagnostics.h"
#include "core/image/oiio_write.h"
#include "core/image/plot.h"

namespace phasor {
namespace {

// Margins around the plot rectangle (pixels): room for tick labels, axis labels and the title.
// Fixed, so that the layout does not depend on whether a font is available.
constexpr int kMarginLeft = 100, kMarginRight = 30, kMarginTop = 60, kMarginBottom = 70;
constexpr int kTickLength = 6;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kFontSize = 15, kTitleFontSize = 18;

const Vec3 kBlack{0, 0, 0}, kGrid{0.88, 0.88, 0.88}, kLegendBorder{0.6, 0.6, 0.6};

// "Nice numbers for graph labels" (Heckbert, Graphics Gems, 1990): the number 1, 2, 5 or 10 times
// a power of ten closest to (round) or not below (!round) x > 0.
double NiceNumber(double x, bool round) {
    const double e = std::floor(std::log10(x));
    const double f = x / std::pow(10.0, e);
    double nf;
    if (round)
        nf = f < 1.5 ? 1 : f < 3 ? 2 : f < 7 ? 5 : 10;
    else
        nf = f <= 1 ? 1 : f <= 2 ? 2 : f <= 5 ? 5 : 10;
    return nf * std::pow(10.0, e);
}

// Tick values at multiples of a nice step inside [lo, hi] (about `count` of them).
std::vector<double> NiceTicks(double lo, double hi, int count, double &step) {
    step = NiceNumber((hi - lo) / (count - 1), true);
    std::vector<double> ticks;
    const double first = std::ceil(lo / step - 1e-9), last = std::floor(hi / step + 1e-9);
    for (double k = first; k <= last; ++k) {
        double v = k * step;
        if (std::abs(v) < 1e-9 * step) v = 0;  // no "-0" or 1e-17 labels
        ticks.push_back(v);
    }
    return ticks;
}

// A tick label with as many digits as the step needs: fixed notation when the axis' largest
// magnitude `maxAbs` is moderate, otherwise scientific with a compact exponent ("1.5e-3").
std::string FormatTick(double v, double step, double maxAbs) {
    const int stepExp = int(std::floor(std::log10(step) + 1e-9));
    char buf[64];
    if (v == 0) return "0";
    if (maxAbs >= 1e5 || maxAbs < 1e-3) {
        const int magExp = int(std::floor(std::log10(std::abs(v)) + 1e-9));
        std::snprintf(buf, sizeof buf, "%.*e", std::max(0, magExp - stepExp), v);
        std::string s(buf);
        // "1.50e-03" → "1.50e-3", "2e+07" → "2e7"
        auto e = s.find('e');
        std::string mant = s.substr(0, e), ex = s.substr(e + 1);
        bool neg = ex[0] == '-';
        ex = ex.substr(1);
        while (ex.size() > 1 && ex[0] == '0') ex.erase(0, 1);
        return mant + "e" + (neg ? "-" : "") + ex;
    }
    std::snprintf(buf, sizeof buf, "%.*f", std::max(0, -stepExp), v);
    return buf;
}

struct Canvas {
    int w, h;
    std::vector<float> rgb;  // display-referred sRGB, packed
    Canvas(int w_, int h_) : w(w_), h(h_), rgb(std::size_t(w_) * h_ * 3, 1.0f) {}
    void Blend(int i, int j, const Vec3 &c, double a) {
        float *p = &rgb[(std::size_t(j) * w + i) * 3];
        for (int k = 0; k < 3; ++k) p[k] = float((1 - a) * p[k] + a * c[k]);
    }
};

struct ClipRect {
    int i0, j0, i1, j1;  // pixels [i0, i1) × [j0, j1)
};

// A dash pattern along the stroke, in pixels of arc length: `on` drawn, then off up to `period`.
struct Dash {
    double on = 0, period = 0;
};

// Adds the coverage of the segment a→b (width 2·halfWidth, round caps) to `cov` (max-combined),
// for pixels inside `clip`. `s0` is the arc length at a, for the dash pattern (period 0: solid).
void StrokeSegment(std::vector<float> &cov, int w, const ClipRect &clip, double ax, double ay, double bx,
                   double by, double halfWidth, const Dash &dash, double s0) {
    const double reach = halfWidth + 1;
    const int i0 = std::max(clip.i0, int(std::floor(std::min(ax, bx) - reach)));
    const int i1 = std::min(clip.i1, int(std::ceil(std::max(ax, bx) + reach)));
    const int j0 = std::max(clip.j0, int(std::floor(std::min(ay, by) - reach)));
    const int j1 = std::min(clip.j1, int(std::ceil(std::max(ay, by) + reach)));
    const double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy, len = std::sqrt(len2);
    for (int j = j0; j < j1; ++j)
        for (int i = i0; i < i1; ++i) {
            const double px = i + 0.5, py = j + 0.5;
            const double t = len2 > 0 ? Clamp(((px - ax) * dx + (py - ay) * dy) / len2, 0, 1) : 0;
            const double ex = px - (ax + t * dx), ey = py - (ay + t * dy);
            double c = Clamp(halfWidth + 0.5 - std::sqrt(ex * ex + ey * ey), 0, 1);
            if (c > 0 && dash.period > 0) {
                // Distance along the stroke to the nearest dash boundary (negative inside a dash),
                // with the same one-pixel ramp as across the stroke.
                const double phase = std::fmod(s0 + t * len, dash.period);
                const double along = phase < dash.on ? -std::min(phase, dash.on - phase)
                                                     : std::min(phase - dash.on, dash.period - phase);
                c *= Clamp(0.5 - along, 0, 1);
            }
            float &dst = cov[std::size_t(j) * w + i];
            dst = std::max(dst, float(c));
        }
}

void Composite(Canvas &cv, const std::vector<float> &cov, const Vec3 &rgb) {
    for (int j = 0; j < cv.h; ++j)
        for (int i = 0; i < cv.w; ++i) {
            const float a = cov[std::size_t(j) * cv.w + i];
            if (a > 0) cv.Blend(i, j, rgb, a);
        }
}

Dash DashFor(PlotSeries::Style style, double width) {
    switch (style) {
        case PlotSeries::Dashed:
            return {4.5 * width + 2, 7.0 * width + 4};
        case PlotSeries::Dotted:
            return {0.6 * width, 2.6 * width + 1};
        default:
            return {};
    }
}

// Strokes a polyline given in pixel coordinates; non-finite points break it.
void StrokePolyline(Canvas &cv, const ClipRect &clip, const std::vector<double> &px,
                    const std::vector<double> &py, const Vec3 &rgb, double width, PlotSeries::Style style) {
    std::vector<float> cov(std::size_t(cv.w) * cv.h, 0.0f);
    const Dash dash = DashFor(style, width);
    double s = 0;
    bool havePrev = false;
    for (std::size_t k = 0; k < px.size(); ++k) {
        if (!std::isfinite(px[k]) || !std::isfinite(py[k])) {
            havePrev = false;
            continue;
        }
        const bool nextFinite = k + 1 < px.size() && std::isfinite(px[k + 1]) && std::isfinite(py[k + 1]);
        if (havePrev) {
            StrokeSegment(cov, cv.w, clip, px[k - 1], py[k - 1], px[k], py[k], width / 2, dash, s);
            s += std::hypot(px[k] - px[k - 1], py[k] - py[k - 1]);
        } else if (!nextFinite) {
            StrokeSegment(cov, cv.w, clip, px[k], py[k], px[k], py[k], width / 2, {}, 0);  // lone point
        }
        havePrev = true;
    }
    Composite(cv, cov, rgb);
}

void StrokeLine(Canvas &cv, const ClipRect &clip, double ax, double ay, double bx, double by, const Vec3 &rgb,
                double width, PlotSeries::Style style = PlotSeries::Solid) {
    StrokePolyline(cv, clip, {ax, bx}, {ay, by}, rgb, width, style);
}

void FillRect(Canvas &cv, int i0, int j0, int i1, int j1, const Vec3 &rgb, double alpha) {
    for (int j = std::max(0, j0); j < std::min(cv.h, j1); ++j)
        for (int i = std::max(0, i0); i < std::min(cv.w, i1); ++i) cv.Blend(i, j, rgb, alpha);
}

Vec3 SafeColour(const Vec3 &c) {
    auto f = [](double v) { return std::isfinite(v) ? Clamp(v, 0, 1) : 0.0; };
    return {f(c.x), f(c.y), f(c.z)};
}

// Text through OpenImageIO (FreeType), drawn into the canvas buffer in place.
class TextPainter {
  public:
    TextPainter(Canvas &cv, const std::string &font) : font_(font) {
        OIIO::ImageSpec spec(cv.w, cv.h, 3, OIIO::TypeDesc::FLOAT);
        buf_ = std::make_unique<OIIO::ImageBuf>(spec, cv.rgb.data());
        OIIO::ROI probe = OIIO::ImageBufAlgo::text_size("0", kFontSize, font_);
        OIIO::geterror();  // drop any message left by the failed font look-up
        if (!probe.defined())
            problem_ = "OpenImageIO found no font '" + font_ +
                       "' (install the Debian package fonts-dejavu-core, or set $OPENIMAGEIO_FONTS)";
    }
    bool Ok() const { return problem_.empty(); }
    const std::string &Problem() const { return problem_; }
    int Width(const std::string &text, int size) const {
        if (!Ok() || text.empty()) return 0;
        OIIO::ROI r = OIIO::ImageBufAlgo::text_size(text, size, font_);
        return r.defined() ? r.xend - std::min(0, r.xbegin) : 0;
    }
    void Draw(int x, int y, const std::string &text, int size, const Vec3 &rgb,
              OIIO::ImageBufAlgo::TextAlignX ax, OIIO::ImageBufAlgo::TextAlignY ay) {
        if (!Ok() || text.empty()) return;
        const float colour[3] = {float(rgb.x), float(rgb.y), float(rgb.z)};
        if (!OIIO::ImageBufAlgo::render_text(*buf_, x, y, text, size, font_, colour, ax, ay, 0, {}, 1)) {
            problem_ = "OpenImageIO could not render text with font '" + font_ + "': " + buf_->geterror();
        }
    }

  private:
    std::string font_, problem_;
    std::unique_ptr<OIIO::ImageBuf> buf_;
};

struct LegendEntry {
    std::string label;
    Vec3 rgb;
    bool bar;
    PlotSeries::Style style;
    double width;
};

}  // namespace

PlotLayout ComputePlotLayout(const std::vector<PlotSeries> &series, const PlotOptions &opt) {
    if (opt.width < 320 || opt.width > 16384 || opt.height < 200 || opt.height > 16384)
        throw Error("the plot size must be within 320..16384 × 200..16384 pixels, got " +
                    std::to_string(opt.width) + "×" + std::to_string(opt.height));
    if (series.empty()) throw Error("nothing to plot: no data series");
    double xMin = Infinity, xMax = -Infinity, yMin = Infinity, yMax = -Infinity;
    for (const PlotSeries &s : series) {
        if (s.x.size() != s.y.size())
            throw Error("series '" + s.label + "' has " + std::to_string(s.x.size()) + " x values but " +
                        std::to_string(s.y.size()) + " y values");
        if (!(s.lineWidth > 0 && s.lineWidth <= 50))
            throw Error("series '" + s.label + "' has line width " + std::to_string(s.lineWidth) +
                        " (must be in (0, 50] pixels)");
        for (std::size_t k = 0; k < s.x.size(); ++k)
            if (std::isfinite(s.x[k]) && std::isfinite(s.y[k])) {
                xMin = std::min(xMin, s.x[k]);
                xMax = std::max(xMax, s.x[k]);
                yMin = std::min(yMin, s.y[k]);
                yMax = std::max(yMax, s.y[k]);
            }
    }
    if (!(xMin <= xMax)) throw Error("nothing to plot: no series has a finite point");
    for (const PlotBar &b : opt.bars) {
        if (!std::isfinite(b.x0) || !std::isfinite(b.x1) || !std::isfinite(b.y) ||
            !(b.thickness > 0 && b.thickness <= 50))
            throw Error("bar '" + b.label + "' has a non-finite position or a bad thickness");
        xMin = std::min({xMin, b.x0, b.x1});
        xMax = std::max({xMax, b.x0, b.x1});
        yMin = std::min(yMin, b.y);
        yMax = std::max(yMax, b.y);
    }
    if (opt.yIncludesZero) {
        yMin = std::min(yMin, 0.0);
        yMax = std::max(yMax, 0.0);
    }
    auto padDegenerate = [](double &lo, double &hi) {
        if (lo < hi) return;
        const double pad = lo == 0 ? 0.5 : 0.05 * std::abs(lo);
        lo -= pad;
        hi += pad;
    };
    padDegenerate(xMin, xMax);
    if (std::isfinite(opt.xMin) || std::isfinite(opt.xMax)) {
        if (!(std::isfinite(opt.xMin) && std::isfinite(opt.xMax) && opt.xMin < opt.xMax))
            throw Error("the x range must be two finite numbers, the first below the second");
        xMin = opt.xMin;
        xMax = opt.xMax;
    }
    if (yMin < yMax) {
        // Headroom so that peaks (and strokes of full width) stay inside the frame.
        const double span = yMax - yMin;
        yMax += 0.05 * span;
        if (!(opt.yIncludesZero && yMin == 0)) yMin -= 0.05 * span;
    }
    padDegenerate(yMin, yMax);

    PlotLayout L;
    L.left = kMarginLeft;
    L.right = opt.width - kMarginRight;
    L.top = kMarginTop;
    L.bottom = opt.height - kMarginBottom;
    L.xMin = xMin;
    L.xMax = xMax;
    L.yMin = yMin;
    L.yMax = yMax;
    double step;
    L.xTicks = NiceTicks(xMin, xMax, std::clamp((L.right - L.left) / 110, 3, 11), step);
    L.yTicks = NiceTicks(yMin, yMax, std::clamp((L.bottom - L.top) / 70, 3, 11), step);
    return L;
}

PlotResult WritePlotPng(OutputFiles &files, const std::string &path, const std::vector<PlotSeries> &series,
                        const PlotOptions &opt) {
    namespace IBA = OIIO::ImageBufAlgo;
    PlotLayout L;
    try {
        L = ComputePlotLayout(series, opt);
    } catch (const Error &e) {
        throw Error(FileLoc{path}, "cannot write '" + path + "': " + e.Message());
    }
    Canvas cv(opt.width, opt.height);
    const ClipRect all{0, 0, cv.w, cv.h};
    const ClipRect inside{L.left, L.top, L.right, L.bottom};

    // Grid lines, snapped to pixel centres so that they stay crisp.
    for (double t : L.xTicks) {
        const double x = std::floor(L.PixelX(t)) + 0.5;
        StrokeLine(cv, inside, x, L.top, x, L.bottom, kGrid, 1);
    }
    for (double t : L.yTicks) {
        const double y = std::floor(L.PixelY(t)) + 0.5;
        StrokeLine(cv, inside, L.left, y, L.right, y, kGrid, 1);
    }

    // Data: series in order (later ones on top), then bars.
    std::vector<std::vector<double>> seriesPx(series.size()), seriesPy(series.size());
    for (std::size_t s = 0; s < series.size(); ++s) {
        for (std::size_t k = 0; k < series[s].x.size(); ++k) {
            const bool ok = std::isfinite(series[s].x[k]) && std::isfinite(series[s].y[k]);
            seriesPx[s].push_back(ok ? L.PixelX(series[s].x[k]) : kNaN);
            seriesPy[s].push_back(ok ? L.PixelY(series[s].y[k]) : kNaN);
        }
        StrokePolyline(cv, inside, seriesPx[s], seriesPy[s], SafeColour(series[s].rgb), series[s].lineWidth,
                       series[s].style);
    }
    for (const PlotBar &b : opt.bars) {
        const double y = L.PixelY(b.y);
        // Butt ends exactly at x0 and x1: a filled rectangle with anti-aliased left/right edges.
        const double xa = L.PixelX(std::min(b.x0, b.x1)), xb = L.PixelX(std::max(b.x0, b.x1));
        const int j0 = int(std::lround(y - b.thickness / 2)),
                  j1 = j0 + std::max(1, int(std::lround(b.thickness)));
        for (int i = std::max(L.left, int(std::floor(xa))); i < std::min(L.right, int(std::ceil(xb)) + 1);
             ++i) {
            const double a = Clamp(std::min(i + 1.0, xb) - std::max(double(i), xa), 0, 1);
            for (int j = std::max(L.top, j0); j < std::min(L.bottom, j1); ++j)
                cv.Blend(i, j, SafeColour(b.rgb), a);
        }
    }

    // Frame (2 px, centred on the rectangle's edges) and outward ticks.
    StrokeLine(cv, all, L.left, L.top, L.right, L.top, kBlack, 2);
    StrokeLine(cv, all, L.left, L.bottom, L.right, L.bottom, kBlack, 2);
    StrokeLine(cv, all, L.left, L.top, L.left, L.bottom, kBlack, 2);
    StrokeLine(cv, all, L.right, L.top, L.right, L.bottom, kBlack, 2);
    for (double t : L.xTicks) {
        const double x = L.PixelX(t);
        StrokeLine(cv, all, x, L.bottom, x, L.bottom + kTickLength, kBlack, 2);
    }
    for (double t : L.yTicks) {
        const double y = L.PixelY(t);
        StrokeLine(cv, all, L.left - kTickLength, y, L.left, y, kBlack, 2);
    }

    TextPainter text(cv, opt.font);
    if (text.Ok()) {
        auto maxAbs = [](const std::vector<double> &v) {
            double m = 0;
            for (double t : v) m = std::max(m, std::abs(t));
            return m;
        };
        const double xStep = L.xTicks.size() > 1 ? L.xTicks[1] - L.xTicks[0] : 1;
        const double yStep = L.yTicks.size() > 1 ? L.yTicks[1] - L.yTicks[0] : 1;
        const double xMaxAbs = maxAbs(L.xTicks), yMaxAbs = maxAbs(L.yTicks);
        for (double t : L.xTicks)
            text.Draw(int(std::lround(L.PixelX(t))), L.bottom + kTickLength + 4,
                      FormatTick(t, xStep, xMaxAbs > 0 ? xMaxAbs : 1), kFontSize, kBlack,
                      IBA::TextAlignX::Center, IBA::TextAlignY::Top);
        for (double t : L.yTicks)
            text.Draw(L.left - kTickLength - 5, int(std::lround(L.PixelY(t))),
                      FormatTick(t, yStep, yMaxAbs > 0 ? yMaxAbs : 1), kFontSize, kBlack,
                      IBA::TextAlignX::Right, IBA::TextAlignY::Center);
        text.Draw((L.left + L.right) / 2, opt.height - 18, opt.xLabel, kFontSize + 1, kBlack,
                  IBA::TextAlignX::Center, IBA::TextAlignY::Bottom);
        text.Draw(L.left, L.top - 10, opt.yLabel, kFontSize + 1, kBlack, IBA::TextAlignX::Left,
                  IBA::TextAlignY::Bottom);
        text.Draw(opt.width / 2, 22, opt.title, kTitleFontSize, kBlack, IBA::TextAlignX::Center,
                  IBA::TextAlignY::Center);

        // Legend, in the corner of the plot rectangle that hides the fewest data points.
        std::vector<LegendEntry> entries;
        for (const PlotSeries &s : series)
            if (!s.label.empty())
                entries.push_back({s.label, SafeColour(s.rgb), false, s.style, s.lineWidth});
        for (const PlotBar &b : opt.bars)
            if (!b.label.empty())
                entries.push_back({b.label, SafeColour(b.rgb), true, PlotSeries::Solid, b.thickness});
        if (!entries.empty()) {
            constexpr int pad = 10, sample = 44, gap = 8, lineHeight = 22;
            int textWidth = 0;
            for (const LegendEntry &e : entries)
                textWidth = std::max(textWidth, text.Width(e.label, kFontSize));
            const int bw = pad + sample + gap + textWidth + pad,
                      bh = 2 * pad + int(entries.size()) * lineHeight - 6;
            const int xs[2] = {L.right - 10 - bw, L.left + 10}, ys[2] = {L.top + 10, L.bottom - 10 - bh};
            int bestX = xs[0], bestY = ys[0];
            // Points along every stroke, about 2 px apart, to count what a legend box would hide.
            std::vector<std::pair<double, double>> ink;
            for (std::size_t s = 0; s < series.size(); ++s)
                for (std::size_t k = 0; k < seriesPx[s].size(); ++k) {
                    const double x1 = seriesPx[s][k], y1 = seriesPy[s][k];
                    if (!std::isfinite(x1)) continue;
                    ink.emplace_back(x1, y1);
                    if (k == 0 || !std::isfinite(seriesPx[s][k - 1])) continue;
                    const double x0 = seriesPx[s][k - 1], y0 = seriesPy[s][k - 1];
                    const int n = std::min(4096, int(std::hypot(x1 - x0, y1 - y0) / 2));
                    for (int m = 1; m < n; ++m)
                        ink.emplace_back(Lerp(double(m) / n, x0, x1), Lerp(double(m) / n, y0, y1));
                }
            for (const PlotBar &b : opt.bars)
                for (double t = 0; t <= 1; t += 1.0 / 16)
                    ink.emplace_back(L.PixelX(Lerp(t, b.x0, b.x1)), L.PixelY(b.y));
            long bestCount = -1;
            for (int yi = 0; yi < 2; ++yi)
                for (int xi = 0; xi < 2; ++xi) {
                    long count = 0;
                    for (const auto &[x, y] : ink)
                        count += x >= xs[xi] && x <= xs[xi] + bw && y >= ys[yi] && y <= ys[yi] + bh;
                    if (bestCount < 0 || count < bestCount) {
                        bestCount = count;
                        bestX = xs[xi];
                        bestY = ys[yi];
                    }
                }
            FillRect(cv, bestX, bestY, bestX + bw, bestY + bh, Vec3(1, 1, 1), 0.9);
            const double x0 = bestX + 0.5, y0 = bestY + 0.5, x1 = bestX + bw - 0.5, y1 = bestY + bh - 0.5;
            StrokeLine(cv, all, x0, y0, x1, y0, kLegendBorder, 1);
            StrokeLine(cv, all, x0, y1, x1, y1, kLegendBorder, 1);
            StrokeLine(cv, all, x0, y0, x0, y1, kLegendBorder, 1);
            StrokeLine(cv, all, x1, y0, x1, y1, kLegendBorder, 1);
            for (std::size_t k = 0; k < entries.size(); ++k) {
                const LegendEntry &e = entries[k];
                const int yc = bestY + pad + int(k) * lineHeight + 8;
                if (e.bar)
                    FillRect(cv, bestX + pad, yc - int(e.width / 2), bestX + pad + sample,
                             yc - int(e.width / 2) + std::max(1, int(std::lround(e.width))), e.rgb, 1);
                else
                    StrokeLine(cv, all, bestX + pad, yc + 0.5, bestX + pad + sample, yc + 0.5, e.rgb, e.width,
                               e.style);
                text.Draw(bestX + pad + sample + gap, yc, e.label, kFontSize, kBlack, IBA::TextAlignX::Left,
                          IBA::TextAlignY::Center);
            }
        }
    }
    PlotResult result;
    result.textDrawn = text.Ok();
    result.textProblem = text.Problem();

    std::vector<uint8_t> bytes(cv.rgb.size());
    for (std::size_t k = 0; k < bytes.size(); ++k)
        bytes[k] = uint8_t(std::lround(Clamp(cv.rgb[k], 0, 1) * 255.0));
    OIIO::ImageSpec spec(opt.width, opt.height, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    if (!opt.title.empty()) spec.attribute("ImageDescription", opt.title);
    detail::StageImage(files, path, "png", spec, OIIO::TypeDesc::UINT8, bytes.data());
    return result;
}

PlotResult WritePlotPng(const std::string &path, const std::vector<PlotSeries> &series,
                        const PlotOptions &opt) {
    OutputFiles files;
    PlotResult result = WritePlotPng(files, path, series, opt);
    files.Commit();
    return result;
}

PlotResult WriteImageWithColourBarPng(OutputFiles &files, const std::string &path, const std::vector<uint8_t> &rgb,
                                      int w, int h, Vec3 (*barColour)(double t),
                                      const std::vector<ColourBarTick> &ticks, const std::string &barTitle,
                                      const std::string &description, const std::string &font) {
    namespace IBA = OIIO::ImageBufAlgo;
    if (w <= 0 || h <= 0 || rgb.size() != std::size_t(w) * h * 3)
        throw Error(FileLoc{path}, "cannot write '" + path + "': the image is empty or its size is inconsistent");
    // Layout: [image] 20 px [bar 24 px] ticks and labels (90 px); 32 px above for the title.
    const int scale = std::clamp(int(std::ceil(256.0 / h)), 1, std::max(1, 4096 / w));
    const int imgW = w * scale, imgH = h * scale;
    const int barH = std::max(imgH, 160), top = 32, gap = 20, barW = 24, labelW = 90;
    const int barX = imgW + gap;
    Canvas cv(barX + barW + labelW, top + std::max(imgH, barH) + 12);
    for (int j = 0; j < imgH; ++j)
        for (int i = 0; i < imgW; ++i) {
            const uint8_t *src = &rgb[(std::size_t(j / scale) * w + i / scale) * 3];
            float *dst = &cv.rgb[(std::size_t(top + j) * cv.w + i) * 3];
            for (int c = 0; c < 3; ++c) dst[c] = src[c] / 255.0f;
        }
    for (int j = 0; j < barH; ++j) {
        const Vec3 c = SafeColour(barColour(1 - (j + 0.5) / barH));
        for (int i = 0; i < barW; ++i) cv.Blend(barX + i, top + j, c, 1);
    }
    const ClipRect all{0, 0, cv.w, cv.h};
    StrokeLine(cv, all, barX, top, barX + barW, top, kBlack, 1);
    StrokeLine(cv, all, barX, top + barH, barX + barW, top + barH, kBlack, 1);
    StrokeLine(cv, all, barX, top, barX, top + barH, kBlack, 1);
    StrokeLine(cv, all, barX + barW, top, barX + barW, top + barH, kBlack, 1);
    TextPainter text(cv, font);
    for (const ColourBarTick &t : ticks) {
        const double y = top + (1 - Clamp(t.t, 0, 1)) * barH;
        StrokeLine(cv, all, barX + barW, y, barX + barW + kTickLength, y, kBlack, 1.5);
        text.Draw(barX + barW + kTickLength + 4, int(std::lround(y)), t.text, kFontSize - 2, kBlack,
                  IBA::TextAlignX::Left, IBA::TextAlignY::Center);
    }
    text.Draw(cv.w - 6, top / 2, barTitle, kFontSize - 1, kBlack, IBA::TextAlignX::Right, IBA::TextAlignY::Center);
    std::vector<uint8_t> bytes(cv.rgb.size());
    for (std::size_t k = 0; k < bytes.size(); ++k) bytes[k] = uint8_t(std::lround(Clamp(cv.rgb[k], 0, 1) * 255.0));
    OIIO::ImageSpec spec(cv.w, cv.h, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    if (!description.empty()) spec.attribute("Description", description);
    detail::StageImage(files, path, "png", spec, OIIO::TypeDesc::UINT8, bytes.data());
    return PlotResult{text.Ok(), text.Problem()};
}

}  // namespace phasor
