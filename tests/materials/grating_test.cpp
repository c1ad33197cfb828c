// SPDX-License-Identifier: Apache-2.0
// Physics of the `grating` kernel (materials/grating.{h,cpp}; theory §0 D6, §4.2) against
// references written here: the vector grating equation (directions, incl. conical incidence and
// transmission), thin-phase efficiencies J_j(m)²·F with std::cyl_bessel_j and the textbook Fresnel
// formulas, Σ_j J_j² = 1, the renormalisation and the dropped share it reports, the Jones matrix of
// an order, the ray-optics limit (= the smooth substrate kernels), textures and dispersion flags.
// Efficiencies are those of the *light's* incidence: the tests take a source direction d, compute
// where its order j goes (out_j) and read the weight that the query at out_j lists towards d — what
// a backward tracer's pixel at out_j receives from a source at d.
// The generic contract suite (kernel_contract_test.cpp) runs the presets on top of this.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <sstream>

#include "material_test_util.h"
#include "materials/grating.h"

namespace phasor::test {
namespace {

constexpr double Um = 1e-6, Nm = 1e-9, Deg = Pi / 180;
const Complex MetalIndex(0.2, 3.4);  // the "metal" substrate below

Value Len(double m) { return Value::Number(m, Dim::Length()); }
Value Ang(double rad) { return Value::Number(rad, Dim::Angle()); }

// A grating in a scene with the fixtures and a conductor of index MetalIndex named "metal" (for
// gratings whose F the test computes itself). Without diagnostics, or (`deep`) with exactly the
// warning that the thin-phase model does not hold at visible wavelengths.
std::shared_ptr<GratingMaterial> MakeGrating(const ParamDict &p, bool deep = false) {
    MiniScene scene;
    scene.WithFixtures()
        .Add("Material", "conductor", "metal", ParamDict().Set("ior", Value::ComplexNumber(MetalIndex)))
        .Add("Material", "grating", "under_test", p);
    auto m = scene.Build<Material>("under_test");
    std::ostringstream os;
    scene.diag.Print(os);
    if (deep)
        EXPECT_TRUE(m && scene.diag.All().size() == 1 && os.str().find("the thin-phase model holds") != std::string::npos)
            << os.str();
    else
        EXPECT_TRUE(m && scene.diag.All().empty()) << os.str();
    auto g = std::dynamic_pointer_cast<GratingMaterial>(m);
    EXPECT_TRUE(g) << "the registry's 'grating' is not a GratingMaterial";
    return g;
}

// A wave-regime query (as grt asks) from direction (θ, φ) of the local frame; θ > 90° is below.
/// A plain grating of period Λ [m] and height 0.1 µm on the metal below.
std::shared_ptr<GratingMaterial> MetalGrating(double period) {
    return MakeGrating(ParamDict().Set("substrate", Value::Ref("metal")).Set("period", Len(period)).Set("height", Len(0.1 * Um)));
}

ScatterQuery Wave(double theta, double phi, const SampledWavelengths &wl, Vec2 uv = Vec2(0.5, 0.5)) {
    ScatterQuery q;
    q.wi = Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    q.wl = &wl;
    q.etaOutside = 1;
    q.rayOptics = false;
    q.tex.uv = uv;
    return q;
}

// Unpolarised Fresnel reflectance and transmittance of a smooth interface n1 | n2 (textbook
// formulas, Born & Wolf §1.5; written here independently of fresnel.h).
struct Fresnel {
    Complex rs, rp;
    double R, T;
};
Fresnel TextbookFresnel(double cosI, double n1, Complex n2) {
    const Complex sinT = n1 * std::sqrt(1 - cosI * cosI) / n2;
    Complex cosT = std::sqrt(1.0 - sinT * sinT);
    if (cosT.imag() < 0) cosT = -cosT;  // the decaying / outgoing branch
    Fresnel f;
    f.rs = (n1 * cosI - n2 * cosT) / (n1 * cosI + n2 * cosT);
    f.rp = (n2 * cosI - n1 * cosT) / (n2 * cosI + n1 * cosT);
    f.R = 0.5 * (std::norm(f.rs) + std::norm(f.rp));
    f.T = n2.imag() == 0 && std::abs(cosT.imag()) < 1e-15 ? 1 - f.R : 0;
    return f;
}

// The expected direction of order j (independent of NearDeltaDirection): the tangential wave
// vector of the specular/refracted wave plus j·2π/Λ·ĝ, divided by the outgoing index; false if
// evanescent.
bool ExpectedDirection(const Vec3 &wi, double nIn, double nOut, Vec2 g, int j, double lambda, double period,
                       bool transmitted, Vec3 *wo) {
    const double tx = (-nIn * wi.x + j * lambda / period * g.x) / nOut;
    const double ty = (-nIn * wi.y + j * lambda / period * g.y) / nOut;
    const double t2 = tx * tx + ty * ty;
    if (t2 >= 1) return false;
    const double side = (wi.z > 0) == !transmitted ? 1 : -1;
    *wo = Vec3(tx, ty, side * std::sqrt(1 - t2));
    return true;
}

double AngleBetween(const Vec3 &a, const Vec3 &b) { return std::atan2(Length(Cross(a, b)), Dot(a, b)); }

double J2(int j, double m) { return std::pow(std::cyl_bessel_j(double(std::abs(j)), std::abs(m)), 2); }

const NearDeltaLobe *Find(std::span<const NearDeltaLobe> lobes, int id) {
    for (const NearDeltaLobe &l : lobes)
        if (l.id == id) return &l;
    return nullptr;
}

// Light from source direction d (a line wavelength): order j (reflected, or transmitted with
// `transmitted`) leaves along `out`, computed here; `weight` is what the kernel's query at out lists
// for its lobe j towards d (−1 if that lobe is missing or does not point at d to 1e-9 rad);
// `energy` the power fraction (the radiance factor undone: weight·Eta²).
struct FromSource {
    bool propagates = false;
    Vec3 out;
    double weight = -1, energy = -1;
    std::optional<LobeResponse> response;  // EvalLobe of that lobe towards d
};
FromSource OrderFrom(const GratingMaterial &grating, const SampledWavelengths &wl, const Vec3 &d, double nD,
                     double nFar, Vec2 g, double period, int j, bool transmitted) {
    FromSource r;
    r.propagates = ExpectedDirection(d, nD, transmitted ? nFar : nD, g, j, wl.lambda[0], period, transmitted, &r.out);
    if (!r.propagates) return r;
    ScatterQuery q;
    q.wi = r.out;
    q.wl = &wl;
    q.etaOutside = 1;
    q.rayOptics = false;
    q.tex.uv = Vec2(0.5, 0.5);
    const Prep lobesK(grating, q);
    const std::span<const NearDeltaLobe> lobes = lobesK->ListNearDelta();
    const NearDeltaLobe *l = Find(lobes, (transmitted ? GratingMaterial::TransmittedId : 0) + j);
    if (!l || AngleBetween(l->wo[0], d) > 1e-9) return r;
    r.weight = l->Weight()[0];
    r.energy = l->Weight()[0] * l->Eta(0) * l->Eta(0);
    r.response = lobesK->EvalLobe(l->id, l->wo[0]);
    return r;
}

TEST(Grating, OrderDirectionsObeyTheVectorGratingEquation) {
    // Conical incidence (wi not in the plane of ĝ), in-plane incidence, incidence along the grooves
    // and from below; reflected orders on a metal, reflected and transmitted on glass. Every
    // propagating order with light must be listed, along the expected direction to 1e-9 rad (the
    // direction is a closed form: rounding leaves ~1e-15); no evanescent order may be listed.
    const double period = 1.3 * Um, alpha = 35 * Deg;
    const Vec2 g(-std::sin(alpha), std::cos(alpha));  // ĝ = groove direction rotated by +90°
    for (const char *substrate : {"metal", "contract_glass"}) {
        const bool glass = std::string(substrate) == "contract_glass";
        auto grating = MakeGrating(ParamDict()
                                       .Set("substrate", Value::Ref(substrate))
                                       .Set("period", Len(period))
                                       .Set("height", Len(0.1 * Um))
                                       .Set("angle", Ang(alpha))
                                       .Set("transmission", Value::Bool(glass)));
        ASSERT_TRUE(grating);
        const SampledWavelengths wl = TestWavelengths(550 * Nm);
        const double phiG = std::atan2(g.y, g.x);
        struct In {
            double theta, phi;
        };
        for (const In in : {In{0, 0}, In{30 * Deg, phiG}, In{30 * Deg, phiG + Pi / 2}, In{55 * Deg, 1.1},
                            In{80 * Deg, 4.0}, In{150 * Deg, 0.4}, In{110 * Deg, phiG}}) {
            const ScatterQuery q = Wave(in.theta, in.phi, wl);
            const Prep lobesK(*grating, q);
            const std::span<const NearDeltaLobe> lobes = lobesK->ListNearDelta();
            const bool inside = glass && q.wi.z < 0;
            int checked = 0;
            for (const bool transmitted : {false, true}) {
                if (transmitted && !glass) continue;
                for (int j = -10; j <= 10; ++j) {
                    const NearDeltaLobe *l = Find(lobes, (transmitted ? GratingMaterial::TransmittedId : 0) + j);
                    for (int i = 0; i < wl.Count(); ++i) {
                        const double nIn = inside ? 1.5 : 1.0;
                        const double nOut = transmitted ? (inside ? 1.0 : 1.5) : nIn;
                        Vec3 expected;
                        const bool propagates =
                            ExpectedDirection(q.wi, nIn, nOut, g, j, wl.lambda[i], period, transmitted, &expected);
                        // The lobe carries the light that arrives along it: a transmitted lobe whose
                        // direction lies in the glass beyond the critical angle carries nothing (that
                        // light is totally reflected: T = 0 multiplies its orders), whereas a lobe into
                        // the glass beyond it is lit (light from the outside reaches it through an order
                        // j ≠ 0). Orders with J_j² < 1e-20 are not listed; none of those here propagate.
                        const Vec2 t(expected.x, expected.y);
                        const bool sourceTir = transmitted && nOut * Length(t) >= nIn;
                        const bool lit = propagates && !sourceTir;
                        ASSERT_EQ(l && l->Weight()[i] > 0, lit)
                            << substrate << ", θ = " << in.theta / Deg << "°, φ = " << in.phi << ", order " << j
                            << (transmitted ? " (T)" : " (R)") << ", slot " << i;
                        if (!lit) continue;
                        EXPECT_LT(AngleBetween(l->wo[i], expected), 1e-9) << "order " << j << ", slot " << i;
                        EXPECT_NEAR(l->nIn[i], nIn, 1e-15);
                        EXPECT_NEAR(l->nOut[i], nOut, 1e-15);
                        ++checked;
                        // In the plane of ĝ (φ = φ_g or φ_g + π) the scalar grating equation holds:
                        // n_out·sinθ_o = −n_in·sinθ_i + jλ/Λ, signed along ĝ, and wo stays in that plane.
                        const Vec3 w = l->wo[i];
                        if (std::abs(std::sin(in.phi - phiG)) < 1e-12) {
                            const double sinI = Dot(Vec2(q.wi.x, q.wi.y), g);
                            EXPECT_NEAR(nOut * Dot(Vec2(w.x, w.y), g), -nIn * sinI + j * wl.lambda[i] / period, 1e-12);
                            EXPECT_NEAR(Dot(Vec2(w.x, w.y), Vec2(g.y, -g.x)), 0, 1e-12);
                        }
                    }
                }
            }
            EXPECT_GE(checked, 4) << "too few propagating orders to test";
        }
    }
}

TEST(Grating, PlainEfficienciesAreBesselSquaredTimesFresnel) {
    // renormalize = false: light from d into order j carries J_j(k·h·cosθ_d)²·R(θ_d) (D6) with
    // std::cyl_bessel_j and the textbook Fresnel reflectance of the metal — at the source's angle,
    // not at the order's (a pixel at out_j sees the source through lobe j). 1e-12 relative covers
    // the Bessel recurrence (≈1e-15 absolute) and the stack's Fresnel evaluation (≈1e-16).
    const double period = 1.6 * Um, h = 0.12 * Um, alpha = 20 * Deg;
    const Vec2 g(-std::sin(alpha), std::cos(alpha));
    auto grating = MakeGrating(ParamDict()
                                   .Set("substrate", Value::Ref("metal"))
                                   .Set("period", Len(period))
                                   .Set("height", Len(h))
                                   .Set("angle", Ang(alpha))
                                   .Set("max_order", Value::Integer(12))
                                   .Set("renormalize", Value::Bool(false)));
    ASSERT_TRUE(grating);
    for (double lambda : {400 * Nm, 550 * Nm, 700 * Nm}) {
        const SampledWavelengths wl = LineWavelength(lambda);
        for (double theta : {0.0, 30 * Deg, 70 * Deg, 135 * Deg}) {
            const Vec3 d = Wave(theta, 0.7, wl).wi;
            const double cosD = std::abs(d.z), m = 2 * Pi / lambda * h * cosD;
            const double F = TextbookFresnel(cosD, 1, MetalIndex).R;
            int orders = 0;
            for (int j = -12; j <= 12; ++j) {
                const FromSource o = OrderFrom(*grating, wl, d, 1, 1, g, period, j, false);
                if (!o.propagates) continue;
                ++orders;
                const double expected = J2(j, m) * F;
                EXPECT_NEAR(o.weight, expected, 1e-12 * expected + 1e-16)
                    << "order " << j << ", λ = " << lambda << ", θ_d = " << theta / Deg << "°, θ_out = "
                    << std::acos(std::abs(o.out.z)) / Deg << "°";
            }
            EXPECT_GE(orders, 2);
        }
    }
}

TEST(Grating, RenormalisationGivesTheDroppedShareToThePropagatingOrders) {
    // Λ = 0.9 µm, h = 0.2 µm: at 700 nm and normal incidence only |j| ≤ 1 propagate and the
    // evanescent orders hold ~20 % of J². With renormalize (default) light from d carries
    // a_j = J_j²·F/Σ_prop J² into order j and Σ_j a_j = F exactly; the dropped share 1 − Σ_prop J² is
    // reported by Orders() for the source direction (evanescent + truncated), and renormalize =
    // false gives J_j²·F, which sums to F·(1 − dropped).
    const double period = 0.9 * Um, h = 0.2 * Um;
    const Vec2 g(0, 1);  // angle 0: grooves along x, ĝ along y
    auto renorm = MakeGrating(ParamDict().Set("substrate", Value::Ref("metal")).Set("period", Len(period)).Set("height", Len(h)));
    auto plain = MakeGrating(ParamDict()
                                 .Set("substrate", Value::Ref("metal"))
                                 .Set("period", Len(period))
                                 .Set("height", Len(h))
                                 .Set("renormalize", Value::Bool(false)));
    ASSERT_TRUE(renorm && plain);
    double largestDropped = 0;
    // (Not 450 nm: there 2λ/Λ = 1, order ±2 grazes at normal incidence and rounding decides whether
    // it propagates — a Rayleigh anomaly, where the renormalisation jumps.)
    for (double lambda : {460 * Nm, 700 * Nm}) {
        const SampledWavelengths wl = LineWavelength(lambda);
        for (double theta : {0.0, 20 * Deg, 50 * Deg}) {
            const ScatterQuery q = Wave(theta, 1.3, wl);
            const Vec3 d = q.wi;
            const double cosD = d.z, m = 2 * Pi / lambda * h * cosD;
            const double F = TextbookFresnel(cosD, 1, MetalIndex).R;
            // The reference: which orders of d propagate, and their J² sum.
            double propagating = 0;
            for (int j = -10; j <= 10; ++j) {
                Vec3 wo;
                if (ExpectedDirection(d, 1, 1, g, j, lambda, period, false, &wo)) propagating += J2(j, m);
            }
            const GratingOrders o = renorm->Orders(q, 0);
            EXPECT_NEAR(o.reflected.Dropped(), 1 - propagating, 1e-13);
            EXPECT_NEAR(o.reflected.evanescent + o.reflected.truncated, o.reflected.Dropped(), 1e-14);
            EXPECT_NEAR(o.reflected.substrate, F, 1e-14);
            EXPECT_NEAR(plain->Orders(q, 0).reflected.Dropped(), o.reflected.Dropped(), 1e-15);
            largestDropped = std::max(largestDropped, o.reflected.Dropped());
            double sumA = 0, sumB = 0;
            for (int j = -10; j <= 10; ++j) {
                const FromSource a = OrderFrom(*renorm, wl, d, 1, 1, g, period, j, false);
                const FromSource b = OrderFrom(*plain, wl, d, 1, 1, g, period, j, false);
                if (!a.propagates) continue;
                EXPECT_NEAR(a.weight, J2(j, m) * F / propagating, 1e-12 * a.weight) << "order " << j;
                // Orders() gives the same order's direction and energy.
                EXPECT_LT(AngleBetween(o.reflected.wo[std::size_t(j + GratingSide::MaxOrder)], a.out), 1e-12);
                EXPECT_NEAR(o.reflected.Energy(j), a.weight, 1e-15);
                sumA += a.weight;
                sumB += b.weight;
            }
            EXPECT_NEAR(sumA, F, 1e-13) << "renormalised: the grating reflects exactly F";
            EXPECT_NEAR(sumB, F * propagating, 1e-13) << "plain thin-phase: F·Σ_prop J²";
        }
    }
    EXPECT_GT(largestDropped, 0.05) << "the settings should drop a visible share";
}

TEST(Grating, AllOrdersSumToOne) {
    // A long period (Λ = 200 µm): all 31 orders |j| ≤ 15 propagate, nothing is evanescent, and
    // J_16(m)² ≤ ((m/2)¹⁶/16!)² < 2e-15 at m ≤ 4.8 (DLMF 10.14.4): Σ_{|j|≤15} J_j(m)² = 1 to 1e-13
    // (DLMF 10.23.3), the plain efficiencies of the light from d sum to F to 1e-12, and no share is
    // reported dropped.
    const double h = 0.3 * Um, period = 200 * Um;
    auto grating = MakeGrating(ParamDict()
                                   .Set("substrate", Value::Ref("metal"))
                                   .Set("period", Len(period))
                                   .Set("height", Len(h))
                                   .Set("max_order", Value::Integer(15))
                                   .Set("renormalize", Value::Bool(false)));
    ASSERT_TRUE(grating);
    for (double lambda : {400 * Nm, 633 * Nm}) {
        const SampledWavelengths wl = LineWavelength(lambda);
        for (double theta : {0.0, 40 * Deg}) {
            const ScatterQuery q = Wave(theta, 2.0, wl);
            const double cosI = std::cos(theta), m = 2 * Pi / lambda * h * cosI;
            double reference = 0;
            for (int j = -15; j <= 15; ++j) reference += J2(j, m);
            EXPECT_NEAR(reference, 1, 1e-13);
            const GratingOrders o = grating->Orders(q, 0);
            EXPECT_EQ(o.reflected.evanescent, 0);
            EXPECT_NEAR(o.reflected.propagatingSum, reference, 1e-13);
            EXPECT_LT(o.reflected.Dropped(), 1e-13);
            double sum = 0;
            int lit = 0;
            for (int j = -15; j <= 15; ++j) {
                const FromSource f = OrderFrom(*grating, wl, q.wi, 1, 1, Vec2(0, 1), period, j, false);
                ASSERT_TRUE(f.propagates) << "order " << j;
                if (f.weight < 0) continue;  // J_j² < 1e-20: not listed
                sum += f.weight;
                lit += f.weight > 1e-12;
            }
            EXPECT_NEAR(sum, TextbookFresnel(cosI, 1, MetalIndex).R, 1e-12);
            EXPECT_GE(lit, 15) << "m = " << m << ": most orders carry light";
        }
    }
}

TEST(Grating, LosslessSubstrateConservesEnergy) {
    // Glass (n = 1.5) with transmission, renormalised: the light from d leaves with R(θ_d) in the
    // reflected orders and T = 1 − R in the transmitted ones (energy: the radiance weights times
    // (n_out/n_in)²), so R + T = 1 to 1e-12, from outside and from inside (including total internal
    // reflection, R = 1); Λ = 0.8 µm drops evanescent orders on both sides.
    const double period = 0.8 * Um;
    auto grating = MakeGrating(ParamDict()
                                   .Set("substrate", Value::Ref("contract_glass"))
                                   .Set("transmission", Value::Bool(true))
                                   .Set("period", Len(period))
                                   .Set("height", Len(0.15 * Um)));
    ASSERT_TRUE(grating);
    for (double lambda : {420 * Nm, 650 * Nm}) {
        const SampledWavelengths wl = LineWavelength(lambda);
        for (double theta : {0.0, 35 * Deg, 75 * Deg, 160 * Deg, 130 * Deg}) {
            const Vec3 d = Wave(theta, 0.3, wl).wi;
            const bool inside = d.z < 0;
            const double nD = inside ? 1.5 : 1.0, nFar = inside ? 1.0 : 1.5;
            const Fresnel f = TextbookFresnel(std::abs(d.z), nD, Complex(nFar, 0));
            double r = 0, t = 0;
            for (int j = -10; j <= 10; ++j)
                for (const bool transmitted : {false, true}) {
                    const FromSource o = OrderFrom(*grating, wl, d, nD, nFar, Vec2(0, 1), period, j, transmitted);
                    if (!o.propagates || o.weight < 0) continue;
                    (transmitted ? t : r) += o.energy;
                }
            EXPECT_NEAR(r, f.R, 1e-12) << "θ = " << theta / Deg;
            EXPECT_NEAR(t, f.T, 1e-12) << "θ = " << theta / Deg;
            EXPECT_NEAR(r + t, 1, 1e-12) << "θ = " << theta / Deg;
        }
    }
}

TEST(Grating, TransmittedOrdersUseTheTransmissionPhase) {
    // Light from d transmitted into order j: J_j(a)²·T with a = k₀·(h/2)·(n_t cosθ_t − n_d cosθ_d)
    // (the optical path through the relief; θ_t the zeroth order's), radiance weight ·(n_t/n_d)²
    // towards the denser side; plain efficiencies, Λ = 5 µm, from outside and from inside. At
    // normal incidence into n = 1.5, |a| = πh(n − 1)/λ, a quarter of the reflection's m = 2πh/λ: a
    // kernel that used m for both sides fails here.
    const double h = 0.4 * Um, n = 1.5, period = 5 * Um;
    auto grating = MakeGrating(ParamDict()
                                   .Set("substrate", Value::Ref("contract_glass"))
                                   .Set("transmission", Value::Bool(true))
                                   .Set("renormalize", Value::Bool(false))
                                   .Set("period", Len(period))
                                   .Set("height", Len(h)));
    ASSERT_TRUE(grating);
    for (double lambda : {450 * Nm, 600 * Nm}) {
        const SampledWavelengths wl = LineWavelength(lambda);
        for (double theta : {0.0, 25 * Deg, 165 * Deg}) {
            const Vec3 d = Wave(theta, 0.9, wl).wi;
            const bool inside = d.z < 0;
            const double nD = inside ? n : 1, nT = inside ? 1 : n;
            const double cosD = std::abs(d.z), sinT = nD / nT * std::sqrt(1 - cosD * cosD);
            const double cosT = std::sqrt(1 - sinT * sinT);
            const double a = 2 * Pi / lambda * h / 2 * (nT * cosT - nD * cosD);
            const Fresnel f = TextbookFresnel(cosD, nD, Complex(nT, 0));
            int transmitted = 0;
            for (int j = -10; j <= 10; ++j) {
                const FromSource o = OrderFrom(*grating, wl, d, nD, nT, Vec2(0, 1), period, j, true);
                if (!o.propagates) continue;
                ++transmitted;
                const double expected = J2(j, a) * f.T;
                EXPECT_NEAR(o.energy, expected, 1e-12 * expected + 1e-16) << "order " << j << ", θ = " << theta;
                EXPECT_NEAR(o.weight, expected * (nT / nD) * (nT / nD), 1e-12 * expected + 1e-16) << "order " << j;
            }
            EXPECT_GE(transmitted, 5);
            if (theta == 0) {
                EXPECT_NEAR(std::abs(a), Pi * h * (n - 1) / lambda, 1e-12);
            }
        }
    }
}

TEST(Grating, OrderJonesIsBesselTimesTheSubstrateFresnel) {
    // Light from d into order j: Jones = J_j(a)·diag(r_s, r_p)(θ_d) with a = −k·h·cosθ_d (the double
    // pass lowers the phase where the relief rises), plain efficiencies: J_j(−m) = (−1)^j J_j(m) for
    // j ≥ 0 and J_{−n}(−m) = J_n(m) (DLMF 10.4.1) — the odd orders' signs are tested, not only |J|².
    const double h = 0.15 * Um, period = 2 * Um;
    auto grating = MakeGrating(ParamDict()
                                   .Set("substrate", Value::Ref("metal"))
                                   .Set("renormalize", Value::Bool(false))
                                   .Set("period", Len(period))
                                   .Set("height", Len(h)));
    ASSERT_TRUE(grating);
    const SampledWavelengths wl = LineWavelength(530 * Nm);
    const Vec3 d = Wave(25 * Deg, 0.2, wl).wi;
    const double cosD = d.z, m = 2 * Pi / 530e-9 * h * cosD;
    const Fresnel f = TextbookFresnel(cosD, 1, MetalIndex);
    int orders = 0;
    for (int j = -5; j <= 5; ++j) {
        const FromSource o = OrderFrom(*grating, wl, d, 1, 1, Vec2(0, 1), period, j, false);
        if (!o.propagates) continue;
        ASSERT_TRUE(o.response) << "order " << j;
        ++orders;
        const LobeResponse &r = *o.response;
        const int n = std::abs(j);
        const double amp = std::cyl_bessel_j(double(n), m) * ((j > 0 && (n & 1)) ? -1 : 1);
        EXPECT_LT(std::abs(r.jones[0].m[0][0] - amp * f.rs), 1e-13) << "order " << j;
        EXPECT_LT(std::abs(r.jones[0].m[1][1] - amp * f.rp), 1e-13) << "order " << j;
        EXPECT_EQ(std::abs(r.jones[0].m[0][1]), 0);
        EXPECT_NEAR(r.mueller[0].m[0][0], o.weight, 1e-14);
        EXPECT_FALSE(r.coherence.any) << "no coherence-dependent terms (see grating.cpp)";
    }
    EXPECT_GE(orders, 5);
}

TEST(Grating, RayOpticsLimitIsTheSmoothSubstrate) {
    // rayOptics: the zeroth orders only with J_0 = 1 — the same lobes as the substrate kernel
    // itself (conductor: mirror R; dielectric: R and T(η_i/η_t)²). A height of 0 gives the same in
    // the wave regime.
    const SampledWavelengths wl = TestWavelengths(480 * Nm);
    struct Case {
        const char *substrate, *type;
        ParamDict params;
        bool transmission;
    };
    const Case cases[] = {
        {"metal", "conductor", ParamDict().Set("ior", Value::ComplexNumber(MetalIndex)), false},
        {"contract_bk7", "dielectric", ParamDict().Set("ior", Value::String("BK7")), true},
    };
    for (const Case &c : cases) {
        Diagnostics diag;
        auto smooth = BuildMaterial(c.type, c.params, diag);
        ASSERT_TRUE(smooth);
        ParamDict p;
        p.Set("substrate", Value::Ref(c.substrate))
            .Set("transmission", Value::Bool(c.transmission))
            .Set("period", Len(1 * Um));
        auto grating = MakeGrating(ParamDict(p).Set("height", Len(0.2 * Um)));
        auto plain = MakeGrating(ParamDict(p).Set("height", Len(0.2 * Um)).Set("renormalize", Value::Bool(false)));
        auto flat = MakeGrating(ParamDict(p).Set("height", Len(0)));
        ASSERT_TRUE(grating && plain && flat);
        for (double theta : {10 * Deg, 60 * Deg, 170 * Deg}) {
            ScatterQuery ray = Wave(theta, 0.5, wl);
            ray.rayOptics = true;
            const Prep expectedK(*smooth, ray);
            const std::span<const NearDeltaLobe> expected = expectedK->ListNearDelta();
            // (renormalize = false: F, not J_0(m)²·F — the grooves are not resolved at all.)
            for (const auto &[name, m, q] : {std::tuple{"ray limit", grating, ray}, std::tuple{"ray limit, plain", plain, ray},
                                             std::tuple{"h = 0", flat, Wave(theta, 0.5, wl)}}) {
                const Prep gotK(*m, q);
                const std::span<const NearDeltaLobe> got = gotK->ListNearDelta();
                ASSERT_EQ(got.size(), expected.size()) << name << ", " << c.substrate << ", θ = " << theta / Deg;
                for (int k = 0; k < int(got.size()); ++k) {
                    const NearDeltaLobe &a = got[std::size_t(k)], &b = expected[std::size_t(k)];
                    EXPECT_EQ(a.id, b.id == 0 ? 0 : GratingMaterial::TransmittedId) << name;
                    EXPECT_EQ(a.flags, b.flags) << name << ", lobe " << a.id;
                    // (Probabilities differ by design: the grating picks ∝ radiance weight, the
                    // dielectric ∝ R and T.)
                    for (int i = 0; i < wl.Count(); ++i) {
                        EXPECT_NEAR(a.Weight()[i], b.Weight()[i], 1e-12) << name << ", lobe " << a.id << ", slot " << i;
                        if (b.Weight()[i] > 0) {
                            EXPECT_LT(AngleBetween(a.wo[i], b.wo[i]), 1e-12) << name;
                        }
                    }
                }
            }
        }
    }
}

TEST(Grating, RayOpticsLimitOfACoatedSubstrateIsTheIncoherentSum) {
    // In the ray-optics limit a grating over a coated substrate is that coated substrate as the
    // smooth kernel answers there: the coating's incoherent sum (lobe weights R and T(η_i/η_t)², a
    // Jones-free Mueller matrix), not its coherent (Airy) response, which stays the wave regime's.
    // A 150 nm Cu₂O film on gold and a two-layer stack on BK7 (transmitting): their coherent and
    // incoherent reflectances differ by ≥ 1e-2 at these angles, so a grating that ignored the
    // regime fails every check by far more than the tolerance.
    struct Case {
        const char *type;
        ParamDict params;
        bool transmission;
    };
    const Case cases[] = {
        {"conductor", ParamDict().Set("ior", Value::String("Au")).Set("coating", Value::Ref("contract_film")), false},
        {"dielectric", ParamDict().Set("ior", Value::String("BK7")).Set("coating", Value::Ref("contract_stack")), true},
    };
    const SampledWavelengths wl = TestWavelengths(520 * Nm);
    for (const Case &c : cases) {
        MiniScene scene;
        scene.WithFixtures()
            .Add("Material", c.type, "coated", c.params)
            .Add("Material", "grating", "g",
                 ParamDict()
                     .Set("substrate", Value::Ref("coated"))
                     .Set("transmission", Value::Bool(c.transmission))
                     .Set("period", Len(1.2 * Um))
                     .Set("height", Len(0.15 * Um)));
        auto coated = scene.Build<Material>("coated"), grating = scene.Build<Material>("g");
        ASSERT_TRUE(coated && grating) << scene.FirstError();
        double largest = 0;
        for (double theta : {0.0, 40 * Deg, 75 * Deg, 150 * Deg}) {
            if (theta > 90 * Deg && !c.transmission) continue;
            ScatterQuery ray = Wave(theta, 0.3, wl), wave = ray;
            ray.rayOptics = true;
            const Prep expectedK(*coated, ray);
            const std::span<const NearDeltaLobe> expected = expectedK->ListNearDelta();
            const Prep gotK(*grating, ray);
            const std::span<const NearDeltaLobe> got = gotK->ListNearDelta();
            const Prep coherentK(*coated, wave);
            const std::span<const NearDeltaLobe> coherent = coherentK->ListNearDelta();
            ASSERT_EQ(got.size(), expected.size()) << c.type << ", θ = " << theta / Deg;
            for (int k = 0; k < int(got.size()); ++k) {
                const NearDeltaLobe &a = got[std::size_t(k)], &b = expected[std::size_t(k)];
                for (int i = 0; i < wl.Count(); ++i) {
                    EXPECT_NEAR(a.Weight()[i], b.Weight()[i], 1e-12) << c.type << ", θ " << theta / Deg << ", lobe " << a.id;
                    largest = std::max(largest, std::abs(b.Weight()[i] - coherent[std::size_t(k)].Weight()[i]));
                }
                auto ga = gotK->EvalLobe(a.id, a.wo[0]);
                auto ca = expectedK->EvalLobe(b.id, b.wo[0]);
                ASSERT_TRUE(ga && ca);
                EXPECT_FALSE(ga->hasJones) << "the incoherent sum has no Jones matrix";
                for (int i = 0; i < wl.Count(); ++i) {
                    if (b.Weight()[i] == 0) continue;
                    for (int x = 0; x < 4; ++x)
                        for (int y = 0; y < 4; ++y)
                            EXPECT_NEAR(ga->mueller[i].m[x][y], ca->mueller[i].m[x][y], 1e-12)
                                << c.type << ", θ " << theta / Deg << ", lobe " << a.id << ", slot " << i;
                }
            }
            // The wave regime keeps the coherent response (J_j² of it): its Jones matrices exist.
            const Prep ordersK(*grating, wave);
            const std::span<const NearDeltaLobe> orders = ordersK->ListNearDelta();
            ASSERT_FALSE(orders.empty());
            auto w = ordersK->EvalLobe(orders[0].id, orders[0].wo[0]);
            ASSERT_TRUE(w);
            EXPECT_TRUE(w->hasJones);
        }
        EXPECT_GT(largest, 1e-2) << c.type << ": the case does not tell the regimes apart";
    }
}

TEST(Grating, TexturesDrivePeriodAndGrooveDirection) {
    // @contract_pitch: Λ = 1.2 µm + 1.2 µm·u; @contract_groove_angle: α = 120°·v (gradients,
    // clamped to [0, 1]). Order j's tangential shift must be j·2π/Λ(uv)·ĝ(α(uv)) at the hit, and
    // `angle_texture = @t` must be the same as `angle = @t`.
    ParamDict p;
    p.Set("substrate", Value::Ref("metal"))
        .Set("period", Value::Ref("contract_pitch"))
        .Set("height", Len(0.1 * Um));
    auto a = MakeGrating(ParamDict(p).Set("angle", Value::Ref("contract_groove_angle")));
    auto b = MakeGrating(ParamDict(p).Set("angle_texture", Value::Ref("contract_groove_angle")));
    ASSERT_TRUE(a && b);
    const SampledWavelengths wl = LineWavelength(500 * Nm);
    for (const Vec2 uv : {Vec2(0.25, 0.75), Vec2(0.8, 0.1), Vec2(1.7, -0.4)}) {
        const double u = Clamp(uv.x, 0.0, 1.0), v = Clamp(uv.y, 0.0, 1.0);
        const double period = (1.2 + 1.2 * u) * Um, alpha = 120 * Deg * v;
        const Vec2 g(-std::sin(alpha), std::cos(alpha));
        const ScatterQuery q = Wave(20 * Deg, 0.4, wl, uv);
        const Prep laK(*a, q);
        const std::span<const NearDeltaLobe> la = laK->ListNearDelta();
        const Prep lbK(*b, q);
        const std::span<const NearDeltaLobe> lb = lbK->ListNearDelta();
        ASSERT_EQ(la.size(), lb.size());
        int orders = 0;
        for (int k = 0; k < int(la.size()); ++k) {
            const NearDeltaLobe &l = la[std::size_t(k)];
            const Vec2 shift = g * (2 * Pi * l.id / period);
            EXPECT_LT(Length(l.shift - shift), 1e-9 * 2 * Pi / period) << "uv " << uv.x << ", " << uv.y;
            EXPECT_EQ(l.id, lb[std::size_t(k)].id);
            EXPECT_EQ(l.wo[0], lb[std::size_t(k)].wo[0]);
            orders += l.id != 0;
        }
        EXPECT_GE(orders, 2);
        const Vec3 gv = a->GratingVector(q);
        EXPECT_NEAR(gv.x, g.x, 1e-15);
        EXPECT_NEAR(gv.y, g.y, 1e-15);
        EXPECT_NEAR(a->Orders(q, 0).period, period, 1e-20);
    }
}

TEST(Grating, DispersionFlags) {
    // Orders j ≠ 0 change direction with λ (ScatterDispersive); the zeroth reflected order does
    // not; the zeroth transmitted order does iff the substrate's index varies (BK7 vs n = 1.5).
    const SampledWavelengths wl = TestWavelengths(550 * Nm);
    for (const char *substrate : {"contract_bk7", "contract_glass"}) {
        auto grating = MakeGrating(ParamDict()
                                       .Set("substrate", Value::Ref(substrate))
                                       .Set("transmission", Value::Bool(true))
                                       .Set("period", Len(2 * Um))
                                       .Set("height", Len(0.2 * Um)));
        ASSERT_TRUE(grating);
        const ScatterQuery q = Wave(30 * Deg, 0.1, wl);
        const Prep lobesK(*grating, q);
        const std::span<const NearDeltaLobe> lobes = lobesK->ListNearDelta();
        const bool bk7 = std::string(substrate) == "contract_bk7";
        for (const NearDeltaLobe &l : lobes) {
            const bool transmitted = l.id >= GratingMaterial::TransmittedId / 2;
            const int j = transmitted ? l.id - GratingMaterial::TransmittedId : l.id;
            const bool dispersive = j != 0 || (transmitted && bk7);
            EXPECT_EQ((l.flags & ScatterDispersive) != 0, dispersive) << substrate << ", lobe " << l.id;
            // A non-dispersive lobe has one direction for every wavelength; a dispersive one does not
            // (compared where it carries light at two or more wavelengths).
            int lit = 0;
            bool same = true;
            for (int i = 0; i < wl.Count(); ++i) {
                if (l.Weight()[i] == 0) continue;
                same = same && (lit == 0 || AngleBetween(l.wo[i], l.wo[0]) < 1e-12);
                ++lit;
            }
            if (lit >= 2) {
                EXPECT_EQ(same, !dispersive) << substrate << ", lobe " << l.id;
            }
        }
    }
}

TEST(Grating, AnOrderEvanescentAtTheHeroIsListedForItsCompanions) {
    // Λ = 0.6 µm at normal incidence: order ±1 is evanescent at the 700 nm hero (λ/Λ > 1) but
    // propagates at the 445 and 530 nm companions. It must be listed (grt measures companions
    // along their own directions), with weight 0 and probability 0 at the hero.
    auto grating = MetalGrating(0.6 * Um);
    ASSERT_TRUE(grating);
    const SampledWavelengths wl = TestWavelengths(700 * Nm);
    ASSERT_NEAR(wl.lambda[1], 445 * Nm, 1e-15);
    const ScatterQuery q = Wave(0, 0, wl);
    const Prep lobesK(*grating, q);
    const std::span<const NearDeltaLobe> lobes = lobesK->ListNearDelta();
    for (int j : {-1, 1}) {
        const NearDeltaLobe *l = Find(lobes, j);
        ASSERT_NE(l, nullptr) << "order " << j;
        EXPECT_EQ(l->Weight()[0], 0);
        EXPECT_EQ(l->prob, 0);
        for (int i = 1; i < wl.Count(); ++i) {
            const bool propagates = wl.lambda[i] < 0.6 * Um;
            EXPECT_EQ(l->Weight()[i] > 0, propagates) << "order " << j << ", slot " << i;
        }
    }
    double hero = 0;
    for (const NearDeltaLobe &l : lobes) hero += l.prob;
    EXPECT_NEAR(hero, 1, 1e-12);
}

TEST(Grating, CompanionEfficienciesAreComputedWhenRead) {
    // Where the hero carries light, the listing computes the companions' efficiencies only when a
    // caller reads them (most lobes reach no light): the orders of a 1.2 µm grating under four
    // wavelengths defer slots 1–3, and once read they are the efficiencies a listing with that
    // wavelength as the hero gives (the kernel contract checks every preset so). A lobe whose
    // pending weights are asked of another kernel — the grating prepared at another incidence —
    // reads differently: the comparison sees a wrong completion.
    auto grating = MetalGrating(1.2 * Um);
    ASSERT_TRUE(grating);
    const SampledWavelengths wl = TestWavelengths(550 * Nm);
    const ScatterQuery q = Wave(20 * Deg, 0.3, wl), other = Wave(35 * Deg, 0.3, wl);
    const Prep k(*grating, q), wrong(*grating, other);
    int deferred = 0, caught = 0;
    for (const NearDeltaLobe &l : k->ListNearDelta()) {
        if (!l.PendingSlots()) continue;
        ++deferred;
        EXPECT_EQ(l.PendingSlots() & 1u, 0u) << "order " << l.id << ": the hero's efficiency is deferred";
        NearDeltaLobe misread = l;
        misread.DeferWeights(l.PendingSlots(), *wrong);
        for (int i = 1; i < wl.Count(); ++i) {
            SampledWavelengths swapped = wl;
            std::swap(swapped.lambda[0], swapped.lambda[std::size_t(i)]);
            ScatterQuery qi = q;
            qi.wl = &swapped;
            const Prep hero(*grating, qi);
            const NearDeltaLobe *there = Find(hero->ListNearDelta(), l.id);
            const double eager = there ? there->Weight()[0] : 0.0;
            EXPECT_EQ(l.Weight()[i], eager) << "order " << l.id << ", slot " << i;
            caught += misread.Weight()[i] != eager;
        }
        EXPECT_EQ(l.PendingSlots(), 0u);
    }
    EXPECT_GE(deferred, 3) << "the orders' companion efficiencies were listed eagerly";
    EXPECT_GT(caught, 0) << "a completion by the wrong kernel went unnoticed";
}

TEST(Grating, ListedWeightsAreTheirSourcesOrderEnergies) {
    // Each listed lobe j at wavelength i carries what its source direction's order j carries:
    // Orders() at the source (every order's direction from the grating equation) gives Energy(j),
    // times (n_query/n_source)² (radiance) on transmission; an order that does not propagate from
    // the query, or is not listed, carries 0. The listing finds the source's propagating orders
    // from the query's own (GratingMaterial::BackOrders) and its Bessel values only up to the
    // largest of them; a wrong shift or sign there changes the renormalisation Σ_prop J² and fails.
    // Renormalised reflection (CD pitch, a long period) and transmission into BK7, from both sides,
    // 400 random incidences each (fixed seed); incidences where some order grazes (|t|² within 1e-9
    // of 1, a Rayleigh anomaly where rounding decides) are skipped.
    struct Case {
        std::shared_ptr<GratingMaterial> grating;
        double period;
        bool transmission;
    };
    std::vector<Case> cases;
    cases.push_back({MetalGrating(1.6 * Um), 1.6 * Um, false});
    cases.push_back({MetalGrating(7.3 * Um), 7.3 * Um, false});
    cases.push_back({MakeGrating(ParamDict()
                                     .Set("substrate", Value::Ref("contract_bk7"))
                                     .Set("transmission", Value::Bool(true))
                                     .Set("period", Len(2.1 * Um))
                                     .Set("height", Len(0.3 * Um))),
                     2.1 * Um, true});
    std::mt19937 rng(20261205);
    std::uniform_real_distribution<double> u(0, 1);
    int compared = 0, skipped = 0;
    for (const Case &c : cases) {
        ASSERT_TRUE(c.grating);
        for (int trial = 0; trial < 400; ++trial) {
            const SampledWavelengths wl = TestWavelengths(380 * Nm + 340 * Nm * u(rng));
            const double theta = std::acos(0.02 + 0.98 * u(rng));
            const bool inside = c.transmission && trial % 2;  // a transmission grating from the glass
            const ScatterQuery q = Wave(inside ? Pi - theta : theta, 2 * Pi * u(rng), wl);
            bool grazes = false;
            for (int i = 0; i < wl.Count() && !grazes; ++i) {
                const double nWi = inside ? c.grating->Orders(q, i).reflected.nIn : 1.0;
                for (int p = -40; p <= 40; ++p) {
                    const double tx = -nWi * q.wi.x, ty = -nWi * q.wi.y + p * wl.lambda[std::size_t(i)] / c.period;
                    grazes = grazes || std::abs((tx * tx + ty * ty) / (nWi * nWi) - 1) < 1e-9;
                }
            }
            if (grazes) {
                ++skipped;
                continue;
            }
            const Prep k(*c.grating, q);
            const std::span<const NearDeltaLobe> lobes = k->ListNearDelta();
            // Every order of every side at every wavelength, listed or not: a lobe missing, or a
            // slot left at 0 where its source's order carries light, fails as a wrong weight.
            for (const bool transmitted : {false, true}) {
                if (transmitted && !c.transmission) continue;
                for (int j = -GratingSide::MaxOrder; j <= GratingSide::MaxOrder; ++j) {
                    const NearDeltaLobe *l = Find(lobes, (transmitted ? GratingMaterial::TransmittedId : 0) + j);
                    const SampledSpectrum w = l ? l->Weight() : SampledSpectrum(0.0);
                    for (int i = 0; i < wl.Count(); ++i) {
                        const GratingOrders here = c.grating->Orders(q, i);
                        const double nWi = here.reflected.nIn, nFar = here.transmitted.nOut;
                        Vec3 source;
                        double expected = 0;
                        if (ExpectedDirection(q.wi, nWi, transmitted ? nFar : nWi, Vec2(0, 1), j,
                                              wl.lambda[std::size_t(i)], c.period, transmitted, &source)) {
                            ScatterQuery from = q;
                            from.wi = source;
                            const GratingOrders o = c.grating->Orders(from, i);
                            const GratingSide &side = transmitted ? o.transmitted : o.reflected;
                            const double ratio = side.nOut / side.nIn;  // the query's medium over the source's
                            expected = side.Energy(j) * (transmitted ? ratio * ratio : 1.0);
                        }
                        // 2e-12 relative: the Bessel values of the two paths (the listing's up to the
                        // orders it sums, Orders()' up to the truncation) and F (Power and R()) differ in
                        // the last bits; 1e-15 absolute where J_j nears a zero (largest seen 1.1e-12
                        // relative at a weight of 1.4e-9).
                        EXPECT_NEAR(w[i], expected, 2e-12 * expected + 1e-15)
                            << (transmitted ? "T" : "R") << " order " << j << ", slot " << i << ", trial " << trial;
                        if (expected > 0 && w[i] > 0) {
                            EXPECT_LT(AngleBetween(l->wo[std::size_t(i)], source), 1e-9) << "order " << j << ", slot " << i;
                            ++compared;
                        }
                    }
                }
            }
        }
    }
    EXPECT_GT(compared, 5000);
    EXPECT_LT(skipped, 20);
}

TEST(Grating, FarOutsideTheThinPhaseRegimeStaysFinite) {
    // h = Λ = 50 µm (m ≈ 785 at 400 nm), grazing and normal incidence, transmission: the kernel is
    // meaningless there but must list finite weights, and the light from one direction must leave
    // with exactly its energy (renormalised, lossless glass).
    const double period = 50 * Um;
    auto grating = MakeGrating(ParamDict()
                                   .Set("substrate", Value::Ref("contract_glass"))
                                   .Set("transmission", Value::Bool(true))
                                   .Set("period", Len(period))
                                   .Set("height", Len(50 * Um))
                                   .Set("max_order", Value::Integer(15)),
                               /*deep=*/true);
    ASSERT_TRUE(grating);
    const SampledWavelengths wl4 = TestWavelengths(400 * Nm), wl = LineWavelength(400 * Nm);
    for (double theta : {0.0, 89.9 * Deg, 90.1 * Deg, 180 * Deg}) {
        const Prep lobesK(*grating, Wave(theta, 0.3, wl4));
        const std::span<const NearDeltaLobe> lobes = lobesK->ListNearDelta();
        ASSERT_FALSE(lobes.empty());
        for (const NearDeltaLobe &l : lobes)
            for (int i = 0; i < wl4.Count(); ++i) ASSERT_TRUE(std::isfinite(l.Weight()[i]) && l.Weight()[i] >= 0);
        const Vec3 d = Wave(theta, 0.3, wl).wi;
        const bool inside = d.z < 0;
        double energy = 0;
        for (int j = -15; j <= 15; ++j)
            for (const bool transmitted : {false, true}) {
                const FromSource o = OrderFrom(*grating, wl, d, inside ? 1.5 : 1, inside ? 1 : 1.5, Vec2(0, 1), period, j,
                                               transmitted);
                if (o.propagates && o.weight >= 0) energy += o.energy;
            }
        EXPECT_NEAR(energy, 1, 1e-9) << "θ = " << theta / Deg;
    }
}

}  // namespace
}  // namespace phasor::test
