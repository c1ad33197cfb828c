// SPDX-License-Identifier: Apache-2.0
// The film: exact means, the variance of the pixel mean, invalid samples, spectral reduction
// against the sensor response (CIE flat spectrum → Y = 1, radiometric, delta lines).

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/diagnostics.h"
#include "core/image/film.h"
#include "support/stats.h"

namespace phasor {
namespace {

constexpr int R = 0, G = 1, B = 2, I = 3, V = 4;

SampledWavelengths DeltaLine(double lambda, double prob) {
    SampledWavelengths wl;
    wl.delta = true;
    wl.lambda = {lambda, 0, 0, 0};
    wl.pdf = {prob, 0, 0, 0};
    return wl;
}

TEST(Film, ResolvesTheDocumentedChannels) {
    Film film(3, 2, SensorResponse(SensorResponse::Kind::Radiometric));
    Image img = film.Resolve();
    EXPECT_EQ(img.width, 3);
    EXPECT_EQ(img.height, 2);
    EXPECT_EQ(img.channels, (std::vector<std::string>{"R", "G", "B", "intensity", "variance"}));
    EXPECT_EQ(img.data.size(), 3u * 2u * 5u);
    EXPECT_EQ(img.ChannelIndex("variance"), V);
    EXPECT_EQ(img.ChannelIndex("alpha"), -1);
    EXPECT_THROW(Film(0, 4, SensorResponse(SensorResponse::Kind::Radiometric)), Error);
}

// Stokes output: S0..S3 reduced like `intensity` (S0 is the intensity), their means, the degree of
// polarisation of the mean, and an invalid sample (NaN in S2) counted as zeros everywhere.
TEST(Film, StokesChannelsAreMeansOfTheReducedStokesVectors) {
    Film film(2, 1, SensorResponse(SensorResponse::Kind::Radiometric));
    film.EnableStokes();
    ASSERT_TRUE(film.HasStokes());
    const SampledWavelengths wl = DeltaLine(600e-9, 0.5);  // the film divides by pdf 0.5
    auto stokes = [](double s0, double s1, double s2, double s3) {
        return std::array<SampledSpectrum, 4>{SampledSpectrum(s0), SampledSpectrum(s1), SampledSpectrum(s2),
                                              SampledSpectrum(s3)};
    };
    film.AddStokesSample(0, 0, stokes(1, 0.5, 0, 0), wl);
    film.AddStokesSample(0, 0, stokes(1, -0.25, 0.5, 0.25), wl);
    film.AddStokesSample(1, 0, stokes(1, 0.5, std::nan(""), 0), wl);
    film.AddStokesSample(1, 0, stokes(2, 0, 0, 0), wl);
    const Image img = film.Resolve();
    EXPECT_EQ(img.channels, (std::vector<std::string>{"R", "G", "B", "intensity", "variance", "S0", "S1", "S2", "S3",
                                                      "DoP"}));
    auto at = [&](int x, const char *c) { return img.At(x, 0, img.ChannelIndex(c)); };
    EXPECT_FLOAT_EQ(at(0, "S0"), 2);  // (1 + 1)/2 / 0.5
    EXPECT_FLOAT_EQ(at(0, "intensity"), 2);
    EXPECT_FLOAT_EQ(at(0, "S1"), 0.25);
    EXPECT_FLOAT_EQ(at(0, "S2"), 0.5);
    EXPECT_FLOAT_EQ(at(0, "S3"), 0.25);
    EXPECT_FLOAT_EQ(at(0, "DoP"), float(std::sqrt(0.25 * 0.25 + 0.5 * 0.5 + 0.25 * 0.25) / 2));
    // Pixel 1: the NaN sample is invalid (a zero), the other reads (4, 0, 0, 0): mean (2, 0, 0, 0).
    EXPECT_EQ(film.InvalidSampleCount(), 1);
    EXPECT_FLOAT_EQ(at(1, "S0"), 2);
    EXPECT_FLOAT_EQ(at(1, "intensity"), 2);
    EXPECT_FLOAT_EQ(at(1, "S1"), 0);
    EXPECT_FLOAT_EQ(at(1, "DoP"), 0);
}

TEST(Film, ConstantSamplesGiveTheExactMeanAndZeroVariance) {
    Film film(2, 1, SensorResponse(SensorResponse::Kind::Radiometric));
    const double c = 0.3;  // not a dyadic rational: a naive running sum would drift
    for (int i = 0; i < 1000; ++i) {
        film.AddReduced(0, 0, Vec3(c, c, c), c);
        // Radiometric response is flat (weight 1): a certain line of value c reads c.
        film.AddSample(1, 0, SampledSpectrum(c), DeltaLine(1064e-9, 1.0));
    }
    Image img = film.Resolve();
    for (int x = 0; x < 2; ++x) {
        EXPECT_EQ(film.SampleCount(x, 0), 1000);
        for (int ch : {R, G, B, I}) EXPECT_EQ(img.At(x, 0, ch), float(c)) << x << " " << ch;
        EXPECT_EQ(img.At(x, 0, V), 0.0f);
    }
}

TEST(Film, VarianceChannelIsTheVarianceOfTheMean) {
    Film film(2, 1, SensorResponse(SensorResponse::Kind::Radiometric));
    // 1 … 5: mean 3, s² = 2.5, s²/n = 0.5 (all exact in binary).
    for (int k = 1; k <= 5; ++k) film.AddReduced(0, 0, Vec3(k, k, k), k);
    // A random sequence against a two-pass computation in double.
    test::TestRng rng(7);
    std::vector<double> xs(2000);
    for (double &x : xs) {
        x = 1e3 + std::exp(3 * rng.Uniform());  // large offset: stresses cancellation
        film.AddReduced(1, 0, Vec3(x, x, x), x);
    }
    double mean = 0;
    for (double x : xs) mean += x;
    mean /= xs.size();
    double s2 = 0;
    for (double x : xs) s2 += (x - mean) * (x - mean);
    s2 /= xs.size() - 1;

    Image img = film.Resolve();
    EXPECT_EQ(img.At(0, 0, I), 3.0f);
    EXPECT_EQ(img.At(0, 0, V), 0.5f);
    EXPECT_EQ(img.At(1, 0, I), float(mean));
    EXPECT_NEAR(img.At(1, 0, V), s2 / xs.size(), 1e-6 * s2 / xs.size());

    Film single(1, 1, SensorResponse(SensorResponse::Kind::Radiometric));
    single.AddReduced(0, 0, Vec3(1, 1, 1), 1);
    EXPECT_EQ(single.Resolve().At(0, 0, V), 0.0f);  // n < 2
}

// White balance is applied to each pixel's mean, not to samples: the Bradford adaptation has
// negative entries, so a monochromatic sample's adapted XYZ can be negative, and the film would
// have discarded it as invalid (15 samples of the demo, a bias).
TEST(Film, WhiteBalanceKeepsMonochromaticSamples) {
    SensorResponse cie(SensorResponse::Kind::CieXyz);
    cie.SetWhiteBalance(ConstantSpectrum(1.0));  // equal-energy white: a non-trivial adaptation
    double lambda = 0;
    for (int nm = 380; nm <= 780 && lambda == 0; ++nm) {
        const Vec3 a = cie.WhiteBalance(cie.Channels(nm * 1e-9));
        if (a.x < 0 || a.y < 0 || a.z < 0) lambda = nm * 1e-9;
    }
    ASSERT_GT(lambda, 0) << "no wavelength whose adapted XYZ is negative";
    Film film(1, 1, cie);
    film.AddSample(0, 0, SampledSpectrum(1.0), DeltaLine(lambda, 1.0));
    const Image img = film.Resolve();
    EXPECT_EQ(film.InvalidSampleCount(), 0);
    const Vec3 rgb = XyzToLinearSrgb(cie.WhiteBalance(cie.Channels(lambda)));
    EXPECT_NEAR(img.At(0, 0, 0), rgb.x, 1e-6 * std::abs(rgb.x) + 1e-9);
    EXPECT_NEAR(img.At(0, 0, 2), rgb.z, 1e-6 * std::abs(rgb.z) + 1e-9);
}

TEST(Film, InvalidSamplesAreCountedAsZeroAndNeverPropagate) {
    Film film(2, 1, SensorResponse(SensorResponse::Kind::Radiometric));
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) film.AddReduced(0, 0, Vec3(2, 2, 2), 2);
    film.AddSample(0, 0, SampledSpectrum(nan), DeltaLine(500e-9, 1));
    film.AddSample(0, 0, SampledSpectrum(-1), DeltaLine(500e-9, 1));
    film.AddReduced(0, 0, Vec3(1, inf, 1), 1);
    film.AddReduced(0, 0, Vec3(1, 1, 1), nan);
    film.AddInvalidSample(0, 0);
    for (int k = 0; k < 2; ++k) film.AddReduced(1, 0, Vec3(1, 1, 1), 1);

    EXPECT_EQ(film.InvalidSampleCount(), 5);
    EXPECT_EQ(film.SampleCount(0, 0), 8);
    Image img = film.Resolve();
    for (float v : img.data) EXPECT_TRUE(std::isfinite(v));
    // Mean of {2, 2, 2, 0, 0, 0, 0, 0} and s²/n of that sequence.
    EXPECT_FLOAT_EQ(img.At(0, 0, I), 0.75f);
    double s2 = (3 * 1.25 * 1.25 + 5 * 0.75 * 0.75) / 7;
    EXPECT_FLOAT_EQ(img.At(0, 0, V), float(s2 / 8));
    EXPECT_EQ(img.metadata.at("phasor:invalid_samples"), "5");
    EXPECT_EQ(img.metadata.at("phasor:samples_per_pixel"), "2");  // min over pixels
}

// Values the float EXR cannot hold (> 3.4e38) are invalid samples like NaN (issue 10 §2: a 1e300 W
// beam used to give Inf pixels with invalid_samples 0); a pixel whose every sample fits but whose
// variance of the mean does not is written as 0 and all its samples are counted.
TEST(Film, ValuesBeyondFloatAreInvalidAndNeverWritten) {
    Film film(3, 1, SensorResponse(SensorResponse::Kind::Radiometric));
    film.AddReduced(0, 0, Vec3(1, 1, 1), 1e39);         // intensity beyond float
    film.AddReduced(0, 0, Vec3(1e300, 1, 1), 1);        // a channel beyond float
    film.AddSample(0, 0, SampledSpectrum(1e300), DeltaLine(500e-9, 1));
    film.AddReduced(0, 0, Vec3(2, 2, 2), 2);  // fits
    EXPECT_EQ(film.SampleCount(0, 0), 4);
    film.AddReduced(1, 0, Vec3(0, 0, 0), 0);  // spread 1e30: variance of the mean ≈ 2.5e59
    film.AddReduced(1, 0, Vec3(1e30, 1e30, 1e30), 1e30);
    film.AddReduced(2, 0, Vec3(1, 1, 1), 1);
    film.AddReduced(2, 0, Vec3(1, 1, 1), 1);
    EXPECT_EQ(film.InvalidSampleCount(), 3 + 2);
    Image img = film.Resolve();
    for (float v : img.data) EXPECT_TRUE(std::isfinite(v));
    EXPECT_EQ(img.At(0, 0, I), 0.5f);  // {0, 0, 0, 2}
    EXPECT_EQ(img.At(0, 0, V), 0.25f);  // s² = 1, n = 4
    for (int c : {R, G, B, I, V}) EXPECT_EQ(img.At(1, 0, c), 0.0f) << c;
    EXPECT_EQ(img.At(2, 0, I), 1.0f);
    EXPECT_EQ(img.metadata.at("phasor:invalid_samples"), "5");
}

// A render stopped during a pass leaves pixels with different sample counts: each pixel's count is
// in a `samples` channel (absent when all pixels agree), and its mean and variance are its own.
TEST(Film, UnequalSampleCountsAreRecordedPerPixel) {
    Film film(2, 1, SensorResponse(SensorResponse::Kind::Radiometric));
    EXPECT_EQ(film.Resolve().ChannelIndex("samples"), -1);  // all 0
    for (int k = 0; k < 3; ++k) film.AddReduced(0, 0, Vec3(1, 1, 1), 1 + k);
    film.AddReduced(1, 0, Vec3(1, 1, 1), 5);
    Image img = film.Resolve();
    const int n = img.ChannelIndex("samples");
    ASSERT_EQ(n, 5);
    EXPECT_EQ(img.At(0, 0, n), 3.0f);
    EXPECT_EQ(img.At(1, 0, n), 1.0f);
    EXPECT_EQ(img.At(0, 0, I), 2.0f);
    EXPECT_FLOAT_EQ(img.At(0, 0, V), 1.0f / 3);  // s² = 1, n = 3
    EXPECT_EQ(img.At(1, 0, I), 5.0f);
    EXPECT_EQ(img.metadata.at("phasor:samples_per_pixel"), "1");
    film.AddReduced(1, 0, Vec3(1, 1, 1), 5);
    film.AddReduced(1, 0, Vec3(1, 1, 1), 5);
    EXPECT_EQ(film.Resolve().ChannelIndex("samples"), -1);
}

TEST(Film, OnlyCarriedWavelengthsContribute) {
    Film film(3, 1, SensorResponse(SensorResponse::Kind::Radiometric));
    // Delta: entry 0 only, divided by the line's selection probability.
    SampledSpectrum L;
    L.v = {1.5, 100, 100, 100};
    film.AddSample(0, 0, L, DeltaLine(633e-9, 0.25));
    // Continuous with terminated companions (pdf 0, hero pdf divided by NumWavelengths): only
    // the hero counts, and it estimates L/pdf with the hero's original pdf.
    SampledWavelengths wl;
    wl.lambda = {500e-9, 600e-9, 700e-9, 800e-9};
    wl.pdf = {8e6, 8e6, 8e6, 8e6};
    wl.TerminateSecondary();
    film.AddSample(1, 0, L, wl);
    // All four carried: the average of L/pdf.
    wl.pdf = {1e6, 2e6, 4e6, 8e6};
    L.v = {1, 2, 4, 8};
    film.AddSample(2, 0, L, wl);
    Image img = film.Resolve();
    EXPECT_FLOAT_EQ(img.At(0, 0, I), float(1.5 / 0.25));
    EXPECT_FLOAT_EQ(img.At(1, 0, I), float(1.5 / 8e6));
    EXPECT_FLOAT_EQ(img.At(2, 0, I), float(1e-6));
    for (int x = 0; x < 3; ++x)
        for (int ch : {R, G, B}) EXPECT_EQ(img.At(x, 0, ch), img.At(x, 0, I));  // radiometric grey
}

TEST(Film, CieSensorReadsYEqualOneForAFlatUnitSpectrum) {
    // Uniform hero wavelength over the CIE range with stratified companions, L(λ) = 1; the
    // estimate of ∫ȳ/∫ȳ dλ must be 1 in expectation — t-test per pixel (Šidák over the pixels).
    const int w = 2, h = 2, spp = 4000;
    const double lo = CieLambdaMin, hi = CieLambdaMax, range = hi - lo;
    Film film(w, h, SensorResponse(SensorResponse::Kind::CieXyz));
    test::TestRng rng(1234);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int s = 0; s < spp; ++s) {
                double u = rng.Uniform();
                SampledWavelengths wl;
                for (int i = 0; i < NumWavelengths; ++i) {
                    double ui = u + double(i) / NumWavelengths;
                    wl.lambda[i] = lo + (ui - std::floor(ui)) * range;
                    wl.pdf[i] = 1 / range;
                }
                film.AddSample(x, y, SampledSpectrum(1.0), wl);
            }
    Image img = film.Resolve();
    const double alpha = test::SidakAlpha(0.01, w * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double mean = img.At(x, y, I), varMean = img.At(x, y, V);
            ASSERT_GT(varMean, 0);
            test::TTestResult t = test::MeanTTest(mean, varMean, spp - 1, 1.0);
            EXPECT_GT(t.pValue, alpha) << "pixel " << x << "," << y << ": Y = " << mean << " "
                                       << t.ToString();
            std::printf("pixel %d,%d: Y = %.6f ± %.2g, p = %.3f\n", x, y, mean, std::sqrt(varMean),
                        t.pValue);
            // RGB is linear Rec.709 of the XYZ means: its luminance is the same Y.
            Vec3 xyz = LinearSrgbToXyz(Vec3(img.At(x, y, R), img.At(x, y, G), img.At(x, y, B)));
            EXPECT_NEAR(xyz.y, mean, 1e-5 * mean);
        }
    EXPECT_EQ(img.metadata.at("phasor:samples_per_pixel"), std::to_string(spp));
    EXPECT_EQ(img.metadata.at("phasor:invalid_samples"), "0");
}

}  // namespace
}  // namespace phasor
