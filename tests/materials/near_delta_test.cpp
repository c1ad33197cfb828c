// SPDX-License-Identifier: Apache-2.0
// Near-delta lobes for generalized rays (design.md §4.1): with !rayOptics, Eval of `conductor` and
// `dielectric` reports each lobe as the GR's own angular Gaussian (materials/near_delta.h). Its
// integral is the lobe's weight, and NEE through it to a plane wave reproduces the closed-form
// Eq. 24 measurement of the reflected GR (theory §2.4 item 2) — the glint of theory §0 D14.
#include <gtest/gtest.h>

#include <functional>

#include "core/genray.h"
#include "material_test_util.h"
#include "materials/fresnel.h"

namespace phasor::test {
namespace {

// ∫ over directions about the unit axis c of F(w)·dω, on a polar grid reaching `reach` radians.
double IntegrateAbout(const Vec3 &c, double reach, const std::function<double(const Vec3 &)> &F) {
    const Frame f = Frame::FromNormal(c);
    const int nG = 4000, nP = 64;  // midpoint rule: relative error ≈ (reach/nG/σ)²/24 ≈ 3e-7
    double sum = 0;
    for (int i = 0; i < nG; ++i) {
        const double g = (i + 0.5) * reach / nG;
        double ring = 0;
        for (int j = 0; j < nP; ++j) {
            const double p = 2 * Pi * (j + 0.5) / nP;
            ring += F(f.ToWorld(Vec3(std::sin(g) * std::cos(p), std::sin(g) * std::sin(p), std::cos(g))));
        }
        sum += ring * (2 * Pi / nP) * std::sin(g) * (reach / nG);
    }
    return sum;
}

ScatterQuery GrQuery(const Vec3 &wi, const SampledWavelengths &wl, double beta2, double rho) {
    ScatterQuery q;
    q.wi = wi;
    q.wl = &wl;
    q.rayOptics = false;
    q.beta2 = beta2;
    q.rho = rho;
    return q;
}

TEST(NearDelta, ConductorLobeIntegratesToFresnelAndMatchesClosedForm) {
    Diagnostics diag;
    auto m =
        BuildMaterial("conductor", ParamDict().Set("ior", Value::ComplexNumber(Complex(0.2, 3.0))), diag);
    ASSERT_TRUE(m);
    const SampledWavelengths wl = LineWavelength(550e-9);
    const double k = 2 * Pi / 550e-9;
    const double sigma = 0.01;  // angular std of the GR [rad]
    const double rho = 0.7;
    const double beta2 = (1 + rho * rho) / (2 * sigma * sigma * k * k);
    const Vec3 wi = DirectionFromCosTheta(0.6, 0.4);
    ScatterQuery q = GrQuery(wi, wl, beta2, rho);
    const double R = FresnelConductor(0.6, Complex(0.2, 3.0));
    const Vec3 wr = ReflectLocal(wi);
    const double total =
        IntegrateAbout(wr, 10 * sigma, [&](const Vec3 &wo) { return m->Eval(q, wo)[0] * std::abs(wo.z); });
    EXPECT_NEAR(total / R, 1, 1e-6);
    // NEE to a plane wave arriving along −wo: f·|cosθo|·E equals the closed-form k²·M of the
    // reflected GR's time reverse, up to the density's cosγ (d²u⊥ = cosγ dω).
    for (double off : {0.0, 0.5 * sigma, 2 * sigma}) {
        const Vec3 wo = Normalize(wr + Frame::FromNormal(wr).s * std::tan(off));
        const double nee = m->Eval(q, wo)[0] * std::abs(wo.z) * 1.0;
        GenRay g{Vec3(), wr, k, beta2, rho};
        const double closed = R * k * k * MeasurePlaneWave(g.TimeReversed(), -wo, 1.0);
        EXPECT_NEAR(nee / (closed * Dot(wo, wr)), 1, 1e-9) << off;
    }
    // The ray-optics limit and grt's NEE (evalNearDelta = false) see no near-delta lobe.
    q.evalNearDelta = false;
    EXPECT_TRUE(m->Eval(q, wr).IsZero());
    q.evalNearDelta = true;
    q.rayOptics = true;
    EXPECT_TRUE(m->Eval(q, wr).IsZero());
}

TEST(NearDelta, DielectricLobesIntegrateToFresnelWeights) {
    Diagnostics diag;
    auto m = BuildMaterial("dielectric", ParamDict().Set("ior", Value::Number(1.5)), diag);
    ASSERT_TRUE(m);
    const SampledWavelengths wl = TestWavelengths(500e-9);
    const double k = 2 * Pi / 500e-9, sigma = 0.01;
    const double beta2 = 1 / (2 * sigma * sigma * k * k);
    for (double cosI : {0.9, -0.95, 0.3}) {
        const Vec3 wi = DirectionFromCosTheta(cosI, 2.0);
        ScatterQuery q = GrQuery(wi, wl, beta2, 0);
        const double eta = cosI > 0 ? 1.5 : 1 / 1.5;
        const double R = FresnelDielectric(std::abs(cosI), eta);
        const double refl = IntegrateAbout(
            ReflectLocal(wi), 10 * sigma, [&](const Vec3 &wo) { return m->Eval(q, wo)[0] * std::abs(wo.z); });
        EXPECT_NEAR(refl / R, 1, 1e-6) << cosI;
        Vec3 wt;
        ASSERT_TRUE(RefractLocal(wi, eta, &wt));
        // The refracted lobe is narrower in the denser medium (σ_k/k_t), so integrate closer in.
        const double trans = IntegrateAbout(
            wt, 10 * sigma, [&](const Vec3 &wo) { return m->Eval(q, wo)[0] * std::abs(wo.z); });
        EXPECT_NEAR(trans / ((1 - R) / (eta * eta)), 1, 1e-6) << cosI;
    }
}

}  // namespace
}  // namespace phasor::test
