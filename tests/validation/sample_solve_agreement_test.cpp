// SPDX-License-Identifier: Apache-2.0
// `sample_solve` and `grt` converge to the same image (issue 13 acceptance) on the grating and
// Harvey–Shack validation scenes — and so does the fully coherent solve (force_coherent), which
// measures distant sources through their coherent modes: a different estimator of the same image.
// Per-block Welch t-tests on independent Sobol' replicas (support/replicas.h; not the film's
// i.i.d. variance channel), Šidák-corrected over every test of this file; spp and replicas stated
// per case. Power: the same renders with the second integrator's source 5 % brighter (the images are
// linear in it: its replica means × 1.05; × 1.15 for the fully coherent solve on the grating, whose
// variance is ~80× grt's) must be rejected by at least one test.
//   * harvey_shack.wscene (a rough metal plate under the sun's 4.65 mrad disc, a camera on the
//     glint; 15×15 pixels of 1.3°; 16 replicas × 16 spp): glint (D14 through the specular lobe) +
//     halo (NEE).
//   * a grating under a `distant` source of 5 mrad seen by a camera across its −1st order (every
//     order's glint is a closed-form measurement through a listed dispersive lobe, D14; 15×15
//     pixels, 16 replicas × 32 spp).
//   * grating.wscene (a plane wave, a sensor row across the orders: D4a through every order) is
//     deterministic: the three integrators read it identically (to 1e-12 of the peak).
#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>

#include "render_row.h"
#include "support/stats.h"

namespace phasor::test {
namespace {

constexpr int Blocks = 5;            // 5×5 blocks per image (3×3 pixels each)
constexpr int TestsPerComparison = Blocks * Blocks + 1;
constexpr int Comparisons = 4;       // two scenes × (partially, fully coherent) vs grt
double Alpha() { return SidakAlpha(0.01, Comparisons * TestsPerComparison); }

const char *GratingCameraScene = R"(wscene 2
# A grating plate (gold, Λ = 2 µm, h = 0.1 µm, grooves along y) under a distant source of 5 mrad
# (Gaussian profile) at 20°, seen by a camera along the −1st order at 550 nm, 2 m away: its 4° field
# is filled by the band of the order's glints over 500–600 nm (the order leaves at 2.4°–5.3°).
Light "distant" "sun" { direction = [0.34202 0 -0.93969]  angular_radius = 5 mrad  profile = "gaussian"
                        spectrum = table(wavelengths = [500 600] nm, values = [1 1])  irradiance = 1 W/m^2 }
Material "conductor" "gold" { ior = "Au" }
Material "grating" "grooves" { substrate = @gold  period = 2 um  height = 0.1 um  angle = -90 deg }
Shape "rectangle" "plate" { material = @grooves  to_world = scale(0.5) }
Detector "perspective" "cam" {
    to_world = lookat(eye = [0.1340 0 1.9955] m, target = [0 0 0] m, up = [0 1 0])
    fov = 4 deg  resolution = [15 15]  response = "radiometric"
}
Integrator "grt" "gr" { max_depth = 1 }
Integrator "sample_solve" "solve" { max_depth = 1 }
Integrator "sample_solve" "coherent" { max_depth = 1  force_coherent = true }
)";

/// Welch tests of the two render sets' replica means on every block and the whole image; returns
/// the rejections. `gainB` scales the second set (a brighter source).
int Rejections(const std::vector<Image> &a, const std::vector<Image> &b, double gainB, const std::string &what,
               std::ostringstream &log) {
    int rejected = 0;
    auto test = [&](const std::string &where, const ReplicaEstimate &ea, ReplicaEstimate eb) {
        eb.mean *= gainB;
        eb.varianceOfMean *= gainB * gainB;
        const TTestResult t = WelchTTest(ea.mean, ea.varianceOfMean, ea.dof, eb.mean, eb.varianceOfMean, eb.dof);
        const bool reject = !(t.pValue > Alpha());
        rejected += reject;
        if (reject || where == "image")
            log << what << " " << where << ": " << ea.mean << " ± " << ea.StdError() << " vs " << eb.mean << " ± "
                << eb.StdError() << " (" << t.ToString() << ")" << (reject ? " REJECTED" : "") << "\n";
    };
    const int w = a[0].width / Blocks, h = a[0].height / Blocks;
    const ReplicaEstimate imageA = ImageOverReplicas(a);
    for (int by = 0; by < Blocks; ++by)
        for (int bx = 0; bx < Blocks; ++bx) {
            const ReplicaEstimate ea = BlockOverReplicas(a, bx * w, by * h, bx * w + w, by * h + h),
                                  eb = BlockOverReplicas(b, bx * w, by * h, bx * w + w, by * h + h);
            // Blocks darker than 1e-6 of the image's mean are the far tails of a source's profile
            // (5e-12 against a band of 200 on the grating), which the fully coherent solve's modes
            // reach with vanishing probability per sample: not tested.
            if (std::max(ea.mean, eb.mean) < 1e-6 * imageA.mean) continue;
            // Nor are blocks whose replica mean is known to worse than 25 % in either set: the
            // fully coherent solve reaches the dim edges of a glint band (1 % of the image's mean)
            // through rare modes, so there its replica means are far from normal — mostly low, with
            // a small error bar, now and then one large sample — and the t-test's premise fails
            // (seen at 33–68 % relative error on four of four seeds, and one of four before the
            // wavelengths were stratified across a pixel's samples).
            if (ea.StdError() > 0.25 * ea.mean || eb.StdError() > 0.25 * eb.mean) continue;
            test("block " + std::to_string(bx) + "," + std::to_string(by), ea, eb);
        }
    test("image", imageA, ImageOverReplicas(b));
    return rejected;
}

/// grt against sample_solve ("solve") and against the fully coherent solve ("coherent"), each at
/// `spp` × `replicas`; `coherentGain`: the brighter source the fully coherent solve's (noisier)
/// comparison must reject.
void Agree(const std::function<std::unique_ptr<Scene>(const std::string &)> &build, const std::string &name, int spp,
           int replicas, double coherentGain) {
    auto gr = build("gr");
    ASSERT_TRUE(gr);
    const std::vector<Image> ref = RenderReplicas(*gr, spp, replicas, 100);
    for (const char *other : {"solve", "coherent"}) {
        auto scene = build(other);
        ASSERT_TRUE(scene);
        const std::vector<Image> imgs = RenderReplicas(*scene, spp, replicas, 200);
        const double gain = std::string(other) == "coherent" ? coherentGain : 1.05;
        std::ostringstream log, biased;
        EXPECT_EQ(Rejections(ref, imgs, 1.0, name + " grt vs " + other, log), 0) << log.str();
        EXPECT_GT(Rejections(ref, imgs, gain, name + " grt vs " + other + " ×" + std::to_string(gain), biased), 0)
            << "a brighter source (×" << gain << ") must be rejected\n"
            << biased.str();
        std::printf("MEASURED %s%s", log.str().c_str(), biased.str().c_str());
    }
}

/// A validation scene with the integrators of this file added (grt "gr", sample_solve "solve" and
/// "coherent" with force_coherent = true), built with `integrator`.
std::unique_ptr<Scene> WithIntegrators(const std::string &file, const DefineList &defines, const std::string &integrator) {
    Diagnostics diag;
    auto desc = ParseSceneFile(ValidationScene(file), defines, diag);
    std::unique_ptr<Scene> scene;
    if (desc) {
        for (const char *name : {"solve", "coherent"}) {
            SceneEntity e;
            e.keyword = "Integrator";
            e.type = "sample_solve";
            e.name = name;
            e.params.Set("max_depth", Value::Integer(2));
            if (std::string(name) == "coherent") e.params.Set("force_coherent", Value::Bool(true));
            desc->entities.push_back(std::move(e));
        }
        scene = Scene::Build(*desc, diag, integrator);
    }
    std::ostringstream os;
    diag.Print(os);
    EXPECT_TRUE(scene) << os.str();
    return scene;
}

TEST(SampleSolveAgreement, HarveyShackPlate) {
    Agree([](const std::string &integrator) {
              return WithIntegrators("harvey_shack.wscene", {{"res", "25"}}, integrator);
          },
          "harvey_shack", 16, 16, 1.05);
}

TEST(SampleSolveAgreement, GratingUnderADistantSource) {
    // The fully coherent solve's variance is ~80× grt's here (Fig. S10's point): its comparison
    // is shown to reject a 15 % brighter source at this cost.
    Agree([](const std::string &integrator) { return BuildSceneText(GratingCameraScene, integrator, {}, "grating_camera.wscene"); }, "grating camera", 32, 16,
          1.15);
}

TEST(SampleSolveAgreement, GratingSensorRowIsIdentical) {
    const DefineList d = {{"pitch", "1 mm"}};
    const Row g = RenderRow(ValidationScene("grating.wscene"), d, "grt", 1);
    const Row s = RenderRow(ValidationScene("grating.wscene"), d, "sample_solve", 1);
    ASSERT_EQ(g.v.size(), s.v.size());
    ASSERT_GT(g.Peak(), 0);
    for (std::size_t i = 0; i < g.v.size(); ++i) EXPECT_NEAR(s.v[i], g.v[i], 1e-12 * g.Peak()) << "pixel " << i;
}

}  // namespace
}  // namespace phasor::test
