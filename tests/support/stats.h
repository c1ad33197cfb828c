// SPDX-License-Identifier: Apache-2.0
// phasor test support — proper statistical tests (docs/architecture.md, "Error estimates"): χ² goodness of fit with
// pooling, Student's t-tests, and the special functions behind them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace phasor::test {

/// Regularized lower incomplete gamma P(a, x).
double GammaP(double a, double x);
/// Regularized incomplete beta I_x(a, b).
double BetaI(double a, double b, double x);
/// Two-sided p-value of Student's t statistic with `dof` degrees of freedom.
double StudentTwoSidedP(double t, double dof);

struct Chi2Result {
    double chi2 = 0;
    int dof = 0;
    double pValue = 0;
    long long observedInEmptyCells = 0;  // samples that fell where the expected count is 0
    std::string ToString() const;
};
/// χ² test of observed counts against expected counts (same length). Cells are sorted by
/// expected count and those with E < minExpected pooled until the pool reaches it.
Chi2Result Chi2Test(const std::vector<double> &observed, const std::vector<double> &expected,
                    double minExpected = 5);
/// Šidák-corrected significance for one of `numTests` tests at family-wise level alpha.
double SidakAlpha(double alpha, int numTests);

struct TTestResult {
    double t = 0, dof = 0, pValue = 1;
    std::string ToString() const;
};
/// One-sample t-test of samples against a reference mean.
TTestResult OneSampleTTest(const std::vector<double> &samples, double reference);
/// One-sample t-test from a mean, the variance *of the mean* and its degrees of freedom.
TTestResult MeanTTest(double mean, double varianceOfMean, double dof, double reference);
/// Welch's two-sample t-test from two means and the variances of the means.
TTestResult WelchTTest(double mean1, double varMean1, double dof1, double mean2, double varMean2,
                       double dof2);

/// Deterministic PCG32 for tests (independent of the renderer's samplers).
class TestRng {
  public:
    explicit TestRng(uint64_t seed = 1);
    uint32_t NextU32();
    double Uniform();  // [0, 1)

  private:
    uint64_t state_, inc_;
};

}  // namespace phasor::test
