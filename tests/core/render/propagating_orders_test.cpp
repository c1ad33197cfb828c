// SPDX-License-Identifier: Apache-2.0
// PropagatingOrders (core/render/material.h) against NearDeltaPropagates asked order by order.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/render/material.h"

namespace phasor {
namespace {

/// Asks every order and checks the range holds exactly the propagating ones.
void ExpectSameOrders(const Vec3 &wi, double nIn, double nOut, const Vec2 &unit, double lambda, int maxOrder) {
    const OrderRange r = PropagatingOrders(wi, nIn, nOut, unit, lambda, maxOrder);
    for (int j = -maxOrder; j <= maxOrder; ++j)
        ASSERT_EQ(r.Contains(j), NearDeltaPropagates(wi, nIn, nOut, unit * double(j), lambda))
            << "order " << j << " of [" << r.lo << ", " << r.hi << "], wi (" << wi.x << ", " << wi.y << ", " << wi.z
            << "), nIn " << nIn << ", nOut " << nOut << ", |unit| " << Length(unit) << " rad/m, λ " << lambda;
    EXPECT_TRUE(r.lo > r.hi || (r.lo >= -maxOrder && r.hi <= maxOrder));
}

TEST(PropagatingOrders, AgreesWithEveryOrdersOwnAnswer) {
    std::mt19937_64 rng(20261204);
    std::uniform_real_distribution<double> u(0, 1);
    for (int n = 0; n < 200000; ++n) {
        const double cosT = n % 7 == 0 ? 1e-6 * u(rng) : u(rng);  // some grazing
        const double phi = 2 * Pi * u(rng), sinT = std::sqrt(1 - cosT * cosT);
        const Vec3 wi(sinT * std::cos(phi), sinT * std::sin(phi), n % 2 ? cosT : -cosT);
        const double lambda = 380e-9 + 400e-9 * u(rng);
        const double nIn = 1 + u(rng), nOut = n % 3 ? nIn : 1 + u(rng);
        // Periods from a tenth of a wavelength (nothing but the zeroth order) to 1 mm (thousands).
        const double period = lambda * std::pow(10.0, -1 + 4.5 * u(rng)), angle = 2 * Pi * u(rng);
        const Vec2 unit = Vec2(std::cos(angle), std::sin(angle)) * (2 * Pi / period);
        ExpectSameOrders(wi, nIn, nOut, unit, lambda, 1 + int(15 * u(rng)));
        if (HasFatalFailure()) return;
    }
}

TEST(PropagatingOrders, EdgeCases) {
    const Vec2 unit(2 * Pi / 1.6e-6, 0);
    ExpectSameOrders(Vec3(0, 0, 1), 1, 1, Vec2(0, 0), 500e-9, 8);      // no shift: all or nothing
    ExpectSameOrders(Vec3(1, 0, 0), 1, 1, Vec2(0, 0), 500e-9, 8);      // grazing, no shift: none
    ExpectSameOrders(Vec3(0, 0, 1), 1, 1, unit, 1.6e-6, 8);             // λ = Λ: orders ±1 exactly grazing
    ExpectSameOrders(Vec3(0.6, 0, 0.8), 1, 1, unit, 1.6e-6 / 1.6, 8);  // order −1 exactly grazing
    ExpectSameOrders(Vec3(0, 0, 1), 1, 1, unit * 1e-12, 500e-9, 15);   // a shift far below one order
}

}  // namespace
}  // namespace phasor
