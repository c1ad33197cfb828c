// SPDX-License-Identifier: Apache-2.0
// Free-space diffraction against the `aperture` kernel (theory §9): the same opening made two ways —
// a disc hole as a triangulated plate (a 256-gon) or a slit between two box meshes for FSD; an
// analytic disc or rectangle opening of an `aperture` plate for the kernel — seen by the same GR
// must give the same lobe f(ω_o). The two share the closed-form strip integral, but not the mask:
// FSD finds the opening from the meshes' edges (edge detection, projection, winding-number union)
// and the kernel from its own parameters (its disc pieces are integrated along arcs).
#include <gtest/gtest.h>

#include <cmath>

#include "fsd_test_util.h"
#include "integrators/fsd/fsd_geometry.h"
#include "integrators/fsd/fsd_lobe.h"
#include "integrators/gr_path.h"
#include "parser/parser.h"

namespace phasor {
namespace {

using namespace test;

constexpr double Um = 1e-6;
constexpr double Lambda = 0.5e-6;

std::unique_ptr<Scene> Build(const std::string &shapes) { return BuildFsdScene(shapes); }

std::string AperturePlate(const std::string &openings) {
    return "Material \"aperture\" \"ap\" { " + openings +
           " }\nShape \"rectangle\" \"plate\" { width = 800 um  height = 800 um  material = @ap }\n";
}

// Largest |f_FSD − f_aperture| over directions up to θmax, relative to the largest f_aperture; the
// GR starts at o (µm) towards +z with waist β0 and meets the plane z = 0.
double WorstDifference(const Scene &meshes, const Scene &plate, const Vec3 &o, double beta0, double thetaMax) {
    const fsd::Occluders occ(meshes);
    fsd::Settings st;
    st.enabled = true;
    const SampledWavelengths wl = OneWavelength(Lambda);
    SpectralGenRay g = OneWavelengthGr(o * Um, Vec3(0, 0, 1), Lambda, std::pow(beta0 * Um, 2), 0);
    fsd::Event ev;
    EXPECT_EQ(fsd::FindEvent(meshes, occ, g, Infinity, nullptr, st, &ev), fsd::Search::Event);
    EXPECT_NEAR(ev.t, -o.z * Um, 1e-12);
    const auto si = plate.Intersect(g.MeanRay());
    EXPECT_TRUE(si && si->material);
    if (!si || !si->material) return Infinity;
    g.Propagate(ev.t);
    const fsd::Lobe lobe(ev, g, wl, st);
    SpectralGenRay gp = g;
    gp.o = si->p;
    const ScatterQuery q = grpath::GrQuery(*si, gp, false, wl);
    ScratchBuffer scratch;
    const PreparedKernel &k = si->material->Prepare(q, scratch);
    double worst = 0, peak = 0;
    for (int a = 0; a < 3; ++a) {
        const double phi = a * Pi / 5;
        for (int i = 0; i <= 40; ++i) {
            const double th = thetaMax * i / 40;
            const Vec3 wo(std::sin(th) * std::cos(phi), std::sin(th) * std::sin(phi), std::cos(th));
            const double ff = lobe.Eval(wo)[0];
            const double fa = k.Eval(si->shading.ToLocal(wo))[0];
            peak = std::max(peak, fa);
            worst = std::max(worst, std::abs(ff - fa));
        }
    }
    return worst / peak;
}

TEST(FsdVsAperture, DiscHoleInAMeshPlate) {
    // r = 10 µm = 20 λ; the 256-gon's area is the disc's to 10⁻⁴. First Airy zero at
    // θ ≈ 0.61λ/r = 0.03 rad; out to 0.15 rad covers the central lobe and several side lobes.
    auto meshes = Build(HolePlate(400, 0, 256, [](double) { return 10.0; }).Shape("plate"));
    auto plate = Build(AperturePlate("discs = [0 um 0 um 10 um]"));
    ASSERT_TRUE(meshes && plate);
    for (const Vec3 &o : {Vec3(2, -1, -30), Vec3(-6, 3, -30), Vec3(1, 1, -300)}) {
        for (double beta0 : {4.0, 8.0}) {
            const double w = WorstDifference(*meshes, *plate, o, beta0, 0.15);
            EXPECT_LT(w, 2e-2) << "GR from (" << o.x << ", " << o.y << ", " << o.z << ") µm, β0 = " << beta0;
            std::printf("disc hole, GR from (%g, %g, %g) µm, β0 = %g µm: worst %.2e of peak\n", o.x, o.y, o.z, beta0, w);
        }
    }
    // The tolerance discriminates: a disc 5 % larger (or moved by 1 µm) is caught.
    auto larger = Build(AperturePlate("discs = [0 um 0 um 10.5 um]"));
    auto moved = Build(AperturePlate("discs = [1 um 0 um 10 um]"));
    ASSERT_TRUE(larger && moved);
    EXPECT_GT(WorstDifference(*meshes, *larger, Vec3(2, -1, -30), 4, 0.15), 2e-2);
    EXPECT_GT(WorstDifference(*meshes, *moved, Vec3(2, -1, -30), 4, 0.15), 2e-2);
}

TEST(FsdVsAperture, SlitBetweenTwoBoxes) {
    // A slit 8 µm wide along y between two 1 µm thick boxes; the kernel's opening is the same
    // rectangle, longer than any footprint. First zero at θ ≈ λ/b = 0.06 rad.
    const std::string boxes = Box(Vec3(-400, -400, 0), Vec3(-4, 400, 1)).Shape("left") +
                              Box(Vec3(4, -400, 0), Vec3(400, 400, 1)).Shape("right");
    auto meshes = Build(boxes);
    auto plate = Build(AperturePlate("rects = [-4 um -390 um 4 um 390 um]"));
    ASSERT_TRUE(meshes && plate);
    for (const Vec3 &o : {Vec3(1, 0, -30), Vec3(-3, 5, -30), Vec3(0.5, 0, -300)}) {
        for (double beta0 : {4.0, 8.0}) {
            const double w = WorstDifference(*meshes, *plate, o, beta0, 0.2);
            EXPECT_LT(w, 2e-2) << "GR from (" << o.x << ", " << o.y << ", " << o.z << ") µm, β0 = " << beta0;
            std::printf("slit, GR from (%g, %g, %g) µm, β0 = %g µm: worst %.2e of peak\n", o.x, o.y, o.z, beta0, w);
        }
    }
}

}  // namespace
}  // namespace phasor
