// SPDX-License-Identifier: Apache-2.0
// Partial coherence in `sample_solve` (issue 13 acceptance; theory §4.4, §0 D5; docs/sample_solve.md)
// on scenes/validation/sample_solve_film.wscene: a thin film (n = 1.38 on a dark glass) under a
// source of chosen coherence, a one-pixel sensor across its specular reflection.
//   * Fully coherent source (a plane wave): sample_solve = grt = the Airy formula (written out
//     here, independently of the kernels) within 1e-4 (measured ≤ 1e-9).
//   * Partially coherent `distant` source (Gaussian profile, Ω = α²/4) measured in closed form:
//     sample_solve reads μR_coh + (1 − μ)R_incoh with μ = exp(−½k²|Δ⊥|²Ω), Δ⊥ = 2d·tanθ_t·cosθ
//     (1e-6); grt reads R_coh; the difference is (1 − μ)(R_incoh − R_coh).
//   * Van Cittert–Zernike: films of growing thickness (at fringe extrema) under sources of growing
//     angular size — the normalised fringe contrast of sample_solve is exp(−v²/8), v = k|Δ⊥|α, and
//     follows 2J₁(v)/v to O(v⁴) (|difference| ≤ v⁴/384·1.1: the series' next terms); the fully
//     coherent solve (force_coherent: coherent plane waves drawn from the profile) converges to the
//     exact average of the Airy R over the profile (Gauss–Hermite quadrature here), within the error
//     of independent replicas; with an `area` lamp (a uniform disc, whose points every integrator
//     samples) sample_solve converges to the exact disc average (quadrature over the pixel's
//     directions), whose contrast is 2J₁(v)/v up to the film's multiple-beam and nonlinear-phase
//     terms (≤ 0.01 measured). Each statistical comparison is shown to reject a 2 % brighter source
//     (the pixel is linear in it: the same data against a reference 2 % higher).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/numerics/gauss_legendre.h"
#include "render_row.h"
#include "support/stats.h"

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

// ---- partially coherent, closed form: μR_coh + (1 − μ)R_incoh ------------------------------------------

TEST(SampleSolveCoherence, PartiallyCoherentFilmIsTheMuMixture) {
    const double thetaDeg = 30, theta = Radians(thetaDeg), k = 2 * Pi / Lambda;
    double worst = 0;
    int distinct = 0;
    for (double d : {2e-6, 7e-6, 15e-6})
        for (double alpha : {0.005, 0.02}) {
            const FilmR f = Film(d, std::cos(theta));
            const double mu = std::exp(-0.5 * k * k * Sqr(Shear(d, theta)) * alpha * alpha / 4);
            auto solve = BuildValidation(ValidationScene("sample_solve_film.wscene"), Defines("distant", d, thetaDeg, alpha), "solve");
            auto gr = BuildValidation(ValidationScene("sample_solve_film.wscene"), Defines("distant", d, thetaDeg, alpha), "gr");
            ASSERT_TRUE(solve && gr);
            const double s = Read(RenderImage(*solve, 1)), g = Read(RenderImage(*gr, 1));
            const double expected = mu * f.coh + (1 - mu) * f.inc;
            // 1e-6: the float image (the closed forms are exact to ~1e-12).
            EXPECT_NEAR(s, expected, 1e-6) << "d = " << d << ", α = " << alpha << ", μ = " << mu;
            EXPECT_NEAR(g, f.coh, 1e-6);
            EXPECT_NEAR(s - g, (1 - mu) * (f.inc - f.coh), 2e-6);
            distinct += std::abs(s - g) > 1e-4;
            worst = std::max(worst, std::abs(s - expected));
            std::printf("MEASURED d = %4.1f um, alpha = %2.0f mrad: mu = %.4f, sample_solve %.6f (mu-mixture %.6f), grt %.6f "
                        "(R_coh %.6f)\n",
                        d * 1e6, alpha * 1e3, mu, s, expected, g, f.coh);
        }
    EXPECT_GE(distinct, 3) << "the sweep must reach partial coherence";
    std::printf("MEASURED |sample_solve − (mu R_coh + (1 − mu) R_incoh)| ≤ %.3g\n", worst);
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

/// ⟨R_coh⟩ over a Gaussian profile of Ω = α²/4 about the central incidence θ (the average over the
/// directions the fully coherent solve draws): the midpoint rule over the two direction cosines on
/// ±6σ (σ = α/2) with 160 points per axis — ≥ 50 per fringe period for these films, and the
/// integrand is analytic, so the rule is accurate to far below the Monte Carlo error. The mode's
/// weights (1/cos of its irradiance, cos at the sensor) cancel to O(u⁴) and are left out.
double GaussianAverage(double d, double theta, double alpha) {
    const double sigma = alpha / 2;
    const int n = 160;
    double sum = 0, norm = 0;
    for (int i = 0; i < n; ++i) {
        const double ux = -6 * sigma + (i + 0.5) * 12 * sigma / n;
        for (int j = 0; j < n; ++j) {
            const double uy = -6 * sigma + (j + 0.5) * 12 * sigma / n;
            const double g = std::exp(-0.5 * (ux * ux + uy * uy) / (sigma * sigma));
            // The mode's direction: the central one tilted by ux in the plane of incidence, uy across.
            const double cosI = std::cos(theta + ux) * std::sqrt(std::max(0.0, 1 - uy * uy));
            sum += g * Film(d, cosI).coh;
            norm += g;
        }
    }
    return sum / norm;
}

TEST(SampleSolveCoherence, FringeContrastFollowsVanCittertZernike) {
    const double thetaDeg = 30, theta = Radians(thetaDeg);
    double worstMu = 0, worstJinc = 0;
    for (const VczCase &c : VczSweep(theta)) {
        const FilmR f = Film(c.d, std::cos(theta));
        auto solve = BuildValidation(ValidationScene("sample_solve_film.wscene"), Defines("distant", c.d, thetaDeg, c.alpha), "solve");
        ASSERT_TRUE(solve);
        const double s = Read(RenderImage(*solve, 1));
        const double contrast = (s - f.inc) / (f.coh - f.inc);
        const double mu = std::exp(-c.v * c.v / 8);
        EXPECT_NEAR(contrast, mu, 1e-4) << "d = " << c.d << ", α = " << c.alpha;  // float image / (R_coh − R_inc)
        // D5: exp(−v²/8) = 2J₁(v)/v + O(v⁴) — the difference is v⁴(1/128 − 1/192) = v⁴/384 to leading order.
        EXPECT_LE(std::abs(contrast - Jinc(c.v)), 1.1 * std::pow(c.v, 4) / 384 + 1e-4) << "v = " << c.v;
        worstMu = std::max(worstMu, std::abs(contrast - mu));
        worstJinc = std::max(worstJinc, std::abs(contrast - Jinc(c.v)));
        std::printf("MEASURED VCZ d = %.2f um, alpha = %4.1f mrad, v = %.3f: contrast %.5f, exp(-v^2/8) %.5f, "
                    "2J1(v)/v %.5f\n",
                    c.d * 1e6, c.alpha * 1e3, c.v, contrast, mu, Jinc(c.v));
    }
    std::printf("MEASURED VCZ: |contrast − mu| ≤ %.3g, |contrast − 2J1(v)/v| ≤ %.3g\n", worstMu, worstJinc);
}

// The fully coherent solve converges to the exact average of R_coh over the Gaussian profile; the
// partially coherent closed form differs from that average only by the linearisation of the phase
// (and the film's multiple-beam terms). Independent replicas; a 2 % brighter source is rejected.
TEST(SampleSolveCoherence, FullyCoherentSolveIsTheEnsembleAverage) {
    const double thetaDeg = 30, theta = Radians(thetaDeg);
    const int spp = 256, replicas = 12;
    const std::vector<VczCase> sweep = VczSweep(theta);
    const double alpha = SidakAlpha(0.01, 3);
    for (int idx : {1, 4, 8}) {  // v ≈ 0.5, 1.0, 3.1
        const VczCase &c = sweep[std::size_t(idx)];
        const double ref = GaussianAverage(c.d, theta, c.alpha);
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
        const FilmR f = Film(c.d, std::cos(theta));
        const double partial = std::exp(-c.v * c.v / 8) * f.coh + (1 - std::exp(-c.v * c.v / 8)) * f.inc;
        std::printf("MEASURED fully coherent solve, v = %.3f: %.6f ± %.6f vs profile average %.6f (%s; biased %s); "
                    "partially coherent closed form %.6f\n",
                    c.v, e.mean, e.StdError(), ref, t.ToString().c_str(), tb.ToString().c_str(), partial);
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
    // directions, as grt's closed form (the profile times the GR's window, D14) and the fully
    // coherent solve show. sample_solve's μ must use the same ensemble — the profile times the
    // GR's window, Ω·Ω_w/(Ω + Ω_w) — and then agrees with grt: the rows' relative L1 difference is
    // 0.002–0.004 (the disc taken as a Gaussian in μ; same paths, so little noise). With the
    // source's whole Ω (the former rule, an outside user's report) it was 0.21–0.40, a dark fringe
    // reading 70× grt's; the bound 0.02 lies between.
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
        EXPECT_LT(diff / sum, 0.02) << "row " << y;
    }
}

}  // namespace
}  // namespace phasor::test
