// SPDX-License-Identifier: Apache-2.0
// `harvey_shack` (materials/harvey_shack.cpp) and its K-correlation PSD (k_correlation_psd.h):
// physics against references written here — the visible PSD mass V by a brute-force 2-D quadrature
// (D7's 0.96 / 0.88 / 0.49), the table against the direct quadrature, the smooth limit against
// `conductor` / `dielectric`, the energy of the light from one direction = F (deterministic
// quadrature of Eval over the directions the light leaves into, and a t-test of an estimator built
// on the kernel's own sampling), the sampler against a quadrature of its own integral, the
// normal-incidence TIS (4πσ_h/λ)², the ray-optics limit of a coated substrate (the incoherent sum),
// and a χ² of the sampling in the tangent plane for halos too narrow for the generic suite's
// (φ, cosθ) grid.
//
// Convention (harvey_shack.cpp): a query's wi is where the light goes (the camera), wo where it
// comes from; f(wi → wo) carries F, α_spec and 1/V of wo's angle, so the light arriving from a
// direction d is reflected with exactly F(θ_d): α_spec·F into the mirror direction (the specular
// lobe of the query at the mirror of d) plus ∫ f(w → d)·cosθ_w dω_w.
#include <gtest/gtest.h>

#include <random>

#include "core/numerics/gauss_legendre.h"
#include "materials/fresnel.h"
#include "materials/k_correlation_psd.h"
#include "energy_test_util.h"
#include "material_test_util.h"
#include "support/stats.h"

namespace phasor::test {
namespace {

constexpr double Lambda = 550e-9;
const double KBar = 2 * Pi / 0.55e-6;

// theory §4.3's T from α_r, in the test's own words.
double TOfAlpha(double a) { return (1 - a * a) / (4 * KBar * KBar * a * a); }

// ---- independent references ------------------------------------------------------------------

// The normalised K-correlation PSD in ξ = ζ/k units, t = k²T (theory §4.3), written out again.
double Psd(double gamma, double t, double r2) { return (gamma - 1) * t / (2 * Pi) * std::pow(1 + t * r2, -(gamma + 1) / 2); }

// V(s, t) by brute force: a polar grid in ξ about the origin, radius on a geometric-then-uniform
// grid fine enough for the PSD's core (width 1/√t), each ring's visible arc measured by sampling
// the azimuth (midpoint rule, 4096 angles), not by the arc formula the kernel uses.
double BruteVisibleMass(double gamma, double t, double s) {
    const double w = 1 / std::sqrt(t);
    std::vector<double> edges = {0};
    for (double r = 1e-3 * std::min(w, 1.0); r < 1 + s; r *= 1.03) edges.push_back(r);
    edges.push_back(1 + s);
    constexpr int NPhi = 4096;
    double v = 0;
    for (std::size_t e = 0; e + 1 < edges.size(); ++e) {
        const double a = edges[e], b = edges[e + 1];
        const GaussLegendreRule &g = GaussLegendre(6);
        for (int i = 0; i < g.n; ++i) {
            const double r = 0.5 * (a + b) + 0.5 * (b - a) * g.x[i];
            int inside = 0;
            for (int j = 0; j < NPhi; ++j) {
                const double phi = (j + 0.5) * 2 * Pi / NPhi;
                inside += Sqr(r * std::cos(phi) - s) + Sqr(r * std::sin(phi)) <= 1 ? 1 : 0;
            }
            v += 0.5 * (b - a) * g.w[i] * 2 * Pi * r * Psd(gamma, t, r * r) * inside / double(NPhi);
        }
    }
    return v;
}

std::shared_ptr<Material> Build(const std::string &type, const ParamDict &p) {
    Diagnostics diag;
    auto m = BuildMaterial(type, p, diag);
    std::ostringstream os;
    diag.Print(os);
    EXPECT_TRUE(m && diag.All().empty()) << os.str();
    return m;
}

ParamDict Rough(const char *substrate, double sigma, double alphaR, double gamma = 3) {
    ParamDict p;
    p.Set("substrate", Value::Ref(substrate))
        .Set("sigma_h", Value::Number(sigma, Dim::Length()))
        .Set("alpha_r", Value::Number(alphaR))
        .Set("gamma", Value::Number(gamma));
    return p;
}
ParamDict RoughT(const char *substrate, double sigma, double t, double gamma = 3) {
    ParamDict p;
    p.Set("substrate", Value::Ref(substrate))
        .Set("sigma_h", Value::Number(sigma, Dim::Length()))
        .Set("correlation_t", Value::Number(t, Dim::Area()))
        .Set("gamma", Value::Number(gamma));
    return p;
}

// The smooth reference: the listed reflection lobe of `conductor` (Au) / `dielectric` (1.5) at
// wavelength slot `slot` — fresnel.h's closed forms, an implementation independent of the layer
// stack harvey_shack uses.
double SmoothReflectance(const Material &smooth, const ScatterQuery &q, int slot = 0) {
    const Prep k(smooth, q);
    for (const NearDeltaLobe &l : k->ListNearDelta())
        if (l.flags & ScatterReflection) return l.Weight()[slot];
    return 0;
}

ScatterQuery Query(const SampledWavelengths &wl, double thetaDeg, double phi = 0.3, bool below = false) {
    ScatterQuery q;
    q.wl = &wl;
    q.wi = DirectionFromCosTheta(std::cos(Radians(thetaDeg)), phi);
    if (below) q.wi.z = -q.wi.z;
    return q;
}

// ---- the PSD ------------------------------------------------------------------------------------

TEST(KCorrelationPsd, CdfDensityAndInverseAgree) {
    for (double gamma : {1.5, 3.0, 7.0})
        for (double t : {0.3, 25.0, 1e4}) {
            KCorrelationPsd psd(gamma);
            for (double r : {0.0, 0.2 / std::sqrt(t), 1 / std::sqrt(t), 0.7, 1.9}) {
                const double c = psd.RadialCdf(t, r);
                // d/dr CDF = 2πr·p (central difference, relative step 1e-5), where 1 − CDF is not
                // lost to rounding.
                if (r > 0 && 1 - c > 1e-4) {
                    const double h = 1e-5 * r;
                    const double d = (psd.RadialCdf(t, r + h) - psd.RadialCdf(t, r - h)) / (2 * h);
                    EXPECT_NEAR(d, 2 * Pi * r * Psd(gamma, t, r * r), 1e-6 * d + 1e-12) << gamma << " " << t << " " << r;
                }
                EXPECT_NEAR(psd.Density(t, r * r), Psd(gamma, t, r * r), 1e-12 * Psd(gamma, t, r * r));
                if (1 - c > 1e-6) {
                    EXPECT_NEAR(psd.InverseRadialCdf(t, c), r, 1e-8 * (1 + r) / (1 - c));
                }
            }
        }
}

TEST(KCorrelationPsd, VisibleMassOfDecisionD7) {
    // D7: V = 0.96 / 0.88 / 0.49 at θ_i = 0 / 45 / 80° for α_r = 0.1 (k²T at k̄), two digits.
    const double t = KBar * KBar * TOfAlpha(0.1);
    const double expected[] = {0.96, 0.88, 0.49};
    const double theta[] = {0, 45, 80};
    auto table = VisibleMassTable::For(3);
    for (int i = 0; i < 3; ++i) {
        const double c = std::cos(Radians(theta[i])), s = std::sin(Radians(theta[i]));
        const double brute = BruteVisibleMass(3, t, s);
        EXPECT_NEAR(brute, expected[i], 0.005) << theta[i] << " deg";  // D7 rounds to 2 digits
        // The brute force's own error (azimuth midpoint rule on 4096 angles: a boundary error of
        // ~1/4096 of the rim's share) is below 1e-5 here; the kernel's direct quadrature is
        // ~1e-7 (see VisibleMassDirectVsBruteForce).
        EXPECT_NEAR(table->Psd().VisibleMass(s, t), brute, 2e-5) << theta[i] << " deg";
        EXPECT_NEAR(table->Eval(c, t), brute, 3e-5) << theta[i] << " deg";
        RecordProperty("V_" + std::to_string(int(theta[i])) + "deg", std::to_string(table->Eval(c, t)));
    }
}

TEST(KCorrelationPsd, VisibleMassDirectVsBruteForce) {
    for (double gamma : {1.3, 8.0})
        for (double t : {0.01, 100.0, 1e6})
            for (double theta : {0.0, 70.0, 89.0}) {
                const double s = std::sin(Radians(theta));
                KCorrelationPsd psd(gamma);
                EXPECT_NEAR(psd.VisibleMass(s, t), BruteVisibleMass(gamma, t, s), 2e-5)
                    << "γ " << gamma << ", t " << t << ", θ " << theta;
            }
}

TEST(KCorrelationPsd, TableWithinItsStatedError) {
    // k_correlation_psd.h: ≤ 2e-4 everywhere, ≤ 2e-5 for cosθ_i ≥ 0.05 (against the direct rule).
    for (double gamma : {1.2, 3.0, 6.0}) {
        auto table = VisibleMassTable::For(gamma);
        std::mt19937_64 rng(7);
        std::uniform_real_distribution<double> u;
        double worst = 0, worstAway = 0;
        for (int k = 0; k < 4000; ++k) {
            double c = u(rng);
            if (k % 2) c = c * c * c * 0.1;  // many points near grazing
            const double t = std::exp(std::log(1e-4) + u(rng) * std::log(1e12));
            const double e = std::abs(table->Eval(c, t) - table->Psd().VisibleMass(SafeSqrt(1 - c * c), t));
            worst = std::max(worst, e);
            if (c >= 0.05) worstAway = std::max(worstAway, e);
        }
        EXPECT_LE(worst, 2e-4) << "γ " << gamma;
        RecordProperty("worst_gamma_" + std::to_string(int(gamma * 10)), std::to_string(worst));
        EXPECT_LE(worstAway, 2e-5) << "γ " << gamma;
        // Outside the tabulated t range: the direct rule itself.
        EXPECT_EQ(table->Eval(0.5, 1e-6), table->Psd().VisibleMass(std::sqrt(0.75), 1e-6));
        EXPECT_EQ(table->Eval(0.5, 1e9), table->Psd().VisibleMass(std::sqrt(0.75), 1e9));
    }
}

// ---- the kernel -------------------------------------------------------------------------------

TEST(HarveyShack, SmoothLimitIsTheSubstrate) {
    // σ_h = 0: one listed lobe, identical to the smooth kernel's reflection (outside, and from
    // inside the glass, where total internal reflection sets in at 41.8°); no continuous lobe.
    const SampledWavelengths wl = TestWavelengths(Lambda);
    auto gold = Build("conductor", ParamDict().Set("ior", Value::String("Au")));
    auto glass = Build("dielectric", ParamDict().Set("ior", Value::Number(1.5)));
    for (auto [sub, smooth] : {std::pair{"contract_gold", gold}, std::pair{"contract_glass", glass}}) {
        auto hs = Build("harvey_shack", Rough(sub, 0, 0.1));
        for (double theta : {0.0, 30.0, 45.0, 60.0, 85.0})
            for (bool below : {false, true}) {
                ScatterQuery q = Query(wl, theta, 0.3, below);
                const Prep aK(*hs, q);
                EXPECT_FALSE(aK->Capabilities() & CapContinuous);
                EXPECT_TRUE(aK->Eval(ReflectLocal(q.wi)).IsZero());
                const std::span<const NearDeltaLobe> a = aK->ListNearDelta();
                const Prep bK(*smooth, q);
                const std::span<const NearDeltaLobe> b = bK->ListNearDelta();
                ASSERT_EQ(a.size(), 1u);
                const NearDeltaLobe *ref = nullptr;
                for (const NearDeltaLobe &l : b)
                    if (l.flags & ScatterReflection) ref = &l;
                ASSERT_TRUE(ref);
                for (int i = 0; i < wl.Count(); ++i) {
                    EXPECT_NEAR(a[0].Weight()[i], ref->Weight()[i], 1e-12) << sub << " θ " << theta << " below " << below;
                    EXPECT_EQ(a[0].nIn[i], ref->nIn[i]);
                }
                EXPECT_LT(Length(a[0].wo[0] - ref->wo[0]), 1e-15);
                auto ja = aK->EvalLobe(0, a[0].wo[0]), jb = bK->EvalLobe(ref->id, ref->wo[0]);
                ASSERT_TRUE(ja && jb);
                for (int r = 0; r < 2; ++r)
                    for (int c = 0; c < 2; ++c) EXPECT_LT(std::abs(ja->jones[0].m[r][c] - jb->jones[0].m[r][c]), 1e-12);
                auto s = aK->Sample(0.7, Vec2(0.2, 0.9));
                ASSERT_TRUE(s);
                EXPECT_NEAR(s->weight[0], ref->Weight()[0], 1e-12);
            }
    }
}

// The kernels and cases of the energy tests: gold and glass, narrow to wide halos, light to heavy tails.
struct EnergyCase {
    const char *sub;
    bool glass;
    ParamDict p;
    double core;  // the quadrature's innermost panel (≲ the halo's width 1/√(k²T))
};
std::vector<EnergyCase> EnergyCases() {
    return {
        {"contract_gold", false, Rough("contract_gold", 40e-9, 0.1), 0.02},
        {"contract_gold", false, Rough("contract_gold", 200e-9, 0.3, 2), 0.05},
        {"contract_glass", true, RoughT("contract_glass", 30e-9, 2e-12, 4), 0.002},
        {"contract_glass", true, Rough("contract_glass", 80e-9, 0.2), 0.02},
    };
}

TEST(HarveyShack, ReflectsExactlyFOfTheLightFromEachDirection) {
    // D7, per incident direction: light arriving from d leaves with α_spec·F(θ_d) in the specular
    // lobe (listed by the query at d's mirror direction) plus ∫ f(w → d)·cosθ_w dω_w in the halo,
    // in sum F(θ_d) — by a deterministic quadrature of Eval over w (the kernel's sampling is not
    // involved), per carried wavelength, from above and from below (inside the glass: total internal
    // reflection past 41.8°, a lossless F = 1). Tolerance: the V table's error ≤ 1e-4 (absolute, at
    // these points; V ≥ 0.3 here) on the scattered share, plus the quadrature's ~1e-7.
    const SampledWavelengths wl = TestWavelengths(Lambda);
    auto gold = Build("conductor", ParamDict().Set("ior", Value::String("Au")));
    auto glass = Build("dielectric", ParamDict().Set("ior", Value::Number(1.5)));
    for (const EnergyCase &c : EnergyCases()) {
        auto hs = Build("harvey_shack", c.p);
        const Material &smooth = c.glass ? *glass : *gold;
        for (double theta : {0.0, 30.0, 60.0, 80.0, 88.0})
            for (bool below : {false, true}) {
                const ScatterQuery q = Query(wl, theta, 1.1, below);  // q.wi = d, the light's direction
                const SampledSpectrum scatter = ContinuousFrom(*hs, q, q.wi, c.core);
                for (int i = 0; i < wl.Count(); ++i) {
                    const double F = SmoothReflectance(smooth, q, i);
                    const SampledSpectrum spec(ListedEnergyFrom(*hs, q, i).energy);
                    const double share = F - spec[i];  // (1 − α_spec)·F
                    EXPECT_NEAR(spec[i] + scatter[i], F, 3.5e-4 * share + 1e-7)
                        << hs->ToString() << "\nlight from θ " << theta << (below ? " below" : "") << ", λ "
                        << wl.lambda[i] * 1e9 << " nm: specular " << spec[i] << " + scatter " << scatter[i]
                        << " vs F " << F << " (" << (spec[i] + scatter[i]) / F - 1 << " relative)";
                }
            }
    }
}

TEST(HarveyShack, SampledLightFromOneDirectionCarriesF) {
    // The same energy, estimated with the kernel's own sampling: draw w from Sample at wi = d (its
    // halo is centred on d's mirror direction, as f(w → d) is) and average f(w → d)·cosθ_w/pdf, or
    // the specular share / p_spec for a specular pick; the mean is F(θ_d) (two-sided t-test per
    // case, Šidák over the cases). The 1/M of the pdf, the 1/V of f and the visible arc must all be
    // right for this (dropping 1/M or 1/V biases it by M or V).
    const SampledWavelengths wl = TestWavelengths(Lambda);
    auto gold = Build("conductor", ParamDict().Set("ior", Value::String("Au")));
    auto glass = Build("dielectric", ParamDict().Set("ior", Value::Number(1.5)));
    struct Case {
        std::shared_ptr<Material> smooth;
        ParamDict p;
    };
    const Case cases[] = {{gold, Rough("contract_gold", 40e-9, 0.1)},
                          {gold, Rough("contract_gold", 300e-9, 0.35)},
                          {glass, Rough("contract_glass", 60e-9, 0.2, 2.2)}};
    const double thetas[] = {0, 30, 60, 80};
    const double alpha = SidakAlpha(0.01, int(std::size(cases) * std::size(thetas) * 2));
    TestRng rng(12345);
    for (const Case &c : cases) {
        auto hs = Build("harvey_shack", c.p);
        for (double theta : thetas)
            for (bool below : {false, true}) {
                const ScatterQuery q = Query(wl, theta, 2.0, below);
                const double F = SmoothReflectance(*c.smooth, q);
                const double spec = ListedEnergyFrom(*hs, q, 0).energy;
                ScatterQuery qw = q;
                std::vector<double> w;
                const Prep k(*hs, q);
                ScratchBuffer atW;  // the kernel prepared at each sampled direction
                for (int i = 0; i < 50000; ++i) {
                    auto s = k->Sample(rng.Uniform(), Vec2(rng.Uniform(), rng.Uniform()));
                    double x = 0;
                    if (s && (s->flags & ScatterNearDelta)) x = spec / s->pdf;
                    else if (s) {
                        qw.wi = s->wo;
                        atW.Reset();
                        x = hs->Prepare(qw, atW).Eval(q.wi)[0] * std::abs(s->wo.z) / s->pdf;
                    }
                    w.push_back(x);
                }
                TTestResult t = OneSampleTTest(w, F);
                double mean = 0;
                for (double x : w) mean += x / double(w.size());
                // At normal incidence every value is F up to the V table's error (the halo's value
                // F·M·φ_max/(πV) has φ_max = π and V = M), so the variance is ~0 and a t-test alone
                // would test the table to 1e-9: accept the table's stated error (2e-4 of V ≥ 0.3, on
                // the scattered share) as well.
                EXPECT_TRUE(t.pValue >= alpha || std::abs(mean - F) <= 7e-4 * F)
                    << hs->ToString() << "\nlight from θ " << theta << (below ? " below" : "") << ", F = " << F
                    << ", mean " << mean << " (" << mean / F - 1 << " relative): " << t.ToString();
            }
    }
}

TEST(HarveyShack, SampledWeightsAverageTheirIntegral) {
    // What Sample estimates at one query, E[weight] = α_spec(θ_i)·F(θ_i) + ∫ f(wi → wo)·cosθo dωo
    // (what a camera at wi gathers from a white sky), against the deterministic quadrature of Eval
    // (two-sided t-test per case, Šidák over the cases): the sampler is unbiased for its own
    // integral, which under this convention is not F(θ_i) (docs/kernels.md, the white furnace).
    const SampledWavelengths wl = TestWavelengths(Lambda);
    const std::vector<EnergyCase> cases = EnergyCases();
    const double thetas[] = {0, 45, 80};
    const double alpha = SidakAlpha(0.01, int(cases.size() * std::size(thetas) * 2));
    TestRng rng(777);
    for (const EnergyCase &c : cases) {
        auto hs = Build("harvey_shack", c.p);
        for (double theta : thetas)
            for (bool below : {false, true}) {
                const ScatterQuery q = Query(wl, theta, 0.7, below);
                ScratchBuffer scratch;
                const PreparedKernel &k = hs->Prepare(q, scratch);
                const std::span<const NearDeltaLobe> lobes = k.ListNearDelta();
                const double expected = (lobes.empty() ? 0.0 : lobes[0].Weight()[0]) + ContinuousAlbedo(k, c.core)[0];
                std::vector<double> w;
                for (int i = 0; i < 50000; ++i) {
                    auto s = k.Sample(rng.Uniform(), Vec2(rng.Uniform(), rng.Uniform()));
                    w.push_back(s ? s->weight[0] : 0.0);
                }
                TTestResult t = OneSampleTTest(w, expected);
                EXPECT_GE(t.pValue, alpha) << hs->ToString() << "\nθ " << theta << (below ? " below" : "")
                                           << ": quadrature " << expected << ", " << t.ToString();
            }
    }
}

TEST(HarveyShack, NormalIncidenceTotalIntegratedScatter) {
    // TIS = scattered / total reflectance of light at normal incidence ≈ (4πσ_h/λ)² within 5 % for
    // k²T ≥ 100 and σ_h ≤ λ/100 (the smooth-surface limit of 1 − exp(−(4πσ_h/λ)²), whose next term
    // is −(4πσ_h/λ)⁴/2: 0.8 % at σ_h = λ/100). The scattered flux is the forward quadrature of
    // f(w → normal) over w.
    const SampledWavelengths wl = TestWavelengths(Lambda);
    auto gold = Build("conductor", ParamDict().Set("ior", Value::String("Au")));
    const double k = 2 * Pi / Lambda;
    for (double sigma : {Lambda / 100, Lambda / 300})
        for (double kkT : {100.0, 1e4}) {
            auto hs = Build("harvey_shack", RoughT("contract_gold", sigma, kkT / (k * k)));
            const ScatterQuery q = Query(wl, 0);
            const double F = SmoothReflectance(*gold, q);
            const double tis = ContinuousFrom(*hs, q, q.wi, 0.05 / std::sqrt(kkT))[0] / F;
            const double expected = Sqr(4 * Pi * sigma / Lambda);
            EXPECT_NEAR(tis / expected, 1, 0.05) << "σ_h = λ/" << Lambda / sigma << ", k²T = " << kkT;
            EXPECT_NEAR(tis, -std::expm1(-expected), 2e-4 * tis) << "the exact Debye–Waller share";
        }
}

TEST(HarveyShack, RayOpticsLimitOfACoatedSubstrateIsTheIncoherentSum) {
    // In the ray-optics limit a coated substrate's F is the coating's incoherent sum, as the smooth
    // coated kernel answers there (smooth_kernel.h): the specular lobe lists α_spec·R_incoherent,
    // EvalLobe gives α_spec × the smooth kernel's (depolarising, Jones-free) Mueller matrix, the
    // light from one direction still carries F = R_incoherent in sum; in the wave regime the
    // coherent (Airy) R. A 150 nm Cu₂O film on gold: the two differ by ≥ 0.05 here, so a kernel that
    // ignored the regime would fail every check by far more than their tolerances.
    MiniScene scene;
    scene.WithFixtures()
        .Add("Material", "conductor", "coated", ParamDict().Set("ior", Value::String("Au")).Set("coating", Value::Ref("contract_film")))
        .Add("Material", "harvey_shack", "rough",
             ParamDict()
                 .Set("substrate", Value::Ref("coated"))
                 .Set("sigma_h", Value::Number(30e-9, Dim::Length()))
                 .Set("alpha_r", Value::Number(0.15)));
    auto coated = scene.Build<Material>("coated"), hs = scene.Build<Material>("rough");
    ASSERT_TRUE(coated && hs) << scene.FirstError();
    const SampledWavelengths wl = TestWavelengths(Lambda);
    double largest = 0;
    for (double theta : {0.0, 35.0, 70.0}) {
        ScatterQuery wave = Query(wl, theta, 0.4), ray = wave;
        wave.rayOptics = false;
        ray.rayOptics = true;
        const Prep swK(*coated, wave);
        const std::span<const NearDeltaLobe> sw = swK->ListNearDelta();
        const Prep srK(*coated, ray);
        const std::span<const NearDeltaLobe> sr = srK->ListNearDelta();
        const Prep hwK(*hs, wave);
        const std::span<const NearDeltaLobe> hw = hwK->ListNearDelta();
        const Prep hrK(*hs, ray);
        const std::span<const NearDeltaLobe> hr = hrK->ListNearDelta();
        ASSERT_TRUE(sw.size() == 1 && sr.size() == 1 && hw.size() == 1 && hr.size() == 1);
        const double alphaSpec = std::exp(-Sqr(2 * 2 * Pi / Lambda * 30e-9 * std::cos(Radians(theta))));
        largest = std::max(largest, std::abs(sr[0].Weight()[0] - sw[0].Weight()[0]));
        EXPECT_NEAR(hr[0].Weight()[0], alphaSpec * sr[0].Weight()[0], 1e-12) << "θ " << theta;
        EXPECT_NEAR(hw[0].Weight()[0], alphaSpec * sw[0].Weight()[0], 1e-12) << "θ " << theta;
        // EvalLobe of the specular lobe: α_spec × the smooth kernel's response in each regime.
        auto er = hrK->EvalLobe(0, hr[0].wo[0]), cr = srK->EvalLobe(0, sr[0].wo[0]);
        auto ew = hwK->EvalLobe(0, hw[0].wo[0]), cw = swK->EvalLobe(0, sw[0].wo[0]);
        ASSERT_TRUE(er && cr && ew && cw);
        EXPECT_FALSE(er->hasJones) << "the incoherent sum has no Jones matrix";
        EXPECT_TRUE(ew->hasJones);
        for (int a = 0; a < 4; ++a)
            for (int b = 0; b < 4; ++b) {
                EXPECT_NEAR(er->mueller[0].m[a][b], alphaSpec * cr->mueller[0].m[a][b], 1e-12) << a << b;
                EXPECT_NEAR(ew->mueller[0].m[a][b], alphaSpec * cw->mueller[0].m[a][b], 1e-12) << a << b;
            }
        // The scattered lobe's Mueller matrix is the incoherent facet's too (M00 = f·cosθo).
        const Vec3 off = Normalize(hr[0].wo[0] + Vec3(0.05, 0.08, 0));
        auto sc = hrK->EvalLobe(1, off);
        ASSERT_TRUE(sc);
        EXPECT_FALSE(sc->hasJones);
        EXPECT_NEAR(sc->mueller[0].m[0][0], hrK->Eval(off)[0] * off.z, 1e-12 * sc->mueller[0].m[0][0]);
        // Energy of the light from this direction: F of the regime.
        const double specR = ListedEnergyFrom(*hs, ray, 0).energy, haloR = ContinuousFrom(*hs, ray, ray.wi, 0.02)[0];
        const double specW = ListedEnergyFrom(*hs, wave, 0).energy, haloW = ContinuousFrom(*hs, wave, wave.wi, 0.02)[0];
        const double shareR = sr[0].Weight()[0] - specR, shareW = sw[0].Weight()[0] - specW;
        EXPECT_NEAR(specR + haloR, sr[0].Weight()[0], 3.5e-4 * shareR + 1e-7) << "ray optics, θ " << theta;
        EXPECT_NEAR(specW + haloW, sw[0].Weight()[0], 3.5e-4 * shareW + 1e-7) << "wave regime, θ " << theta;
    }
    EXPECT_GT(largest, 0.05) << "the film's coherent and incoherent reflectances should differ here";
    RecordProperty("largest_coherent_minus_incoherent", std::to_string(largest));
}

TEST(HarveyShack, SamplingMatchesPdfInTheTangentPlane) {
    // χ² of the sampled halo for narrow halos (k²T up to 1e5), which the generic suite's
    // (φ, cosθ) grid cannot resolve near the pole: cells in ξ = wo∥ + wi∥ (a 30×30 grid over
    // ±5/√(k²T)), expected counts = N·∫cell Pdf/cosθo d²ξ (Simpson, 4×4 intervals per cell),
    // plus one cell for the specular lobe and one for the rest of the hemisphere.
    const SampledWavelengths wl = LineWavelength(Lambda);
    const double k = 2 * Pi / Lambda;
    constexpr int G = 30, Sub = 4;
    const double kkTs[] = {1e3, 1e5};
    const double thetas[] = {0, 45};
    const double alpha = SidakAlpha(0.01, int(std::size(kkTs) * std::size(thetas)));
    for (double kkT : kkTs)
        for (double theta : thetas) {
            auto hs = Build("harvey_shack", RoughT("contract_gold", 30e-9, kkT / (k * k)));
            ScatterQuery q = Query(wl, theta, 0.8);
            const double L = 5 / std::sqrt(kkT), cell = 2 * L / G;
            const Prep k(*hs, q);
            auto pdfXi = [&](double x, double y) {
                const double ux = x - q.wi.x, uy = y - q.wi.y, z = SafeSqrt(1 - ux * ux - uy * uy);
                return z > 0 ? k->Pdf(Vec3(ux, uy, z)) / z : 0.0;
            };
            constexpr double W[Sub + 1] = {1, 4, 2, 4, 1};
            const long long n = 200000;
            std::vector<double> ex(G * G + 2, 0.0), obs(G * G + 2, 0.0);
            double inGrid = 0;
            for (int a = 0; a < G; ++a)
                for (int b = 0; b < G; ++b) {
                    double sum = 0;
                    const double h = cell / Sub;
                    for (int i = 0; i <= Sub; ++i)
                        for (int j = 0; j <= Sub; ++j) sum += W[i] * W[j] * pdfXi(-L + a * cell + i * h, -L + b * cell + j * h);
                    ex[std::size_t(a * G + b)] = sum * (h / 3) * (h / 3);
                    inGrid += ex[std::size_t(a * G + b)];
                }
            const std::span<const NearDeltaLobe> lobes = k->ListNearDelta();
            const double pSpec = lobes.empty() ? 0 : lobes[0].prob;
            ex[G * G] = pSpec;
            ex[G * G + 1] = std::max(0.0, 1 - pSpec - inGrid);
            for (double &e : ex) e *= double(n);
            TestRng rng(uint64_t(kkT) + uint64_t(theta));
            for (long long i = 0; i < n; ++i) {
                auto s = k->Sample(rng.Uniform(), Vec2(rng.Uniform(), rng.Uniform()));
                if (!s) continue;
                if (s->flags & ScatterNearDelta) {
                    obs[G * G] += 1;
                    continue;
                }
                const double x = s->wo.x + q.wi.x, y = s->wo.y + q.wi.y;
                const int a = int(std::floor((x + L) / cell)), b = int(std::floor((y + L) / cell));
                if (a < 0 || b < 0 || a >= G || b >= G) obs[G * G + 1] += 1;
                else obs[std::size_t(a * G + b)] += 1;
            }
            Chi2Result r = Chi2Test(obs, ex);
            EXPECT_TRUE(r.pValue >= alpha && r.observedInEmptyCells == 0)
                << "k²T " << kkT << ", θ " << theta << ": " << r.ToString() << ", in grid " << inGrid
                << ", specular " << pSpec;
        }
}

TEST(HarveyShack, ScatterPolarisationIsTheFacetsAtTheMirrorDirection) {
    // At ξ = 0 the facet is the mean surface: the scattered lobe's Mueller matrix, normalised, is
    // the specular lobe's; elsewhere M00 = f·|cosθo| (the energy of the lobe, not R(θ_h)).
    const SampledWavelengths wl = TestWavelengths(Lambda);
    auto hs = Build("harvey_shack", Rough("contract_gold", 40e-9, 0.1));
    ScatterQuery q = Query(wl, 50, 0.4);
    const Vec3 mirror = ReflectLocal(q.wi);
    const Prep k(*hs, q);
    auto spec = k->EvalLobe(0, mirror), scat = k->EvalLobe(1, mirror);
    ASSERT_TRUE(spec && scat);
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
            EXPECT_NEAR(scat->mueller[0].m[a][b] / scat->mueller[0].m[0][0],
                        spec->mueller[0].m[a][b] / spec->mueller[0].m[0][0], 1e-12);
    const Vec3 off = Normalize(mirror + Vec3(0.1, -0.05, 0));
    auto r = k->EvalLobe(1, off);
    ASSERT_TRUE(r);
    const SampledSpectrum f = k->Eval(off);
    for (int i = 0; i < wl.Count(); ++i) EXPECT_NEAR(r->mueller[i].m[0][0], f[i] * off.z, 1e-12 * f[i]);
    EXPECT_FALSE(k->EvalLobe(1, Vec3(off.x, off.y, -off.z))) << "reflection only";
}

TEST(HarveyShack, AlphaRSetsTheCorrelationParameter) {
    // alpha_r = 0.1 and correlation_t = T(0.1) are the same kernel (theory §4.3's conversion).
    const SampledWavelengths wl = TestWavelengths(Lambda);
    auto a = Build("harvey_shack", Rough("contract_gold", 40e-9, 0.1));
    auto b = Build("harvey_shack", RoughT("contract_gold", 40e-9, TOfAlpha(0.1)));
    ScatterQuery q = Query(wl, 35);
    for (const Vec3 &wo : {Vec3(0.1, 0.2, 0.97), Vec3(-0.5, 0.1, 0.8)}) {
        const Vec3 w = Normalize(wo);
        const Prep ka(*a, q), kb(*b, q);
        EXPECT_NEAR(ka->Eval(w)[0], kb->Eval(w)[0], 1e-12 * kb->Eval(w)[0]);
        EXPECT_NEAR(ka->Pdf(w), kb->Pdf(w), 1e-12 * kb->Pdf(w));
    }
}

}  // namespace
}  // namespace phasor::test
