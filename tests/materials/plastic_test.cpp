// SPDX-License-Identifier: Apache-2.0
// `plastic` (the worked example of docs/kernels.md) and FresnelDiffuseReflectance (fresnel.h):
// analytic references written here, independent of the kernel's code — the textbook Fresnel
// formula, the hemispherical integral by composite Simpson, and Saunderson's total reflectance.
#include <gtest/gtest.h>

#include <cmath>

#include "material_test_util.h"
#include "materials/fresnel.h"
#include "support/stats.h"

namespace phasor::test {
namespace {

// Unpolarised Fresnel reflectance of a dielectric interface, relative index eta = n_t/n_i (Hecht
// §4.6), written out again so the references below do not share the kernel's code.
double RefFresnel(double mu, double eta) {
    const double sin2T = (1 - mu * mu) / (eta * eta);
    if (sin2T >= 1) return 1;
    const double ct = std::sqrt(1 - sin2T);
    const double rs = (mu - eta * ct) / (mu + eta * ct), rp = (eta * mu - ct) / (eta * mu + ct);
    return 0.5 * (rs * rs + rp * rp);
}

// 2∫₀¹ F(μ) μ dμ by composite Simpson. For η < 1, F = 1 below the critical cosine μ_c and rises
// like √(μ − μ_c) above it: the integral over [μ_c, 1] is taken in s with μ = μ_c + (1 − μ_c)s²,
// which makes the integrand smooth.
double RefDiffuseReflectance(double eta) {
    const double muC = eta < 1 ? std::sqrt(1 - eta * eta) : 0;  // below it: total internal reflection
    const int n = 400000;
    const double h = 1.0 / n;
    double s = 0;
    for (int i = 0; i <= n; ++i) {
        const double t = i * h, mu = muC + (1 - muC) * t * t, jacobian = 2 * (1 - muC) * t;
        s += (i == 0 || i == n ? 1 : i % 2 ? 4 : 2) * RefFresnel(mu, eta) * mu * jacobian;
    }
    return 2 * (muC * muC / 2 + s * h / 3);
}

// Saunderson's total reflectance of a coat of index eta over a Lambertian base of albedo rho for
// light at cosθ_i = mu: the coat's Fresnel reflection plus the diffuse light that escapes.
double RefTotalReflectance(double mu, double eta, double rho) {
    const double f = RefFresnel(mu, eta), inner = RefDiffuseReflectance(1 / eta);
    return f + (1 - f) * rho * (1 - inner) / (1 - rho * inner);
}

std::shared_ptr<Material> Plastic(double rho, double ior) {
    Diagnostics diag;
    auto m = BuildMaterial("plastic", ParamDict().Set("reflectance", Value::Number(rho)).Set("ior", Value::Number(ior)),
                           diag);
    EXPECT_TRUE(m && diag.All().empty());
    return m;
}

// The listed specular weight plus ∫ Eval·cosθ_o dω over wi's hemisphere (Eval is isotropic in φ:
// 2π∫₀¹ f(μ) μ dμ, composite Simpson), at the hero wavelength.
double TotalReflectance(const Material &m, const ScatterQuery &q) {
    double total = 0;
    const Prep k(m, q);
    for (const NearDeltaLobe &l : k->ListNearDelta()) total += l.Weight()[0];
    const int n = 20000;
    const double h = 1.0 / n, side = q.wi.z > 0 ? 1 : -1;
    double s = 0;
    for (int i = 0; i <= n; ++i) {
        const double mu = i * h;
        const Vec3 wo(SafeSqrt(1 - mu * mu), 0, side * mu);
        s += (i == 0 || i == n ? 1 : i % 2 ? 4 : 2) * k->Eval(wo)[0] * mu;
    }
    return total + 2 * Pi * s * h / 3;
}

// Closed form (η ≥ 1.01), quadrature (1 ≤ η < 1.01) and reciprocity (η < 1) against the integral.
// Tolerance 1e-10: measured differences are ≤ 4e-14 except 2.4e-11 at η = 1.00001 (the quadrature
// branch, where F varies on the scale √(η² − 1) near μ = 0); the closed form alone would be off by
// 1.4e-9 at η = 1.0001 (cancellation).
TEST(FresnelDiffuseReflectance, MatchesTheHemisphericalIntegral) {
    for (double eta : {0.25, 0.5, 1 / 1.5, 0.9, 0.995, 1.0, 1.00001, 1.0001, 1.001, 1.005, 1.0099, 1.01, 1.02, 1.1, 1.33, 1.5, 2.42, 4.0}) {
        SCOPED_TRACE(eta);
        EXPECT_NEAR(FresnelDiffuseReflectance(eta), RefDiffuseReflectance(eta), 1e-10);
    }
    // Published values: ≈ 0.092 (glass from air) and ≈ 0.596 (glass towards air).
    EXPECT_NEAR(FresnelDiffuseReflectance(1.5), 0.0918, 1e-4);
    EXPECT_NEAR(FresnelDiffuseReflectance(1 / 1.5), 0.5963, 1e-4);
}

// Saunderson: total reflectance F + (1 − F)ρ(1 − F̄_in)/(1 − ρF̄_in) at every angle, and exactly 1 for
// a white base (lossless). Tolerance 1e-8: Simpson on 2·10⁴ panels of a smooth integrand.
TEST(Plastic, TotalReflectanceIsSaunderson) {
    const SampledWavelengths wl = LineWavelength(550e-9);
    for (double ior : {1.33, 1.5, 2.0})
        for (double rho : {0.0, 0.3, 1.0}) {
            auto m = Plastic(rho, ior);
            for (double cosI : {1.0, 0.7, 0.3, 0.05, -0.6}) {
                SCOPED_TRACE(testing::Message() << "ior " << ior << " rho " << rho << " cos " << cosI);
                ScatterQuery q;
                q.wi = DirectionFromCosTheta(cosI, 0.3);
                q.wl = &wl;
                const double expected = RefTotalReflectance(std::abs(cosI), ior, rho);
                EXPECT_NEAR(TotalReflectance(*m, q), expected, 1e-8);
                if (rho == 1) {
                    EXPECT_NEAR(TotalReflectance(*m, q), 1, 1e-8);
                }
            }
        }
}

// A black base leaves the coat's mirror: ((n−1)/(n+1))² at normal incidence, nothing continuous.
TEST(Plastic, BlackBaseIsTheBareCoat) {
    const SampledWavelengths wl = LineWavelength(600e-9);
    auto m = Plastic(0, 1.5);
    ScatterQuery q;
    q.wi = Vec3(0, 0, 1);
    q.wl = &wl;
    const Prep k(*m, q);
    const std::span<const NearDeltaLobe> lobes = k->ListNearDelta();
    ASSERT_EQ(lobes.size(), 1u);
    EXPECT_NEAR(lobes[0].Weight()[0], 0.04, 1e-15);
    EXPECT_EQ(lobes[0].prob, 1);
    EXPECT_EQ(k->Eval(DirectionFromCosTheta(0.5, 1))[0], 0);
}

// What Sample delivers, E[weight] over all lobes, is the total reflectance (t-test at fixed seed;
// the contract suite checks weight = Eval·cos/Pdf, this ties it to Saunderson's formula).
TEST(Plastic, SampledReflectanceMatchesSaunderson) {
    const SampledWavelengths wl = LineWavelength(500e-9);
    auto m = Plastic(0.7, 1.5);
    ScatterQuery q;
    q.wi = DirectionFromCosTheta(std::cos(Radians(40)), 1.0);
    q.wl = &wl;
    TestRng rng(12);
    std::vector<double> w;
    const Prep k(*m, q);
    for (int i = 0; i < 200000; ++i) {
        const double u0 = rng.Uniform(), u1 = rng.Uniform(), u2 = rng.Uniform();
        auto s = k->Sample(u0, Vec2(u1, u2));
        w.push_back(s ? s->weight[0] : 0.0);
    }
    const TTestResult t = OneSampleTTest(w, RefTotalReflectance(std::cos(Radians(40)), 1.5, 0.7));
    EXPECT_GT(t.pValue, 1e-3) << t.ToString();
}

}  // namespace
}  // namespace phasor::test
