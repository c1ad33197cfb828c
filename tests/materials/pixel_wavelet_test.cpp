// SPDX-License-Identifier: Apache-2.0
// A sensor pixel's state at an aperture plate (materials/aperture_integral.h, PixelWavelet,
// IntegrateWavelet; docs/narrow_pixels.md) against its definition, computed here by brute force:
//     A = ∫_openings t·U_inc(x') · [∫ g(δ)·e^{ik u·δ}·K(x', x_p + δ) d²δ] · √w_n(x') d²x',
// with the exact Rayleigh–Sommerfeld kernel K at every point δ of the pixel (no expansion in δ),
// Gauss–Legendre over the pixel's Gaussian and over the openings. Wide pixels (the double slit of
// theory §6, β = 11.3 λ), narrow ones (σ = λ/2 behind a 60 µm hole, the scene) and labels
// inside and outside the propagating disc.
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>

#include "core/numerics/gauss_legendre.h"
#include "core/render/aperture.h"
#include "core/render/genray.h"
#include "materials/aperture_integral.h"

namespace phasor::test {
namespace {

struct Geometry {
    double lambda, sigma, z;  // wavelength, pixel σ, plate-to-sensor distance [m]
    Vec3 pixel;               // pixel centre (the sensor plane is z = −z, facing +z)
    Vec3 s{0, 0, 1};          // the incident plane wave's direction (travelling towards the sensor: −z)
};

// The brute-force A of the file comment for a plane wave e^{ik s·(x' − hit)} through `pieces`
// (rectangles [x0, x1] × [y0, y1] and discs), integrated over `box` per opening.
struct Rect {
    double x0, x1, y0, y1;
};
Complex BruteForce(const Geometry &c, const Vec2 &label, const Vec3 &hit, const std::vector<Rect> &rects,
                   int nx, int ny, int nDelta) {
    const double k = 2 * Pi / c.lambda, beta = std::sqrt(2.0) * c.sigma;
    const GaussLegendreRule &rd = GaussLegendre(nDelta);
    const double reach = 6 * beta;
    // The pixel's Gaussian on a tensor Gauss–Legendre grid over ±6β.
    std::vector<Vec2> delta;
    std::vector<Complex> weight;
    for (int i = 0; i < rd.n; ++i)
        for (int j = 0; j < rd.n; ++j) {
            const Vec2 d(reach * rd.x[std::size_t(i)], reach * rd.x[std::size_t(j)]);
            const double w = reach * reach * rd.w[std::size_t(i)] * rd.w[std::size_t(j)];
            const double g = std::exp(-LengthSquared(d) / (2 * beta * beta)) / std::sqrt(Pi * beta * beta);
            delta.push_back(d);
            weight.push_back(w * g * std::exp(Complex(0, k * Dot(label, d))));
        }
    auto point = [&](double x, double y) {
        const Vec3 xp(x, y, 0);
        // √w_n at the pixel centre, w = (x' − x_p)/r; the incident wave relative to the hit.
        const Vec3 D = xp - c.pixel;
        const double wn = D.z / Length(D);
        Complex h = 0;
        for (std::size_t m = 0; m < delta.size(); ++m) {
            const Vec3 q = c.pixel + Vec3(delta[m].x, delta[m].y, 0);
            const Vec3 R3 = q - xp;
            const double R = Length(R3), zz = std::abs(R3.z);
            h += weight[m] * (zz / R) * (1 / R - Complex(0, k)) * std::exp(Complex(0, k * R)) / (2 * Pi * R);
        }
        return std::exp(Complex(0, k * Dot(c.s, xp - hit))) * std::sqrt(wn) * h;
    };
    Complex a = 0;
    for (const Rect &r : rects)
        a += IntegrateGaussLegendre(
            [&](double y) { return IntegrateGaussLegendre([&](double x) { return point(x, y); }, r.x0, r.x1, 16, nx); },
            r.y0, r.y1, 16, ny);
    return a;
}

// The kernel's A for the same set-up: the label's ray from the pixel meets the plate at `hit`.
Complex Kernel(const Geometry &c, const Vec2 &label, const Vec3 &hit, const ApertureMask &mask) {
    const double k = 2 * Pi / c.lambda;
    PixelState p;
    p.valid = true;
    p.centre = c.pixel;
    p.frame = Frame{Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    p.beta2 = 2 * c.sigma * c.sigma;
    p.label = label;
    const Vec3 e1(1, 0, 0), e2(0, 1, 0), n(0, 0, 1);
    // The incident wave of the kernel: MakePlateGaussian's s (its GR part is not used).
    const PlateGaussian g = MakePlateGaussian(Vec3(0, 0, 1), c.s, e1, e2, n, k, p.beta2, 0, Infinity, 4);
    const PixelWavelet w = PixelWavelet::Make(p, hit, e1, e2, n, k);
    return IntegrateWavelet(g, w, mask, Vec2(hit.x, hit.y), 4);
}

Vec3 HitOf(const Geometry &c, const Vec2 &u) {
    if (LengthSquared(u) >= 1) return Vec3(0, 0, 0);
    const Vec3 d(u.x, u.y, std::sqrt(1 - LengthSquared(u)));
    return c.pixel + d * (c.z / d.z);
}

TEST(PixelWavelet, WidePixelThroughTheDoubleSlitMatchesBruteForce) {
    // Theory §6: λ = 1 µm, σ = 7.98 µm, z = 10 mm, slits 40 µm wide, 100 µm apart (4 mm long:
    // the brute force takes ±600 µm, where the state's amplitude is e^{−9}).
    Geometry c{1e-6, 7.98e-6, 10e-3, Vec3(35e-6, 0, -10e-3)};
    ApertureMask mask;
    mask.AddRect(Vec2(-70e-6, -2e-3), Vec2(-30e-6, 2e-3));
    mask.AddRect(Vec2(30e-6, -2e-3), Vec2(70e-6, 2e-3));
    const std::vector<Rect> rects = {{-70e-6, -30e-6, -600e-6, 600e-6}, {30e-6, 70e-6, -600e-6, 600e-6}};
    double peak = 0;
    std::vector<std::pair<double, double>> results;
    for (const Vec2 u : {Vec2(-0.0035, 0), Vec2(-0.012, -0.003), Vec2(0.03, 0)}) {
        const Vec3 hit = HitOf(c, u);
        const double ref = std::norm(BruteForce(c, u, hit, rects, 1, 48, 32));
        const double got = std::norm(Kernel(c, u, hit, mask));
        peak = std::max(peak, ref);
        results.push_back({got, ref});
        std::printf("wide pixel, u = (%g, %g): |A|^2 = %.8g, brute force %.8g\n", u.x, u.y, got, ref);
    }
    for (auto [got, ref] : results) EXPECT_NEAR(got, ref, 2e-5 * peak);
}

TEST(PixelWavelet, NarrowPixelBehindAHoleMatchesBruteForce) {
    // The scene: λ = 0.633 µm, a 60 µm hole 20 mm in front of a pixel of σ = 0.3 µm
    // (pitch 1 µm), on and off the axis; labels inside and outside the propagating disc.
    for (double xp : {0.0, 80e-6}) {
        Geometry c{0.6328e-6, 0.3e-6, 20e-3, Vec3(xp, 0, -20e-3)};
        ApertureMask mask;
        mask.AddDisc(Vec2(0, 0), 30e-6);
        double peak = 0;
        std::vector<std::pair<double, double>> results;
        for (const Vec2 u : {Vec2(0, 0), Vec2(0.3, -0.1), Vec2(-0.6, 0.5), Vec2(1.1, 0.4)}) {
            const Vec3 hit = HitOf(c, u);
            // The disc as its bounding square with the transmission of a disc (brute force over
            // the square, the integrand masked): 60 µm = 95 λ, so ~8 panels of 16 nodes per axis.
            Complex ref = 0;
            {
                const double k = 2 * Pi / c.lambda, beta = std::sqrt(2.0) * c.sigma;
                const GaussLegendreRule &rd = GaussLegendre(24);
                const double reach = 6 * beta;
                auto point = [&](double x, double y) -> Complex {
                    if (x * x + y * y > 30e-6 * 30e-6) return 0;
                    const Vec3 xq(x, y, 0), D = xq - c.pixel;
                    Complex h = 0;
                    for (int i = 0; i < rd.n; ++i)
                        for (int j = 0; j < rd.n; ++j) {
                            const Vec2 d(reach * rd.x[std::size_t(i)], reach * rd.x[std::size_t(j)]);
                            const double w = reach * reach * rd.w[std::size_t(i)] * rd.w[std::size_t(j)] *
                                             std::exp(-LengthSquared(d) / (2 * beta * beta)) /
                                             std::sqrt(Pi * beta * beta);
                            const Vec3 R3 = c.pixel + Vec3(d.x, d.y, 0) - xq;
                            const double R = Length(R3);
                            h += w * std::exp(Complex(0, k * Dot(u, d))) * (std::abs(R3.z) / R) *
                                 (1 / R - Complex(0, k)) * std::exp(Complex(0, k * R)) / (2 * Pi * R);
                        }
                    return std::exp(Complex(0, k * Dot(c.s, xq - hit))) * std::sqrt(D.z / Length(D)) * h;
                };
                // Polar quadrature over the disc (smooth in r and φ).
                ref = IntegrateGaussLegendre(
                    [&](double r) {
                        return r * IntegrateGaussLegendre(
                                       [&](double phi) { return point(r * std::cos(phi), r * std::sin(phi)); }, 0,
                                       2 * Pi, 16, 4);
                    },
                    0, 30e-6, 16, 2);
            }
            const double refN = std::norm(ref), got = std::norm(Kernel(c, u, hit, mask));
            peak = std::max(peak, refN);
            results.push_back({got, refN});
            std::printf("narrow pixel at x = %g um, u = (%g, %g): |A|^2 = %.8g, brute force %.8g\n", xp * 1e6, u.x,
                        u.y, got, refN);
        }
        for (auto [got, ref] : results) EXPECT_NEAR(got, ref, 2e-5 * peak);
    }
}

}  // namespace
}  // namespace phasor::test
