// SPDX-License-Identifier: Apache-2.0
#include "support/stats.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

namespace phasor::test {

// Series / continued fraction for the regularized incomplete gamma (Numerical Recipes §6.2).
double GammaP(double a, double x) {
    if (x <= 0) return 0;
    double gln = std::lgamma(a);
    if (x < a + 1) {
        double ap = a, sum = 1 / a, del = sum;
        for (int n = 0; n < 100000; ++n) {
            ap += 1;
            del *= x / ap;
            sum += del;
            if (std::abs(del) < std::abs(sum) * 1e-15) break;
        }
        return sum * std::exp(-x + a * std::log(x) - gln);
    }
    double b = x + 1 - a, c = 1 / 1e-300, d = 1 / b, h = d;
    for (int i = 1; i < 100000; ++i) {
        double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        if (std::abs(d) < 1e-300) d = 1e-300;
        c = b + an / c;
        if (std::abs(c) < 1e-300) c = 1e-300;
        d = 1 / d;
        double del = d * c;
        h *= del;
        if (std::abs(del - 1) < 1e-15) break;
    }
    return 1 - std::exp(-x + a * std::log(x) - gln) * h;
}

namespace {
// Continued fraction for the incomplete beta (Lentz's method).
double BetaCf(double a, double b, double x) {
    const double tiny = 1e-300;
    double qab = a + b, qap = a + 1, qam = a - 1, c = 1, d = 1 - qab * x / qap;
    if (std::abs(d) < tiny) d = tiny;
    d = 1 / d;
    double h = d;
    for (int m = 1; m < 100000; ++m) {
        int m2 = 2 * m;
        double aa = m * (b - m) * x / ((qam + m2) * (a + m2));
        d = 1 + aa * d;
        if (std::abs(d) < tiny) d = tiny;
        c = 1 + aa / c;
        if (std::abs(c) < tiny) c = tiny;
        d = 1 / d;
        h *= d * c;
        aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
        d = 1 + aa * d;
        if (std::abs(d) < tiny) d = tiny;
        c = 1 + aa / c;
        if (std::abs(c) < tiny) c = tiny;
        d = 1 / d;
        double del = d * c;
        h *= del;
        if (std::abs(del - 1) < 1e-15) break;
    }
    return h;
}
}  // namespace

double BetaI(double a, double b, double x) {
    if (x <= 0) return 0;
    if (x >= 1) return 1;
    double bt = std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) +
                         b * std::log(1 - x));
    if (x < (a + 1) / (a + b + 2)) return bt * BetaCf(a, b, x) / a;
    return 1 - bt * BetaCf(b, a, 1 - x) / b;
}

double StudentTwoSidedP(double t, double dof) {
    if (!std::isfinite(t)) return 0;
    return BetaI(0.5 * dof, 0.5, dof / (dof + t * t));
}

std::string Chi2Result::ToString() const {
    std::ostringstream os;
    os << "chi2 = " << chi2 << ", dof = " << dof << ", p = " << pValue
       << ", samples in empty cells = " << observedInEmptyCells;
    return os.str();
}

Chi2Result Chi2Test(const std::vector<double> &observed, const std::vector<double> &expected,
                    double minExpected) {
    Chi2Result r;
    std::vector<std::size_t> order(observed.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](auto a, auto b) { return expected[a] < expected[b]; });
    double poolO = 0, poolE = 0;
    int cells = 0;
    for (std::size_t i : order) {
        if (expected[i] <= 0) {
            r.observedInEmptyCells += (long long)observed[i];
            continue;
        }
        // Cells come in increasing expected count: small ones are pooled until the pool reaches
        // minExpected; a pool still short when the large cells begin is merged into the first
        // of them, so no tested cell has E < minExpected.
        poolO += observed[i];
        poolE += expected[i];
        if (poolE >= minExpected) {
            r.chi2 += (poolO - poolE) * (poolO - poolE) / poolE;
            ++cells;
            poolO = poolE = 0;
        }
    }
    if (poolE > 0) {
        // Only possible when every cell together is below minExpected.
        r.chi2 += (poolO - poolE) * (poolO - poolE) / poolE;
        ++cells;
    }
    r.dof = std::max(1, cells - 1);
    r.pValue = 1 - GammaP(0.5 * r.dof, 0.5 * r.chi2);
    return r;
}

double SidakAlpha(double alpha, int numTests) { return 1 - std::pow(1 - alpha, 1.0 / numTests); }

std::string TTestResult::ToString() const {
    std::ostringstream os;
    os << "t = " << t << ", dof = " << dof << ", p = " << pValue;
    return os.str();
}

TTestResult MeanTTest(double mean, double varianceOfMean, double dof, double reference) {
    TTestResult r;
    r.dof = dof;
    if (varianceOfMean <= 0) {
        r.t = mean == reference ? 0 : std::numeric_limits<double>::infinity();
        r.pValue = mean == reference ? 1 : 0;
        return r;
    }
    r.t = (mean - reference) / std::sqrt(varianceOfMean);
    r.pValue = StudentTwoSidedP(r.t, dof);
    return r;
}

TTestResult OneSampleTTest(const std::vector<double> &s, double reference) {
    double n = double(s.size());
    double mean = std::accumulate(s.begin(), s.end(), 0.0) / n;
    double var = 0;
    for (double x : s) var += (x - mean) * (x - mean);
    var /= (n - 1);
    return MeanTTest(mean, var / n, n - 1, reference);
}

TTestResult WelchTTest(double m1, double v1, double d1, double m2, double v2, double d2) {
    TTestResult r;
    double v = v1 + v2;
    if (v <= 0) {
        r.t = m1 == m2 ? 0 : std::numeric_limits<double>::infinity();
        r.pValue = m1 == m2 ? 1 : 0;
        return r;
    }
    r.t = (m1 - m2) / std::sqrt(v);
    // Welch–Satterthwaite degrees of freedom.
    r.dof = v * v / (v1 * v1 / d1 + v2 * v2 / d2);
    r.pValue = StudentTwoSidedP(r.t, r.dof);
    return r;
}

TestRng::TestRng(uint64_t seed) : state_(0), inc_((seed << 1u) | 1u) {
    NextU32();
    state_ += 0x853c49e6748fea9bULL + seed;
    NextU32();
}

uint32_t TestRng::NextU32() {
    uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = uint32_t(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32 - rot) & 31));
}

double TestRng::Uniform() { return std::min(NextU32() * 0x1p-32, 0x1.fffffffffffffp-1); }

}  // namespace phasor::test
