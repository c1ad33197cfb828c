// SPDX-License-Identifier: Apache-2.0
// The error metrics and the choice of the reference of `phasor compare` (app/compare_report.h),
// against values worked out by hand.

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "app/compare_report.h"

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

CompareRun MakeRun(const std::string &name, bool deterministic, CompareRun::Status status,
                   std::vector<double> intensity, std::vector<double> variance, int spp) {
    CompareRun r;
    r.name = name;
    r.deterministic = deterministic;
    r.status = status;
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

TEST(CompareReference, BestConvergedRun) {
    using S = CompareRun::Status;
    // The least relative noise Σvar/ΣI² wins among sampling runs: b (0.02/8 = 0.0025) over a (0.1/8).
    std::vector<CompareRun> runs = {MakeRun("a", false, S::Done, {2, 2}, {0.05, 0.05}, 16),
                                    MakeRun("b", false, S::Done, {2, 2}, {0.01, 0.01}, 16)};
    CompareReference ref;
    ChooseReference(runs, ref);
    EXPECT_TRUE(runs[1].isReference);
    EXPECT_FALSE(runs[0].isReference);
    EXPECT_NE(ref.description.find("b, the best-converged run"), std::string::npos) << ref.description;
    ComputeErrors(runs, ref);
    ASSERT_TRUE(runs[0].metrics.has_value());
    EXPECT_FALSE(runs[1].metrics.has_value());
    EXPECT_EQ(ref.peak, 2);

    // A complete deterministic run beats any sampling run; an interrupted one does not, nor a run
    // with one sample (no variance estimate).
    std::vector<CompareRun> more = {
        MakeRun("grt", false, S::Done, {2, 2}, {1e-9, 1e-9}, 4096), MakeRun("rs", true, S::Done, {2, 2}, {}, 0),
        MakeRun("half", false, S::Interrupted, {2, 0}, {0, 0}, 0), MakeRun("one", false, S::Done, {2, 2}, {0, 0}, 1)};
    CompareReference r2;
    ChooseReference(more, r2);
    EXPECT_TRUE(more[1].isReference);
    EXPECT_NE(r2.description.find("deterministic"), std::string::npos) << r2.description;
    more.erase(more.begin() + 1);
    for (CompareRun &r : more) r.isReference = false;
    CompareReference r3;
    ChooseReference(more, r3);
    EXPECT_TRUE(more[0].isReference) << r3.description;
}

}  // namespace
}  // namespace phasor
