// SPDX-License-Identifier: Apache-2.0
// The error metrics, the consistency test against the reference's noise and the grading of runs by
// the reference of `phasor compare` (app/compare_report.h), against values worked out by hand and
// synthetic images drawn from fixed seeds.

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "app/compare_report.h"
#include "core/math.h"
#include "core/render/sampler.h"

namespace phasor {
namespace {

TEST(CompareMetrics, HandWorkedValues) {
    // R = (1, 2, 3, 4), I = R + (0.1, −0.2, 0, 0.4): mean(R) = 2.5, ε = 0.0625.
    const std::vector<double> ref = {1, 2, 3, 4}, img = {1.1, 1.8, 3, 4.4};
    const CompareMetrics m = ErrorMetrics(img, ref);
    EXPECT_NEAR(m.rmse, std::sqrt((0.01 + 0.04 + 0 + 0.16) / 4), 1e-12);
    EXPECT_NEAR(m.relMse, (0.01 / 1.0625 + 0.04 / 4.0625 + 0 + 0.16 / 16.0625) / 4, 1e-12);
    EXPECT_NEAR(m.maxError, 0.4 / 4, 1e-12);  // max |I − R| / max(R)
    EXPECT_EQ(m.skipped, 0);
}

TEST(CompareMetrics, NonFinitePixelsAreSkippedAndDegenerateReferencesGiveNaN) {
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    const CompareMetrics m = ErrorMetrics({1, nan, 5, 2}, {1, 1, inf, 4});
    EXPECT_EQ(m.skipped, 2);
    EXPECT_NEAR(m.rmse, std::sqrt((0 + 4) / 2.0), 1e-12);
    EXPECT_NEAR(m.maxError, 2.0 / 4, 1e-12);
    // A black reference: RMSE only.
    const CompareMetrics black = ErrorMetrics({0.5, 0}, {0, 0});
    EXPECT_NEAR(black.rmse, std::sqrt(0.125), 1e-12);
    EXPECT_TRUE(std::isnan(black.relMse));
    EXPECT_TRUE(std::isnan(black.maxError));
    EXPECT_TRUE(std::isnan(ErrorMetrics({1}, {1, 2}).rmse));  // sizes differ
}

TEST(CompareMetrics, RgbRmseOverTheThreeColourChannels) {
    Image a, b;
    a.width = b.width = 2;
    a.height = b.height = 1;
    a.channels = b.channels = {"R", "G", "B", "intensity"};
    a.data = {1, 2, 3, 9, 0, 0, 0, 9};
    b.data = {1, 2, 5, 0, 1, 0, 0, 0};  // differences 0, 0, 2 and 1, 0, 0
    EXPECT_NEAR(RgbRmse(a, b), std::sqrt((4.0 + 1.0) / 6), 1e-12);
    Image grey = a;
    grey.channels = {"X", "Y", "Z", "intensity"};
    EXPECT_TRUE(std::isnan(RgbRmse(grey, b)));  // no colour channels
}

// Images of `w` × `h` pixels whose pixel i is an independent normal draw of mean mu(i) and
// variance `var` (the variance of a pixel mean), from a fixed seed; with `shared` the draws of
// another image (the same seed: correlated noise).
struct Drawn {
    std::vector<double> values, variance;
};
Drawn Draw(int w, int h, double mu, double bias, double var, uint64_t seed) {
    Pcg32 rng(seed, 7);
    Drawn d;
    for (int i = 0; i < w * h; ++i) {
        const double u1 = std::max(rng.Uniform(), 1e-300), u2 = rng.Uniform();
        const double z = std::sqrt(-2 * std::log(u1)) * std::cos(2 * Pi * u2);
        d.values.push_back(mu + bias + std::sqrt(var) * z);
        d.variance.push_back(var);
    }
    return d;
}

TEST(CompareConsistency, IndependentUnbiasedImagesPassAndABiasIsCaught) {
    // 64 × 64 pixels of mean 1 and noise 0.1 (run) and 0.05 (reference, 4× the samples), 256
    // blocks of 16 pixels. Unbiased: z within the test's 3.09 for 20 seeds (each a p = 0.001 test).
    for (uint64_t s = 0; s < 20; ++s) {
        const Drawn run = Draw(64, 64, 1, 0, 0.01, 2 * s), ref = Draw(64, 64, 1, 0, 0.0025, 2 * s + 1);
        const ConsistencyTest t = TestConsistency(run.values, run.variance, ref.values, ref.variance, 64, 64);
        ASSERT_TRUE(t.tested);
        EXPECT_EQ(t.dof, 256);
        EXPECT_TRUE(t.consistent) << "seed " << s << ": z = " << t.z;
    }
    // A bias of 3 % (0.3 of one pixel's noise): a block of 16 pixels is shifted by 0.48 against a
    // noise variance of 16 · 0.0125 = 0.2, so E[T] − dof = 256 · 0.48²/0.2 ≈ 295 and z ≈ 295/√512 ≈ 13.
    const Drawn run = Draw(64, 64, 1, 0.03, 0.01, 100), ref = Draw(64, 64, 1, 0, 0.0025, 101);
    const ConsistencyTest biased = TestConsistency(run.values, run.variance, ref.values, ref.variance, 64, 64);
    EXPECT_FALSE(biased.consistent) << "z = " << biased.z;
    EXPECT_GT(biased.z, 8);
}

TEST(CompareConsistency, AReferenceThatSharesTheRunsNoiseHidesTheBias) {
    // The failure compare's reference avoids: the same random numbers in run and reference (the
    // same seed) cancel the noise in I − R, so T collapses and the same 3 % bias passes.
    const Drawn ref = Draw(64, 64, 1, 0, 0.01, 200);
    Drawn run = ref;
    for (double &v : run.values) v += 0.03;
    const ConsistencyTest t = TestConsistency(run.values, run.variance, ref.values, ref.variance, 64, 64);
    EXPECT_TRUE(t.consistent) << "z = " << t.z;
}

TEST(CompareConsistency, NoiselessImagesAreEqualOrDiffer) {
    const std::vector<double> zero(4, 0.0), a = {1, 2, 3, 4}, b = {1, 2, 3, 4.5};
    EXPECT_TRUE(TestConsistency(a, zero, a, zero, 2, 2).consistent);
    EXPECT_FALSE(TestConsistency(a, zero, a, zero, 2, 2).tested);  // nothing to test: equal and noiseless
    const ConsistencyTest t = TestConsistency(b, zero, a, zero, 2, 2);
    EXPECT_TRUE(t.tested);
    EXPECT_FALSE(t.consistent);
}

CompareRun MakeRun(const std::string &name, bool deterministic, bool wave, std::vector<double> intensity,
                   std::vector<double> variance, int spp) {
    CompareRun r;
    r.name = name;
    r.deterministic = deterministic;
    r.waveOptical = wave;
    r.status = CompareRun::Status::Done;
    r.sppReached = spp;
    r.intensity = intensity;
    r.variance = variance;
    Image img;
    img.width = int(intensity.size());
    img.height = 1;
    img.channels = {"intensity"};
    for (double v : intensity) img.data.push_back(float(v));
    r.image = img;
    return r;
}

TEST(CompareReference, TheReferenceRunGradesRunsOfItsPhysicsOnly) {
    // The reference: a wave-optical run whose variance is the spread of its replicas.
    std::vector<CompareRun> runs = {MakeRun("grt", false, true, {2, 2}, {0.01, 0.01}, 16),
                                    MakeRun("ray", false, false, {1, 1}, {0.01, 0.01}, 16),
                                    MakeRun("ref", false, true, {2.05, 1.95}, {0.0025, 0.0025}, 64)};
    runs[2].isReferenceRun = true;
    CompareReference ref;
    ComputeErrors(runs, ref);
    ASSERT_EQ(ref.kind, CompareReference::Kind::Run);
    EXPECT_EQ(ref.name, "ref");
    EXPECT_TRUE(runs[2].isReference);
    EXPECT_EQ(ref.peak, 2.05);
    ASSERT_TRUE(runs[0].metrics && runs[1].metrics);
    EXPECT_TRUE(runs[0].comparable);
    EXPECT_FALSE(runs[1].comparable);     // ray optics against a wave-optical reference
    EXPECT_FALSE(runs[1].test.has_value());  // … is never tested as if the difference were error
    EXPECT_NEAR(runs[0].metrics->rmse, 0.05, 1e-12);
    // The reference's variance was not set here (the caller sets it from its replicas): untested.
    EXPECT_FALSE(runs[0].test.has_value());
    SetNoiseFloor(ref, {0.0025, 0.0025}, "replicas");
    EXPECT_NEAR(ref.noiseFloor, 0.05, 1e-12);
    runs[0].metrics.reset();
    ComputeErrors(runs, ref);
    ASSERT_TRUE(runs[0].test.has_value());
    EXPECT_TRUE(runs[0].test->consistent);

    // A complete deterministic run marked as the reference has no noise.
    std::vector<CompareRun> more = {MakeRun("grt", false, true, {2, 2}, {1e-4, 1e-4}, 4096),
                                    MakeRun("rs", true, true, {2, 2}, {}, 0)};
    more[1].isReference = true;
    CompareReference r2;
    ComputeErrors(more, r2);
    EXPECT_EQ(r2.noiseFloor, 0);
    ASSERT_TRUE(more[0].test.has_value());
    EXPECT_TRUE(more[0].test->consistent);
}

}  // namespace
}  // namespace phasor
