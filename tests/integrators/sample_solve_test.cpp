// SPDX-License-Identifier: Apache-2.0
// `sample_solve` (src/integrators/sample_solve.cpp): the forward polarised solve over grt's paths.
//   * On scenes whose vertices do not couple polarisations (one scattering event, or diffuse ones)
//     its estimate equals grt's sample by sample (same sampler, same dimensions), to 1e-12; on a
//     scene with two Fresnel interfaces in a row (the Cornell box's glass sphere) it does not —
//     the comparison sees the coupling.
//   * Brewster: unpolarised light reflected by glass at Brewster's angle is fully s-polarised:
//     DoP = 1 and S1/S0 = 1 (s along the image x axis) to 1e-6; 50° is not (DoP 0.2…).
//   * Malus: that light through the detector's polariser at θ keeps cos²θ of it, within the Monte
//     Carlo error of independent replicas (a panel lamp seen in the glass: the lobe choice is random);
//     the same data reject a cosθ law; crossed, < 1e-4 passes.
//   * A conductor turns linear polarisation into elliptical as its Fresnel phases say: light
//     s-polarised by a Brewster reflection meets a metal mirror whose plane of incidence is turned
//     45°; S/S0 at the camera equals an independent complex-field calculation (the field as a 3-D
//     vector, reflected by each interface's r_s, r_p written out here) to 1e-9.
//   * The S0 channel is the intensity channel.
#include <gtest/gtest.h>

#include <cstdio>

#include "core/render/pixel_integrator.h"
#include "parser/parser.h"
#include "support/replicas.h"
#include "validation/render_row.h"
#include "support/stats.h"

namespace phasor::test {
namespace {

std::unique_ptr<Scene> FromText(const std::string &text, const std::string &integrator = "",
                                const DefineList &defines = {}) {
    return BuildSceneText(text, integrator, defines);
}

std::unique_ptr<Scene> FromFile(const std::string &file, const std::string &integrator, const DefineList &defines = {}) {
    return BuildValidation(ValidationScene(file), defines, integrator);
}

// ---- sample by sample ------------------------------------------------------------------------------

/// Largest relative difference between grt's and sample_solve's estimates, sample by sample, over
/// a grid of pixels (the same sampler stream for both), and the number of non-zero samples.
std::pair<double, int> PerSampleDifference(const std::string &file, const DefineList &defines, int stepX, int stepY,
                                           int spp) {
    auto a = FromFile(file, "grt", defines), b = FromFile(file, "sample_solve", defines);
    if (!a || !b) return {Infinity, 0};
    const auto &ia = dynamic_cast<const PixelIntegrator &>(a->GetIntegrator());
    const auto &ib = dynamic_cast<const PixelIntegrator &>(b->GetIntegrator());
    auto proto = MakeSobolSampler(5);
    double worst = 0;
    int nonZero = 0;
    const Detector &det = a->GetDetector();
    for (int y = 0; y < det.Height(); y += stepY)
        for (int x = 0; x < det.Width(); x += stepX)
            for (int s = 0; s < spp; ++s) {
                auto run = [&](const Scene &scene, const PixelIntegrator &in) {
                    auto sampler = proto->Clone();
                    sampler->StartPixelSample(x, y, s);
                    PathStats ps;
                    ps.sample = PixelSampleIndex{s, spp, 5};
                    SampledWavelengths wl = scene.Wavelengths().Sample(sampler->Get1D());
                    ScratchBuffer scratch;
                    return in.EstimatePixel(scene, x, y, wl, *sampler, scratch, ps);
                };
                const SampledSpectrum va = run(*a, ia), vb = run(*b, ib);
                double m = 0;
                for (int i = 0; i < NumWavelengths; ++i) m = std::max(m, std::abs(va[i]));
                if (!(m > 0)) continue;
                ++nonZero;
                for (int i = 0; i < NumWavelengths; ++i) worst = std::max(worst, std::abs(vb[i] - va[i]) / m);
            }
    return {worst, nonZero};
}

TEST(SampleSolve, EqualsGrtSampleBySampleWithoutPolarisationCoupling) {
    struct Case {
        std::string file;
        DefineList defines;
        int stepX, stepY, spp;
    };
    const std::vector<Case> cases = {
        {"grt_sun_glint.wscene", {}, 3, 3, 2},                                   // a mirror: D14 through its lobe
        {"harvey_shack.wscene", {{"res", "9"}}, 1, 1, 8},                        // glint + NEE through the halo
        {"grt_sun_diffuse.wscene", {}, 2, 2, 8},                                 // a diffuse floor: NEE
        {"screen_behind_mirror.wscene", {}, 7, 1, 2},                            // D4a through a lobe
        {"grating.wscene", {{"pitch", "2 mm"}}, 1, 1, 2},                        // every order of a grating
        {"double_slit.wscene", {}, 8, 1, 4},                                     // the scalar aperture
    };
    for (const Case &c : cases) {
        const auto [worst, n] = PerSampleDifference(c.file, c.defines, c.stepX, c.stepY, c.spp);
        EXPECT_GT(n, 0) << c.file;
        EXPECT_LE(worst, 1e-12) << c.file;
        std::printf("MEASURED %s: %d samples, max relative difference %.3g\n", c.file.c_str(), n, worst);
    }
    // The comparison sees polarisation coupling: in the Cornell box, light refracted into the glass
    // sphere and out again is partly polarised by the first interface before the second.
    const auto [worst, n] = PerSampleDifference("grt_cornell.wscene", {}, 4, 4, 8);
    EXPECT_GT(worst, 1e-4) << "two Fresnel interfaces in a row couple S1 into S0";
    std::printf("MEASURED grt_cornell.wscene (couples): %d samples, max relative difference %.3g\n", n, worst);
}

// ---- polarisation ------------------------------------------------------------------------------------

// A unit plane wave reflected by a glass plate (n = 1.5) at `theta`, seen by a one-pixel camera on
// the exact specular direction (a Gaussian pixel: its GR on the mirror direction), Stokes output.
const char *PlateScene = R"(wscene 2
Define theta = 56.30993247402022 deg
Define pol = 0 deg
Define usePol = false
Light "plane_wave" "wave" { direction = [sin($theta) 0 -cos($theta)]  irradiance = 1 W/m^2  spectrum = line(550 nm) }
Material "dielectric" "glass" { ior = 1.5 }
Shape "rectangle" "plate" { material = @glass  to_world = scale(10) }
Detector "perspective" "cam" {
    to_world = lookat(eye = [sin($theta) 0 cos($theta)] m, target = [0 0 0] m, up = [0 0 1])
    fov = 0.01 deg  resolution = [1 1]  pixel = "gaussian"  response = "radiometric"
    stokes = true  polarizer = select($usePol, $pol, 0 deg)
}
Integrator "sample_solve" "ss" { max_depth = 1 }
)";

std::array<double, 4> PixelStokes(const Image &img, int x = 0, int y = 0) {
    std::array<double, 4> s{};
    for (int c = 0; c < 4; ++c) s[std::size_t(c)] = img.At(x, y, img.ChannelIndex("S" + std::to_string(c)));
    return s;
}

TEST(SampleSolve, BrewsterReflectionIsFullySPolarised) {
    // The polariser is a Define: without it the scene has none (select picks 0 deg, so build without).
    std::string text = PlateScene;
    text.replace(text.find("stokes = true  polarizer = select($usePol, $pol, 0 deg)"),
                 std::string("stokes = true  polarizer = select($usePol, $pol, 0 deg)").size(), "stokes = true");
    for (double thetaDeg : {Degrees(std::atan(1.5)), 50.0}) {
        auto scene = FromText(text, "", {{"theta", std::to_string(thetaDeg) + " deg"}});
        ASSERT_TRUE(scene);
        const Image img = RenderImage(*scene, 1);
        const auto s = PixelStokes(img);
        ASSERT_GT(s[0], 0);
        const double dop = std::sqrt(s[1] * s[1] + s[2] * s[2] + s[3] * s[3]) / s[0];
        // S0 is the intensity channel (float EXR channels: 1e-7).
        EXPECT_NEAR(s[0], img.At(0, 0, img.ChannelIndex("intensity")), 1e-7 * s[0]);
        if (thetaDeg > 55) {
            // Brewster: r_p = 0 exactly, so S = (R_s/2)(1, 1, 0, 0) in the s/p frame; the camera's x
            // axis (image right, world −y) is ŝ. 1e-6: float channels (the value is exact to 1e-16).
            EXPECT_NEAR(dop, 1, 1e-6);
            EXPECT_NEAR(s[1] / s[0], 1, 1e-6);
            // And the intensity is grt's: R_s/2 of the plane wave's closed form.
        } else {
            // Off Brewster the reflection is partly polarised: DoP = (R_s − R_p)/(R_s + R_p).
            const double c = std::cos(Radians(thetaDeg)), n = 1.5, ct = std::sqrt(1 - (1 - c * c) / (n * n));
            const double rs = (c - n * ct) / (c + n * ct), rp = (n * c - ct) / (n * c + ct);
            EXPECT_NEAR(dop, (rs * rs - rp * rp) / (rs * rs + rp * rp), 1e-6);
            EXPECT_LT(dop, 0.999);
        }
        std::printf("MEASURED plate at %.4f deg: S/S0 = (1, %.9f, %.2g, %.2g), DoP %.9f\n", thetaDeg, s[1] / s[0],
                    s[2] / s[0], s[3] / s[0], dop);
    }
}

// A 4 cm panel lamp 1 m along the Brewster reflection of a glass plate, seen by a 4×4 camera
// through its polariser: the reflected light is s-polarised (along image x), so the polariser at θ
// passes I(0)·cos²θ (Malus). Each sample picks reflection (p = R) or refraction at random: a Monte
// Carlo estimate whose error comes from independent replicas.
const char *PanelScene = R"(wscene 2
Define pol = 0 deg
Define b = 56.30993247402022 deg
Material "dielectric" "glass" { ior = 1.5 }
Shape "rectangle" "plate" { material = @glass  to_world = scale(10) }
Shape "rectangle" "panel" { width = 4 cm  height = 4 cm
    to_world = [rotate(180 deg + $b, [0 1 0]) translate([sin($b) 0 cos($b)] m)] }
Light "area" "lamp" { shape = @panel  radiance = 1 W/m^2/sr  spectrum = line(550 nm) }
Detector "perspective" "cam" {
    to_world = lookat(eye = [-sin($b) 0 cos($b)] m, target = [0 0 0] m, up = [0 0 1])
    fov = 0.5 deg  resolution = [4 4]  response = "radiometric"  polarizer = $pol
}
Integrator "sample_solve" "ss" { max_depth = 2 }
)";

TEST(SampleSolve, MalusLawThroughThePolariser) {
    const int spp = 64, replicas = 16;
    auto render = [&](double deg, uint64_t seed) {
        auto scene = FromText(PanelScene, "", {{"pol", std::to_string(deg) + " deg"}});
        return ImageOverReplicas(RenderReplicas(*scene, spp, replicas, seed));
    };
    const ReplicaEstimate i0 = render(0, 100);
    ASSERT_GT(i0.mean, 0);
    const double alpha = SidakAlpha(0.01, 3);
    int rejectedCos = 0;
    for (double deg : {30.0, 45.0, 60.0}) {
        const ReplicaEstimate e = render(deg, 200 + uint64_t(deg));
        const double c = std::cos(Radians(deg));
        // I(θ) against I(0)·cos²θ: Welch's test of e.mean vs cos²θ·i0.mean (independent seeds).
        const TTestResult t = WelchTTest(e.mean, e.varianceOfMean, e.dof, c * c * i0.mean,
                                         c * c * c * c * i0.varianceOfMean, i0.dof);
        EXPECT_GT(t.pValue, alpha) << deg << " deg: " << e.mean << " vs " << c * c * i0.mean << " " << t.ToString();
        std::printf("MEASURED Malus %g deg: I/I0 = %.5f (cos² %.5f), %s\n", deg, e.mean / i0.mean, c * c,
                    t.ToString().c_str());
        // The same data against a biased law, I(0)·cosθ.
        const TTestResult tb =
            WelchTTest(e.mean, e.varianceOfMean, e.dof, c * i0.mean, c * c * i0.varianceOfMean, i0.dof);
        rejectedCos += tb.pValue < alpha;
        std::printf("MEASURED biased Malus (cosθ) %g deg: %s\n", deg, tb.ToString().c_str());
    }
    EXPECT_EQ(rejectedCos, 3) << "a cosθ law must be rejected at 30°, 45° and 60°";
    // Crossed (90°): only the p light of the panel's rays off Brewster's angle (±1.1° across the
    // panel: R_p/R_s ≲ 1e-4) passes.
    const ReplicaEstimate i90 = render(90, 300);
    EXPECT_LT(i90.mean, 1e-4 * i0.mean);
    std::printf("MEASURED Malus 90 deg: I/I0 = %.3g\n", i90.mean / i0.mean);
}

// ---- a conductor makes elliptical polarisation --------------------------------------------------------

using CVec3 = std::array<Complex, 3>;
CVec3 Scaled(const Vec3 &v, Complex a) { return {v.x * a, v.y * a, v.z * a}; }
CVec3 Sum(const CVec3 &a, const CVec3 &b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Complex Proj(const CVec3 &e, const Vec3 &v) { return e[0] * v.x + e[1] * v.y + e[2] * v.z; }

/// Reflects the field e (travelling along kIn) at a plane of unit normal n with amplitude
/// coefficients r_s, r_p (s = n × k normalised, p = k × s for each wave).
CVec3 Reflect(const CVec3 &e, const Vec3 &kIn, const Vec3 &n, Complex rs, Complex rp) {
    const Vec3 kOut = kIn - n * (2 * Dot(kIn, n));
    const Vec3 s = Normalize(Cross(n, kIn)), pIn = Cross(kIn, s), pOut = Cross(kOut, s);
    return Sum(Scaled(s, rs * Proj(e, s)), Scaled(pOut, rp * Proj(e, pIn)));
}
/// Fresnel amplitude coefficients for incidence cosine c from index 1 onto index n (complex),
/// written out (theory §4.1).
std::pair<Complex, Complex> Fresnel(double c, Complex n) {
    const Complex ct = std::sqrt(1.0 - (1 - c * c) / (n * n));
    return {(c - n * ct) / (c + n * ct), (n * c - ct) / (n * c + ct)};
}

TEST(SampleSolve, ConductorTurnsLinearIntoEllipticalPolarisation) {
    // Backwards from the camera (at the origin): along c0 to a metal mirror at G, along c1 = +x to a
    // glass plate at P (Brewster), along c2 to the light. The mirror's plane of incidence (c0, c1)
    // is turned 45° about c1 from the plate's (c1, c2) = the x–z plane.
    const double thB = std::atan(1.5), thM = Radians(60);
    const Vec3 c1(1, 0, 0);
    const double dP = Pi - 2 * thB, dM = Pi - 2 * thM;  // deviations
    const Vec3 c2(std::cos(dP), 0, std::sin(dP));
    const Vec3 u = Normalize(Vec3(0, 1, 1));            // the mirror plane: span(c1, u)
    const Vec3 c0 = Normalize(c1 * std::cos(dM) - u * std::sin(dM));
    const Vec3 G = c0 * 1.0, P = G + c1 * 1.0;
    const Vec3 nM = Normalize(c1 - c0), nP = Normalize(c2 - c1);
    const Complex metal(0.2, 3.4);
    // Independent reference: the sun's unpolarised light as two incoherent orthogonal fields.
    const Vec3 kSun = -c2, kMid = -c1, kCam = -c0;
    Stokes ref{};
    const Vec3 camX = Normalize(Cross(c0, Vec3(0, 0, 1)));  // image right for lookat(up = z): forward × up
    const Frame f0 = Frame::FromNormal(kSun);
    for (const Vec3 &pol : {f0.s, f0.t}) {
        CVec3 e = Scaled(pol, 1);
        const auto [rsP, rpP] = Fresnel(std::abs(Dot(kSun, nP)), Complex(1.5, 0));
        e = Reflect(e, kSun, nP, rsP, rpP);
        const auto [rsM, rpM] = Fresnel(std::abs(Dot(kMid, nM)), metal);
        e = Reflect(e, kMid, nM, rsM, rpM);
        const Stokes s = StokesFromField(Proj(e, camX), Proj(e, Cross(kCam, camX)));
        for (int c = 0; c < 4; ++c) ref[std::size_t(c)] += s[std::size_t(c)];
    }
    ASSERT_GT(ref[0], 0);
    char buf[2048];
    auto v = [](const Vec3 &a) {
        char b[128];
        std::snprintf(b, sizeof b, "[%.17g %.17g %.17g]", a.x, a.y, a.z);
        return std::string(b);
    };
    // Rectangles: local z → the normal (a frame from the normal; the grooveless surfaces are isotropic).
    auto placed = [&](const Vec3 &n, const Vec3 &at) {
        const Frame f = Frame::FromNormal(n);
        char b[512];
        std::snprintf(b, sizeof b,
                      "[%.17g %.17g %.17g %.17g  %.17g %.17g %.17g %.17g  %.17g %.17g %.17g %.17g  0 0 0 1]", f.s.x,
                      f.t.x, f.n.x, at.x, f.s.y, f.t.y, f.n.y, at.y, f.s.z, f.t.z, f.n.z, at.z);
        return std::string(b);
    };
    std::snprintf(buf, sizeof buf, R"(wscene 2
Light "plane_wave" "sun" { direction = %s  irradiance = 1 W/m^2  spectrum = line(633 nm) }
Material "conductor" "metal" { ior = 0.2+3.4i }
Material "dielectric" "glass" { ior = 1.5 }
Shape "rectangle" "mirror" { width = 10 cm  height = 10 cm  material = @metal  to_world = matrix(%s) }
Shape "rectangle" "plate" { width = 10 cm  height = 10 cm  material = @glass  to_world = matrix(%s) }
Detector "perspective" "cam" {
    to_world = lookat(eye = [0 0 0] m, target = %s m, up = [0 0 1])
    fov = 0.01 deg  resolution = [1 1]  pixel = "gaussian"  response = "radiometric"  stokes = true
}
Integrator "sample_solve" "ss" { max_depth = 3 }
)",
                  v(kSun).c_str(), placed(nM, G).c_str(), placed(nP, P).c_str(), v(G).c_str());
    auto scene = FromText(buf);
    ASSERT_TRUE(scene);
    const Image img = RenderImage(*scene, 8);
    const auto s = PixelStokes(img);
    ASSERT_GT(s[0], 0);
    for (int c = 1; c < 4; ++c)
        EXPECT_NEAR(s[std::size_t(c)] / s[0], ref[std::size_t(c)] / ref[0], 1e-6) << "S" << c << "/S0";
    // Elliptical: S3 ≠ 0, of the size the metal's phase difference gives.
    EXPECT_GT(std::abs(ref[3] / ref[0]), 0.3);
    std::printf("MEASURED metal after Brewster (45°): S/S0 = (%.7f, %.7f, %.7f), reference (%.7f, %.7f, %.7f)\n",
                s[1] / s[0], s[2] / s[0], s[3] / s[0], ref[1] / ref[0], ref[2] / ref[0], ref[3] / ref[0]);
}

}  // namespace
}  // namespace phasor::test
