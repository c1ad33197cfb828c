// SPDX-License-Identifier: Apache-2.0
// Shadow rays cross free-standing films (Scene::Transmittance, theory §3.5): a dark floor (ρ = 0.1)
// lit by a distant source seen only through a horizontal soap film (thin_film in air, 100 nm of
// n = 1.33, 0.3 m above it and 60 m wide: an infinite sheet as seen from the floor's centre)
// reads the bare floor's value times T̄/(1 − ρ·R̄): T̄ the film's transmittance averaged over the
// source's disc (each direction weighted by its cosine on the floor), R̄ = 2∫R(μ)μ dμ its
// reflectance for the floor's diffuse light, which it sends back (the geometric series of the
// bounces between the two sheets). T and R = 1 − T are the coherent Airy values for `grt` (a GR's
// path: the wave regime) and the incoherent sum of the two faces for `ray` (the ray-optics
// limit). The references are independent of the kernels: tests/support/tmm.h's transfer matrices
// and the closed form (1 − R₁)/(1 + R₁) per polarisation (R₁ one face's) for the incoherent film.
//
// Two sources: a 2° disc, which path sampling alone finds through the film with probability
// ~1e-3 per sample — the old shadow rays, stopped by the film, left it to that, at a relative
// error of tens of per cent at these sample counts; here 16 spp must give 0.3 % — and a 28° disc,
// where half of the floor's light sampling is MIS-shared with its kernel sampling through the
// film: a path sampled into the film's straight lobe must keep the floor vertex's MIS state
// (counting the escape in full would read ~10 % high). Statistics: independent-sampler replicas
// (support/replicas.h), Welch's t on the ratio; each check is shown to reject the other regime's
// transmittance (4 % away), i.e. a biased render.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "support/replicas.h"
#include "support/scene_text.h"
#include "support/stats.h"
#include "support/tmm.h"

namespace phasor::test {
namespace {

constexpr double FilmIndex = 1.33, FilmThickness = 100e-9, Lambda = 550e-9;
const double Elevation = Radians(60);

std::unique_ptr<Scene> FloorScene(const std::string &integrator, double angularRadiusDeg, bool film) {
    const double s = std::cos(Elevation), c = std::sin(Elevation);
    std::string text = "wscene 2\n"
                       "Material \"diffuse\" \"paper\" { reflectance = 0.1 }\n"
                       "Shape \"rectangle\" \"floor\" { material = @paper  to_world = scale(50) }\n";
    if (film)
        text += "Material \"thin_film\" \"soap\" { ior = 1.33  thickness = 100 nm }\n"
                "Shape \"rectangle\" \"film\" { material = @soap  to_world = [scale(30) translate([0 0 0.3] m)] }\n";
    text += "Light \"distant\" \"sun\" { direction = [" + std::to_string(-s) + " 0 " + std::to_string(-c) +
            "]  irradiance = 1 W/m^2  angular_radius = " + std::to_string(angularRadiusDeg) +
            " deg  spectrum = line(550 nm) }\n"
            "Detector \"perspective\" \"cam\" { to_world = lookat(eye = [0 -2 0.1] m, target = [0 0 0] m, up = [0 0 1])"
            "  fov = 3 deg  resolution = [6 6]  response = \"radiometric\" }\n"
            "Integrator \"" + integrator + "\" \"it\" { max_depth = 10 }\n"
            "Render { integrator = @it }\n";
    return SceneFromText(text, "floor.wscene");
}

// The film's unpolarised transmittance at cosθ = mu in air: coherent (transfer matrices) or the
// incoherent sum of the two faces, (1 − R)/(1 + R) per polarisation with R the single face's.
double FilmT(double mu, bool coherent) {
    const double sin0 = std::sqrt(std::max(0.0, 1 - mu * mu));
    if (coherent) return Tmm(Lambda, 1, sin0, {{Cplx(FilmIndex, 0), FilmThickness}}, Cplx(1, 0)).T();
    const TmmRT face = Tmm(Lambda, 1, sin0, {}, Cplx(FilmIndex, 0));
    return 0.5 * ((1 - face.Rs) / (1 + face.Rs) + (1 - face.Rp) / (1 + face.Rp));
}

// T̄/(1 − ρ·R̄) (see the top): T̄ = ∫ T(ω_z)·ω_z dω / ∫ ω_z dω over the uniform disc of the given
// radius around the source's direction, R̄ = 2∫₀¹ (1 − T(μ))·μ dμ.
double ExpectedRatio(double angularRadiusDeg, bool coherent) {
    double rBar = 0;
    const int nmu = 4000;
    for (int i = 0; i < nmu; ++i) {
        const double mu = (i + 0.5) / nmu;
        rBar += 2 * (1 - FilmT(mu, coherent)) * mu / nmu;
    }
    const double delta = Radians(angularRadiusDeg);
    const Vec3 axis(std::cos(Elevation), 0, std::sin(Elevation));  // towards the source
    const Vec3 u(-std::sin(Elevation), 0, std::cos(Elevation)), v(0, 1, 0);
    const int na = 200, nphi = 256;
    double num = 0, den = 0;
    for (int i = 0; i < na; ++i) {
        const double a = (i + 0.5) * delta / na;
        for (int j = 0; j < nphi; ++j) {
            const double phi = (j + 0.5) * 2 * Pi / nphi;
            const Vec3 w = axis * std::cos(a) + (u * std::cos(phi) + v * std::sin(phi)) * std::sin(a);
            if (w.z <= 0) continue;
            num += std::sin(a) * w.z * FilmT(w.z, coherent);
            den += std::sin(a) * w.z;
        }
    }
    return num / den / (1 - 0.1 * rBar);
}

struct Ratio {
    double value = 0, stdError = 0, dof = 0;
};

// The film render's mean over the image divided by the bare render's, from `replicas` independent
// renders of each at `spp` (independent sampler: honest spreads); delta-method error of the ratio.
Ratio MeasureRatio(const std::string &integrator, double angularRadiusDeg, int spp, int replicas) {
    auto withFilm = FloorScene(integrator, angularRadiusDeg, true), bare = FloorScene(integrator, angularRadiusDeg, false);
    if (!withFilm || !bare) return {};
    const ReplicaEstimate f = ImageOverReplicas(RenderReplicas(*withFilm, spp, replicas, 11, "independent"));
    const ReplicaEstimate b = ImageOverReplicas(RenderReplicas(*bare, spp, replicas, 101, "independent"));
    Ratio r;
    r.value = f.mean / b.mean;
    r.stdError = r.value * std::sqrt(f.varianceOfMean / (f.mean * f.mean) + b.varianceOfMean / (b.mean * b.mean));
    r.dof = f.dof;
    return r;
}

void CheckRatio(const std::string &integrator, double angularRadiusDeg, int spp, double maxRelError) {
    const bool coherent = integrator == "grt";
    const Ratio r = MeasureRatio(integrator, angularRadiusDeg, spp, 8);
    const double expected = ExpectedRatio(angularRadiusDeg, coherent), other = ExpectedRatio(angularRadiusDeg, !coherent);
    SCOPED_TRACE(integrator + ", disc of " + std::to_string(angularRadiusDeg) + " deg: ratio " + std::to_string(r.value) +
                 " +- " + std::to_string(r.stdError) + ", expected " + std::to_string(expected) + " (the other regime's " +
                 std::to_string(other) + ")");
    ASSERT_GT(r.value, 0);
    // Precise enough to tell the regimes apart (the power of the test) …
    EXPECT_LT(r.stdError, maxRelError * expected);
    ASSERT_GT(std::abs(expected - other), 8 * r.stdError) << "the test could not tell coherent from incoherent";
    // … and in agreement with the right one: two-sided t-test at α = 0.001, which the other
    // regime's transmittance (a biased render by ~4 %) fails.
    const double tRight = (r.value - expected) / r.stdError, tWrong = (r.value - other) / r.stdError;
    EXPECT_GT(StudentTwoSidedP(tRight, r.dof), 0.001);
    EXPECT_LT(StudentTwoSidedP(tWrong, r.dof), 0.001);
}

TEST(ShadowTransmittance, SmallSourceThroughAFilmAtLowSampleCounts) {
    for (const char *integrator : {"grt", "ray"}) CheckRatio(integrator, 2, 16, 0.003);
}

TEST(ShadowTransmittance, WideSourceSharedBetweenLightAndKernelSampling) {
    for (const char *integrator : {"grt", "ray"}) CheckRatio(integrator, 28, 64, 0.005);
}

}  // namespace
}  // namespace phasor::test
