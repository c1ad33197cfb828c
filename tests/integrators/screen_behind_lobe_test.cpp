// SPDX-License-Identifier: Apache-2.0
// A screen behind a mirror or a grating (issue 12; src/integrators/lobe_incidence.h): a
// `virtual_plane` that sees a plane wave or a point light only through the listed lobes of a flat
// surface reads, in every pixel and from a single sample, the closed form of flux conservation:
//   mirror, plane wave:  R(θ)·E·cosθ_screen;
//   mirror, point light: R(θ_p)·I·cosθ'/|x − L'|² with L' the light's mirror image;
//   grating order j:     a_j·E·(cosθ_i/cosθ_j)·cosθ'_j  (the anamorphic factor of the order's beam).
// The references are computed here from geometry and the Fresnel equations written out, not from
// the kernel's listing. scenes/validation/screen_behind_mirror.wscene is the scene.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "core/render/pixel_integrator.h"
#include "core/render/registry.h"
#include "core/spectrum/named_ior.h"
#include "parser/parser.h"
#include "support/scene_builder.h"

namespace phasor::test {
namespace {

const std::string ScenePath = std::string(PHASOR_SOURCE_DIR) + "/scenes/validation/screen_behind_mirror.wscene";
const std::string TwoMirrorsPath =
    std::string(PHASOR_SOURCE_DIR) + "/scenes/validation/screen_behind_two_mirrors.wscene";

std::unique_ptr<Scene> Load(const DefineList &defines, const std::function<void(SceneDesc &)> &edit = {},
                            const std::string &path = ScenePath) {
    Diagnostics diag;
    auto desc = ParseSceneFile(path, defines, diag);
    EXPECT_TRUE(desc);
    if (!desc) return nullptr;
    if (edit) edit(*desc);
    auto scene = Scene::Build(*desc, diag);
    std::ostringstream os;
    diag.Print(os);
    EXPECT_TRUE(scene) << os.str();
    return scene;
}

// Unpolarised Fresnel reflectance of air → n + iκ at angle θ (Born & Wolf), written out.
double FresnelR(double cosI, std::complex<double> n) {
    const double sin2 = 1 - cosI * cosI;
    const std::complex<double> cosT = std::sqrt(1.0 - sin2 / (n * n));
    const std::complex<double> rs = (cosI - n * cosT) / (cosI + n * cosT);
    const std::complex<double> rp = (n * cosI - cosT) / (n * cosI + cosT);
    return 0.5 * (std::norm(rs) + std::norm(rp));
}

// One pixel estimate from a single sample (Sobol', seed 7), reduced as the film does.
double OneSample(const Scene &scene, int x, int spp = 1, int index = 0) {
    const auto &integrator = dynamic_cast<const PixelIntegrator &>(scene.GetIntegrator());
    auto sampler = MakeSobolSampler(7);
    sampler->StartPixelSample(x, 0, index);
    SampledWavelengths wl = scene.Wavelengths().Sample(sampler->Get1D());
    PathStats stats;
    stats.sample = PixelSampleIndex{index, spp, 7};
    ScratchBuffer scratch;
    const SampledSpectrum L = integrator.EstimatePixel(scene, x, 0, wl, *sampler, scratch, stats);
    double v = 0;
    for (int i = 0; i < wl.Count(); ++i)
        if (wl.pdf[i] > 0) v += scene.GetDetector().Response().Intensity(wl.lambda[i]) * L[i] / wl.pdf[i];
    return v / wl.Count();
}

// The render path (film, Sobol', all samples) for a few spp: every sample gives the same value.
std::vector<double> Row(const Scene &scene, int spp) {
    const Image img = RenderImage(scene, spp);
    std::vector<double> row;
    const int c = img.ChannelIndex("intensity");
    for (int x = 0; x < img.width; ++x) row.push_back(img.At(x, 0, c));
    return row;
}

Vec3 PixelCentre(const Scene &scene, int i) {
    const SensorPlaneGeometry *g = scene.GetDetector().SensorPlane();
    const Vec2 c = g->PixelCenter(i, 0);
    return g->origin + g->frame.s * c.x + g->frame.t * c.y;
}

const std::complex<double> Gold550 = FindNamedIndex("Au")->index(550e-9);

TEST(ScreenBehindLobe, MirrorPlaneWaveReadsRECosTheta) {
    for (double theta : {0.0, 30.0, 70.0})
        for (double tilt : {0.0, 25.0}) {
            SCOPED_TRACE("theta " + std::to_string(theta) + " tilt " + std::to_string(tilt));
            auto scene = Load({{"theta", std::to_string(theta) + " deg"}, {"screen_tilt", std::to_string(tilt) + " deg"}});
            ASSERT_TRUE(scene);
            // Gaussian pixels of σ = 2 µm: 1 − e^{−β²k²} = 1 to 1e-60.
            // Mirror term, plus the wave itself where it reaches the screen's front directly (its
            // rays towards the source climb away from the mirror plane z = 0: never blocked).
            const Vec3 toSource(-std::sin(Radians(theta)), 0, std::cos(Radians(theta)));
            const double direct = std::max(0.0, Dot(toSource, scene->GetDetector().SensorPlane()->frame.n));
            const double expected = FresnelR(std::cos(Radians(theta)), Gold550) * std::cos(Radians(tilt)) + direct;
            for (int x = 0; x < scene->GetDetector().Width(); ++x) EXPECT_NEAR(OneSample(*scene, x), expected, 1e-9);
            for (double v : Row(*scene, 4)) EXPECT_NEAR(v, expected, 1e-7);  // the film stores floats
        }
}

TEST(ScreenBehindLobe, MirrorPointLightReadsTheImageSource) {
    for (double theta : {10.0, 50.0}) {  // at 50° the light also shines on the screen directly
        SCOPED_TRACE("theta " + std::to_string(theta));
        auto scene = Load({{"theta", std::to_string(theta) + " deg"}, {"source", "\"point\""}, {"screen_tilt", "15 deg"},
                           {"width", "20 mm"}});
        ASSERT_TRUE(scene);
        const double th = Radians(theta), distance = 0.2, I = distance * distance;  // E = 1 W/m² → I = E·d²
        const Vec3 light(-distance * std::sin(th), 0, distance * std::cos(th)), image(light.x, light.y, -light.z);
        const Vec3 n = scene->GetDetector().SensorPlane()->frame.n;
        for (int x = 0; x < scene->GetDetector().Width(); ++x) {
            const Vec3 p = PixelCentre(*scene, x), toImage = image - p;
            const double r = Length(toImage);
            const Vec3 u = toImage / r;
            const double cosMirror = std::abs(u.z);  // the ray p → L' meets the mirror plane z = 0
            // Plus the light itself where it faces the screen (the segment to it stays above z = 0).
            const Vec3 toLight = light - p;
            const double rl = Length(toLight), direct = std::max(0.0, Dot(toLight / rl, n)) * I / (rl * rl);
            const double expected = FresnelR(cosMirror, Gold550) * I * Dot(u, n) / (r * r) + direct;
            EXPECT_NEAR(OneSample(*scene, x), expected, 1e-9 * expected) << "pixel " << x;
        }
    }
}

TEST(ScreenBehindLobe, GratingOrderReadsItsAnamorphicFlux) {
    // The mirror replaced by the two-lobe test kernel of listed_lobes_test.cpp (a₀ = 0.6 mirror,
    // a₁ = 0.3 order shifted by 2π/Λ along the surface's x axis), Λ = 2 µm, and a plate large
    // enough that the order's beam also covers the screen; at 550 nm the order leaves at
    // sinθ₁ = sinθ + λ/Λ.
    const double theta = Radians(20), lambda = 550e-9, period = 2e-6;
    auto scene = Load({{"theta", "20 deg"}, {"screen_tilt", "5 deg"}}, [&](SceneDesc &d) {
        for (SceneEntity &e : d.entities) {
            if (e.keyword == "Material") {
                e.type = "two_lobe_test";
                e.params = ParamDict(e.loc);
                e.params.Set("a0", Num(0.6)).Set("a1", Num(0.3)).Set("period", Len(period));
            }
            if (e.keyword == "Shape") {
                ParamDict p(e.loc);
                p.Set("width", Len(1.0)).Set("height", Len(1.0)).Set("material", e.params.GetValue("material"));
                e.params = p;
            }
        }
    });
    ASSERT_TRUE(scene);
    ASSERT_LT(Length(scene->Intersect(Ray{Vec3(0, 0, 1), Vec3(0, 0, -1)})->shading.s - Vec3(1, 0, 0)), 1e-12)
        << "the reference assumes the plate's first tangent is +x";
    const double sin1 = std::sin(theta) + lambda / period, cos1 = std::sqrt(1 - sin1 * sin1);
    const Vec3 d0(std::sin(theta), 0, std::cos(theta)), d1(sin1, 0, cos1);  // directions of travel
    const Vec3 n = scene->GetDetector().SensorPlane()->frame.n;                // faces the mirror
    const double expected = 0.6 * Dot(-d0, n) + 0.3 * (std::cos(theta) / cos1) * Dot(-d1, n);
    ASSERT_GT(Dot(-d1, n), 0.5);  // the order reaches the screen's front
    for (int x = 0; x < scene->GetDetector().Width(); ++x) EXPECT_NEAR(OneSample(*scene, x), expected, 1e-9);
}

TEST(ScreenBehindLobe, SampledPathDoesNotMeasureTheMirrorAgain) {
    // Pixels of σ = 0.2 µm: the GR's angular spread (≈0.2 rad) makes the sampled directions meet
    // the reflected wave often, so measuring it again at the first vertex (D14) would add ≈ the
    // analytic value once more on average; the render must equal the one-sample analytic value.
    auto scene = Load({{"theta", "30 deg"}, {"sigma", "0.2 um"}});
    ASSERT_TRUE(scene);
    const std::vector<double> row = Row(*scene, 64);
    for (int x = 0; x < scene->GetDetector().Width(); ++x) {
        const double analytic = OneSample(*scene, x);
        EXPECT_GT(analytic, 0.5);
        EXPECT_NEAR(row[x], analytic, 1e-6 * analytic) << "pixel " << x;
    }
}

TEST(ScreenBehindLobe, TwoMirrorsAreFoundBySampledPathsAtTheDocumentedCost) {
    // A periscope (scenes/validation/screen_behind_two_mirrors.wscene): the wave reaches the
    // screen only through two near-delta vertices. Listed-lobe incidence follows the first vertex
    // only, so the sampled path finds the wave at its second vertex (D14): right — R²·E, here at
    // 64² spp on the pixels' lattice (D4b), measured error 1e-4 — but dear: at 16² spp the error is
    // tens of per cent, as the scene's header documents. If chains are ever integrated in closed
    // form the second check fails: then update that header and docs/generalized_rays.md.
    auto scene = Load({{"pixels", "3"}}, {}, TwoMirrorsPath);
    ASSERT_TRUE(scene);
    const double R = FresnelR(std::cos(Radians(30.0)), Gold550), expected = R * R;
    for (double v : Row(*scene, 4096)) EXPECT_NEAR(v, expected, 2e-3 * expected);
    double sum2 = 0;
    const std::vector<double> coarse = Row(*scene, 256);
    for (double v : coarse) sum2 += (v - expected) * (v - expected);
    EXPECT_GT(std::sqrt(sum2 / double(coarse.size())), 0.2 * expected);
}

}  // namespace
}  // namespace phasor::test
