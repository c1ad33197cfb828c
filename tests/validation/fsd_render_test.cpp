// SPDX-License-Identifier: Apache-2.0
// Free-space diffraction in full `grt` renders (docs/fsd.md §8): the acceptance tests of issue 24.
//   * Knife edge (scenes/validation/fsd_knife_edge.wscene) at λ = 0.5 µm and 5 mm: the row behind
//     the straight edge of a box mesh against Fresnel's closed form, integrated over the Gaussian
//     pixels, across the shadow boundary and the first 5 fringes, within 2e-2 of the unobstructed
//     irradiance; the same scene without FSD (a sharp shadow) and a reference with the edge moved
//     by a tenth of a Fresnel zone are rejected.
//   * A slit between two boxes and a disc hole in a mesh plate (scenes/validation/fsd_openings.wscene)
//     against `rs` on an aperture plate with the same openings: within 2e-2 of the peak over the
//     central lobe and the first side lobes; a slit 5 % wider is rejected.
//   * Energy: the flux through the slit over a wide row is at most the open flux; a furnace (a
//     uniform emitting room around a white plate, radiance Le everywhere) with every camera GR
//     meeting the plate's edges reads Le, not more (t-test on independent replicas; a 20 % brighter
//     room is rejected).
//   * Edges outside every footprint: fsd on and off render bit-identical images.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/numerics/gauss_legendre.h"
#include "validation/fresnel_reference.h"
#include "support/stats.h"
#include "validation/render_row.h"

namespace phasor {
namespace {

using test::RenderRow;
using test::Row;
const std::string kKnife = test::ValidationScene("fsd_knife_edge.wscene");

// ∫ N(x − xc; σ²)·I(x) dx for the pixel centred at xc (Gauss–Legendre over ±8σ).
template <class I>
double PixelIntegrated(I intensity, double xc, double sigma) {
    return IntegrateGaussLegendre(
        [&](double x) {
            const double u = (x - xc) / sigma;
            return std::exp(-0.5 * u * u) * intensity(x);
        },
        xc - 8 * sigma, xc + 8 * sigma, 32, 8) / (std::sqrt(2 * Pi) * sigma);
}

class FsdRenderKnifeEdge : public ::testing::TestWithParam<double> {};

TEST_P(FsdRenderKnifeEdge, RowMatchesPixelIntegratedFresnel) {
    const double scale = GetParam(), unit = 1e-6 * scale;
    const double lambda = 0.5 * unit, z = 1000 * unit, sigma = 1 * unit;
    const double zone = std::sqrt(lambda * z / 2);  // x = w·zone
    const DefineList defines{{"scale", std::to_string(scale)}};
    Row row = RenderRow(kKnife, defines, "grt");
    ASSERT_EQ(row.v.size(), 55u);
    // Row positions are on the sensor, whose centre is at x0 + width/2 = 25 units.
    for (double &x : row.x) x += 25 * unit;
    auto reference = [&](double shift) {
        std::vector<double> ref;
        for (double xc : row.x)
            ref.push_back(PixelIntegrated([&](double x) { return test::KnifeEdgeIntensity(x - shift, lambda, z); }, xc, sigma));
        return ref;
    };
    const std::vector<double> ref = reference(0), moved = reference(0.1 * zone);
    double worst = 0, worstMoved = 0;
    int counted = 0;
    for (std::size_t i = 0; i < row.v.size(); ++i) {
        const double w = row.x[i] / zone;
        if (w < -1.5 || w > 4.6) continue;  // from the shadow to beyond the 5th bright fringe (w ≈ 4.4)
        ++counted;
        worst = std::max(worst, std::abs(row.v[i] - ref[i]));
        worstMoved = std::max(worstMoved, std::abs(row.v[i] - moved[i]));
        EXPECT_NEAR(row.v[i], ref[i], 2e-2) << "scale " << scale << ", pixel " << i << " (w = " << w << ")";
    }
    EXPECT_GE(counted, 45);
    // sample_solve samples the same paths and solves them forward: the same row.
    const Row solved = RenderRow(kKnife, defines, "sample_solve");
    ASSERT_EQ(solved.v.size(), row.v.size());
    for (std::size_t i = 0; i < row.v.size(); ++i) EXPECT_NEAR(solved.v[i], row.v[i], 1e-6) << "sample_solve, pixel " << i;
    // The tolerance discriminates: the edge a tenth of a zone away, and a sharp shadow, are rejected.
    EXPECT_GT(worstMoved, 2e-2);
    const Row sharp = RenderRow(kKnife, {{"scale", std::to_string(scale)}, {"fsd", "false"}}, "grt");
    double worstSharp = 0;
    for (std::size_t i = 0; i < std::min(sharp.v.size(), ref.size()); ++i)
        worstSharp = std::max(worstSharp, std::abs(sharp.v[i] - ref[i]));
    EXPECT_GT(worstSharp, 0.2);
    std::printf("knife edge x%g through grt: worst |grt - Fresnel| = %.2e (edge moved by 0.1 zone: %.2e, no FSD: %.2e)\n",
                scale, worst, worstMoved, worstSharp);
}

INSTANTIATE_TEST_SUITE_P(Scales, FsdRenderKnifeEdge, ::testing::Values(1.0, 1e4),
                         [](const ::testing::TestParamInfo<double> &i) {
                             return i.param == 1.0 ? std::string("visible") : std::string("mm_wave");
                         });

const std::string kOpenings = test::ValidationScene("fsd_openings.wscene");

TEST(FsdRender, SlitAndHoleOfMeshesMatchRsOnAnAperturePlate) {
    for (const char *opening : {"slit", "hole"}) {
        const Row fsd = RenderRow(kOpenings, {{"opening", opening}}, "grt");
        const Row rs = RenderRow(kOpenings, {{"opening", opening}, {"obstacle", "plate"}}, "rs");
        ASSERT_EQ(fsd.v.size(), 80u);
        ASSERT_EQ(rs.v.size(), fsd.v.size());
        // The central lobe and the first side lobes: |x| ≤ 75 µm covers the first two side lobes of
        // the slit (zeros at λz/b = 25, 50, 75 µm) and of the hole (Airy zeros at 30.5, 55.8 µm).
        const double diff = test::MaxDiffOfPeak(fsd, rs);
        EXPECT_LT(diff, 2e-2) << opening;
        EXPECT_GT(rs.Peak(), 0.3) << opening;  // the lobe is there (the slit 0.77, the hole 0.38)
        std::printf("%s of meshes (grt + fsd) vs rs on an aperture plate: max diff %.2e of the peak\n", opening, diff);
    }
    // The tolerance discriminates: the same slit 5 % wider is rejected.
    const Row fsd = RenderRow(kOpenings, {}, "grt");
    const Row wider = RenderRow(kOpenings, {{"obstacle", "plate"}, {"b", "21 um"}}, "rs");
    EXPECT_GT(test::MaxDiffOfPeak(fsd, wider), 2e-2);
}

TEST(FsdRender, FsdNeverCreatesLight) {
    // Over a row much wider than the pattern, Σ I·pitch is the flux per unit length through the
    // slit (b·E) and at most it: the diffracted light beyond the row and the angles the pixel's
    // GR does not see (docs/fsd.md §5) are lost, nothing is gained. A hole: Σ over a row, at most
    // the flux per unit length of the open lines through it (≤ 2a·E at the centre line).
    const Row slit = RenderRow(kOpenings, {{"width", "2000 um"}}, "grt");
    double flux = 0;
    for (double v : slit.v) flux += v * 2e-6;
    const double open = 20e-6;
    EXPECT_LE(flux, open * (1 + 1e-3));
    EXPECT_GT(flux, 0.9 * open);
    std::printf("slit: flux over a 2 mm row %.4f of the open flux\n", flux / open);
    // Without FSD the sharp slit passes exactly its width (the pixel centres inside it).
    const Row sharp = RenderRow(kOpenings, {{"width", "2000 um"}, {"fsd", "false"}}, "grt");
    double sharpFlux = 0;
    for (double v : sharp.v) sharpFlux += v * 2e-6;
    EXPECT_NEAR(sharpFlux, open, 2e-6 + 1e-9);
}

// A room (a sphere emitting Le = 1 W/m²/sr over the default flat band inwards, black) around a thin
// white plate (albedo 1) whose corner a camera views: radiance Le everywhere. The camera GRs' waist
// (~13 µm) is far below the plate (800 µm): inside the thin-obstacle regime of docs/fsd.md §5.
const char *kFurnace = R"(wscene 2
Define gain = 1
Define fsd = true
Material "diffuse" "white" { reflectance = 1 }
Shape "sphere" "room" { radius = 4 mm }
Light "area" "glow" { shape = @room  two_sided = true  radiance = $gain * 1 W/m^2/sr }
Shape "trianglemesh" "plate" {
    positions = [-4 -4 -4  4 -4 -4  -4 4 -4  4 4 -4  -4 -4 -3.8  4 -4 -3.8  -4 4 -3.8  4 4 -3.8] * 100 um
    indices = [0 2 3  0 3 1   4 5 7  4 7 6   0 1 5  0 5 4   2 6 7  2 7 3   0 4 6  0 6 2   1 3 7  1 7 5]
    material = @white
}
Detector "perspective" "cam" { resolution = [4 1]  fov = 3 deg  to_world = lookat(eye = [0 0 -3] mm, target = [400 400 -400] um, up = [0 1 0]) }
Integrator "grt" "grt" { max_depth = -1  rr_depth = 1  fsd = $fsd }
Render { detector = @cam  integrator = @grt  spp = 64 }
)";

TEST(FsdRender, FurnaceWithEdgesReadsTheRoomsRadiance) {
    constexpr double FlatBand = 470e-9;  // the default flat band [m]: pixels read Le / FlatBand
    auto mean = [&](const char *gain) {
        auto scene = test::BuildSceneText(kFurnace, "", {{"gain", gain}});
        return scene ? test::ImageOverReplicas(test::RenderReplicas(*scene, 128, 12, 7)) : test::ReplicaEstimate{};
    };
    const test::ReplicaEstimate e = mean("1");
    const test::TTestResult t = test::MeanTTest(e.mean, e.varianceOfMean, e.dof, 1 / FlatBand);
    EXPECT_GT(t.pValue, 1e-3) << t.ToString();
    std::printf("furnace with edges: %.5f ± %.5f of Le (%s)\n", e.mean * FlatBand, e.StdError() * FlatBand,
                t.ToString().c_str());
    const test::ReplicaEstimate b = mean("1.2");
    EXPECT_LT(test::MeanTTest(b.mean, b.varianceOfMean, b.dof, 1 / FlatBand).pValue, 1e-3);
}

TEST(FsdRender, EdgesOutsideEveryFootprintRenderBitIdentical) {
    // The box behind the sensor: no GR's footprint meets it; paths are traced (4 spp over the
    // sensor's directions), the plane wave measured in closed form.
    auto render = [&](const char *fsd) {
        auto scene = test::BuildValidation(kKnife, {{"fsd", fsd}, {"edge_z", "-3000 um"}, {"spp", "4"}}, "grt");
        return scene ? test::RenderImage(*scene, 4) : Image{};
    };
    const Image on = render("true"), off = render("false");
    ASSERT_EQ(on.width, off.width);
    ASSERT_GT(on.width, 0);
    const int c = on.ChannelIndex("intensity");
    int differ = 0;
    double sum = 0;
    for (int y = 0; y < on.height; ++y)
        for (int x = 0; x < on.width; ++x) {
            differ += on.At(x, y, c) != off.At(x, y, c);
            sum += on.At(x, y, c);
        }
    EXPECT_EQ(differ, 0);
    EXPECT_NEAR(sum / (on.width * on.height), 1.0, 1e-6);  // the unobstructed plane wave
}

}  // namespace
}  // namespace phasor
