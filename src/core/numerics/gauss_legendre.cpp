// SPDX-License-Identifier: Apache-2.0
// phasor — Gauss–Legendre rules (gauss_legendre.h).
#include "core/numerics/gauss_legendre.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/math.h"

namespace phasor {

namespace {

struct Table {
    // Rule n in x[n], w[n] (first n entries); index 0 unused.
    std::array<std::array<double, MaxGaussLegendreNodes>, MaxGaussLegendreNodes + 1> x{}, w{};
    std::array<GaussLegendreRule, MaxGaussLegendreNodes + 1> rules{};
};

// P_n(x) by the three-term recurrence, and P_n'(x) from (x² − 1)P_n' = n(x P_n − P_{n−1}).
double Legendre(int n, double x, double *dp) {
    double p0 = 1, p1 = x;
    for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
    }
    *dp = n * (x * p1 - p0) / (x * x - 1);
    return p1;
}

// The positive half of the nodes by Newton's method from Tricomi's initial guess (A&S 22.16),
// mirrored so the rule is exactly symmetric; weights 2/((1 − x²)P_n'(x)²) (A&S 25.4.29).
void MakeRule(int n, double *x, double *w) {
    for (int i = 0; i < (n + 1) / 2; ++i) {
        double z = std::cos(Pi * (i + 0.75) / (n + 0.5)), dp;
        for (int it = 0; it < 100; ++it) {
            const double dz = Legendre(n, z, &dp) / dp;
            z -= dz;
            if (std::abs(dz) < 1e-16) break;
        }
        Legendre(n, z, &dp);
        const double wi = 2 / ((1 - z * z) * dp * dp);
        x[i] = -z;
        w[i] = wi;
        x[n - 1 - i] = z;  // the middle node of an odd rule: z ≈ 0 (|z| ~ 1e-17)
        w[n - 1 - i] = wi;
    }
}

const Table &Rules() {
    static const Table table = [] {
        Table t;
        for (int n = 1; n <= MaxGaussLegendreNodes; ++n) {
            MakeRule(n, t.x[std::size_t(n)].data(), t.w[std::size_t(n)].data());
            t.rules[std::size_t(n)] = {n, t.x[std::size_t(n)].data(), t.w[std::size_t(n)].data()};
        }
        return t;
    }();
    return table;
}

}  // namespace

const GaussLegendreRule &GaussLegendre(int n) {
    return Rules().rules[std::size_t(std::clamp(n, 1, MaxGaussLegendreNodes))];
}

double GaussLegendreMaxPhase(int n, double tol) {
    const double logErrPerPhase =
        4 * std::lgamma(n + 1.0) - std::log(2 * n + 1.0) - 3 * std::lgamma(2 * n + 1.0);
    return std::exp((std::log(tol) - logErrPerPhase) / (2 * n));
}

}  // namespace phasor
