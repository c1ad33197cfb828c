// SPDX-License-Identifier: Apache-2.0
// SphericalRectangle (Ureña et al. 2013): its solid angle against the closed form of a rectangle
// parallel to a plane seen from a point, samples on the rectangle, an integral by its samples
// against one over the rectangle's area, and where it declines. (The χ² of its directions against
// the density is the light contract's SamplingMatchesPdf on the `area` light's panel.)
#include <gtest/gtest.h>

#include <cmath>

#include "core/geometry/spherical_rectangle.h"

namespace phasor {
namespace {

// Solid angle of [x0, x1] × [y0, y1] in the plane z = h seen from the origin: the signed sum of
// the corner terms atan(x·y / (h·√(x² + y² + h²))).
double ClosedFormSolidAngle(double x0, double x1, double y0, double y1, double h) {
    auto f = [h](double x, double y) { return std::atan(x * y / (h * std::sqrt(x * x + y * y + h * h))); };
    return f(x1, y1) - f(x0, y1) - f(x1, y0) + f(x0, y0);
}

struct Case {
    Vec3 o;
    double x0, x1, y0, y1, h;  // the rectangle [x0, x1] × [y0, y1] at z = h (world axes)
};

const Case Cases[] = {
    {{0, 0, 0}, -1, 1, -1, 1, 0.2},     // a large panel close above
    {{0, 0, 0}, 0.3, 0.5, -2, 3, 1.0},  // a long strip off to the side
    {{0, 0, 0}, -0.1, 0.1, -0.1, 0.1, 3.0},
    {{0, 0, 0}, 2, 4, 1, 1.5, -0.7},    // below the point, off axis
};

TEST(SphericalRectangle, SolidAngleMatchesTheClosedForm) {
    for (const Case &c : Cases) {
        const auto r = SphericalRectangle::From(c.o, Vec3(c.x0, c.y0, c.h), Vec3(c.x1 - c.x0, 0, 0), Vec3(0, c.y1 - c.y0, 0));
        ASSERT_TRUE(r);
        const double ref = std::abs(ClosedFormSolidAngle(c.x0, c.x1, c.y0, c.y1, std::abs(c.h)));
        EXPECT_NEAR(r->SolidAngle(), ref, 1e-12 + 1e-10 * ref) << c.x0 << " " << c.h;
    }
}

TEST(SphericalRectangle, SamplesIntegrateLikeTheRectanglesArea) {
    // ∫ g(ω) dω over the rectangle, g = (ω·ẑ)² (a smooth weight), two ways: from the samples
    // (midpoints of a 400² grid in u, each weighted by Ω) and over the area, ∫ g·|cos θ_l|/r² dA.
    for (const Case &c : Cases) {
        const Vec3 corner(c.x0, c.y0, c.h), ex(c.x1 - c.x0, 0, 0), ey(0, c.y1 - c.y0, 0);
        const auto r = SphericalRectangle::From(c.o, corner, ex, ey);
        ASSERT_TRUE(r);
        const int n = 400;
        double bySamples = 0, byArea = 0;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const Vec2 u((i + 0.5) / n, (j + 0.5) / n);
                const Vec3 p = r->Sample(u);
                EXPECT_NEAR(p.z, c.h, 1e-12 * (1 + std::abs(c.h)));
                EXPECT_TRUE(p.x >= c.x0 - 1e-12 && p.x <= c.x1 + 1e-12 && p.y >= c.y0 - 1e-12 && p.y <= c.y1 + 1e-12);
                const Vec3 w = Normalize(p - c.o);
                bySamples += w.z * w.z * r->SolidAngle() / (n * n);
                const Vec3 q = corner + ex * u.x + ey * u.y, d = q - c.o;
                const double r2 = LengthSquared(d), cosL = std::abs(d.z) / std::sqrt(r2);
                byArea += Sqr(d.z) / r2 * cosL / r2 * Length(ex) * Length(ey) / (n * n);
            }
        // Both are midpoint rules of smooth integrands at 400²: ~1e-5 relative.
        EXPECT_NEAR(bySamples, byArea, 1e-4 * byArea) << c.x0 << " " << c.h;
    }
}

TEST(SphericalRectangle, DeclinesWhereItWouldLoseDigits) {
    const Vec3 corner(-1, -1, 1), ex(2, 0, 0), ey(0, 2, 0);
    EXPECT_TRUE(SphericalRectangle::From(Vec3(0, 0, 0), corner, ex, ey));
    EXPECT_FALSE(SphericalRectangle::From(Vec3(0, 0, 0), corner, ex, Vec3(0.5, 2, 0)));  // sheared
    EXPECT_FALSE(SphericalRectangle::From(Vec3(5, 0, 1), corner, ex, ey));                // in its plane
    EXPECT_FALSE(SphericalRectangle::From(Vec3(0, 0, 300), corner, ex, ey));              // Ω = 4.4e-5 sr
    EXPECT_FALSE(SphericalRectangle::From(Vec3(0, 0, 1 - 1e-9), corner, ex, ey));         // on it: Ω → 2π
}

}  // namespace
}  // namespace phasor
