// SPDX-License-Identifier: Apache-2.0
// WavelengthSampler (theory §0 D10): χ² goodness of fit of the continuous samples against the
// tabulated density, line selection, the 1 µm laser, fallbacks, and unbiasedness (t-tests).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "core/spectrum/spectrum.h"
#include "core/spectrum/test_spectra.h"
#include "support/stats.h"

namespace phasor {
namespace {

using test::TestGaussian;
using test::TestLine;
using test::TestPlanck;
using Emitters = std::vector<std::pair<const Spectrum *, double>>;

const SensorResponse Cie(SensorResponse::Kind::CieXyz);
const SensorResponse Radiometric(SensorResponse::Kind::Radiometric);

std::vector<double> LinearEdges(double lo, double hi, int n) {
    std::vector<double> e(n + 1);
    for (int i = 0; i <= n; ++i) e[i] = lo + (hi - lo) * i / n;
    return e;
}
std::vector<double> LogEdges(double lo, double hi, int n) {
    std::vector<double> e(n + 1);
    for (int i = 0; i <= n; ++i) e[i] = lo * std::pow(hi / lo, double(i) / n);
    return e;
}

// ∫ Pdf over [a, b] by the midpoint rule with `m` points (Pdf is piecewise constant on ≤ 1 nm cells,
// so with m large the error is far below the χ² resolution).
double PdfIntegral(const WavelengthSampler &ws, double a, double b, int m = 2000) {
    double s = 0;
    for (int j = 0; j < m; ++j) s += ws.Pdf(a + (b - a) * (j + 0.5) / m);
    return s * (b - a) / m;
}

// χ² of wavelength entry `which` of the continuous samples against N·∫Pdf over `edges`; one extra
// cell collects everything else (delta samples, samples outside the edges).
// With `twoD` the samples are Sample(Vec2) (the render loop's), otherwise Sample(u).
test::Chi2Result Chi2Entry(const WavelengthSampler &ws, int which, const std::vector<double> &edges, int n,
                           uint64_t seed, int pointsPerBin, bool twoD) {
    const int bins = int(edges.size()) - 1;
    std::vector<double> observed(bins + 1, 0.0), expected(bins + 1, 0.0);
    test::TestRng rng(seed);
    for (int s = 0; s < n; ++s) {
        const double u = rng.Uniform();
        const SampledWavelengths wl = twoD ? ws.Sample(Vec2(u, rng.Uniform())) : ws.Sample(u);
        const double l = wl.lambda[which];
        auto it = std::upper_bound(edges.begin(), edges.end(), l);
        const long b = long(it - edges.begin()) - 1;
        if (wl.delta || b < 0 || b >= bins)
            observed[bins] += 1;
        else
            observed[b] += 1;
    }
    double inside = 0;
    for (int b = 0; b < bins; ++b) {
        expected[b] = n * PdfIntegral(ws, edges[b], edges[b + 1], pointsPerBin);
        inside += expected[b];
    }
    expected[bins] = std::max(0.0, n - inside);
    return test::Chi2Test(observed, expected);
}

void ExpectChi2Passes(const WavelengthSampler &ws, const std::vector<double> &edges, const char *what,
                      int pointsPerBin = 2000) {
    // Hero and one companion (each is marginally distributed with the tabulated density), from
    // Sample(u) and from Sample(Vec2).
    const double alpha = test::SidakAlpha(0.01, 4);
    for (bool twoD : {false, true})
        for (int which : {0, 2}) {
            const test::Chi2Result r = Chi2Entry(ws, which, edges, 300000, 17 + which + 4 * twoD, pointsPerBin, twoD);
            EXPECT_GE(r.pValue, alpha) << what << ", entry " << which << (twoD ? " (2-D)" : "") << ": " << r.ToString();
            EXPECT_EQ(r.observedInEmptyCells, 0) << what;
        }
}

TEST(WavelengthSampler, Chi2PlanckWithCie) {
    TestPlanck planck(5800);
    WavelengthSampler ws({{&planck, 1.0}}, Cie);
    EXPECT_DOUBLE_EQ(ws.LambdaMin(), CieLambdaMin);
    EXPECT_DOUBLE_EQ(ws.LambdaMax(), CieLambdaMax);
    EXPECT_NEAR(PdfIntegral(ws, ws.LambdaMin(), ws.LambdaMax(), 200000), 1.0, 1e-6);
    ExpectChi2Passes(ws, LinearEdges(CieLambdaMin, CieLambdaMax, 94), "planck × cie");
}

TEST(WavelengthSampler, Chi2PlanckRadiometricSpansTheWholeSpectrum) {
    // No visible-band clamp: a 3000 K body seen radiometrically is sampled from ~190 nm to ~58 µm.
    TestPlanck planck(3000);
    WavelengthSampler ws({{&planck, 1.0}}, Radiometric);
    const double lMax = 2.897771955e-3 / 3000;
    EXPECT_NEAR(ws.LambdaMin(), lMax / 5, 1e-15);
    EXPECT_NEAR(ws.LambdaMax(), 60 * lMax, 1e-12);
    ExpectChi2Passes(ws, LogEdges(lMax / 5, 60 * lMax, 80), "planck × radiometric");
}

TEST(WavelengthSampler, Chi2NarrowAndBroadGaussians) {
    // A 0.005 nm-wide band next to a broad one: the grid must refine around the narrow band.
    TestGaussian narrow(1064e-9, 0.005e-9, 1.0), broad(900e-9, 50e-9, 1e-4);
    WavelengthSampler ws({{&narrow, 1.0}, {&broad, 1.0}}, Radiometric);
    const double narrowMass = 0.005e-9 * std::sqrt(2 * Pi), broadMass = 1e-4 * 50e-9 * std::sqrt(2 * Pi);
    const double pNarrow = PdfIntegral(ws, 1064e-9 - 0.03e-9, 1064e-9 + 0.03e-9, 20000);
    EXPECT_NEAR(pNarrow, narrowMass / (narrowMass + broadMass), 2e-3);
    ExpectChi2Passes(ws, LinearEdges(1064e-9 - 0.03e-9, 1064e-9 + 0.03e-9, 60), "narrow gaussian");
    // These bins also hold the narrow band (at 1064 nm): integrate Pdf finely enough to resolve it.
    ExpectChi2Passes(ws, LinearEdges(600e-9, 1200e-9, 60), "broad gaussian", 100000);
}

TEST(WavelengthSampler, LinesAreChosenWithTheirProbability) {
    TestGaussian band(550e-9, 30e-9, 1.0);
    TestLine green(532e-9, 2e-8), red(632.8e-9, 1e-8), infrared(1064e-9, 1.0);
    const Emitters emitters = {{&band, 1.0}, {&green, 1.5}, {&red, 1.0}, {&infrared, 5.0}};
    WavelengthSampler ws(emitters, Cie);
    // Expected masses: line strength · scale · (x̄+ȳ+z̄), the continuum's ∫ band · (x̄+ȳ+z̄) dλ.
    double cont = 0;
    const double h = 0.01e-9;
    for (double l = CieLambdaMin; l < CieLambdaMax; l += h)
        cont += band.Eval(l + h / 2) * Cie.Importance(l + h / 2) * h;
    const double mGreen = 1.5 * 2e-8 * Cie.Importance(532e-9), mRed = 1e-8 * Cie.Importance(632.8e-9);
    const double total = cont + mGreen + mRed;  // the 1064 nm line is invisible to the CIE observer
    const std::vector<double> probs = {cont / total, mGreen / total, mRed / total};

    const int n = 400000;
    for (bool twoD : {false, true}) {
        std::vector<double> observed(3, 0.0), expected(3);
        test::TestRng rng(5 + twoD);
        for (int s = 0; s < n; ++s) {
            const double u = rng.Uniform();
            const SampledWavelengths wl = twoD ? ws.Sample(Vec2(rng.Uniform(), u)) : ws.Sample(u);
            if (!wl.delta) {
                observed[0] += 1;
                continue;
            }
            ASSERT_EQ(wl.Count(), 1);
            ASSERT_TRUE(wl.lambda[0] == 532e-9 || wl.lambda[0] == 632.8e-9) << wl.lambda[0];
            const int k = wl.lambda[0] == 532e-9 ? 1 : 2;
            observed[k] += 1;
            EXPECT_NEAR(wl.pdf[0], probs[k], 1e-6 * probs[k]);
            for (int i = 1; i < NumWavelengths; ++i) EXPECT_EQ(wl.pdf[i], 0.0);
        }
        for (int k = 0; k < 3; ++k) expected[k] = n * probs[k];
        const test::Chi2Result r = test::Chi2Test(observed, expected);
        EXPECT_GE(r.pValue, test::SidakAlpha(0.01, 2)) << (twoD ? "2-D: " : "") << r.ToString();
    }
    // The continuous density carries the probability of the continuous part.
    EXPECT_NEAR(PdfIntegral(ws, CieLambdaMin, CieLambdaMax, 200000), probs[0], 1e-6);
}

TEST(WavelengthSampler, InfraredLaserRendersDeterministically) {
    // theory §0 D10: a 1 µm laser must render; with a single line every path carries exactly it.
    TestLine laser(1e-6, 0.02);
    WavelengthSampler ws({{&laser, 3.0}}, Radiometric);
    EXPECT_EQ(ws.LambdaMin(), 1e-6);
    EXPECT_EQ(ws.LambdaMax(), 1e-6);
    EXPECT_EQ(ws.Pdf(1e-6), 0.0);
    test::TestRng rng(3);
    for (int s = 0; s < 1000; ++s) {
        const SampledWavelengths wl =
            ws.Sample(s == 0 ? 0.0 : (s == 1 ? std::nextafter(1.0, 0.0) : rng.Uniform()));
        ASSERT_TRUE(wl.delta);
        ASSERT_EQ(wl.Count(), 1);
        ASSERT_EQ(wl.lambda[0], 1e-6);
        ASSERT_EQ(wl.pdf[0], 1.0);
        ASSERT_EQ(EvalEmission(laser, wl)[0], 0.02);
    }
}

TEST(WavelengthSampler, InvisibleLineDoesNotCrash) {
    // The CIE observer cannot see 1 µm: the laser has no mass; the sampler falls back to the
    // observer's importance and the laser contributes 0.
    TestLine laser(1e-6, 1.0);
    WavelengthSampler ws({{&laser, 1.0}}, Cie);
    test::TestRng rng(4);
    for (int s = 0; s < 1000; ++s) {
        const SampledWavelengths wl = ws.Sample(rng.Uniform());
        ASSERT_FALSE(wl.delta);
        for (int i = 0; i < NumWavelengths; ++i) {
            ASSERT_GE(wl.lambda[i], CieLambdaMin);
            ASSERT_LE(wl.lambda[i], CieLambdaMax);
            ASSERT_GT(wl.pdf[i], 0.0);
        }
        ASSERT_TRUE(EvalEmission(laser, wl).IsZero());
    }
}

TEST(WavelengthSampler, NoEmittersSamplesTheResponse) {
    WavelengthSampler cie({}, Cie);
    EXPECT_NEAR(PdfIntegral(cie, CieLambdaMin, CieLambdaMax, 200000), 1.0, 1e-6);
    ExpectChi2Passes(cie, LinearEdges(CieLambdaMin, CieLambdaMax, 94), "cie importance");
    // Radiometric: uniform over the 360–830 nm fallback band.
    WavelengthSampler rad({}, Radiometric);
    EXPECT_DOUBLE_EQ(rad.LambdaMin(), 360e-9);
    EXPECT_DOUBLE_EQ(rad.LambdaMax(), 830e-9);
    EXPECT_NEAR(rad.Pdf(500e-9) * 470e-9, 1.0, 1e-9);
    EXPECT_NEAR(rad.Pdf(829e-9) * 470e-9, 1.0, 1e-9);
    EXPECT_EQ(rad.Pdf(900e-9), 0.0);
}

TEST(WavelengthSampler, ConstantSeenRadiometricallyFallsBackToTheVisibleBand) {
    ConstantSpectrum c(1);
    WavelengthSampler ws({{&c, 1.0}}, Radiometric);
    EXPECT_DOUBLE_EQ(ws.LambdaMin(), 360e-9);
    EXPECT_DOUBLE_EQ(ws.LambdaMax(), 830e-9);
    EXPECT_NEAR(ws.Pdf(600e-9) * 470e-9, 1.0, 1e-9);
}

TEST(WavelengthSampler, CompanionsAreStratified) {
    TestPlanck planck(6500);
    WavelengthSampler ws({{&planck, 1.0}}, Cie);
    // With u = 0 the four entries sit at CDF values 0, ¼, ½, ¾: increasing wavelengths, each pdf
    // equal to Pdf() there.
    const SampledWavelengths wl = ws.Sample(0.0);
    for (int i = 1; i < NumWavelengths; ++i) EXPECT_GT(wl.lambda[i], wl.lambda[i - 1]);
    for (int i = 0; i < NumWavelengths; ++i) EXPECT_NEAR(wl.pdf[i], ws.Pdf(wl.lambda[i]), 1e-9 * wl.pdf[i]);
    EXPECT_NEAR(PdfIntegral(ws, CieLambdaMin, wl.lambda[2], 200000), 0.5, 1e-5);
    // Sample(Vec2): u.y picks the hero's quarter, u.x its place in it; the companions follow at
    // quarter steps, so (0.3, 0.6) is Sample((2 + 0.3)/4) and (0.3, 0.1) is Sample(0.3/4).
    for (auto [uy, quarter] : {std::pair{0.6, 2}, std::pair{0.1, 0}, std::pair{0.99, 3}}) {
        const SampledWavelengths a = ws.Sample(Vec2(0.3, uy)), b = ws.Sample((quarter + 0.3) / NumWavelengths);
        for (int i = 0; i < NumWavelengths; ++i) EXPECT_NEAR(a.lambda[i], b.lambda[i], 1e-15) << uy << " " << i;
    }
}

// ---- unbiasedness -------------------------------------------------------------------------

struct Weighted {
    const Spectrum *s;
    double scale;
};

// Mean of (1/Count) Σ_i Σ_e scale_e·EvalEmission(e)(λ_i)·g(λ_i)/pdf_i over n samples, t-tested
// against `reference`.
test::TTestResult EstimatorTTest(const WavelengthSampler &ws, const std::vector<Weighted> &emitters,
                                 const std::function<double(double)> &g, double reference, bool heroOnly,
                                 uint64_t seed, bool twoD = false) {
    test::TestRng rng(seed);
    std::vector<double> samples;
    const int n = 200000;
    samples.reserve(n);
    for (int s = 0; s < n; ++s) {
        const double u = rng.Uniform();
        SampledWavelengths wl = twoD ? ws.Sample(Vec2(u, rng.Uniform())) : ws.Sample(u);
        if (heroOnly) wl.TerminateSecondary();
        SampledSpectrum L;
        for (const Weighted &e : emitters) L += EvalEmission(*e.s, wl) * e.scale;
        double est = 0;
        for (int i = 0; i < wl.Count(); ++i)
            if (wl.pdf[i] > 0) est += L[i] * g(wl.lambda[i]) / wl.pdf[i];
        samples.push_back(est / wl.Count());
    }
    return test::OneSampleTTest(samples, reference);
}

TEST(WavelengthSampler, EstimatorIsUnbiasedCie) {
    TestPlanck planck(4000);
    TestGaussian band(600e-9, 10e-9, 1.0);
    TestLine line(532e-9, 1e-8);
    const std::vector<Weighted> emitters = {{&planck, 2.0}, {&band, 1.0}, {&line, 3.0}};
    WavelengthSampler ws({{&planck, 2.0}, {&band, 1.0}, {&line, 3.0}}, Cie);
    // g is not the sampling importance, so the test sees a wrong density.
    auto g = [](double l) { return Cie.Intensity(l) * (1.5 + std::sin(l / 17e-9)); };
    // Reference by Simpson's rule at 0.01 nm plus the line's contribution.
    const int m = 47000;
    const double h = (CieLambdaMax - CieLambdaMin) / m;
    double ref = 0;
    for (int i = 0; i <= m; ++i) {
        const double l = CieLambdaMin + i * h, w = (i == 0 || i == m) ? 1 : (i % 2 ? 4 : 2);
        ref += w * (2 * planck.Eval(l) + band.Eval(l)) * g(l);
    }
    ref = ref * h / 3 + 3 * 1e-8 * g(532e-9);
    for (bool twoD : {false, true})
        for (bool heroOnly : {false, true}) {
            const test::TTestResult t = EstimatorTTest(ws, emitters, g, ref, heroOnly, 11 + heroOnly + 2 * twoD, twoD);
            EXPECT_GE(t.pValue, test::SidakAlpha(0.01, 4)) << (twoD ? "2-D, " : "")
                << (heroOnly ? "hero only: " : "hero+companions: ") << t.ToString() << " reference " << ref;
        }
}

TEST(WavelengthSampler, EstimatorIsUnbiasedRadiometric) {
    TestPlanck planck(2000);
    TestLine laser(1.55e-6, 2e-7);
    const std::vector<Weighted> emitters = {{&planck, 1.0}, {&laser, 1.0}};
    WavelengthSampler ws({{&planck, 1.0}, {&laser, 1.0}}, Radiometric);
    auto g = [](double l) { return 1.0 + 0.5 * std::sin(l / 300e-9); };
    const double lMax = 2.897771955e-3 / 2000, lo = lMax / 5, hi = 60 * lMax;
    // Reference: Simpson's rule in ln λ.
    const int m = 200000;
    const double u0 = std::log(lo), u1 = std::log(hi), h = (u1 - u0) / m;
    double ref = 0;
    for (int i = 0; i <= m; ++i) {
        const double l = std::exp(u0 + i * h), w = (i == 0 || i == m) ? 1 : (i % 2 ? 4 : 2);
        ref += w * planck.Eval(l) * g(l) * l;
    }
    ref = ref * h / 3 + 2e-7 * g(1.55e-6);
    const test::TTestResult t = EstimatorTTest(ws, emitters, g, ref, false, 23);
    EXPECT_GE(t.pValue, 0.01) << t.ToString() << " reference " << ref;
}

}  // namespace
}  // namespace phasor
