// SPDX-License-Identifier: Apache-2.0
// The Faddeeva function (core/numerics/faddeeva.h) against known values, its symmetries, and the
// fast upper-half-plane approximation against the libcerf reference.
#include <gtest/gtest.h>

#include <cmath>

#include "core/numerics/faddeeva.h"

namespace phasor {
namespace {

// w(z) = e^{−z²} erfc(−iz) to 20 digits (mpmath, 30-digit arithmetic).
struct Known {
    Complex z, w;
};
const Known kKnown[] = {
    {{1, 1}, {0.30474420525691259246, 0.20821893820283162729}},
    {{1, 0}, {0.3678794411714423216, 0.60715770584139372912}},  // e^{−1} + i·(2/√π)·Dawson(1)
    {{0, 1}, {0.42758357615580700441, 0}},                      // e·erfc(1)
    {{3, 0.5}, {0.037126366054692344667, 0.19298375530036208839}},
    {{-2, 0.1}, {0.040201398161451288505, -0.33158268733456308067}},
    {{0.5, 5}, {0.10970302798911379741, 0.01057305653580245353}},
    {{20, 1}, {0.001412234766392966132, 0.028173995667521982511}},
};

TEST(Faddeeva, MatchesKnownValues) {
    // libcerf's stated accuracy is ~1e-14 relative; Weideman's N = 28 rule 2e-12 absolute
    // (|w| ≤ 1 in the upper half-plane).
    EXPECT_EQ(FaddeevaW(Complex(0, 0)), Complex(1, 0));
    for (const Known &k : kKnown) {
        EXPECT_LT(std::abs(FaddeevaW(k.z) - k.w), 1e-14 * std::abs(k.w)) << k.z;
        EXPECT_LT(std::abs(FaddeevaWUpper(k.z) - k.w), 2e-12) << k.z;
    }
}

TEST(Faddeeva, ObeysItsSymmetries) {
    // DLMF 7.4.3–7.4.4: w(−z̄) = conj(w(z)) and w(−z) = 2e^{−z²} − w(z). Checked in the upper
    // half-plane, where 2e^{−z²} stays ≤ 2e^{y²}·… moderate for |z| ≤ 3.
    for (double x : {-2.5, -0.3, 0.0, 0.7, 2.9})
        for (double y : {0.0, 0.2, 1.0, 2.5}) {
            const Complex z(x, y), w = FaddeevaW(z);
            EXPECT_LT(std::abs(FaddeevaW(-std::conj(z)) - std::conj(w)), 1e-15) << z;
            const Complex other = 2.0 * std::exp(-z * z) - w;
            EXPECT_LT(std::abs(FaddeevaW(-z) - other), 1e-13 * std::max(1.0, std::abs(other))) << z;
        }
}

TEST(Faddeeva, FastUpperHalfPlaneMatchesLibcerf) {
    // Over 1e-3 ≤ |z| < 1e4 on rays of the closed upper half-plane (Weideman's bound 2e-12).
    double worst = 0;
    for (double r = 1e-3; r < 1e4; r *= 1.07)
        for (int j = 0; j <= 60; ++j) {
            const Complex z = std::polar(r, Pi * j / 60);
            worst = std::max(worst, std::abs(FaddeevaWUpper(z) - FaddeevaW(z)));
        }
    EXPECT_LT(worst, 5e-12);
}

TEST(Faddeeva, BatchEqualsSingleCalls) {
    double zr[37], zi[37], wr[37], wi[37];
    for (int i = 0; i < 37; ++i) zr[i] = -9 + 0.5 * i, zi[i] = 0.1 * i;
    FaddeevaWUpperBatch(37, zr, zi, wr, wi);  // more than two blocks of 16
    for (int i = 0; i < 37; ++i) EXPECT_EQ(Complex(wr[i], wi[i]), FaddeevaWUpper(Complex(zr[i], zi[i]))) << i;
}

}  // namespace
}  // namespace phasor
