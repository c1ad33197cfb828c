// SPDX-License-Identifier: Apache-2.0
// Partial coherence in `sample_solve` (issue 13 and issue 20 §2 acceptance; theory §0 D15;
// docs/sample_solve.md) on scenes/validation/sample_solve_film.wscene: a thin film (n = 1.38 on a dark
// glass) under a source of chosen coherence, a one-pixel sensor across its specular reflection.
//   * Fully coherent source (a plane wave): sample_solve = grt = the Airy formula (written out
//     here, independently of the kernels) within 1e-4 (measured ≤ 1e-9).
//   * Partially coherent `distant` source (Gaussian profile, Ω = α²/4) measured in closed form:
//     sample_solve and grt read the Airy R averaged over the profile (its exact average, not the
//     first-order μR_coh + (1 − μ)R_incoh of before); the normalised fringe contrast is then the
//     profile's characteristic function exp(−v²/8), v = k|Δ⊥|α, up to the film's second-order phase
//     and multiple-beam terms; the fully coherent solve (force_coherent: coherent plane waves drawn
//     from the profile) converges to the same average within the error of independent replicas;
//     with an `area` lamp (a uniform disc, whose points every integrator samples) sample_solve
//     converges to the exact disc average (quadrature over the pixel's directions), whose contrast is
//     2J₁(v)/v up to the film's multiple-beam and nonlinear-phase terms (≤ 0.01 measured). Each
//     statistical comparison is shown to reject a 2 % brighter source (the pixel is linear in it:
//     the same data against a reference 2 % higher).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/numerics/gauss_legendre.h"
#include "render_row.h"
#include "support/stats.h"
#include "support/tmm.h"

namespace phasor::test {
namespace {

// ---- an independent reference: the film's Airy and incoherent reflectances ----------------------

constexpr double Lambda = 550e-9, FilmN = 1.38;
const Complex SubstrateN(1.52, 0.001);

Complex CosIn(Complex n, double sin0) { return std::sqrt(1.0 - sin0 * sin0 / (n * n)); }

struct FilmR {
    double coh = 0, inc = 0;  // unpolarised: ½(s + p)
};
/// R of the film of thickness d at incidence cosθ0 (from air): Airy (coherent) and the sum in power
/// (incoherent: |r01|² + |t01 t10|²|r12|²/(1 − |r10 r12|²), theory §4.4), per polarisation.
FilmR Film(double d, double cos0) {
    const double sin0 = std::sqrt(std::max(0.0, 1 - cos0 * cos0));
    const Complex n1(FilmN, 0), n2 = SubstrateN, c0(cos0, 0), c1 = CosIn(n1, sin0), c2 = CosIn(n2, sin0);
    const Complex e = std::exp(Complex(0, 2 * (2 * Pi / Lambda) * FilmN * d) * c1);
    FilmR out;
    for (int pol = 0; pol < 2; ++pol) {
        const Complex r01 = pol == 0 ? (c0 - n1 * c1) / (c0 + n1 * c1) : (n1 * c0 - c1) / (n1 * c0 + c1);
        const Complex r12 = pol == 0 ? (n1 * c1 - n2 * c2) / (n1 * c1 + n2 * c2) : (n2 * c1 - n1 * c2) / (n2 * c1 + n1 * c2);
        const Complex r = (r01 + r12 * e) / (1.0 + r01 * r12 * e);
        out.coh += 0.5 * std::norm(r);
        out.inc += 0.5 * (std::norm(r01) + std::norm(1.0 - r01 * r01) * std::norm(r12) / (1 - std::norm(r01) * std::norm(r12)));
    }
    return out;
}

/// |Δ⊥| = 2d·tanθ_t·cosθ: the shear of the film's two reflections across the incident beam.
double Shear(double d, double theta) {
    const double st = std::sin(theta) / FilmN;
    return 2 * d * st / std::sqrt(1 - st * st) * std::cos(theta);
}

/// A film thickness near `d` at an extremum of its fringes at θ (2δ = 2πm).
double AtExtremum(double d, double theta) {
    const double c1 = std::sqrt(1 - Sqr(std::sin(theta) / FilmN));
    const double step = Lambda / (2 * FilmN * c1);
    return std::round(d / step) * step;
}

double Jinc(double v) { return v == 0 ? 1 : 2 * std::cyl_bessel_j(1, v) / v; }

std::string Len(double m) { return std::to_string(m * 1e9) + " nm"; }

double Read(const Image &img) { return img.At(0, 0, img.ChannelIndex("intensity")); }

DefineList Defines(const std::string &source, double d, double thetaDeg, double alpha) {
    return {{"source", "\"" + source + "\""},
            {"thickness", Len(d)},
            {"theta", std::to_string(thetaDeg) + " deg"},
            {"radius", std::to_string(alpha * 1e3) + " mrad"}};
}

// ---- fully coherent: Airy ------------------------------------------------------------------------

TEST(SampleSolveCoherence, FullyCoherentFilmIsAiry) {
    double worst = 0;
    for (double thetaDeg : {15.0, 30.0, 50.0})
        for (double d : {0.3e-6, 3e-6}) {
            const double ref = Film(d, std::cos(Radians(thetaDeg))).coh;
            for (const char *integrator : {"solve", "gr"}) {
                auto scene = BuildValidation(ValidationScene("sample_solve_film.wscene"),
                                             Defines("plane_wave", d, thetaDeg, 0.01), integrator);
                ASSERT_TRUE(scene);
                const double r = Read(RenderImage(*scene, 1));
                EXPECT_NEAR(r, ref, 1e-4) << integrator << " θ = " << thetaDeg << "°, d = " << d;
                worst = std::max(worst, std::abs(r - ref));
            }
        }
    std::printf("MEASURED plane wave on a film: |sample_solve, grt − Airy| ≤ %.3g\n", worst);
}

// ---- van Cittert–Zernike ---------------------------------------------------------------------------------

struct VczCase {
    double d, alpha, v;
};
std::vector<VczCase> VczSweep(double theta) {
    const double k = 2 * Pi / Lambda;
    std::vector<VczCase> out;
    for (double d0 : {5e-6, 10e-6, 20e-6})
        for (double alpha : {0.005, 0.01, 0.02}) {
            const double d = AtExtremum(d0, theta);
            out.push_back({d, alpha, k * Shear(d, theta) * alpha});
        }
    return out;
}

/// ⟨R_coh⟩ over the Gaussian profile of Ω = α²/4 about the central incidence θ — the average over
/// the directions the fully coherent solve draws — in the source's transverse direction cosines
/// (tests/support/tmm.h's polar quadrature; the Airy R of Film() at each direction's incidence).
double ProfileAverage(double d, double theta, double alpha) {
    return GaussianAverage(Vec3(std::sin(theta), 0, std::cos(theta)), alpha * alpha / 4,
                           [&](const Vec3 &w) { return Film(d, w.z).coh; }, 48, 384);
}

// ---- partially coherent, closed form: the profile's average ------------------------------------

TEST(SampleSolveCoherence, PartiallyCoherentFilmIsTheProfileAverage) {
    const double thetaDeg = 30, theta = Radians(thetaDeg);
    double worst = 0;
    int distinct = 0;
    for (double d : {2e-6, 7e-6, 15e-6})
        for (double alpha : {0.005, 0.02}) {
            const FilmR f = Film(d, std::cos(theta));
            auto solve = BuildValidation(ValidationScene("sample_solve_film.wscene"), Defines("distant", d, thetaDeg, alpha), "solve");
            auto gr = BuildValidation(ValidationScene("sample_solve_film.wscene"), Defines("distant", d, thetaDeg, alpha), "gr");
            ASSERT_TRUE(solve && gr);
            const double s = Read(RenderImage(*solve, 1)), g = Read(RenderImage(*gr, 1));
            const double expected = ProfileAverage(d, theta, alpha);
            // 2e-6: the rules' bound (3e-4 of sup R ≈ 0.05) is far looser than what they reach.
            EXPECT_NEAR(s, expected, 2e-6) << "d = " << d << ", α = " << alpha;
            EXPECT_NEAR(g, s, 1e-7) << "grt and sample_solve average over the same ensemble";
            distinct += std::abs(s - f.coh) > 1e-5;  // 2000× the agreement asserted above
            worst = std::max(worst, std::abs(s - expected));
            std::printf("MEASURED d = %4.1f um, alpha = %2.0f mrad: sample_solve %.6f, grt %.6f, profile average %.6f "
                        "(mean direction %.6f)\n",
                        d * 1e6, alpha * 1e3, s, g, expected, f.coh);
        }
    EXPECT_GE(distinct, 4) << "the sweep must reach partial coherence";
    std::printf("MEASURED |sample_solve − profile average| ≤ %.3g\n", worst);
}

TEST(SampleSolveCoherence, FringeContrastFollowsVanCittertZernike) {
    // The two-beam, linear-phase limit of the exact average is the profile's characteristic
    // function exp(−v²/8) (D5); the film's second-order phase over the profile and its multiple-beam
    // terms (r² ≈ 1e-3) add the measured remainder.
    const double thetaDeg = 30, theta = Radians(thetaDeg);
    double worstMu = 0;
    for (const VczCase &c : VczSweep(theta)) {
        const FilmR f = Film(c.d, std::cos(theta));
        auto solve = BuildValidation(ValidationScene("sample_solve_film.wscene"), Defines("distant", c.d, thetaDeg, c.alpha), "solve");
        ASSERT_TRUE(solve);
        const double s = Read(RenderImage(*solve, 1));
        const double contrast = (s - f.inc) / (f.coh - f.inc);
        const double mu = std::exp(-c.v * c.v / 8);
        EXPECT_NEAR(contrast, mu, 0.02) << "d = " << c.d << ", α = " << c.alpha;
        EXPECT_NEAR(s, ProfileAverage(c.d, theta, c.alpha), 2e-6);
        worstMu = std::max(worstMu, std::abs(contrast - mu));
        std::printf("MEASURED VCZ d = %.2f um, alpha = %4.1f mrad, v = %.3f: contrast %.5f, exp(-v^2/8) %.5f, "
                    "2J1(v)/v %.5f\n",
                    c.d * 1e6, c.alpha * 1e3, c.v, contrast, mu, Jinc(c.v));
    }
    std::printf("MEASURED VCZ: |contrast − exp(-v^2/8)| ≤ %.3g\n", worstMu);
}

// The fully coherent solve converges to the exact average of R_coh over the Gaussian profile, which
// the partially coherent closed form computes (the same mean, without the noise). Independent
// replicas; a 2 % brighter source is rejected.
TEST(SampleSolveCoherence, FullyCoherentSolveIsTheEnsembleAverage) {
    const double thetaDeg = 30, theta = Radians(thetaDeg);
    const int spp = 256, replicas = 12;
    const std::vector<VczCase> sweep = VczSweep(theta);
    const double alpha = SidakAlpha(0.01, 3);
    for (int idx : {1, 4, 8}) {  // v ≈ 0.5, 1.0, 3.1
        const VczCase &c = sweep[std::size_t(idx)];
        const double ref = ProfileAverage(c.d, theta, c.alpha);
        auto scene = BuildValidation(ValidationScene("sample_solve_film.wscene"), Defines("distant", c.d, thetaDeg, c.alpha),
                                     "coherent");
        ASSERT_TRUE(scene);
        const ReplicaEstimate e = ImageOverReplicas(RenderReplicas(*scene, spp, replicas, 10));
        const TTestResult t = MeanTTest(e.mean, e.varianceOfMean, e.dof, ref);
        // The pixel is linear in the source (flux / E_ref): the render of a 2 % brighter source is
        // this one against a reference 2 % higher.
        const TTestResult tb = MeanTTest(e.mean, e.varianceOfMean, e.dof, 1.02 * ref);
        EXPECT_GT(t.pValue, alpha) << "v = " << c.v << ": " << e.mean << " ± " << e.StdError() << " vs " << ref;
        EXPECT_LT(tb.pValue, alpha) << "a 2 % brighter source must be rejected (v = " << c.v << ")";
        auto solve = BuildValidation(ValidationScene("sample_solve_film.wscene"), Defines("distant", c.d, thetaDeg, c.alpha), "solve");
        ASSERT_TRUE(solve);
        const double closed = Read(RenderImage(*solve, 1));
        EXPECT_NEAR(closed, ref, 2e-6);
        std::printf("MEASURED fully coherent solve, v = %.3f: %.6f ± %.6f vs profile average %.6f (%s; biased %s); "
                    "partially coherent closed form %.6f\n",
                    c.v, e.mean, e.StdError(), ref, t.ToString().c_str(), tb.ToString().c_str(), closed);
    }
}

// An `area` lamp (a uniform Lambertian disc of angular radius α): every integrator samples its
// points; sample_solve converges to the exact average over the pixel's directions (quadrature),
// whose normalised contrast follows 2J₁(v)/v.
TEST(SampleSolveCoherence, AreaLampWashesOutFringesAsVanCittertZernike) {
    const double thetaDeg = 30, theta = Radians(thetaDeg), lamp = 1, distance = 5e-3;
    const int spp = 4096, replicas = 24;
    const double alphaT = SidakAlpha(0.01, 3);
    const std::vector<VczCase> sweep = VczSweep(theta);
    double worstJinc = 0;
    for (int idx : {1, 4, 8}) {
        const VczCase &c = sweep[std::size_t(idx)];
        // Quadrature of the estimator's integrand over the pixel's direction cosines u (𝒟 = 1 per
        // d²u): L·R(θ_i(u))·[the mirrored ray meets the lamp disc]. The lamp's image is a disc
        // about the specular direction: per azimuth (midpoint rule, spectrally accurate for this
        // periodic integrand) its edge radius by bisection, then Gauss–Legendre in u to the edge
        // (the integrand is smooth inside) — and the same with R = 1 (the image's irradiance).
        const Vec3 s0(std::sin(theta), 0, std::cos(theta));  // plate → sensor
        const Vec3 sensor = s0 * distance, nS = -s0;
        const Frame fs = Frame::FromNormal(nS);
        const Vec3 lampC = Vec3(-std::sin(theta), 0, std::cos(theta)) * lamp, lampN = Normalize(-lampC);
        const double lampR = lamp * std::tan(c.alpha), L = 1 / (Pi * Sqr(std::sin(c.alpha)));
        // The mirrored ray along u: its incidence cosine and whether it meets the lamp.
        auto trace = [&](double r, double phi, double *cosI) {
            const Vec3 dir = Normalize(fs.s * (r * std::cos(phi)) + fs.t * (r * std::sin(phi)) + fs.n * std::sqrt(1 - r * r));
            const Vec3 p = sensor + dir * (-sensor.z / dir.z), refl(dir.x, dir.y, -dir.z);
            *cosI = refl.z;
            const double t = Dot(lampC - p, lampN) / Dot(refl, lampN);
            return t > 0 && Length(p + refl * t - lampC) <= lampR;
        };
        double sumR = 0, sum1 = 0;
        const int nphi = 64;
        for (int b = 0; b < nphi; ++b) {
            const double phi = (b + 0.5) * 2 * Pi / nphi;
            double lo = 0, hi = 1.5 * std::sin(c.alpha), cosI = 0;
            for (int it = 0; it < 60; ++it) (trace(0.5 * (lo + hi), phi, &cosI) ? lo : hi) = 0.5 * (lo + hi);
            sumR += IntegrateGaussLegendre([&](double r) { trace(r, phi, &cosI); return r * Film(c.d, cosI).coh; }, 0.0, lo, 16, 4);
            sum1 += 0.5 * lo * lo;
        }
        sumR *= L * 2 * Pi / nphi;
        sum1 *= L * 2 * Pi / nphi;
        const double ref = sumR;
        auto scene = BuildValidation(ValidationScene("sample_solve_film.wscene"), Defines("area", c.d, thetaDeg, c.alpha),
                                     "solve");
        ASSERT_TRUE(scene);
        const ReplicaEstimate e = ImageOverReplicas(RenderReplicas(*scene, spp, replicas, 20));
        const TTestResult t = MeanTTest(e.mean, e.varianceOfMean, e.dof, ref);
        const TTestResult tb = MeanTTest(e.mean, e.varianceOfMean, e.dof, 1.02 * ref);  // a 2 % brighter lamp
        EXPECT_GT(t.pValue, alphaT) << "v = " << c.v << ": " << e.mean << " ± " << e.StdError() << " vs " << ref;
        EXPECT_LT(tb.pValue, alphaT) << "a 2 % brighter lamp must be rejected (v = " << c.v << ")";
        // The exact disc average's normalised contrast against 2J₁(v)/v (two-beam, linear phase).
        const FilmR f = Film(c.d, std::cos(theta));
        const double contrast = (ref / sum1 - f.inc) / (f.coh - f.inc);
        EXPECT_NEAR(contrast, Jinc(c.v), 0.05) << "v = " << c.v;
        worstJinc = std::max(worstJinc, std::abs(contrast - Jinc(c.v)));
        std::printf("MEASURED area lamp, v = %.3f: %.6f ± %.6f vs quadrature %.6f (%s; biased %s); contrast %.4f, "
                    "2J1(v)/v %.4f, exp(-v^2/8) %.4f\n",
                    c.v, e.mean, e.StdError(), ref, t.ToString().c_str(), tb.ToString().c_str(), contrast, Jinc(c.v),
                    std::exp(-c.v * c.v / 8));
    }
    std::printf("MEASURED area lamp: |contrast − 2J1(v)/v| ≤ %.3g\n", worstJinc);
}

TEST(SampleSolveCoherence, CameraPixelsSeeTheirPartOfTheSource) {
    // A 10 µm soap film under a 30 mrad sun, seen by a 32-pixel, 8° camera: each pixel (≈ 4 mrad)
    // is far narrower than the source, so it resolves the fringes of R_coh over the source's
    // directions, as grt's closed form (the profile times the GR's window, D14, D15) and the fully
    // coherent solve show. sample_solve averages over the same ensemble — the profile times the GR's
    // window — and agrees with grt to rounding (the same paths; before the exact average its μ with
    // the source's whole Ω read a dark fringe 70× grt's, an outside user's report).
    const std::string text = R"(wscene 2
Light "distant" "sun" {
    direction = [(sin(30 deg)) 0 (-cos(30 deg))]
    irradiance = 1 W/m^2
    profile = "disc"
    angular_radius = 30 mrad
    spectrum = line(550 nm)
}
Material "thin_film" "soap" { ior = 1.33  thickness = 10 um }
Shape "rectangle" "plate" { material = @soap  to_world = scale(0.5) }
Detector "perspective" "cam" {
    to_world = lookat(eye = [(0.2 * sin(30 deg)) 0 (0.2 * cos(30 deg))] m, target = [0 0 0] m, up = [0 1 0])
    fov = 8 deg
    resolution = [32 32]
    response = "radiometric"
    pixel = "gaussian"
}
Integrator "grt" "g" { max_depth = 2 }
Integrator "sample_solve" "ss" { max_depth = 2 }
Render { integrator = @ss spp = 8 }
)";
    auto grt = BuildSceneText(text, "g"), ss = BuildSceneText(text, "ss");
    ASSERT_TRUE(grt && ss);
    const Image a = RenderImage(*grt, 8), b = RenderImage(*ss, 8);
    const int ca = a.ChannelIndex("intensity"), cb = b.ChannelIndex("intensity");
    for (int y : {8, 16, 24}) {
        double sum = 0, diff = 0, lo = Infinity, hi = 0;
        for (int x = 0; x < a.width; ++x) {
            const double va = a.At(x, y, ca), vb = b.At(x, y, cb);
            sum += va;
            diff += std::abs(vb - va);
            if (va > 0) lo = std::min(lo, va), hi = std::max(hi, va);
        }
        ASSERT_GT(sum, 0) << "row " << y;
        EXPECT_GT(hi, 5 * lo) << "row " << y << ": the fringes are not resolved at all (the test would not tell)";
        std::printf("MEASURED camera film row %d: relative L1 difference sample_solve vs grt %.4g\n", y, diff / sum);
        EXPECT_LT(diff / sum, 1e-6) << "row " << y;
    }
}

}  // namespace
}  // namespace phasor::test
