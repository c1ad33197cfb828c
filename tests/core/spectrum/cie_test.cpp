// SPDX-License-Identifier: Apache-2.0
// Colorimetry of the spectrum module: the CIE 1931 table, D65, the sRGB matrices, Planck's law and
// the sensor responses.
#include <gtest/gtest.h>

#include <cmath>

#include "core/spectrum/spectrum.h"

namespace phasor {
namespace {

// ∫ f over [lo, hi] [m] by the trapezoid rule with step h [m]; exact for the piecewise-linear
// tables when h divides their 1 nm / 5 nm spacing.
template <typename F>
double Trapezoid(F f, double lo, double hi, double h) {
    const int n = int(std::lround((hi - lo) / h));
    double s = 0.5 * (f(lo) + f(hi));
    for (int i = 1; i < n; ++i) s += f(lo + (hi - lo) * i / n);
    return s * (hi - lo) / n;
}

TEST(Cie1931, TableChecksumsMatchThePublishedTable) {
    // Sums of the 1 nm table (360–830 nm) as published with the CIE data set.
    Vec3 sum;
    for (int nm = 360; nm <= 830; ++nm) sum += CieXyz(nm * 1e-9);
    EXPECT_NEAR(sum.x, 106.865469489595, 1e-9);
    EXPECT_NEAR(sum.y, 106.856917101172, 1e-9);
    EXPECT_NEAR(sum.z, 106.892251278636, 1e-9);
}

TEST(Cie1931, IntegralsOfTheInterpolatedFunctions) {
    // Integrals of the piecewise-linear x̄, ȳ, z̄ [nm]: the sums minus half the end values.
    const double ix =
        Trapezoid([](double l) { return CieXyz(l).x; }, CieLambdaMin, CieLambdaMax, 0.25e-9) * 1e9;
    const double iy =
        Trapezoid([](double l) { return CieXyz(l).y; }, CieLambdaMin, CieLambdaMax, 0.25e-9) * 1e9;
    const double iz =
        Trapezoid([](double l) { return CieXyz(l).z; }, CieLambdaMin, CieLambdaMax, 0.25e-9) * 1e9;
    std::printf("  ∫x̄ = %.7f nm, ∫ȳ = %.7f nm, ∫z̄ = %.7f nm\n", ix, iy, iz);
    EXPECT_NEAR(ix, 106.8654694896 - 0.5 * (0.0001299 + 1.251141e-6), 1e-7);
    EXPECT_NEAR(iy, 106.8569171012 - 0.5 * (3.917e-6 + 4.5181e-7), 1e-7);
    EXPECT_NEAR(iz, 106.8922512786 - 0.5 * 0.0006061, 1e-7);
    EXPECT_NEAR(CieYIntegral(), iy * 1e-9, 1e-16);
}

TEST(Cie1931, PointValuesAndRange) {
    EXPECT_DOUBLE_EQ(CieXyz(555e-9).y, 1.0);                             // ȳ peaks at 1 at 555 nm
    EXPECT_DOUBLE_EQ(CieXyz(600e-9).x, 1.0622);                          // tabulated value
    EXPECT_NEAR(CieXyz(600.5e-9).x, 0.5 * (1.0622 + 1.0607352), 1e-12);  // linear interpolation
    EXPECT_EQ(CieXyz(359.9e-9), Vec3());
    EXPECT_EQ(CieXyz(830.1e-9), Vec3());
    EXPECT_EQ(CieXyz(1e-6), Vec3());
    EXPECT_GT(CieXyz(830e-9).x, 0.0);
}

TEST(CieD65, TableValues) {
    EXPECT_DOUBLE_EQ(CieD65(560e-9), 100.0);
    EXPECT_DOUBLE_EQ(CieD65(460e-9), 117.812);
    EXPECT_NEAR(CieD65(562.5e-9), 0.5 * (100.0 + 98.1671), 1e-12);
    EXPECT_DOUBLE_EQ(CieD65(830e-9), 60.3125);
    EXPECT_EQ(CieD65(299e-9), 0.0);
    EXPECT_EQ(CieD65(831e-9), 0.0);
}

TEST(Srgb, MatricesMatchRec709D65) {
    // XYZ → linear sRGB derived exactly from the Rec. 709 primaries and the D65 white
    // (0.3127, 0.3290) (SMPTE RP 177 procedure); IEC 61966-2-1 prints this matrix rounded to 4
    // digits (3.2406, −1.5372, −0.4986 / −0.9689, 1.8758, 0.0415 / 0.0557, −0.2040, 1.0570).
    const Vec3 c0 = XyzToLinearSrgb({1, 0, 0}), c1 = XyzToLinearSrgb({0, 1, 0}),
               c2 = XyzToLinearSrgb({0, 0, 1});
    EXPECT_NEAR(c0.x, 3.2409699, 1e-6);
    EXPECT_NEAR(c1.x, -1.5373832, 1e-6);
    EXPECT_NEAR(c2.x, -0.4986108, 1e-6);
    EXPECT_NEAR(c0.y, -0.9692436, 1e-6);
    EXPECT_NEAR(c1.y, 1.8759675, 1e-6);
    EXPECT_NEAR(c2.y, 0.0415551, 1e-6);
    EXPECT_NEAR(c0.z, 0.0556301, 1e-6);
    EXPECT_NEAR(c1.z, -0.2039770, 1e-6);
    EXPECT_NEAR(c2.z, 1.0569715, 1e-6);
    // The forward matrix's middle row is the luminance of the primaries (0.2126, 0.7152, 0.0722).
    EXPECT_NEAR(LinearSrgbToXyz({1, 0, 0}).y, 0.2126, 1e-4);
    EXPECT_NEAR(LinearSrgbToXyz({0, 1, 0}).y, 0.7152, 1e-4);
    EXPECT_NEAR(LinearSrgbToXyz({0, 0, 1}).y, 0.0722, 1e-4);
    // White (1, 1, 1) is D65 with Y = 1, and the two matrices are inverses.
    const Vec3 w = LinearSrgbToXyz({1, 1, 1});
    EXPECT_NEAR(w.x / (w.x + w.y + w.z), 0.3127, 1e-12);
    EXPECT_NEAR(w.y / (w.x + w.y + w.z), 0.3290, 1e-12);
    EXPECT_NEAR(w.y, 1.0, 1e-12);
    const Vec3 v(0.3, -0.2, 1.7), r = LinearSrgbToXyz(XyzToLinearSrgb(v));
    EXPECT_NEAR(r.x, v.x, 1e-12);
    EXPECT_NEAR(r.y, v.y, 1e-12);
    EXPECT_NEAR(r.z, v.z, 1e-12);
}

TEST(CieD65, IsTheSrgbWhite) {
    // XYZ of D65 through the 1931 observer, normalised to Y = 1, maps to linear sRGB (1, 1, 1).
    Vec3 xyz;
    const double h = 0.1e-9;
    for (double l = CieLambdaMin; l <= CieLambdaMax + 1e-15; l += h) {
        const double w = (l == CieLambdaMin || l + h > CieLambdaMax + 1e-15) ? 0.5 : 1.0;
        xyz += CieXyz(l) * (w * CieD65(l) * h);
    }
    xyz = xyz / xyz.y;
    const Vec3 rgb = XyzToLinearSrgb(xyz);
    const double residual = std::max({std::abs(rgb.x - 1), std::abs(rgb.y - 1), std::abs(rgb.z - 1)});
    std::printf("  D65 → linear sRGB = (%.6f, %.6f, %.6f), max residual %.2e\n", rgb.x, rgb.y, rgb.z,
                residual);
    EXPECT_LT(residual, 1e-3);
}

TEST(Blackbody, PeakObeysWiensLaw) {
    const double b = 2.897771955e-3;  // Wien's displacement constant [m·K] (CODATA 2018)
    for (double T : {300.0, 1000.0, 2856.0, 5800.0, 6504.0, 20000.0}) {
        // Golden-section search for the maximum on [0.5, 2]·b/T.
        double lo = 0.5 * b / T, hi = 2 * b / T;
        const double g = 0.5 * (std::sqrt(5.0) - 1);
        for (int it = 0; it < 200 && hi - lo > 1e-13 * hi; ++it) {
            const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
            if (Blackbody(m1, T) < Blackbody(m2, T))
                lo = m1;
            else
                hi = m2;
        }
        const double lambdaMax = 0.5 * (lo + hi);
        EXPECT_NEAR(lambdaMax * T / b, 1.0, 1e-4) << "T = " << T;
    }
}

TEST(Blackbody, StefanBoltzmann) {
    // π ∫ B(λ, T) dλ = σ T⁴ (radiant exitance of a black body); σ = 5.670374419e-8 W/(m²K⁴).
    const double sigma = 5.670374419e-8;
    for (double T : {300.0, 5800.0}) {
        const double lMax = 2.897771955e-3 / T;
        // Integrate in u = ln λ over [λ_max/20, 400 λ_max]: ∫ B λ du, Simpson with 20000 steps.
        const double u0 = std::log(lMax / 20), u1 = std::log(lMax * 400);
        const int n = 20000;
        const double h = (u1 - u0) / n;
        double s = 0;
        for (int i = 0; i <= n; ++i) {
            const double l = std::exp(u0 + i * h);
            const double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
            s += w * Blackbody(l, T) * l;
        }
        const double exitance = Pi * s * h / 3;
        EXPECT_NEAR(exitance / (sigma * T * T * T * T), 1.0, 1e-5) << "T = " << T;
    }
    EXPECT_EQ(Blackbody(500e-9, 0), 0.0);
    EXPECT_EQ(Blackbody(0, 5800), 0.0);
    EXPECT_EQ(Blackbody(1e-9, 300), 0.0);  // deep Wien tail underflows cleanly
}

TEST(SensorResponse, FlatSpectrumReadsOne) {
    const SensorResponse cie(SensorResponse::Kind::CieXyz), rad(SensorResponse::Kind::Radiometric);
    const double iy =
        Trapezoid([&](double l) { return cie.Channels(l).y; }, CieLambdaMin, CieLambdaMax, 0.5e-9);
    const double ii =
        Trapezoid([&](double l) { return cie.Intensity(l); }, CieLambdaMin, CieLambdaMax, 0.5e-9);
    EXPECT_NEAR(iy, 1.0, 1e-12);
    EXPECT_NEAR(ii, 1.0, 1e-12);
    EXPECT_EQ(rad.Channels(1e-6), Vec3(1, 1, 1));
    EXPECT_EQ(rad.Intensity(1e-6), 1.0);
    EXPECT_EQ(rad.Importance(1e-6), 1.0);
    EXPECT_EQ(cie.Importance(1e-6), 0.0);
    EXPECT_GT(cie.Importance(360e-9), 0.0);
    EXPECT_GT(cie.Importance(830e-9), 0.0);
    EXPECT_EQ(cie.Name(), "cie_xyz");
    EXPECT_EQ(rad.Name(), "radiometric");
}

}  // namespace
}  // namespace phasor
