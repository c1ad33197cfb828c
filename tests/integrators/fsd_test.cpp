// SPDX-License-Identifier: Apache-2.0
// Free-space diffraction (integrators/fsd): the event search on Embree, the edge detector and the
// shadow mask, the lobe's amplitude against brute-force quadrature and its normalisation against the
// closed-form measurement of an unobstructed GR (theory §2.4, §4.8; docs/fsd.md).
#include <gtest/gtest.h>

#include <cmath>

#include "core/numerics/gauss_legendre.h"
#include "fsd_test_util.h"
#include "integrators/fsd/fsd_geometry.h"
#include "integrators/fsd/fsd_lobe.h"
#include "parser/parser.h"

namespace phasor {
namespace {

using namespace test;

constexpr double Um = 1e-6;
constexpr double Lambda = 0.5e-6;

std::unique_ptr<Scene> Build(const std::string &shapes) { return BuildFsdScene(shapes); }

// The knife edge: a thin box covering x < 0 (|y| < 200 µm, z ∈ [0, 2] µm), seen by GRs travelling
// towards +z from z = −50 µm.
const std::string KnifeEdge = Box(Vec3(-200, -200, 0), Vec3(0, 200, 2)).Shape("edge");

TEST(FsdGeometry, KnifeEdgeEventAndMask) {
    auto scene = Build(KnifeEdge);
    ASSERT_TRUE(scene);
    fsd::Occluders occ(*scene);
    fsd::Settings s;
    s.enabled = true;
    const double beta2 = std::pow(4 * Um, 2);
    for (double x0 : {3.0, -2.0, 9.0}) {
        const SpectralGenRay g = OneWavelengthGr(Vec3(x0 * Um, 0, -50 * Um), Vec3(0, 0, 1), Lambda, beta2, 0);
        fsd::Event ev;
        const fsd::Search r = fsd::FindEvent(*scene, occ, g, Infinity, nullptr, s, &ev);
        ASSERT_EQ(r, fsd::Search::Event) << "x0 = " << x0;
        // The event sits at the box's near face (the nearest approach to the edge).
        EXPECT_NEAR(ev.t, 50 * Um, 1e-12);
        // The covered fraction of a straight edge at distance δ from the centre: ½erfc(δ/β), with
        // β the footprint at the event (the GR has spread over 50 µm).
        const double b2 = fsd::Beta2At(g.k[0], beta2, 0, ev.t);
        // The mask's box stops at ±ϱ = ±4β across the edge: erfc(4)/2 ≈ 8·10⁻⁹ is missing.
        EXPECT_NEAR(ev.coveredFraction, 0.5 * std::erfc(x0 * Um / std::sqrt(b2)), 3e-8) << "x0 = " << x0;
        // The outline in the window: the front face's and the back face's edges along x = 0 (both
        // silhouettes for a GR along z; the side faces are edge-on; each face's diagonal cancels).
        int alongEdge = 0;
        for (const OrientedSegment &e : ev.edges) {
            const double xa = Dot(ev.p + ev.frame.s * e.a.x + ev.frame.t * e.a.y, Vec3(1, 0, 0));
            const double xb = Dot(ev.p + ev.frame.s * e.b.x + ev.frame.t * e.b.y, Vec3(1, 0, 0));
            if (std::abs(xa) < 1e-12 && std::abs(xb) < 1e-12) ++alongEdge;
            // No diagonal of a face survives inside the mask's box (one whose other triangle lies
            // outside the gather ball is kept, but then outside the box too).
            const bool inBox = std::abs(0.5 * (e.a.x + e.b.x)) < 2 * ev.halfWidth &&
                               std::abs(0.5 * (e.a.y + e.b.y)) < ev.halfWidth;
            EXPECT_FALSE(inBox && std::abs(xa - xb) > 1e-9 && std::abs(e.a.y - e.b.y) > 1e-9)
                << "a diagonal edge survived: " << e.a.x << "," << e.a.y << " → " << e.b.x << "," << e.b.y;
        }
        EXPECT_EQ(alongEdge, 2);
    }
}

TEST(FsdGeometry, NoneBlockedAndNegligible) {
    auto scene = Build(KnifeEdge);
    ASSERT_TRUE(scene);
    fsd::Occluders occ(*scene);
    fsd::Settings s;
    s.enabled = true;
    fsd::Event ev;
    const double beta2 = std::pow(4 * Um, 2);
    // Far from the edge on the open side: the geometry never enters 4β.
    EXPECT_EQ(fsd::FindEvent(*scene, occ, OneWavelengthGr(Vec3(60 * Um, 0, -50 * Um), Vec3(0, 0, 1), Lambda, beta2, 0),
                             Infinity, nullptr, s, &ev),
              fsd::Search::None);
    // Deep in the shadow: the box covers the whole footprint.
    EXPECT_EQ(fsd::FindEvent(*scene, occ, OneWavelengthGr(Vec3(-60 * Um, 0, -50 * Um), Vec3(0, 0, 1), Lambda, beta2, 0),
                             Infinity, nullptr, s, &ev),
              fsd::Search::Blocked);
    // Travelling away from the box: nothing ahead.
    EXPECT_EQ(fsd::FindEvent(*scene, occ, OneWavelengthGr(Vec3(3 * Um, 0, -50 * Um), Vec3(0, 0, -1), Lambda, beta2, 0),
                             Infinity, nullptr, s, &ev),
              fsd::Search::None);
    // A segment that ends before the box (the mean ray hit something at t = 20 µm).
    EXPECT_EQ(fsd::FindEvent(*scene, occ, OneWavelengthGr(Vec3(3 * Um, 0, -50 * Um), Vec3(0, 0, 1), Lambda, beta2, 0),
                             20 * Um, nullptr, s, &ev),
              fsd::Search::None);
}

TEST(FsdGeometry, HoleInAPlateKeepsOnlyItsRim) {
    // A single-sided plate with a circular hole of 32 segments: the ring's interior edges cancel;
    // what bounds the shadow are the hole's 32 rim edges (and the plate's outline, outside the ball).
    const double r = 10;
    auto scene = Build(HolePlate(400, 0, 32, [&](double) { return r; }).Shape("plate"));
    ASSERT_TRUE(scene);
    fsd::Occluders occ(*scene);
    fsd::Settings s;
    s.enabled = true;
    fsd::Event ev;
    const SpectralGenRay g = OneWavelengthGr(Vec3(2 * Um, 1 * Um, -30 * Um), Vec3(0, 0, 1), Lambda, std::pow(6 * Um, 2), 0);
    ASSERT_EQ(fsd::FindEvent(*scene, occ, g, Infinity, nullptr, s, &ev), fsd::Search::Event);
    // The square's 32 outer edges are kept too (they fix the winding number) but lie far outside.
    int near = 0;
    for (const OrientedSegment &e : ev.edges) near += Length(0.5 * (e.a + e.b)) < ev.gatherRadius;
    EXPECT_EQ(near, 32);
    // The open part of the box is the hole: its |ψ|² mass against a direct sum over a fine grid.
    double open = 1 - ev.coveredFraction, grid = 0;
    const double beta = std::sqrt(ev.heroBeta2), h = 0.05 * Um;
    for (double x = -r * Um; x < r * Um; x += h)
        for (double y = -r * Um; y < r * Um; y += h) {
            const double px = x + 0.5 * h, py = y + 0.5 * h;
            if (px * px + py * py > r * r * Um * Um) continue;
            // The GR centre is at (2, 1) µm: plane coordinates are relative to it (the frame's axes
            // are some rotation of x, y; the Gaussian is isotropic).
            const double dx = px - 2 * Um, dy = py - 1 * Um;
            grid += std::exp(-(dx * dx + dy * dy) / (beta * beta)) / (Pi * beta * beta) * h * h;
        }
    // The 32-gon has a slightly different area than the circle: 1 − sin(2π/32)·32/(2π) = 0.64 %.
    EXPECT_NEAR(open, grid, 0.007 * grid);
}

// Brute force: A(s) for a unit plane wave along s of a GR (traced direction n = frame.n, β², ρ)
// over the open part of the event's box, by a product Gauss–Legendre rule split at the mask's
// slab boundaries (each trapezoid integrated on its own with many nodes).
Complex BruteAmplitude(const fsd::Event &ev, double k, double beta2, double rho, const Vec3 &s, double window) {
    const Frame &f = ev.frame;
    const double s1 = Dot(s, f.s), s2 = Dot(s, f.t);
    const double rw = window * std::sqrt(beta2);
    const Complex gamma = Complex(1, -rho) / (2 * beta2);
    Complex sum = 0;
    for (const Trapezoid &t : ev.mask.open) {
        const double v0 = std::max(t.v0, -rw), v1 = std::min(t.v1, rw);
        if (!(v1 > v0)) continue;
        sum += IntegrateGaussLegendre(
            [&](double v) {
                const double lo = std::max(t.Lo(v), -2 * rw), hi = std::min(t.Hi(v), 2 * rw);
                if (!(hi > lo)) return Complex(0);
                return IntegrateGaussLegendre(
                    [&](double u) {
                        return std::exp(-gamma * (u * u + v * v) + Complex(0, k * (s1 * u + s2 * v)));
                    },
                    lo, hi, 32, 8);
            },
            v0, v1, 32, 8);
    }
    return sum / std::sqrt(Pi * beta2);
}

TEST(FsdLobe, AmplitudeMatchesBruteForce) {
    // The closed-form/Gauss–Legendre amplitude of the lobe (Babinet or direct) against a dense
    // product rule (32 nodes × 8 panels per axis per trapezoid; 64 × 16 changes it by < 10⁻¹⁰), for a straight edge, a wedge (a box's corner) and a star-shaped hole, with and
    // without the GR's curvature, straight through and oblique.
    const std::string wedge = Box(Vec3(-200, -200, 0), Vec3(0, 0, 2)).Shape("corner");
    const std::string star = HolePlate(400, 0, 40, Star(9, 4, 5)).Shape("star");
    const std::string post = Box(Vec3(-1.5, -1, 0), Vec3(1.5, 1, 2)).Shape("post");  // Babinet: few covered pieces
    struct Case {
        std::string shapes;
        Vec3 o;
    };
    const std::vector<Case> cases = {{KnifeEdge, Vec3(3 * Um, 0, -50 * Um)},
                                     {wedge, Vec3(2 * Um, 3 * Um, -40 * Um)},
                                     {star, Vec3(1 * Um, -1 * Um, -30 * Um)},
                                     {post, Vec3(0.5 * Um, 0.2 * Um, -30 * Um)}};
    for (const Case &c : cases) {
        auto scene = Build(c.shapes);
        ASSERT_TRUE(scene);
        fsd::Occluders occ(*scene);
        fsd::Settings st;
        st.enabled = true;
        for (double rho : {0.0, 4.0}) {
            const double beta2 = std::pow(3 * Um, 2);
            SpectralGenRay g = OneWavelengthGr(c.o, Vec3(0.02, -0.01, 1), Lambda, beta2, rho);
            fsd::Event ev;
            ASSERT_EQ(fsd::FindEvent(*scene, occ, g, Infinity, nullptr, st, &ev), fsd::Search::Event);
            g.Propagate(ev.t);
            const SampledWavelengths wl = OneWavelength(Lambda);
            const fsd::Lobe lobe(ev, g, wl, st);
            for (const Vec3 &w : {Vec3(0, 0, 1), Vec3(0.05, 0.03, 1), Vec3(-0.2, 0.1, 1)}) {
                const Vec3 s = -Normalize(ev.frame.ToWorld(w));
                const Complex a = lobe.Amplitude(0, s);
                const Complex b = BruteAmplitude(ev, g.k[0], g.beta2[0], g.rho[0], s, st.window);
                // Relative to the unobstructed amplitude √(πβ²): worst measured 3·10⁻⁶ (the knife
                // edge with ρ = 4, straight through), elsewhere ≤ 10⁻⁷.
                EXPECT_NEAR(std::abs(a - b), 0, 1e-5 * std::sqrt(Pi * g.beta2[0]))
                    << c.o.x / Um << " µm: ρ = " << rho << ", w = " << w.x << "," << w.y << ": " << a << " vs " << b;
            }
        }
    }
}

TEST(FsdLobe, UnobstructedGrMatchesTheClosedFormMeasurement) {
    // An event whose mask is empty is a free GR: f·(wo·d)·E must be the camera-unit closed form
    // k²·M of a plane wave (theory §2.4 item 2) for the physical GR, to the window's truncation.
    fsd::Event ev;
    ev.p = Vec3(0, 0, 0);
    ev.frame = Frame::FromNormal(Vec3(0, 0, 1));
    const double beta2 = std::pow(2 * Um, 2);
    ev.halfWidth = 4 * std::sqrt(beta2);
    ev.heroBeta2 = beta2;
    ev.mask = DecomposeUnion({}, 2 * ev.halfWidth, ev.halfWidth);
    fsd::Settings st;
    for (double rho : {0.0, 2.5, -3.0}) {
        const SpectralGenRay g = OneWavelengthGr(ev.p, ev.frame.n, Lambda, beta2, rho);
        const SampledWavelengths wl = OneWavelength(Lambda);
        const fsd::Lobe lobe(ev, g, wl, st);
        for (double a : {0.0, 0.02, 0.06}) {
            const Vec3 wo = Normalize(Vec3(a, 0.3 * a, 1));
            const double f = lobe.Eval(wo)[0] * Dot(wo, ev.frame.n);
            const GenRay physical = g.At(0).TimeReversed();
            const double m = g.k[0] * g.k[0] * MeasurePlaneWave(physical, -wo, 1.0);
            EXPECT_NEAR(f, m, 2e-3 * m + 1e-12 * g.k[0] * g.k[0] * beta2) << "ρ = " << rho << ", tilt " << a;
        }
    }
}

}  // namespace
}  // namespace phasor

namespace phasor {
namespace {

// |ψ|² mass (waist form, β at the event) of the region `inside` of the event plane, by a grid sum
// over the footprint's box (plane coordinates relative to the GR's centre).
template <typename Inside>
double GridMass(const fsd::Event &ev, Inside inside) {
    const double beta = std::sqrt(ev.heroBeta2), h = beta / 100;
    double sum = 0;
    for (double u = -5 * beta; u < 5 * beta; u += h)
        for (double v = -5 * beta; v < 5 * beta; v += h) {
            const double pu = u + 0.5 * h, pv = v + 0.5 * h;
            if (!inside(ev.p + ev.frame.s * pu + ev.frame.t * pv)) continue;
            sum += std::exp(-(pu * pu + pv * pv) / ev.heroBeta2) / (Pi * ev.heroBeta2) * h * h;
        }
    return sum;
}

TEST(FsdGeometry, AnalyticSphereOutlineAndDiskRim) {
    // A sphere's outline (a circle in every projection) and a tilted disk's rim (an ellipse) enter
    // the mask as polygons of the curve's area: the covered mass matches a grid sum over the exact
    // curve to the grid's resolution.
    fsd::Settings s;
    s.enabled = true;
    const double beta2 = std::pow(3 * Um, 2);
    {
        auto scene = Build("Shape \"sphere\" \"ball\" { radius = 20 um }\n");
        ASSERT_TRUE(scene);
        fsd::Occluders occ(*scene);
        fsd::Event ev;
        const SpectralGenRay g = OneWavelengthGr(Vec3(21 * Um, 2 * Um, -100 * Um), Vec3(0, 0, 1), Lambda, beta2, 0);
        ASSERT_EQ(fsd::FindEvent(*scene, occ, g, Infinity, nullptr, s, &ev), fsd::Search::Event);
        // The nearest approach is at the sphere's equator, z = 0.
        EXPECT_NEAR(ev.t, 100 * Um, 1e-3 * Um);
        const double ref = GridMass(ev, [](const Vec3 &x) { return x.x * x.x + x.y * x.y < std::pow(20 * Um, 2); });
        EXPECT_NEAR(ev.coveredFraction, ref, 3e-3) << ev.coveredFraction << " vs " << ref;
        EXPECT_GT(ref, 0.2);
    }
    {
        // A disk of radius 15 µm tilted by 40° about x (normal in the y–z plane), centred at z = 0.
        auto scene = Build("Shape \"disk\" \"lid\" { radius = 15 um  to_world = rotate(40 deg, [1 0 0]) }\n");
        ASSERT_TRUE(scene);
        fsd::Occluders occ(*scene);
        fsd::Event ev;
        const SpectralGenRay g = OneWavelengthGr(Vec3(2 * Um, 11 * Um, -100 * Um), Vec3(0, 0, 1), Lambda, beta2, 0);
        ASSERT_EQ(fsd::FindEvent(*scene, occ, g, Infinity, nullptr, s, &ev), fsd::Search::Event);
        // Projected along z the rim is the ellipse x² + (y/cos40°)² < r².
        const double c = std::cos(40 * Pi / 180), r = 15 * Um;
        const double ref = GridMass(ev, [&](const Vec3 &x) { return x.x * x.x + std::pow(x.y / c, 2) < r * r; });
        EXPECT_NEAR(ev.coveredFraction, ref, 3e-3) << ev.coveredFraction << " vs " << ref;
        EXPECT_GT(ref, 0.2);
        EXPECT_LT(ref, 0.8);
    }
}

}  // namespace
}  // namespace phasor
