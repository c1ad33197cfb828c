// SPDX-License-Identifier: Apache-2.0
// The forward Rayleigh–Sommerfeld integrator `rs` (src/integrators/rs.cpp): its numerical core
// against independent references (composite Simpson with std::cyl_bessel / finite differences,
// brute-force surface quadrature, closed forms), energy and obliquity, the 2-D/3-D relation, and
// the errors for every unsupported scene.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <tbb/global_control.h>

#include "integrators/rs/propagator.h"
#include "integrators/rs/sensor_quadrature.h"
#include "integrators/rs/slit_end_error.h"
#include "parser/parser.h"
#include "support/scene_builder.h"
#include "support/stats.h"

namespace phasor::test {
namespace {

using rs::Propagator;

constexpr double Um = 1e-6;

CoherentWave PlaneWave(double lambda, Vec3 dir, double e = 1) {
    CoherentWave w;
    w.kind = CoherentWave::Kind::Plane;
    w.dir = Normalize(dir);
    w.strength = e;
    w.lambda = lambda;
    return w;
}

ApertureMask Slits(double d, double b, double length) {
    ApertureMask m;
    m.AddRect(Vec2(-d / 2 - b / 2, -length / 2), Vec2(-d / 2 + b / 2, length / 2));
    m.AddRect(Vec2(d / 2 - b / 2, -length / 2), Vec2(d / 2 + b / 2, length / 2));
    return m;
}

/// A sensor in the plane z = −z facing the plate (front normal +z), like double_slit.wscene:
/// nx × ny pixels of the given pitch centred on the axis.
SensorPlaneGeometry Sensor(double z, int nx, int ny, double pitch, double sigma, bool gaussian = true) {
    SensorPlaneGeometry g;
    g.origin = Vec3(0, 0, -z);
    g.frame.s = Vec3(1, 0, 0);
    g.frame.t = Vec3(0, 1, 0);
    g.frame.n = Vec3(0, 0, 1);
    g.nx = nx;
    g.ny = ny;
    g.pitchX = g.pitchY = pitch;
    g.width = nx * pitch;
    g.height = ny * pitch;
    g.sigma = sigma;
    g.gaussianPixel = gaussian;
    return g;
}

double Peak(const std::vector<double> &v) { return *std::max_element(v.begin(), v.end()); }
double MaxDiff(const std::vector<double> &a, const std::vector<double> &b) {
    double m = 0;
    for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
    return m;
}

double Seconds(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// The grid with `f` − 1 extra nodes in every interval of its (uncollapsed) axes.
rs::SensorGrid Refined(const rs::SensorGrid &grid, int f) {
    auto refine = [f](const std::vector<double> &xs) {
        std::vector<double> out;
        for (std::size_t i = 0; i < xs.size(); ++i) {
            out.push_back(xs[i]);
            for (int j = 1; j < f && i + 1 < xs.size(); ++j) out.push_back(xs[i] + (xs[i + 1] - xs[i]) * j / f);
        }
        return out;
    };
    rs::SensorGrid dense = grid;
    if (!grid.collapseX) {
        dense.xs = refine(grid.xs);
        dense.hx = grid.hx / f;
    }
    if (!grid.collapseY) {
        dense.ys = refine(grid.ys);
        dense.hy = grid.hy / f;
    }
    return dense;
}

// ---- 2-D mode: the double slit against an independent 2-D RS ------------------------------------

/// Independent 2-D RS (theory §6.2) behind slits [lo, hi] for a unit plane wave tilted by `tilt`
/// in the x–z plane, at height z: U by composite Simpson (λ/8 steps) with std::cyl_bessel_j /
/// cyl_neumann, ∂U/∂z by a central difference (δ = λ/10⁴), flux Im(U*∂U/∂z)/k; pixel values by
/// the trapezoid rule on a 1 µm grid against the Gaussian sensitivity.
std::vector<double> ReferenceFlux2D(const std::vector<std::pair<double, double>> &slits, double lambda,
                                    double z, double tilt, double sigma, const std::vector<double> &centres) {
    const double k = 2 * Pi / lambda;
    auto field = [&](double x, double zz) {
        Complex u = 0;
        for (auto [lo, hi] : slits) {
            const int n = 2 * int(std::ceil((hi - lo) / (lambda / 8) / 2));
            const double h = (hi - lo) / n;
            for (int j = 0; j <= n; ++j) {
                const double xp = lo + j * h, r = std::hypot(x - xp, zz);
                const double w = (j == 0 || j == n) ? 1 : (j % 2 ? 4 : 2);
                const Complex h1(std::cyl_bessel_j(1.0, k * r), std::cyl_neumann(1.0, k * r));
                u += w * h / 3 * std::polar(1.0, k * std::sin(tilt) * xp) * h1 / r;
            }
        }
        return Complex(0, k * zz / 2) * u;
    };
    const double dx = 1 * Um, delta = lambda / 1e4;
    const double lo = centres.front() - 7 * sigma, hi = centres.back() + 7 * sigma;
    const int n = int(std::ceil((hi - lo) / dx));
    std::vector<double> xs(n + 1), flux(n + 1);
    for (int i = 0; i <= n; ++i) {
        xs[i] = lo + i * dx;
        const Complex u = field(xs[i], z);
        const Complex du = (field(xs[i], z + delta) - field(xs[i], z - delta)) / (2 * delta);
        flux[i] = (std::conj(u) * du).imag() / k;
    }
    std::vector<double> out;
    for (double xc : centres) {
        double acc = 0;
        for (int i = 0; i <= n; ++i) acc += flux[i] * std::exp(-0.5 * Sqr((xs[i] - xc) / sigma));
        out.push_back(acc * dx / (std::sqrt(2 * Pi) * sigma));
    }
    return out;
}

std::vector<double> Centres(const SensorPlaneGeometry &g) {
    std::vector<double> c;
    for (int i = 0; i < g.nx; ++i) c.push_back(g.PixelCenter(i, 0).x);
    return c;
}

TEST(Rs, TwoDDoubleSlitMatchesIndependentRs) {
    const double lambda = 1 * Um, z = 10000 * Um, b = 40 * Um, d = 100 * Um, sigma = 7.98 * Um;
    const ApertureMask mask = Slits(d, b, 4000 * Um);
    const SensorPlaneGeometry g = Sensor(z, 48, 1, 25 * Um, sigma);
    for (double tiltDeg : {0.0, 1.0}) {  // (5° on an asymmetric pair: the next test)
        const double tilt = Radians(tiltDeg);
        const Propagator prop(PlateFrame{}, mask, PlaneWave(lambda, Vec3(std::sin(tilt), 0, -std::cos(tilt))),
                              true, true);
        const auto t0 = std::chrono::steady_clock::now();
        const rs::SensorGrid grid = rs::MakeGrid(g, prop);
        const std::vector<double> v = rs::IntegrateSensor(g, prop, grid, rs::Quantity::Flux);
        const double t = Seconds(t0);
        const std::vector<double> ref =
            ReferenceFlux2D({{-d / 2 - b / 2, -d / 2 + b / 2}, {d / 2 - b / 2, d / 2 + b / 2}}, lambda, z,
                            tilt, sigma, Centres(g));
        const double e = MaxDiff(v, ref) / Peak(ref);
        std::printf(
            "2-D double slit, tilt %.0f deg: max|rs - ref| = %.2e of peak (peak %.5f, %zu grid nodes, %.3f "
            "s)\n",
            tiltDeg, e, Peak(ref), grid.Nodes(), t);
        EXPECT_LE(e, 1e-3);
        EXPECT_TRUE(grid.collapseY);
        if (tiltDeg != 0) continue;
        // The reference itself against the Fresnel-regime two-slit formula with the Gaussian
        // pixel's decoherence factor (theory §6.7; bounded here by 6 % of peak).
        const double k = 2 * Pi / lambda;
        double worst = 0;
        for (int i = 0; i < g.nx; ++i) {
            const double x = g.PixelCenter(i, 0).x;
            auto sinc = [&](double u) {
                const double a = k * b * u / (2 * z);
                return a == 0 ? 1.0 : std::sin(a) / a;
            };
            const double s1 = sinc(x + d / 2), s2 = sinc(x - d / 2);
            const double f =
                b * b / (lambda * z) *
                (s1 * s1 + s2 * s2 +
                 2 * s1 * s2 * std::cos(k * d * x / z) * std::exp(-0.5 * Sqr(k * d * sigma / z)));
            worst = std::max(worst, std::abs(f - ref[i]));
        }
        std::printf("  reference vs the Fresnel-regime formula (theory §6.7): %.3f of peak\n",
                    worst / Peak(ref));
        EXPECT_LT(worst / Peak(ref), 0.06);
    }
}

// Oblique incidence (theory §0 D3: sign errors hide at normal incidence) on an asymmetric pair
// (b = 40 and 25 µm): at 5° the pattern moves by z·tan 5° = 0.87 mm, so the row is 2.4 mm wide.
TEST(Rs, TwoDObliqueAsymmetricPairMatchesIndependentRs) {
    const double lambda = 1 * Um, z = 10000 * Um, d = 100 * Um, b1 = 40 * Um, b2 = 25 * Um, sigma = 7.98 * Um;
    ApertureMask mask;
    mask.AddRect(Vec2(-d / 2 - b1 / 2, -2000 * Um), Vec2(-d / 2 + b1 / 2, 2000 * Um));
    mask.AddRect(Vec2(d / 2 - b2 / 2, -2000 * Um), Vec2(d / 2 + b2 / 2, 2000 * Um));
    const SensorPlaneGeometry g = Sensor(z, 96, 1, 25 * Um, sigma);
    const double tilt = Radians(5);
    const Propagator prop(PlateFrame{}, mask, PlaneWave(lambda, Vec3(std::sin(tilt), 0, -std::cos(tilt))),
                          true, true);
    const std::vector<double> v = rs::IntegrateSensor(g, prop, rs::MakeGrid(g, prop), rs::Quantity::Flux);
    const std::vector<double> ref =
        ReferenceFlux2D({{-d / 2 - b1 / 2, -d / 2 + b1 / 2}, {d / 2 - b2 / 2, d / 2 + b2 / 2}}, lambda, z,
                        tilt, sigma, Centres(g));
    const double e = MaxDiff(v, ref) / Peak(ref);
    std::printf("2-D asymmetric pair at 5 deg: max|rs - ref| = %.2e of peak\n", e);
    EXPECT_LE(e, 1e-3);
    // The pattern sits where the tilted wave carries it: the wave drifts towards +x by z·tan θ.
    double num = 0, den = 0;
    for (int i = 0; i < g.nx; ++i) {
        num += v[i] * g.PixelCenter(i, 0).x;
        den += v[i];
    }
    EXPECT_NEAR(num / den, z * std::tan(tilt), 60 * Um);
}

// Flux through the sensor vs |U|²: the obliquity of the waves (≤ 0.7° here) changes the pixel
// values by less than 1e-4 of the peak.
TEST(Rs, FluxDiffersFromIntensityBelow1e4OfPeak) {
    const SensorPlaneGeometry g = Sensor(10000 * Um, 48, 1, 25 * Um, 7.98 * Um);
    const Propagator prop(PlateFrame{}, Slits(100 * Um, 40 * Um, 4000 * Um),
                          PlaneWave(1 * Um, Vec3(0, 0, -1)), true, true);
    const rs::SensorGrid grid = rs::MakeGrid(g, prop);
    const std::vector<double> flux = rs::IntegrateSensor(g, prop, grid, rs::Quantity::Flux);
    const std::vector<double> inten = rs::IntegrateSensor(g, prop, grid, rs::Quantity::Intensity);
    const double e = MaxDiff(flux, inten) / Peak(inten);
    std::printf("double slit: max|flux - |U|^2| = %.2e of peak\n", e);
    EXPECT_LT(e, 1e-4);
    EXPECT_GT(e, 1e-7);  // the two quantities do differ (the flux is not |U|² by construction)
}

// ---- energy and obliquity ----------------------------------------------------------------------

TEST(Rs, ParsevalPowerThroughTheSlits) {
    // 6 mm sensor, pitch 10 µm ≤ 1.5σ: Σ pixel·pitch = power per unit slit length = 2b·E (theory §9).
    const double b = 40 * Um;
    const SensorPlaneGeometry g = Sensor(10000 * Um, 600, 1, 10 * Um, 7.98 * Um);
    const Propagator prop(PlateFrame{}, Slits(100 * Um, b, 4000 * Um), PlaneWave(1 * Um, Vec3(0, 0, -1), 2.0),
                          true, true);
    const std::vector<double> v = rs::IntegrateSensor(g, prop, rs::MakeGrid(g, prop), rs::Quantity::Flux);
    double sum = 0;
    for (double p : v) sum += p * g.pitchX;
    std::printf("Parseval: sum pixel*pitch / (2bE) = %.5f\n", sum / (2 * b * 2.0));
    EXPECT_NEAR(sum / (2 * b * 2.0), 1, 0.01);
    EXPECT_LT(sum / (2 * b * 2.0), 1);  // the tails beyond ±3 mm are missing, never added
}

TEST(Rs, OpenPlateGivesIrradianceTimesCosine) {
    // A 600 µm slit 100 µm above the sensor acts as an open plate for the central pixels: the
    // edge waves arrive at ~70° (their fringes are averaged out by σ = 8 µm) with |U_edge|² ~ 3e-5.
    const SensorPlaneGeometry g = Sensor(100 * Um, 3, 1, 25 * Um, 7.98 * Um);
    ApertureMask m;
    m.AddRect(Vec2(-300 * Um, -1), Vec2(300 * Um, 1));
    for (double deg : {0.0, 10.0}) {
        const double th = Radians(deg), e = 3.0;
        const Propagator prop(PlateFrame{}, m, PlaneWave(1 * Um, Vec3(std::sin(th), 0, -std::cos(th)), e),
                              true, true);
        const std::vector<double> v = rs::IntegrateSensor(g, prop, rs::MakeGrid(g, prop), rs::Quantity::Flux);
        for (double p : v) {
            std::printf("open plate %2.0f deg: flux/(E cos) - 1 = %+.2e\n", deg, p / (e * std::cos(th)) - 1);
            EXPECT_NEAR(p / (e * std::cos(th)), 1, 2e-4) << deg;
        }
    }
}

// ---- 3-D mode ------------------------------------------------------------------------------------

// A disc, plane wave at normal incidence, on the axis: RS-I is exact in closed form,
// U = e^{ikz} − (z/R_a)·e^{ikR_a}, R_a = √(z² + a²) (the radial integrand is a total derivative).
TEST(Rs, DiscOnAxisMatchesClosedForm) {
    const double lambda = 1 * Um, k = 2 * Pi / lambda, a = 50 * Um;
    ApertureMask m;
    m.AddDisc(Vec2(0, 0), a);
    const Propagator prop(PlateFrame{}, m, PlaneWave(lambda, Vec3(0, 0, -1)), true, false);
    for (double z : {200 * Um, 1000 * Um, 3000 * Um}) {
        const double ra = std::hypot(z, a);
        const Complex i(0, 1);
        const Complex u = std::exp(i * k * z) - z / ra * std::exp(i * k * ra);
        // d/dz of the closed form, along the travel direction (−z in the world).
        const Complex du = i * k * std::exp(i * k * z) - std::exp(i * k * ra) / ra -
                           z * (i * k - 1 / ra) * std::exp(i * k * ra) * z / (ra * ra);
        const double flux = (std::conj(u) * du).imag() / k;
        const Vec3 p(0, 0, -z);
        const rs::FieldValue f = prop.Field(p, Vec3(0, 0, -1));
        EXPECT_NEAR(std::norm(f.u), std::norm(u), 1e-9 * std::norm(u)) << z;
        EXPECT_NEAR(prop.Flux(p, Vec3(0, 0, 1)), flux, 1e-9 * std::abs(flux)) << z;
        std::printf("disc on axis z = %4.0f um: |U|^2 = %.10f (closed form %.10f), flux %.10f (%.10f)\n",
                    z / Um, std::norm(f.u), std::norm(u), prop.Flux(p, Vec3(0, 0, 1)), flux);
    }
}

/// Brute-force RS-I (theory §6.2, 3-D form) over a rectangle [u0,u1]×[v0,v1] at point p (plate at
/// z = 0, light towards −z), composite Simpson with `n` intervals per axis; returns U and ∂U/∂m.
rs::FieldValue BruteForce3D(double u0, double u1, double v0, double v1, int nu, int nv, const CoherentWave &w,
                            const Vec3 &p, const Vec3 &m) {
    const double k = 2 * Pi / w.lambda, hu = (u1 - u0) / nu, hv = (v1 - v0) / nv;
    const Complex i(0, 1);
    Complex u = 0, du = 0;
    for (int a = 0; a <= nu; ++a)
        for (int b = 0; b <= nv; ++b) {
            const double wa = (a == 0 || a == nu) ? 1 : (a % 2 ? 4 : 2),
                         wb = (b == 0 || b == nv) ? 1 : (b % 2 ? 4 : 2);
            const Vec3 q(u0 + a * hu, v0 + b * hv, 0);
            Complex u0v;
            if (w.kind == CoherentWave::Kind::Plane) {
                u0v = std::sqrt(w.strength) * std::exp(i * k * Dot(w.dir, q));
            } else {
                const double rho = Length(q - w.pos);
                u0v = std::sqrt(w.strength) * std::exp(i * k * rho) / rho;
            }
            const Vec3 r = p - q;
            const double R = Length(r), z = -r.z;  // distance in front of the plate (towards −z)
            const Complex g = std::exp(i * k * R);
            const Complex kern = z * (1.0 / R - i * k) * g / (R * R);
            // ∇ of z·f(R) with ∇z = (0, 0, −1): −ẑ f + z f'(R) r/R.
            const Complex f = (1.0 - i * k * R) * g / (R * R * R);
            const Complex fp = (k * k * R * R + 3.0 * i * k * R - 3.0) * g / (R * R * R * R);
            const Complex dk = -m.z * f + z * fp * Dot(m, r) / R;
            u += wa * wb * u0v * kern;
            du += wa * wb * u0v * dk;
        }
    const double c = hu * hv / 9 / (2 * Pi);
    return {u * c, du * c};
}

TEST(Rs, ThreeDRectangleMatchesBruteForce) {
    // A 40 × 200 µm rectangle, 2 mm in front, plane wave tilted in x and y, and a point source.
    const double lambda = 1 * Um, z = 2000 * Um;
    ApertureMask m;
    m.AddRect(Vec2(-20 * Um, -100 * Um), Vec2(20 * Um, 100 * Um));
    const CoherentWave plane = PlaneWave(lambda, Vec3(0.05, -0.03, -1), 2.0);
    CoherentWave point;
    point.kind = CoherentWave::Kind::Spherical;
    point.pos = Vec3(30 * Um, 10 * Um, 500 * Um);
    point.strength = 0.7;
    point.lambda = lambda;
    for (const CoherentWave &w : {plane, point}) {
        const Propagator prop(PlateFrame{}, m, w, true, false);
        double worst = 0;
        for (const Vec3 &p : {Vec3(0, 0, -z), Vec3(60 * Um, -20 * Um, -z), Vec3(-150 * Um, 90 * Um, -z)}) {
            const Vec3 mdir = Normalize(Vec3(0.1, 0.2, 1));
            const rs::FieldValue f = prop.Field(p, mdir);
            // Simpson converges as h⁴: Richardson-extrapolate two resolutions (λ/5 and λ/10).
            const rs::FieldValue r1 =
                BruteForce3D(-20 * Um, 20 * Um, -100 * Um, 100 * Um, 200, 1000, w, p, mdir);
            const rs::FieldValue r2 =
                BruteForce3D(-20 * Um, 20 * Um, -100 * Um, 100 * Um, 400, 2000, w, p, mdir);
            const rs::FieldValue r{(16.0 * r2.u - r1.u) / 15.0, (16.0 * r2.dudm - r1.dudm) / 15.0};
            // Compare phase-free quantities: |U|², and U*·∂U.
            const double scale = std::norm(r.u) + 1e-30;
            worst = std::max(worst, std::abs(std::norm(f.u) - std::norm(r.u)) / scale);
            const Complex a = std::conj(f.u) * f.dudm, b = std::conj(r.u) * r.dudm;
            worst = std::max(worst, std::abs(a - b) / std::abs(b));
        }
        std::printf("3-D rectangle (%s): max relative difference to brute-force Simpson = %.2e\n",
                    w.kind == CoherentWave::Kind::Plane ? "plane wave" : "point source", worst);
        EXPECT_LT(worst, 1e-7);
    }
}

TEST(Rs, ThreeDSensorQuadratureIsConverged) {
    // The 40 × 200 µm rectangle on a 3 × 3 sensor: the grid rule against a grid twice as fine and
    // a stricter aperture rule.
    const double lambda = 1 * Um, z = 2000 * Um;
    ApertureMask m;
    m.AddRect(Vec2(-20 * Um, -100 * Um), Vec2(20 * Um, 100 * Um));
    const CoherentWave w = PlaneWave(lambda, Vec3(0.01, 0, -1));
    const SensorPlaneGeometry g = Sensor(z, 3, 3, 25 * Um, 7.98 * Um, false);
    const Propagator prop(PlateFrame{}, m, w, true, false);
    const rs::SensorGrid grid = rs::MakeGrid(g, prop);
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<double> v = rs::IntegrateSensor(g, prop, grid, rs::Quantity::Flux);
    const double t = Seconds(t0);
    rs::QuadratureRule strict;  // π per panel, 12 nodes each
    strict.maxPanelPhase = Pi;
    strict.minNodes = strict.maxNodes = 12;
    const Propagator fine(PlateFrame{}, m, w, true, false, strict);
    const rs::SensorGrid dense = Refined(grid, 2);
    const std::vector<double> refGrid = rs::IntegrateSensor(g, prop, dense, rs::Quantity::Flux);
    const std::vector<double> refRule = rs::IntegrateSensor(g, fine, grid, rs::Quantity::Flux);
    const double eGrid = MaxDiff(v, refGrid) / Peak(refGrid), eRule = MaxDiff(v, refRule) / Peak(refRule);
    std::printf(
        "3-D 40x200 um rect, 3x3 box pixels: %zu nodes in %.2f s; vs 2x denser grid %.2e, vs stricter "
        "aperture rule %.2e of peak\n",
        grid.Nodes(), t, eGrid, eRule);
    EXPECT_LT(eGrid, 1e-6);
    EXPECT_LT(eRule, 1e-8);
    // Deterministic: one thread gives the same bits.
    std::vector<double> single;
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        single = rs::IntegrateSensor(g, prop, grid, rs::Quantity::Flux);
    }
    EXPECT_EQ(single, v);
}

// The integrator's `accuracy` (QuadratureRule::ForAccuracy) holds its target against a far
// stricter rule, on a 3-D rectangle under an oblique wave with Gaussian pixels.
TEST(Rs, AccuracyParameterHoldsItsTarget) {
    ApertureMask m;
    m.AddRect(Vec2(-20 * Um, -100 * Um), Vec2(20 * Um, 100 * Um));
    const CoherentWave w = PlaneWave(1 * Um, Vec3(0.03, 0.01, -1));
    const SensorPlaneGeometry g = Sensor(2000 * Um, 5, 3, 25 * Um, 7.98 * Um);
    auto row = [&](double accuracy) {
        const Propagator p(PlateFrame{}, m, w, true, false, rs::QuadratureRule::ForAccuracy(accuracy));
        return rs::IntegrateSensor(g, p, rs::MakeGrid(g, p), rs::Quantity::Flux);
    };
    const std::vector<double> ref = row(1e-10);
    for (double a : {1e-4, 2e-3, 1e-2}) {
        const double e = MaxDiff(row(a), ref) / Peak(ref);
        std::printf("accuracy %.0e: %.2e of peak from accuracy 1e-10\n", a, e);
        EXPECT_LE(e, a);
    }
}

// The band limit of the grid rule is bounded over the whole window, not sampled: a sensor 30 µm
// behind a 30 µm square at u = 70 µm sees directions spreading by 0.89 only under the opening, a
// spot a 9 × 9 sample of the 1 mm window missed (the grid was then 2.5× too coarse: 1.4e-2 of
// peak). The spacing must satisfy the rule h ≤ 2π/(kΔ + 5/σ) for the spread Δ seen from every
// point of the row (sampled densely here).
TEST(Rs, SensorGridResolvesTheBandUnderAnOffsetOpening) {
    ApertureMask m;
    m.AddRect(Vec2(55 * Um, -15 * Um), Vec2(85 * Um, 15 * Um));
    const double z = 30 * Um, sigma = 7.98 * Um, k = 2 * Pi / Um;
    const SensorPlaneGeometry g = Sensor(z, 41, 1, 25 * Um, sigma);
    const Propagator prop(PlateFrame{}, m, PlaneWave(1 * Um, Vec3(0, 0, -1)), true, false);
    const rs::SensorGrid grid = rs::MakeGrid(g, prop);
    double spread = 0;
    for (double x = -560 * Um; x <= 560 * Um; x += 1 * Um) {
        double lo = Infinity, hi = -Infinity;
        for (int i = 0; i <= 30; ++i)
            for (int j = 0; j <= 30; ++j) {
                const Vec3 q((55 + i) * Um, (-15 + j) * Um, 0);
                const double c = Normalize(Vec3(x, 0, -z) - q).x;
                lo = std::min(lo, c);
                hi = std::max(hi, c);
            }
        spread = std::max(spread, hi - lo);
    }
    const double hRule = 2 * Pi / (k * spread + 5 / sigma);
    std::printf("30 um square 30 um from the sensor: spread %.3f, grid h = %.3f um (rule: <= %.3f um)\n", spread,
                grid.hx / Um, hRule / Um);
    EXPECT_GT(spread, 0.85);
    EXPECT_LE(grid.hx, hRule);
    EXPECT_GT(grid.hx, 0.5 * hRule);  // the bound is not wastefully loose
}

// DirectionSpread never falls below the spread seen from any point of the region (checked on a
// dense sample of the openings' box from random points), in 3-D and 2-D modes.
TEST(Rs, DirectionSpreadBoundsEveryPointOfTheRegion) {
    ApertureMask m;
    m.AddRect(Vec2(-40 * Um, -300 * Um), Vec2(-20 * Um, 300 * Um));
    m.AddRect(Vec2(60 * Um, -300 * Um), Vec2(90 * Um, 300 * Um));
    TestRng rng(7);
    for (bool twoD : {false, true}) {
        const Propagator prop(PlateFrame{}, m, PlaneWave(1 * Um, Vec3(0.05, 0, -1)), true, twoD);
        for (int trial = 0; trial < 20; ++trial) {
            const Vec3 corner((rng.Uniform() - 0.5) * 2e-3, (rng.Uniform() - 0.5) * 1e-3, -(20 + 2000 * rng.Uniform()) * Um);
            const Vec3 es(200 * Um * rng.Uniform(), 0, 0), et(0, 200 * Um * rng.Uniform(), 0);
            for (const Vec3 &axis : {Vec3(1, 0, 0), Vec3(0, 1, 0)}) {
                if (twoD && axis.y != 0) continue;  // the 2-D mode collapses the axis along the slits
                const double bound = prop.DirectionSpread(corner, es, et, axis);
                double worst = 0;
                for (int s = 0; s < 16; ++s) {
                    const Vec3 p = corner + es * rng.Uniform() + et * rng.Uniform();
                    double lo = Infinity, hi = -Infinity;
                    for (int i = 0; i <= 60; ++i)
                        for (int j = 0; j <= (twoD ? 0 : 60); ++j) {
                            const Vec3 q(-40 * Um + 130 * Um * i / 60, twoD ? p.y : -300 * Um + 600 * Um * j / 60, 0);
                            const double c = Dot(Normalize(p - q), axis);
                            lo = std::min(lo, c);
                            hi = std::max(hi, c);
                        }
                    worst = std::max(worst, hi - lo);
                }
                EXPECT_GE(bound, worst) << "trial " << trial << (twoD ? " (2-D)" : "");
                EXPECT_LT(bound, 3 * worst + 0.3) << "trial " << trial;  // not absurdly loose
            }
        }
    }
}

// Finite slits of length L against infinite ones, on the row through their middle: the ends add
// edge waves of relative amplitude 1/(π·w·√2), w = (L/2)·√(2/(λz)) (Fresnel integral asymptotics);
// their fringes along y are averaged out by the pixels, leaving 2·|edge|² = λz/(2π²(L/2)²) of the
// peak (1.3e-4 for the paper's 4000 µm slits, as theory §9 measured).
TEST(Rs, ThreeDLongSlitsApproachTwoD) {
    const double lambda = 1 * Um, z = 1000 * Um, b = 10 * Um, d = 30 * Um, length = 600 * Um;
    const ApertureMask mask = Slits(d, b, length);
    const SensorPlaneGeometry g = Sensor(z, 6, 1, 10 * Um, 3 * Um);
    const CoherentWave w = PlaneWave(lambda, Vec3(0, 0, -1));
    const Propagator p2(PlateFrame{}, mask, w, true, true), p3(PlateFrame{}, mask, w, true, false);
    const auto t0 = std::chrono::steady_clock::now();
    const rs::SensorGrid grid3 = rs::MakeGrid(g, p3);
    const std::vector<double> v3 = rs::IntegrateSensor(g, p3, grid3, rs::Quantity::Flux);
    const double t3 = Seconds(t0);
    const std::vector<double> v2 = rs::IntegrateSensor(g, p2, rs::MakeGrid(g, p2), rs::Quantity::Flux);
    const double e = MaxDiff(v3, v2) / Peak(v2);
    const double expected = lambda * z / (2 * Pi * Pi * Sqr(length / 2));
    std::printf("3-D (L = %.0f um, %zu nodes, %.2f s) vs 2-D: %.2e of peak (edge-wave estimate %.2e)\n",
                length / Um, grid3.Nodes(), t3, e, expected);
    EXPECT_LT(e, 2 * expected);
    EXPECT_GT(e, 0.3 * expected);  // the 3-D mode does see the slit ends
}

// The 2-D mode's error predictor (the Fresnel factor of the slit length, averaged over the pixel)
// against the measured 3-D − 2-D difference: on the middle row and on a row 50 µm from the slit
// ends, where it is a thousand times larger. The factorisation is paraxial along the slits, so the
// prediction is good to tens of per cent, which is what choosing a mode needs.
TEST(Rs, SlitEndErrorPredictsTheThreeDDifference) {
    const double lambda = 1 * Um, k = 2 * Pi / lambda, z = 1000 * Um, b = 10 * Um, d = 30 * Um, length = 600 * Um;
    const ApertureMask mask = Slits(d, b, length);
    const CoherentWave w = PlaneWave(lambda, Vec3(0, 0, -1));
    const Propagator p2(PlateFrame{}, mask, w, true, true), p3(PlateFrame{}, mask, w, true, false);
    Bounds2 slits = mask.Bounds();
    for (double y : {0.0, 250 * Um}) {
        SensorPlaneGeometry g = Sensor(z, 6, 1, 10 * Um, 3 * Um);
        g.origin.y = y;
        const std::vector<double> v3 = rs::IntegrateSensor(g, p3, rs::MakeGrid(g, p3), rs::Quantity::Flux);
        const std::vector<double> v2 = rs::IntegrateSensor(g, p2, rs::MakeGrid(g, p2), rs::Quantity::Flux);
        double measured = 0;  // relative to the local intensity, as predicted
        for (std::size_t i = 0; i < v2.size(); ++i)
            if (v2[i] > 0.1 * Peak(v2)) measured = std::max(measured, std::abs(v3[i] - v2[i]) / v2[i]);
        const double predicted = rs::SlitEndError(PlateFrame{}, slits, g, k);
        std::printf("row at y = %.0f um: 3-D vs 2-D %.3e, predicted %.3e\n", y / Um, measured, predicted);
        EXPECT_GT(predicted, 0.6 * measured) << y;
        EXPECT_LT(predicted, 1.6 * measured) << y;
    }
    // 2 m slits: too many fringes under the pixel to average, so the unaveraged edge-wave bound
    // 2t + t², t ≈ √(λz/2)/(π·1 m) = 7e-6, is used; a row beyond the ends sees almost nothing.
    Bounds2 longer = slits;
    longer.lo.y = -1;
    longer.hi.y = 1;
    EXPECT_LT(rs::SlitEndError(PlateFrame{}, longer, Sensor(z, 6, 1, 10 * Um, 3 * Um), k), 3e-5);
    SensorPlaneGeometry beyond = Sensor(z, 6, 1, 10 * Um, 3 * Um);
    beyond.origin.y = 400 * Um;
    EXPECT_GT(rs::SlitEndError(PlateFrame{}, slits, beyond, k), 0.5);
}

// Point source on the axis behind a large disc: the field is the spherical wave I/R² (plus the
// disc's edge wave), checked against a radial composite-Simpson RS integral.
TEST(Rs, PointSourceThroughLargeDisc) {
    const double lambda = 1 * Um, k = 2 * Pi / lambda, zs = 300 * Um, z = 200 * Um, a = 150 * Um, I = 2.5;
    ApertureMask m;
    m.AddDisc(Vec2(0, 0), a);
    CoherentWave w;
    w.kind = CoherentWave::Kind::Spherical;
    w.pos = Vec3(0, 0, zs);
    w.strength = I;
    w.lambda = lambda;
    const Propagator prop(PlateFrame{}, m, w, true, false);
    // Radial RS integral on the axis: U = z ∫₀^a s (1/R − ik) e^{ik(R+ρ)}/(R²ρ) √I ds.
    const int n = 200000;
    Complex ref = 0;
    const Complex i(0, 1);
    for (int j = 0; j <= n; ++j) {
        const double s = a * j / n, R = std::hypot(z, s), rho = std::hypot(zs, s);
        const double wj = (j == 0 || j == n) ? 1 : (j % 2 ? 4 : 2);
        ref += wj * s * (1 / R - i * k) * std::exp(i * k * (R + rho)) / (R * R * rho);
    }
    ref *= std::sqrt(I) * z * (a / n) / 3;
    const Vec3 p(0, 0, -z);
    const double u2 = std::norm(prop.Field(p, Vec3(0, 0, 1)).u);
    std::printf("point source through a disc, on the axis: |U|^2 = %.10e, radial reference %.10e\n", u2,
                std::norm(ref));
    EXPECT_NEAR(u2, std::norm(ref), 1e-8 * std::norm(ref));
    // Off the axis the rim's edge wave comes from two stationary points only (relative amplitude
    // ~ √(λz_eff)/(π·distance to the rim) ≈ 0.01): |U|² and the flux are the spherical wave's
    // I/R² and I·cosθ/R² to a few per cent.
    for (const Vec3 &q : {Vec3(-30 * Um, 45 * Um, -z)}) {
        const Vec3 r = q - w.pos;
        const double geometric = I / LengthSquared(r), cosTheta = -r.z / Length(r);
        const double uq = std::norm(prop.Field(q, Vec3(0, 0, 1)).u), fq = prop.Flux(q, Vec3(0, 0, 1));
        std::printf("  at (%.0f, %.0f) um: |U|^2 R^2/I = %.4f, flux R^2/(I cos) = %.4f\n", q.x / Um, q.y / Um,
                    uq / geometric, fq / (geometric * cosTheta));
        EXPECT_NEAR(uq / geometric, 1, 0.05);
        EXPECT_NEAR(fq / (geometric * cosTheta), 1, 0.05);
    }
}

// ---- the integrator in a scene --------------------------------------------------------------------

// The double slit of scenes/validation/double_slit.wscene, with markers for the variations below.
const char *const kDoubleSlit = R"(wscene 1
Light "plane_wave" "wave" {
    direction = [0 0 -1]
    irradiance = 2 W/m^2
    spectrum = line(1 um)
}
@LIGHTS@
@APERTURE@
Material "diffuse" "grey" { reflectance = 0.5 }
Shape "rectangle" "plate" {
    width = 20 mm
    height = 20 mm
    material = @@MATERIAL@
    to_world = @PLATE@
}
@SHAPES@
Detector "virtual_plane" "sensor" {
    to_world = @SENSOR@
    extent = @EXTENT@
    pitch = 25 um
    sigma = 7.98 um
    reference_irradiance = 2 W/m^2
}
Detector "perspective" "camera" { resolution = [4 4] }
Integrator "rs" "rs" { @RS@ }
Render { detector = @@DETECTOR@ integrator = @rs }
)";

using Edits = std::vector<std::pair<std::string, std::string>>;

std::unique_ptr<Scene> BuildDoubleSlit(const Edits &edits, std::string *log = nullptr, bool expectBuilt = true) {
    Edits all = {{"@APERTURE@",
                  "Material \"aperture\" \"slits\" { rects = [-70 -2000 -30 2000 30 -2000 70 2000] um }"},
                 {"@LIGHTS@", ""},
                 {"@MATERIAL@", "slits"},
                 {"@PLATE@", "translate([0 0 0] m)"},
                 {"@SHAPES@", ""},
                 {"@SENSOR@", "translate([0 0 -10] mm)"},
                 {"@EXTENT@", "[1200 25] um"},
                 {"@RS@", ""},
                 {"@DETECTOR@", "sensor"}};
    for (auto &[key, value] : all)
        for (const auto &[k, v] : edits)
            if (k == key) value = v;
    std::string text = kDoubleSlit;
    for (const auto &[key, value] : all)
        for (std::size_t pos; (pos = text.find(key)) != std::string::npos;)
            text.replace(pos, key.size(), value);
    Diagnostics diag;
    auto desc = ParseSceneString(text, "rs_test.wscene", DefineList{}, diag);
    std::unique_ptr<Scene> scene;
    if (desc) scene = Scene::Build(*desc, diag);
    std::ostringstream os;
    diag.Print(os);
    if (log) *log = os.str();
    if (expectBuilt) {
        EXPECT_TRUE(scene) << os.str();
    }
    return scene;
}

/// The message of the phasor::Error that rendering `scene` throws ("" if none).
std::string RenderError(const Scene &scene) {
    Film film(scene.GetDetector().Width(), scene.GetDetector().Height(), scene.GetDetector().Response());
    try {
        scene.GetIntegrator().Render(scene, film, RenderOptions{});
    } catch (const Error &e) {
        return e.Message();
    }
    return "";
}

std::vector<double> IntensityRow(const Image &img, int y = 0) {
    std::vector<double> r;
    for (int x = 0; x < img.width; ++x) r.push_back(img.At(x, y, img.ChannelIndex("intensity")));
    return r;
}

TEST(RsScene, DoubleSlitRendersTheCoreResult) {
    auto scene = BuildDoubleSlit({});
    ASSERT_TRUE(scene);
    const Detector &det = scene->GetDetector();
    Film film(det.Width(), det.Height(), det.Response());
    int calls = 0, lastDone = 0, lastTotal = 0;
    RenderOptions opt;
    opt.progress = [&](int done, int total) {
        ++calls;
        EXPECT_GT(done, lastDone);
        lastDone = done;
        lastTotal = total;
    };
    const RenderStats stats = scene->GetIntegrator().Render(*scene, film, opt);
    // rs takes no samples: it says what it solved (issue 10 §2), with its node count as metadata.
    EXPECT_TRUE(scene->GetIntegrator().Deterministic());
    EXPECT_EQ(stats.work.rfind("solved 48 pixels (48x1, 2d) from ", 0), 0u) << stats.work;
    EXPECT_EQ(stats.metadata.at("phasor:rs_mode"), "2d");
    EXPECT_GT(std::stoll(stats.metadata.at("phasor:rs_field_points")), 48);
    EXPECT_FALSE(stats.cancelled);
    EXPECT_TRUE(stats.hasImage);
    EXPECT_GT(calls, 0);
    EXPECT_EQ(lastDone, lastTotal);
    const Image img = film.Resolve();
    ASSERT_EQ(img.width, 48);
    ASSERT_EQ(img.height, 1);
    // The same problem through the core (auto = 2-D here: 4000 µm ≥ 100 × 40 µm), E_ref = E.
    const SensorPlaneGeometry g = Sensor(10000 * Um, 48, 1, 25 * Um, 7.98 * Um);
    const Propagator prop(PlateFrame{}, Slits(100 * Um, 40 * Um, 4000 * Um),
                          PlaneWave(1 * Um, Vec3(0, 0, -1), 2), true, true);
    const std::vector<double> core = rs::IntegrateSensor(g, prop, rs::MakeGrid(g, prop), rs::Quantity::Flux);
    const std::vector<double> row = IntensityRow(img);
    for (int i = 0; i < 48; ++i) {
        EXPECT_NEAR(row[i], core[i] / 2, 1e-6 * Peak(core)) << i;
        EXPECT_EQ(img.At(i, 0, img.ChannelIndex("variance")), 0);
    }
}

// A plate turned by 90° about z (slits along world x) seen by a sensor column along y: the
// auto mode collapses the sensor's x axis (parallel to the slits) and the column reads the row
// of the unrotated scene.

// A stop request (Ctrl-C, SIGTERM) ends rs at once and without an image: a partial field gives
// no pixel that is right (docs/rs.md).
TEST(RsScene, CancelledRenderHasNoImage) {
    auto scene = BuildDoubleSlit({});
    ASSERT_TRUE(scene);
    const Detector &det = scene->GetDetector();
    Film film(det.Width(), det.Height(), det.Response());
    std::atomic<bool> cancel{true};
    RenderOptions opt;
    opt.cancel = &cancel;
    const RenderStats stats = scene->GetIntegrator().Render(*scene, film, opt);
    EXPECT_TRUE(stats.cancelled);
    EXPECT_FALSE(stats.hasImage);
    EXPECT_EQ(stats.work.rfind("stopped after 0 of ", 0), 0u) << stats.work;
    EXPECT_EQ(film.SampleCount(0, 0), 0);
}
TEST(RsScene, RotatedPlateAndSensorColumn) {
    auto base = BuildDoubleSlit({});
    auto turned = BuildDoubleSlit({{"@PLATE@", "rotate(90 deg, [0 0 1])"}, {"@EXTENT@", "[25 1200] um"}});
    ASSERT_TRUE(base && turned);
    const Image a = RenderImage(*base, 1), b = RenderImage(*turned, 1);
    ASSERT_EQ(b.width, 1);
    ASSERT_EQ(b.height, 48);
    // Image y runs downwards along world −y; the pattern is symmetric, so compare mirrored too.
    for (int i = 0; i < 48; ++i)
        EXPECT_NEAR(b.At(0, i, b.ChannelIndex("intensity")), a.At(47 - i, 0, a.ChannelIndex("intensity")),
                    1e-6);
}

// `auto` takes the 2-D mode only where the slit ends are predicted to matter less than
// auto_2d_tolerance: short slits (600 µm) seen 1 mm away on the middle row (predicted 5.7e-4)
// are 2-D for a tolerance of 1e-3 and 3-D for the default 2e-4; a row 50 µm from the ends is
// 3-D even for 1e-3.
TEST(RsScene, AutoModeFollowsThePredictedSlitEndError) {
    const std::string slits = "Material \"aperture\" \"slits\" { rects = [-20 -300 -10 300 10 -300 20 300] um }";
    auto row = [&](const std::string &y, const std::string &rs) {
        auto scene = BuildDoubleSlit({{"@APERTURE@", slits},
                                      {"@SENSOR@", "translate([0 m " + y + " -1 mm])"},
                                      {"@EXTENT@", "[100 25] um"},
                                      {"@RS@", rs}});
        return scene ? IntensityRow(RenderImage(*scene, 1)) : std::vector<double>{};
    };
    const std::vector<double> two = row("0 m", "mode = \"2d\""), three = row("0 m", "mode = \"3d\"");
    ASSERT_EQ(two.size(), 4u);
    ASSERT_GT(MaxDiff(two, three), 1e-4 * Peak(three));  // the modes do differ here
    EXPECT_EQ(row("0 m", "auto_2d_tolerance = 1e-3"), two);
    EXPECT_EQ(row("0 m", ""), three);
    EXPECT_EQ(row("250 um", "auto_2d_tolerance = 1e-3"), row("250 um", "mode = \"3d\""));
}

TEST(RsScene, CancelStopsBeforeWriting) {
    auto scene = BuildDoubleSlit({});
    ASSERT_TRUE(scene);
    Film film(48, 1, scene->GetDetector().Response());
    std::atomic<bool> cancel{true};
    RenderOptions opt;
    opt.cancel = &cancel;
    const RenderStats stats = scene->GetIntegrator().Render(*scene, film, opt);
    EXPECT_TRUE(stats.cancelled);
    EXPECT_EQ(stats.sppReached, 0);
    EXPECT_EQ(film.SampleCount(0, 0), 0);
}

void ExpectRenderError(const Edits &edits, const std::vector<std::string> &fragments) {
    auto scene = BuildDoubleSlit(edits);
    ASSERT_TRUE(scene);
    const std::string msg = RenderError(*scene);
    for (const std::string &f : fragments)
        EXPECT_NE(msg.find(f), std::string::npos) << "'" << f << "' not in: " << msg;
}

TEST(RsScene, UnsupportedScenesAreClearErrors) {
    // Detector, lights, shapes and materials are checked first (a diffuse plate suffices).
    const std::pair<std::string, std::string> grey[] = {{"@APERTURE@", ""}, {"@MATERIAL@", "grey"}};
    auto with = [&](std::pair<std::string, std::string> e) { return Edits{grey[0], grey[1], std::move(e)}; };
    ExpectRenderError(with({"@DETECTOR@", "camera"}), {"virtual_plane", "'camera'"});
    ExpectRenderError(with({"@LIGHTS@", "Light \"directional\" \"sun\" { direction = [0 0 -1] }"}),
                      {"light 'sun'", "monochromatic", "isotropic point lights or Gaussian beams"});
    ExpectRenderError(with({"@LIGHTS@", "Light \"plane_wave\" \"white\" { direction = [0 0 -1] }"}),
                      {"light 'white'", "monochromatic"});
    ExpectRenderError(with({"@LIGHTS@",
                            "Light \"spot\" \"torch\" { from = [0 0 1] m  to = [0 0 0] m  spectrum = "
                            "line(1 um) }"}),
                      {"light 'torch'", "isotropic point lights"});
    ExpectRenderError(
        with({"@SHAPES@", "Shape \"sphere\" \"ball\" { radius = 1 mm  to_world = translate([0 0 5] mm) }"}),
        {"exactly one planar aperture plate", "'plate'", "'ball'"});
    ExpectRenderError(Edits{grey[0], grey[1]}, {"'plate'", "no material with openings"});
}

TEST(RsScene, GeometryErrorsNameTheObjects) {
    ExpectRenderError(
        {{"@LIGHTS@", "Light \"point\" \"lamp\" { position = [0 0 -20] mm  spectrum = line(1 um) }"}},
        {"light 'lamp'", "sensor 'sensor'", "same side", "'plate'"});
    ExpectRenderError({{"@SENSOR@", "[rotate(180 deg, [1 0 0]) translate([0 0 10] mm)]"}},
                      {"light 'wave'", "same side"});
    ExpectRenderError({{"@SENSOR@", "[rotate(180 deg, [1 0 0]) translate([0 0 -10] mm)]"}},
                      {"sensor 'sensor'", "not in front", "faces away"});
    {  // A sensor in the plate's plane is refused when the scene is built (for every integrator).
        std::string log;
        EXPECT_FALSE(BuildDoubleSlit({{"@SENSOR@", "translate([0 0 0] m)"}}, &log, false));
        EXPECT_NE(log.find("rs_test.wscene:17:1: error: sensor 'sensor' lies in the plane of the aperture plate 'plate'"),
                  std::string::npos)
            << log;
    }
    ExpectRenderError({{"@RS@", "mode = \"2d\""},
                       {"@LIGHTS@",
                        "Light \"point\" \"lamp\" { position = [0 0 20] mm  "
                        "spectrum = line(1 um) }"}},
                      {"mode = \"2d\"", "light 'lamp'", "plane wave"});
}

}  // namespace
}  // namespace phasor::test
