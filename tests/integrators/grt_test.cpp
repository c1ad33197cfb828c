// SPDX-License-Identifier: Apache-2.0
// The `grt` integrator (Algorithm 1) on the validation scenes in scenes/validation/grt_*.wscene:
// exact normalisations of sensor planes (theory §0 D4, D4a), a thin lens on a point source and
// the sun glint on a mirror (D14) in closed form. The camera on an emitter and the agreement with
// `ray` on a Cornell box are cases of the integrator contract suite (integrator_contract_test.cpp).
#include <gtest/gtest.h>

#include "core/render/genray.h"
#include "core/render/pixel_integrator.h"
#include "materials/fresnel.h"
#include "parser/parser.h"
#include "support/replicas.h"
#include "support/scene_builder.h"
#include "support/stats.h"

namespace phasor::test {
namespace {

std::unique_ptr<Scene> LoadScene(const std::string &name, const DefineList &defines = {},
                                 const std::string &integrator = "") {
    Diagnostics diag;
    auto desc = ParseSceneFile(std::string(PHASOR_SOURCE_DIR) + "/scenes/validation/" + name, defines, diag);
    std::ostringstream os;
    diag.Print(os);
    EXPECT_TRUE(desc) << os.str();
    if (!desc) return nullptr;
    auto scene = Scene::Build(*desc, diag, integrator);
    diag.Print(os);
    EXPECT_TRUE(scene) << os.str();
    return scene;
}

// One pixel estimate reduced exactly as the film does (intensity channel), in double precision —
// the EXR stores floats, which cannot show 1e-9.
double PixelEstimate(const Scene &scene, int x, int y, int index = 0, int count = 1, uint64_t seed = 1) {
    const auto &integrator = dynamic_cast<const PixelIntegrator &>(scene.GetIntegrator());
    auto sampler = MakeSobolSampler(seed);
    sampler->StartPixelSample(x, y, index);
    SampledWavelengths wl = scene.Wavelengths().Sample(sampler->Get1D());
    PathStats stats;
    stats.sample = PixelSampleIndex{index, count, seed};
    ScratchBuffer scratch;
    SampledSpectrum L = integrator.EstimatePixel(scene, x, y, wl, *sampler, scratch, stats);
    const SensorResponse &r = scene.GetDetector().Response();
    double v = 0;
    for (int i = 0; i < wl.Count(); ++i)
        if (wl.pdf[i] > 0) v += r.Intensity(wl.lambda[i]) * L[i] / wl.pdf[i];
    return v / wl.Count();
}

// D4/D4a: a unit plane wave at θ_s on a virtual plane reads its flux cosθ_s exactly — also for a
// pixel a fifth of a wavelength wide (σ = 0.1 µm at 550 nm), whose states labelled outside the
// propagating disc carry e^{−β²k²} = 7 % of it (docs/narrow_pixels.md; the propagating labels
// alone gave cosθ_s·(1 − e^{−β²k²})).
TEST(Grt, PlaneWaveOnSensorPlaneIsExact) {
    for (double thetaDeg : {0.0, 30.0}) {
        auto scene =
            LoadScene("grt_plane_wave_sensor.wscene", {{"theta", std::to_string(thetaDeg) + " deg"}});
        ASSERT_TRUE(scene);
        const double sigma = 0.1e-6, k = 2 * Pi / 550e-9, beta2 = 2 * sigma * sigma;
        const double expected = std::cos(Radians(thetaDeg));
        ASSERT_GT(std::exp(-beta2 * k * k), 0.05) << "the labels beyond the disc must matter here";
        ASSERT_EQ(scene->GetDetector().Height(), 1);
        for (int x = 0; x < scene->GetDetector().Width(); ++x)
            for (int s = 0; s < 4; ++s)
                EXPECT_NEAR(PixelEstimate(*scene, x, 0, s, 4), expected, 1e-9 * expected)
                    << thetaDeg << " deg, pixel " << x;
        // The whole render (float EXR) agrees too, with zero variance.
        Image img = RenderImage(*scene, 4);
        for (int x = 0; x < img.width; ++x) {
            EXPECT_NEAR(img.At(x, 0, img.ChannelIndex("intensity")), expected, 1e-6 * expected);
            EXPECT_EQ(img.At(x, 0, img.ChannelIndex("variance")), 0);
        }
    }
}

// D4a: a point source reads I·cosθ/R² at every pixel centre.
TEST(Grt, PointSourceOnSensorPlaneIsExact) {
    auto scene = LoadScene("grt_point_source_sensor.wscene");
    ASSERT_TRUE(scene);
    const Detector &d = scene->GetDetector();
    ASSERT_EQ(d.Width(), 20);  // resolution from pitch
    ASSERT_EQ(d.Height(), 12);
    const Vec3 light(3e-3, -1e-3, 20e-3);
    const double I = 2;
    for (int y = 0; y < d.Height(); ++y)
        for (int x = 0; x < d.Width(); ++x) {
            const Vec3 p(-10e-3 + (x + 0.5) * 1e-3, 6e-3 - (y + 0.5) * 1e-3, 0);
            const Vec3 v = light - p;
            const double r2 = LengthSquared(v), expected = I * (v.z / std::sqrt(r2)) / r2;
            EXPECT_NEAR(PixelEstimate(*scene, x, y), expected, 1e-6 * expected) << x << " " << y;
        }
}

// A Gaussian beam: the centre pixel reads P/(π(2σ_pix² + β_s²(z))) and the pixels sum to P.
TEST(Grt, GaussianBeamOnSensorPlane) {
    auto scene = LoadScene("grt_laser_sensor.wscene");
    ASSERT_TRUE(scene);
    const double P = 1e-3, k = 2 * Pi / 633e-9, beta0 = 0.3e-3 / std::sqrt(2.0), sigma = 20e-6, z = 0.2;
    const double zR = k * beta0 * beta0, betaZ2 = beta0 * beta0 * (1 + Sqr(z / zR));
    EXPECT_NEAR(PixelEstimate(*scene, 10, 10) / (P / (Pi * (2 * sigma * sigma + betaZ2))), 1, 1e-9);
    double sum = 0;
    for (int y = 0; y < 21; ++y)
        for (int x = 0; x < 21; ++x) sum += PixelEstimate(*scene, x, y);
    const double pitch = 0.1e-3;
    EXPECT_NEAR(sum * pitch * pitch / P, 1, 1e-5);  // tails beyond ±1 mm: e^{-36}; tilt: cos ≈ 1 − 1e-7
}

// D2/D3: a thin lens focused on a point source; the centre pixel's GR (waist β_f = √2σ_θd_f on the
// plane of focus, carried back to the lens) is measured as its time reverse against the spherical
// wave: k²·(I/R²)/(π(β⁻² + a²)), a = βk/R − ρ_phys/β with ρ_phys = +z̄/β_f² (diverging from the
// source, like the wave). Out of focus the value drops.
TEST(Grt, ThinLensFocusedOnPointSource) {
    auto scene = LoadScene("grt_point_focus.wscene");
    ASSERT_TRUE(scene);
    const double k = 2 * Pi / 500e-9, R = 1, I = 1;
    const double sigmaTheta = 2 * std::tan(0.55e-3) / 5 / std::sqrt(12.0);
    const double bf2 = 2 * Sqr(sigmaTheta * R), zb = R / k;
    const double beta2 = bf2 + zb * zb / bf2, rhoPhys = zb / bf2, beta = std::sqrt(beta2);
    const double a = beta * k / R - rhoPhys / beta;
    const double expected = I / (R * R) * k * k / (Pi * (1 / beta2 + a * a));
    const double focused = PixelEstimate(*scene, 2, 2);
    EXPECT_NEAR(focused / expected, 1, 1e-9);
    // With the traced (wrong-sign) ρ the overlap would be smaller by orders of magnitude.
    const double aWrong = beta * k / R + rhoPhys / beta;
    EXPECT_GT(expected / (I / (R * R) * k * k / (Pi * (1 / beta2 + aWrong * aWrong))), 100);
    auto defocused = LoadScene("grt_point_focus.wscene", {{"focus", "0.5 m"}});
    ASSERT_TRUE(defocused);
    EXPECT_LT(PixelEstimate(*defocused, 2, 2), 0.1 * focused);
}

struct GlintCase {
    const char *profile;
    double radius;  // rad
};

/// ⟨R⟩ of the plate (n = 0.2 + 3.4i) over the plane waves the glint's closed form integrates (theory §0
/// D15): the GR's window N(0, σ²) about the mirrored GR direction `dr` times the source's profile
/// about `toSource` (a Gaussian of Ω = α²/4, or the disc of radius α), by the midpoint rule (48²
/// points) over the product's support: for a Gaussian profile the product Gaussian's ±6 std about
/// its mean, for a disc the disc (when it is narrower than the window) or the window's ±6σ.
double EnsembleR(const Vec3 &dr, const Vec3 &toSource, double sigma, const GlintCase &c) {
    const bool gaussian = std::string(c.profile) == "gaussian";
    const double omega = c.radius * c.radius / 4;
    Vec3 centre = dr;
    double half = 6 * sigma;
    if (gaussian) {
        const double v = 1 / (1 / (sigma * sigma) + 1 / omega);
        centre = Normalize(dr * (v / (sigma * sigma)) + toSource * (v / omega));
        half = 6 * std::sqrt(v);
    } else if (c.radius < 6 * sigma) {
        centre = toSource;
        half = c.radius;
    }
    const Frame f = Frame::FromNormal(centre);
    double sum = 0, norm = 0;
    const int n = 48;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double ux = (-1 + 2 * (i + 0.5) / n) * half, uy = (-1 + 2 * (j + 0.5) / n) * half;
            const Vec3 w = Normalize(centre + f.s * ux + f.t * uy);
            const double g2 = std::max(0.0, 1 - Sqr(Dot(w, toSource)));  // sin² of the angle to the source
            const double d2 = std::max(0.0, 1 - Sqr(Dot(w, dr)));        // and to the window's axis
            double p = gaussian ? std::exp(-0.5 * g2 / omega) : (g2 <= Sqr(std::sin(c.radius)) ? 1.0 : 0.0);
            p *= std::exp(-0.5 * d2 / (sigma * sigma));
            sum += p * FresnelComplex(std::abs(w.z), 1.0, Complex(0.2, 3.4));
            norm += p;
        }
    return norm > 0 ? sum / norm : FresnelComplex(std::abs(dr.z), 1.0, Complex(0.2, 3.4));
}

// D14: the glint of a distant source in a smooth conductor, per pixel in closed form:
// ⟨R⟩·E·N₂(s⊥; 0, (σ_θ² + Ω)I) (Gaussian profile, Ω = α²/4) or ⟨R⟩·E·P_disc/(π sin²α) (disc), with s⊥
// the source direction transverse to the mirrored GR, σ_θ = pixel angle/√12 and ⟨R⟩ the plate's
// reflectance averaged over the window × the profile (EnsembleR; within 1e-5 of R at the GR's mean
// direction here, but that is what the pixel measures).
double GlintExpected(const Scene &scene, int x, int y, const GlintCase &c) {
    const double elevation = Radians(50), offset = 0.15e-3, E = 1000;
    const Vec3 s(std::cos(elevation + offset), 0, -std::sin(elevation + offset));
    auto ds = scene.GetDetector().Generate(Vec2(x + 0.5, y + 0.5), Vec2(0.5, 0.5));
    const Vec3 d = ds->ray.d;
    const Vec3 dr(d.x, d.y, -d.z);  // mirrored by the plate z = 0
    const double cosG = -Dot(s, dr), sin2 = std::max(0.0, 1 - cosG * cosG);
    const double sigmaTheta = std::tan(0.5e-3) / std::sqrt(12.0);
    const double R = EnsembleR(dr, -s, sigmaTheta, c);
    if (std::string(c.profile) == "gaussian")
        return R * E * Normal2(sin2, sigmaTheta * sigmaTheta + c.radius * c.radius / 4);
    const double sa = std::sin(c.radius);
    return R * E * DiscGaussianProbability(std::sqrt(sin2), sa, sigmaTheta) / (Pi * sa * sa);
}

TEST(Grt, SunGlintTinySourceMatchesClosedForm) {
    for (GlintCase c :
         {GlintCase{"gaussian", 1e-6}, GlintCase{"disc", 1e-6}, GlintCase{"gaussian", 0.2e-3}}) {
        auto scene =
            LoadScene("grt_sun_glint.wscene",
                      {{"profile", c.profile}, {"radius", std::to_string(c.radius) + " rad"}, {"res", "7"}});
        ASSERT_TRUE(scene);
        // The closed form with Ω = α²/4 (D5); the 1 µrad disc differs from it by O((α/σ_θ)⁴).
        // Far out in the tails (values < 1e-9 of the peak) the disc and its Gaussian differ relatively.
        GlintCase gauss{"gaussian", c.radius};
        double peak = 0, peakExpected = 0;
        for (int y = 0; y < 7; ++y)
            for (int x = 0; x < 7; ++x)
                peakExpected = std::max(peakExpected, GlintExpected(*scene, x, y, gauss));
        for (int y = 0; y < 7; ++y)
            for (int x = 0; x < 7; ++x) {
                const double v = PixelEstimate(*scene, x, y), e = GlintExpected(*scene, x, y, gauss);
                peak = std::max(peak, v);
                EXPECT_NEAR(v, e, 1e-6 * e + 1e-9 * peakExpected)
                    << c.profile << " α " << c.radius << " pixel " << x << " " << y;
            }
        EXPECT_GT(peak, 1e9) << "the glint must be in the image";
    }
    // The classical path tracer renders nothing: a mirror cannot be light-sampled and the pixel
    // rays miss a 1 µrad source.
    auto ray = LoadScene("grt_sun_glint.wscene", {{"radius", "1 urad"}, {"res", "7"}}, "ray");
    ASSERT_TRUE(ray);
    Image img = RenderImage(*ray, 4);
    for (float v : img.data) EXPECT_EQ(v, 0);
}

TEST(Grt, SunGlintSolarDiscInteriorReadsReflectedRadiance) {
    auto scene = LoadScene("grt_sun_glint.wscene");  // 4.65 mrad disc, 31×31 pixels of 0.5 mrad
    ASSERT_TRUE(scene);
    const double alpha = 4.65e-3, E = 1000, sigmaTheta = std::tan(0.5e-3) / std::sqrt(12.0);
    const double lSun = E / (Pi * Sqr(std::sin(alpha)));
    const double elevation = Radians(50), offset = 0.15e-3;
    const Vec3 s(std::cos(elevation + offset), 0, -std::sin(elevation + offset));
    int interior = 0, exterior = 0;
    for (int y = 0; y < 31; ++y)
        for (int x = 0; x < 31; ++x) {
            auto ds = scene->GetDetector().Generate(Vec2(x + 0.5, y + 0.5), Vec2(0.5, 0.5));
            const Vec3 d = ds->ray.d, dr(d.x, d.y, -d.z);
            const double gamma = std::acos(std::min(1.0, -Dot(s, dr)));
            const double R = FresnelComplex(std::abs(d.z), 1.0, Complex(0.2, 3.4));
            const double v = PixelEstimate(*scene, x, y);
            if (gamma < alpha - 4 * sigmaTheta) {
                ++interior;
                EXPECT_NEAR(v / (R * lSun), 1, 1e-3) << x << " " << y;
            } else if (gamma > alpha + 4 * sigmaTheta) {
                ++exterior;
                EXPECT_LT(v, 1e-3 * R * lSun) << x << " " << y;
            }
            EXPECT_NEAR(v, GlintExpected(*scene, x, y, GlintCase{"disc", alpha}), 1e-6 * R * lSun);
        }
    EXPECT_GT(interior, 150);
    EXPECT_GT(exterior, 400);
}

// The lights' classical side, through both integrators: a diffuse floor (albedo a) under a
// `distant` disc, a `plane_wave`, a wide `gaussian_beam`, a `directional` light or a far `point`
// light of irradiance E at elevation ε reads a·E·sin ε/π (NEE; for the disc also MIS against
// escaping rays) on a radiometric camera — with a line and with a continuous spectrum alike, since
// every light's strength is the total over its spectrum (with the strength a scale of the spectrum,
// as directional and point lights had it in wscene 1, a 40 nm Gaussian of peak 1 read 4.3e-8 of it).
TEST(Grt, NewLightsOnDiffuseFloorMatchRadiometry) {
    const double expected = 0.5 * 1000 * std::sin(Radians(50)) / Pi;
    struct Source {
        const char *name, *spectrum;
    };
    for (const Source source : {Source{"distant", "line(550 nm)"}, Source{"plane_wave", "line(550 nm)"},
                                Source{"beam", "line(550 nm)"}, Source{"directional", "line(550 nm)"},
                                Source{"point", "line(550 nm)"}, Source{"plane_wave", "gaussian(550 nm, 40 nm)"},
                                Source{"directional", "gaussian(550 nm, 40 nm)"},
                                Source{"point", "gaussian(550 nm, 40 nm)"}})
        for (const char *integrator : {"gr", "classic"})
            // The true scene, and the same with the source 1 % too bright, which must be rejected.
            for (const bool biased : {false, true}) {
                const char *irradiance = biased ? "1010 W/m^2" : "1000 W/m^2";
                auto scene = LoadScene("grt_sun_diffuse.wscene",
                                       {{"source", source.name},
                                        {"spectrum", source.spectrum},
                                        {"irradiance", irradiance}},
                                       integrator);
                ASSERT_TRUE(scene);
                // 8 Sobol' scramble replicas of 8 spp: their spread is the honest error (support/replicas.h).
                const ReplicaEstimate e = ImageOverReplicas(RenderReplicas(*scene, 8, 8, 3));
                const std::string what =
                    std::string(source.name) + " " + source.spectrum + " " + integrator + " " + irradiance;
                if (e.StdError() > 1e-6 * expected) {  // Monte Carlo (the disc)
                    // Measured t, true → 1 % too bright: gr 0.04 → 1141, classic −1.5 → 626
                    // (relative standard errors 9e-6 and 1.6e-5).
                    TTestResult t = MeanTTest(e.mean, e.varianceOfMean, e.dof, expected);
                    std::printf("%s: %.6g +- %.2g (%s)\n", what.c_str(), e.mean, e.StdError(), t.ToString().c_str());
                    if (biased) {
                        EXPECT_LT(t.pValue, 0.001) << what << ": " << e.mean << " (" << t.ToString() << ")";
                    } else {
                        EXPECT_GT(t.pValue, 0.001) << what << ": " << e.mean << " (" << t.ToString() << ")";
                        EXPECT_NEAR(e.mean, expected, 2e-3 * expected) << what;
                    }
                } else {  // delta lights: deterministic up to the beam's 1e-8 profile across the patch
                    EXPECT_EQ(std::abs(e.mean - expected) <= 1e-6 * expected, !biased) << what << ": " << e.mean;
                }
            }
}

}  // namespace
}  // namespace phasor::test
