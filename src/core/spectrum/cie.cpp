// SPDX-License-Identifier: Apache-2.0
// phasor — CIE 1931 colour-matching functions, illuminant D65 and the XYZ ↔ linear sRGB
// matrices (spectrum.h). The tables are in cie_tables.cpp.
#include <algorithm>
#include <array>
#include <cmath>

#include "core/spectrum/spectrum.h"
#include "core/diagnostics.h"
#include "core/spectrum/cie_tables.h"

namespace phasor {

namespace {

using Mat3 = std::array<std::array<double, 3>, 3>;

Vec3 Mul(const Mat3 &m, const Vec3 &v) {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

Mat3 Inverse(const Mat3 &m) {
    // Adjugate / determinant.
    Mat3 r;
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const int a = (j + 1) % 3, b = (j + 2) % 3, c = (i + 1) % 3, d = (i + 2) % 3;
            r[i][j] = (m[a][c] * m[b][d] - m[a][d] * m[b][c]) / det;
        }
    return r;
}

// RGB → XYZ for the Rec. ITU-R BT.709 / sRGB (IEC 61966-2-1) primaries R (0.64, 0.33),
// G (0.30, 0.60), B (0.15, 0.06) and white D65 (0.3127, 0.3290) with Y_white = 1, derived the
// standard way (SMPTE RP 177): columns are the primaries' XYZ scaled so that R = G = B = 1 gives
// the white point.
Mat3 SrgbToXyzMatrix() {
    const double xy[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
    const double wx = 0.3127, wy = 0.3290;
    Mat3 p;
    for (int c = 0; c < 3; ++c) {
        p[0][c] = xy[c][0] / xy[c][1];
        p[1][c] = 1;
        p[2][c] = (1 - xy[c][0] - xy[c][1]) / xy[c][1];
    }
    const Vec3 white(wx / wy, 1, (1 - wx - wy) / wy);
    const Vec3 s = Mul(Inverse(p), white);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) p[r][c] *= s[c];
    return p;
}

const Mat3 &RgbToXyz() {
    static const Mat3 m = SrgbToXyzMatrix();
    return m;
}
const Mat3 &XyzToRgb() {
    static const Mat3 m = Inverse(RgbToXyz());
    return m;
}

// Linear interpolation in a uniformly spaced table starting at `firstNm` with `stepNm` spacing;
// 0 outside the table.
double Interp(const double *table, int size, double firstNm, double stepNm, double lambda) {
    double t = (lambda * 1e9 - firstNm) / stepNm;
    if (!(t >= -1e-9) || t > size - 1 + 1e-9) return 0;  // slack for the end points' round-off
    t = std::clamp(t, 0.0, double(size - 1));
    const int i = std::min(int(t), size - 2);
    const double f = t - i;
    return (1 - f) * table[i] + f * table[i + 1];
}

}  // namespace

Vec3 CieXyz(double lambda) {
    using namespace detail;
    // Table index (1 nm steps); a relative slack of 1e-12 keeps the end points (360e-9 · 1e9 is
    // not exactly 360 in floating point).
    double t = lambda * 1e9 - CieTableFirstNm;
    if (!(t >= -1e-9) || t > CieTableSize - 1 + 1e-9) return {};
    t = std::clamp(t, 0.0, double(CieTableSize - 1));
    const int i = std::min(int(t), CieTableSize - 2);
    const double f = t - i;
    return {(1 - f) * CieXBar1931[i] + f * CieXBar1931[i + 1],
            (1 - f) * CieYBar1931[i] + f * CieYBar1931[i + 1],
            (1 - f) * CieZBar1931[i] + f * CieZBar1931[i + 1]};
}

double CieYIntegral() {
    // Exact integral of the piecewise-linear ȳ (trapezoid rule on the 1 nm table), in metres.
    static const double integral = [] {
        using namespace detail;
        double sum = 0;
        for (int i = 0; i < CieTableSize; ++i) sum += CieYBar1931[i];
        sum -= 0.5 * (CieYBar1931[0] + CieYBar1931[CieTableSize - 1]);
        return sum * 1e-9;
    }();
    return integral;
}

double CieD65(double lambda) {
    using namespace detail;
    return Interp(CieD65Spd, D65TableSize, D65FirstNm, D65StepNm, lambda);
}

Vec3 XyzToLinearSrgb(const Vec3 &xyz) { return Mul(XyzToRgb(), xyz); }
Vec3 LinearSrgbToXyz(const Vec3 &rgb) { return Mul(RgbToXyz(), rgb); }

// ---- SensorResponse -----------------------------------------------------------------------

SensorResponse::Weights SensorResponse::At(double lambda) const {
    if (kind_ == Kind::Radiometric) return {{1, 1, 1}, 1};
    const Vec3 c = CieXyz(lambda) / CieYIntegral();
    return {c, c.y};
}

Vec3 SensorResponse::Channels(double lambda) const { return At(lambda).channels; }

Vec3 SensorResponse::WhiteBalance(const Vec3 &xyz) const {
    if (!balanced_) return xyz;
    const auto &m = adapt_;
    return {m[0] * xyz.x + m[1] * xyz.y + m[2] * xyz.z, m[3] * xyz.x + m[4] * xyz.y + m[5] * xyz.z,
            m[6] * xyz.x + m[7] * xyz.y + m[8] * xyz.z};
}

void SensorResponse::SetWhiteBalance(const Spectrum &illuminant) {
    // The illuminant's white: its XYZ (a line contributes its strength × x̄ȳz̄ at the line).
    Vec3 src;
    if (auto line = illuminant.LineWavelength()) src = CieXyz(*line) * illuminant.Eval(*line);
    else
        for (int nm = 360; nm <= 830; ++nm) src += CieXyz(nm * 1e-9) * illuminant.Eval(nm * 1e-9);
    if (!(src.y > 0) || !(src.x >= 0) || !(src.z >= 0))
        throw Error("the white-balance illuminant has no luminance (it emits nothing within 360–830 nm)");
    src = src / src.y;
    const Vec3 dst(0.3127 / 0.3290, 1, (1 - 0.3127 - 0.3290) / 0.3290);  // D65, the sRGB white
    // Bradford cone response matrix (Lam 1985).
    const Mat3 b = {{{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}}};
    const Vec3 ls = Mul(b, src), ld = Mul(b, dst);
    Mat3 scaled = b;
    for (int c = 0; c < 3; ++c) scaled[0][c] *= ld.x / ls.x, scaled[1][c] *= ld.y / ls.y, scaled[2][c] *= ld.z / ls.z;
    const Mat3 bi = Inverse(b);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            adapt_[3 * r + c] = bi[r][0] * scaled[0][c] + bi[r][1] * scaled[1][c] + bi[r][2] * scaled[2][c];
    balanced_ = true;
}

double SensorResponse::Intensity(double lambda) const { return At(lambda).intensity; }

double SensorResponse::Importance(double lambda) const {
    if (kind_ == Kind::Radiometric) return 1;
    // x̄ + ȳ + z̄: positive wherever any output channel responds (theory §0 D10).
    const Vec3 c = CieXyz(lambda);
    return c.x + c.y + c.z;
}

}  // namespace phasor
