// SPDX-License-Identifier: Apache-2.0
// Free-space diffraction against Fresnel's knife edge (Born & Wolf §8.7): a plane wave passes the
// straight edge of a box mesh; a generalized ray leaves a detector point a distance z behind it
// (waist β0, travelling back towards the source) and meets the edge inside its footprint. What
// the FSD lobe passes, |A|² relative to the unobstructed GR's, must be the overlap of the
// detector's Gaussian mode with Fresnel's diffracted field, |∫ψ0·U|² / |∫ψ0·U0|², by the
// exactness of paraxial propagation (Parseval between the event plane and the detector plane).
// ψ0 is real (a waist), so the reference does not depend on the phase convention. This is the
// lobe's physics alone; the path integration is tested elsewhere (docs/fsd.md §7).
#include <gtest/gtest.h>

#include <cmath>

#include "core/numerics/gauss_legendre.h"
#include "fsd_test_util.h"
#include "integrators/fsd/fsd_geometry.h"
#include "integrators/fsd/fsd_lobe.h"
#include "parser/parser.h"
#include "validation/fresnel_reference.h"

namespace phasor {
namespace {

using namespace test;

// Fresnel's knife-edge field relative to the incident plane wave, the screen covering x < 0, a
// distance z behind it: (1/√(2i))·[(½ + C(w)) + i(½ + S(w))], w = x·√(2/(λz)). |·|² is
// KnifeEdgeIntensity.
Complex KnifeEdgeField(double x, double lambda, double z) {
    const Complex cs = Fresnel(x * std::sqrt(2 / (lambda * z)));
    return Complex(0.5 + cs.real(), 0.5 + cs.imag()) / std::sqrt(Complex(0, 2));
}

// |∫ψ0(x)·U(x) dx|² / |∫ψ0(x) dx|², ψ0(x) = exp(−(x − x0)²/(2β0²)) (the y factor cancels).
double ModeOverlap(double x0, double beta0, double lambda, double z) {
    const Complex a = IntegrateGaussLegendre(
        [&](double x) {
            const double u = (x - x0) / beta0;
            return std::exp(-0.5 * u * u) * KnifeEdgeField(x, lambda, z);
        },
        x0 - 9 * beta0, x0 + 9 * beta0, 32, 16);
    return std::norm(a) / (2 * Pi * beta0 * beta0);
}

class FsdKnifeEdge : public ::testing::TestWithParam<double> {};

TEST(FresnelReference, FieldAndLimits) {
    // C(∞) = S(∞) = ½; C(1) = 0.7798934, S(1) = 0.4382591 (Abramowitz & Stegun, Table 7.7);
    // |U|² is the tabulated intensity: ¼ at the geometric shadow boundary.
    EXPECT_NEAR(Fresnel(1).real(), 0.7798934, 1e-7);
    EXPECT_NEAR(Fresnel(1).imag(), 0.4382591, 1e-7);
    EXPECT_NEAR(Fresnel(60).real(), 0.5, 6e-3);
    EXPECT_NEAR(KnifeEdgeIntensity(0, 1, 1), 0.25, 1e-15);
    for (double x : {-2.0, -0.3, 0.7, 3.1}) EXPECT_NEAR(std::norm(KnifeEdgeField(x, 1, 1)), KnifeEdgeIntensity(x, 1, 1), 1e-14);
}

TEST_P(FsdKnifeEdge, LobeMatchesFresnelAcrossTheShadowBoundaryAndFiveFringes) {
    const double scale = GetParam();
    const double um = 1e-6 * scale, lambda = 0.5 * um;
    // A box covering x < 0, 2 (scaled) µm thick, much wider than the footprint along y.
    const std::string box = Box(Vec3(-4000 * scale, -4000 * scale, 0), Vec3(0, 4000 * scale, 2 * scale)).Shape("edge");
    auto scene = BuildFsdScene(box, 500 * scale);
    ASSERT_TRUE(scene);
    const fsd::Occluders occ(*scene);
    fsd::Settings st;
    st.enabled = true;
    const double zDet = 1002 * um, beta0 = 3 * um;
    const SampledWavelengths wl = OneWavelength(lambda);
    // From 3 fringe periods deep in the shadow to beyond the 5th bright fringe (w ≈ 4.4).
    const double zone = std::sqrt(lambda * 1000 * um / 2);  // x = w·zone
    double worst = 0, shifted = 0;
    int events = 0;
    for (double w = -1.5; w <= 4.6; w += 0.1) {
        const double x0 = w * zone;
        SpectralGenRay g = OneWavelengthGr(Vec3(x0, 0, zDet), Vec3(0, 0, -1), lambda, beta0 * beta0, 0);
        fsd::Event ev;
        const fsd::Search r = fsd::FindEvent(*scene, occ, g, Infinity, nullptr, st, &ev);
        double fsdValue;
        if (r == fsd::Search::Event) {
            ++events;
            const double z = ev.t;  // from the event plane (the box's back face) to the detector
            g.Propagate(ev.t);
            fsd::Event free = ev;
            free.edges.clear();
            free.mask = DecomposeUnion({}, 2 * ev.halfWidth, ev.halfWidth);
            const fsd::Lobe lobe(ev, g, wl, st), open(free, g, wl, st);
            const Vec3 s(0, 0, 1);  // the plane wave's direction of travel
            fsdValue = std::norm(lobe.Amplitude(0, s)) / std::norm(open.Amplitude(0, s));
            const double ref = ModeOverlap(x0, beta0, lambda, z);
            worst = std::max(worst, std::abs(fsdValue - ref));
            // The tolerance discriminates: the edge moved by a tenth of a zone is caught.
            shifted = std::max(shifted, std::abs(fsdValue - ModeOverlap(x0 + 0.1 * zone, beta0, lambda, z)));
            EXPECT_NEAR(fsdValue, ref, 2e-2) << "scale " << scale << ", w = " << w << " (x0 = " << x0 / um << " µm)";
        } else {
            // Only far from the edge may the footprint miss it (none) or lie wholly behind it.
            ADD_FAILURE() << "no event at w = " << w;
        }
    }
    EXPECT_GT(events, 50);
    EXPECT_GT(shifted, 2e-2);
    std::printf("knife edge ×%g: worst |FSD − Fresnel| = %.2e of the unobstructed value\n", scale, worst);
}

INSTANTIATE_TEST_SUITE_P(Scales, FsdKnifeEdge, ::testing::Values(1.0, 1e4),
                         [](const ::testing::TestParamInfo<double> &i) {
                             return i.param == 1.0 ? std::string("visible") : std::string("mm_wave");
                         });

}  // namespace
}  // namespace phasor
