// SPDX-License-Identifier: Apache-2.0
// layer_stack.h against closed forms (bare interface, Airy, quarter-wave stack), an independent
// characteristic-matrix (Abelès) product, and energy conservation.
#include "materials/layer_stack.h"

#include <gtest/gtest.h>

#include <vector>

#include "materials/fresnel.h"

namespace phasor {
namespace {

constexpr double Lambda = 550e-9;

// Incidence from a real medium n0 at angle theta0 [rad].
Complex CosIn(double theta0) { return {std::cos(theta0), 0}; }

TEST(LayerStack, NoLayersIsTheBareInterface) {
    for (Complex ns : {Complex(1.5, 0), Complex(0.2, 3.0), Complex(1, 0)})
        for (double th : {0.0, 0.5, 1.2}) {
            const StackResponse r = LayerStackResponse(Lambda, 1.0, CosIn(th), {}, ns);
            const FresnelCoefficients f = FresnelAmplitudes(std::cos(th), 1.0, ns);
            EXPECT_EQ(r.rs, f.rs);
            EXPECT_EQ(r.rp, f.rp);
            EXPECT_EQ(r.ts, f.ts);
            EXPECT_EQ(r.tp, f.tp);
        }
}

TEST(LayerStack, SingleFilmIsTheAiryFormula) {
    // theory §4.4: r = (r₀₁ + r₁₂e^{2iδ})/(1 + r₀₁r₁₂e^{2iδ}), δ = (2π/λ) n₁ d cosθ₁, with a Cu₂O-like
    // absorbing film on a metal and a MgF₂-like film on glass.
    struct Case {
        Complex film, substrate;
        double d;
    } cases[] = {{{2.95, 0.1}, {0.94, 2.6}, 120e-9}, {{1.38, 0}, {1.52, 0}, 99.6e-9}, {{2.0, 0}, {1.5, 0}, 3e-6}};
    for (const Case &c : cases)
        for (double th : {0.0, 0.4, 1.0, 1.45}) {
            const Complex cos0 = CosIn(th);
            const FresnelCoefficients f01 = FresnelAmplitudes(1.0, cos0, c.film);
            const FresnelCoefficients f12 = FresnelAmplitudes(c.film, f01.cosThetaT, c.substrate);
            const Complex e2 = std::exp(Complex(0, 2) * (2 * Pi / Lambda) * c.film * f01.cosThetaT * c.d);
            const Complex rs = (f01.rs + f12.rs * e2) / (1.0 + f01.rs * f12.rs * e2);
            const Complex rp = (f01.rp + f12.rp * e2) / (1.0 + f01.rp * f12.rp * e2);
            const Layer film[] = {{c.film, c.d}};
            const StackResponse r = LayerStackResponse(Lambda, 1.0, cos0, film, c.substrate);
            EXPECT_LT(std::abs(r.rs - rs), 1e-12) << c.film << " θ = " << th;
            EXPECT_LT(std::abs(r.rp - rp), 1e-12) << c.film << " θ = " << th;
        }
}

// Independent reference: the characteristic-matrix product (Macleod, Thin-Film Optical Filters,
// §2.2) with tilted admittances η_s = n cosθ, η_p = n/cosθ, layer matrix
// [[cos δ, −i sin δ/η], [−i η sin δ, cos δ]], [B C]ᵀ = Π M_j [1 η_sub]ᵀ, r = (η₀B − C)/(η₀B + C),
// T = 4 Re(η₀) Re(η_sub)/|η₀B + C|² (real incident medium). Macleod's p amplitude has the
// opposite sign of fresnel.h's r_p (it is the ratio of tangential H, not of E along p̂).
struct Abeles {
    Complex r;
    double T;
};
Abeles AbelesProduct(double n0, double theta0, const std::vector<Layer> &layers, Complex ns, bool p) {
    const double s0 = std::sin(theta0);
    auto cosIn = [&](Complex n) { return std::sqrt(1.0 - Sqr(n0 * s0 / n)); };  // real, lossless cases only
    auto eta = [&](Complex n) { return p ? n / cosIn(n) : n * cosIn(n); };
    const Complex eta0 = eta(n0), etaS = eta(ns);
    Complex m00 = 1, m01 = 0, m10 = 0, m11 = 1;
    for (const Layer &l : layers) {
        const Complex d = 2 * Pi / Lambda * l.n * cosIn(l.n) * l.thickness, e = eta(l.n), i(0, 1);
        const Complex a = std::cos(d), b = -i * std::sin(d) / e, c = -i * e * std::sin(d);
        const Complex n00 = m00 * a + m01 * c, n01 = m00 * b + m01 * a;
        const Complex n10 = m10 * a + m11 * c, n11 = m10 * b + m11 * a;
        m00 = n00, m01 = n01, m10 = n10, m11 = n11;
    }
    const Complex B = m00 + m01 * etaS, C = m10 + m11 * etaS;
    const Complex r = (eta0 * B - C) / (eta0 * B + C);
    return {p ? -r : r, 4 * eta0.real() * etaS.real() / std::norm(eta0 * B + C)};
}

std::vector<Layer> SomeStack() {
    // A 7-layer dielectric filter with unequal thicknesses (no special structure).
    return {{1.38, 80e-9}, {2.3, 55e-9}, {1.46, 130e-9}, {2.3, 61e-9}, {1.38, 250e-9}, {1.7, 10e-9}, {2.0, 1.1e-6}};
}

TEST(LayerStack, MatchesTheCharacteristicMatrixProduct) {
    for (double th : {0.0, 0.3, 0.9, 1.3}) {
        const StackResponse r = LayerStackResponse(Lambda, 1.0, CosIn(th), SomeStack(), Complex(1.52, 0));
        const Abeles s = AbelesProduct(1.0, th, SomeStack(), 1.52, false), p = AbelesProduct(1.0, th, SomeStack(), 1.52, true);
        // 1e-12: O(1) amplitudes after ~10 matrix products in double precision.
        EXPECT_LT(std::abs(r.rs - s.r), 1e-12) << th;
        EXPECT_LT(std::abs(r.rp - p.r), 1e-12) << th;
        EXPECT_NEAR(r.Ts, s.T, 1e-12) << th;
        EXPECT_NEAR(r.Tp, p.T, 1e-12) << th;
    }
}

TEST(LayerStack, QuarterWaveStackMatchesClosedForm) {
    // (HL)^N quarter-wave pairs on a substrate at normal incidence: each quarter-wave layer of
    // index n maps the admittance Y below it to n²/Y, so the stack's admittance is
    // Y = (n_H/n_L)^{2N} n_s and R = ((n₀ − Y)/(n₀ + Y))² (Macleod §5.2).
    const double n0 = 1.0, nH = 1.70, nL = 1.55, ns = 1.52, lambda0 = 530e-9;
    for (int pairs : {1, 4, 10, 15}) {
        std::vector<Layer> stack;
        for (int k = 0; k < pairs; ++k) {
            stack.push_back({nH, lambda0 / (4 * nH)});
            stack.push_back({nL, lambda0 / (4 * nL)});
        }
        const double y = std::pow(nH / nL, 2 * pairs) * ns;
        const double expected = Sqr((n0 - y) / (n0 + y));
        const StackResponse r = LayerStackResponse(lambda0, n0, 1.0, stack, ns);
        EXPECT_NEAR(r.Rs, expected, 1e-13) << pairs;
        EXPECT_NEAR(r.Rp, expected, 1e-13) << pairs;  // s and p coincide at normal incidence
        EXPECT_NEAR(r.Rs + r.Ts, 1, 1e-13) << pairs;
        // Off the design wavelength the closed form no longer holds: the test can tell (by 5e-4
        // for one pair, more for more).
        EXPECT_GT(std::abs(LayerStackResponse(1.2 * lambda0, n0, 1.0, stack, ns).Rs - expected), 1e-4) << pairs;
    }
}

TEST(LayerStack, LosslessStacksConserveEnergy) {
    for (double th : {0.0, 0.5, 1.0, 1.5})
        for (double lambda : {400e-9, 550e-9, 700e-9}) {
            const StackResponse r = LayerStackResponse(lambda, 1.0, CosIn(th), SomeStack(), Complex(1.52, 0));
            EXPECT_NEAR(r.Rs + r.Ts, 1, 1e-12) << th << " " << lambda;
            EXPECT_NEAR(r.Rp + r.Tp, 1, 1e-12) << th << " " << lambda;
        }
    // From a dense incident medium past the substrate's critical angle: R = 1, T = 0, even with
    // propagating layers between.
    const StackResponse tir = LayerStackResponse(Lambda, 1.6, CosIn(1.2), SomeStack(), Complex(1.0, 0));
    EXPECT_NEAR(tir.Rs, 1, 1e-12);
    EXPECT_NEAR(tir.Rp, 1, 1e-12);
    EXPECT_EQ(tir.Ts, 0);
}

TEST(LayerStack, LosslessArithmeticAgreesWithTheComplexOne) {
    // Lossless media in which every wave propagates take real arithmetic (RealMedia); an index with a
    // 1e-200 imaginary part — physically the same stack — takes the complex recursion. Both agree
    // to round-off over angles (up to grazing), wavelengths, and films thin and thick.
    const double tiny = 1e-200;
    for (double th : {0.0, 0.4, 1.0, 1.5, 1.5707})
        for (double lambda : {380e-9, 550e-9, 780e-9})
            for (double d : {0.0, 30e-9, 400e-9, 20e-6}) {
                std::vector<Layer> stack = SomeStack();
                stack.push_back({1.33, d});  // a soap film's water last
                const StackResponse real = LayerStackResponse(lambda, 1.0, CosIn(th), stack, Complex(1.0, 0));
                const StackResponse cplx = LayerStackResponse(lambda, 1.0, CosIn(th), stack, Complex(1.0, tiny));
                SCOPED_TRACE(::testing::Message() << th << " " << lambda << " " << d);
                // 1e-12: O(1) amplitudes; the phases' products are rounded in a different order.
                EXPECT_LT(std::abs(real.rs - cplx.rs), 1e-12);
                EXPECT_LT(std::abs(real.rp - cplx.rp), 1e-12);
                EXPECT_LT(std::abs(real.ts - cplx.ts), 1e-12);
                EXPECT_LT(std::abs(real.tp - cplx.tp), 1e-12);
                EXPECT_NEAR(real.Ts, cplx.Ts, 1e-12);
                EXPECT_NEAR(real.Tp, cplx.Tp, 1e-12);
                EXPECT_EQ(real.cosSubstrate, Complex(real.cosSubstrate.real(), 0));
            }
}

TEST(LayerStack, AbsorbingLayerLosesEnergy) {
    std::vector<Layer> stack = SomeStack();
    stack[2].n = Complex(1.46, 0.05);
    for (double th : {0.0, 0.7}) {
        const StackResponse r = LayerStackResponse(Lambda, 1.0, CosIn(th), stack, Complex(1.52, 0));
        EXPECT_LT(r.Rs + r.Ts, 1 - 1e-3) << th;
        EXPECT_LT(r.Rp + r.Tp, 1 - 1e-3) << th;
        EXPECT_GT(r.Ts, 0);
    }
}

TEST(LayerStack, ZeroThicknessLayerChangesNothing) {
    std::vector<Layer> with = SomeStack();
    with.insert(with.begin() + 3, Layer{{0.3, 4.0}, 0.0});  // even a metal, at zero thickness
    for (double th : {0.0, 0.8}) {
        const StackResponse a = LayerStackResponse(Lambda, 1.0, CosIn(th), SomeStack(), Complex(1.52, 0));
        const StackResponse b = LayerStackResponse(Lambda, 1.0, CosIn(th), with, Complex(1.52, 0));
        EXPECT_LT(std::abs(a.rs - b.rs), 1e-13);
        EXPECT_LT(std::abs(a.rp - b.rp), 1e-13);
        EXPECT_LT(std::abs(a.ts - b.ts), 1e-13);
        EXPECT_LT(std::abs(a.tp - b.tp), 1e-13);
    }
}

TEST(LayerStack, ThickAbsorbingAndEvanescentLayersAreStable) {
    // 1 mm of metal: the matrix product's e^{−iδ} would be e^{+10⁵}; here the layer is opaque and
    // the stack reflects like the bare metal.
    const Layer metal[] = {{{0.2, 3.0}, 1e-3}};
    const StackResponse r = LayerStackResponse(Lambda, 1.0, CosIn(0.3), metal, Complex(1.5, 0));
    const FresnelCoefficients bare = FresnelAmplitudes(std::cos(0.3), 1.0, Complex(0.2, 3.0));
    EXPECT_LT(std::abs(r.rs - bare.rs), 1e-15);
    EXPECT_LT(std::abs(r.rp - bare.rp), 1e-15);
    EXPECT_EQ(r.Ts, 0);
    // Frustrated total internal reflection: glass | 1 µm … 1 m of air | glass beyond the critical
    // angle. Thin gaps tunnel (T > 0); thick ones reflect totally, without overflow.
    for (double gap : {50e-9, 1e-6, 1.0}) {
        const Layer air[] = {{1.0, gap}};
        const StackResponse f = LayerStackResponse(Lambda, 1.5, CosIn(1.0), air, Complex(1.5, 0));
        EXPECT_TRUE(std::isfinite(f.Rs) && std::isfinite(f.Ts)) << gap;
        EXPECT_NEAR(f.Rs + f.Ts, 1, 1e-12) << gap;
        EXPECT_NEAR(f.Rp + f.Tp, 1, 1e-12) << gap;
        if (gap < 1e-7) {
            EXPECT_GT(f.Ts, 0.1) << gap;
        }
        if (gap > 1e-3) {
            EXPECT_LT(f.Ts, 1e-300) << gap;
        }
    }
}


// ---- the incoherent response (LayerStackIncoherent) and the shear ----------------------------------

TEST(LayerStackIncoherent, NoPropagatingLayerIsTheCoherentResponse) {
    // Without layers, and when every layer is evanescent or metallic, nothing is summed in power.
    const Layer metal[] = {{{0.05, 3.3}, 20e-9}};  // silver-like: coherent even in the ray limit
    for (double th : {0.0, 0.6, 1.3}) {
        for (std::span<const Layer> layers : {std::span<const Layer>(), std::span<const Layer>(metal)}) {
            const StackResponse c = LayerStackResponse(Lambda, 1.0, CosIn(th), layers, Complex(1.5, 0));
            const IncoherentStackResponse n = LayerStackIncoherent(Lambda, 1.0, CosIn(th), layers, Complex(1.5, 0));
            EXPECT_NEAR(n.Rs, c.Rs, 1e-15);
            EXPECT_NEAR(n.Rp, c.Rp, 1e-15);
            EXPECT_NEAR(n.Ts, c.Ts, 1e-15);
            EXPECT_NEAR(n.Tp, c.Tp, 1e-15);
            EXPECT_LT(std::abs(n.Rsp - c.rs * std::conj(c.rp)), 1e-15);
        }
    }
}

TEST(LayerStackIncoherent, TwoThickSlabsAddInPowerLikeARayTracer) {
    // Two lossless slabs: the incoherent sum is the "net radiation" result of a ray tracer that
    // bounces rays inside each slab — written here with face powers ρ = |r|², τ = 1 − ρ:
    // a slab on a stack of reflectance G, transmittance Tb (both seen from inside the slab):
    //   R = ρ₀ + τ₀²G/(1 − ρ₀G),  T = τ₀·Tb/(1 − ρ₀G)   (for s and p separately).
    const Layer slabs[] = {{1.8, 3e-6}, {1.3, 5e-6}};
    const Complex ns(1.6, 0);
    for (double th : {0.0, 0.5, 1.1}) {
        const double beta = std::sin(th);
        auto cosIn = [&](double n) { return std::sqrt(1 - Sqr(beta / n)); };
        auto face = [&](double n1, double n2, bool p) {
            const double c1 = cosIn(n1), c2 = cosIn(n2);
            const double r = p ? (n2 * c1 - n1 * c2) / (n2 * c1 + n1 * c2) : (n1 * c1 - n2 * c2) / (n1 * c1 + n2 * c2);
            return r * r;
        };
        for (bool p : {false, true}) {
            const double r0 = face(1.0, 1.8, p), r1 = face(1.8, 1.3, p), r2 = face(1.3, 1.6, p);
            const double g2 = r2, t2 = 1 - r2;                                    // below slab 2
            const double g1 = r1 + Sqr(1 - r1) * g2 / (1 - r1 * g2), t1 = (1 - r1) * t2 / (1 - r1 * g2);  // below slab 1
            const double R = r0 + Sqr(1 - r0) * g1 / (1 - r0 * g1), T = (1 - r0) * t1 / (1 - r0 * g1);
            const IncoherentStackResponse n = LayerStackIncoherent(Lambda, 1.0, CosIn(th), slabs, ns);
            EXPECT_NEAR(p ? n.Rp : n.Rs, R, 1e-13) << th << " p " << p;
            EXPECT_NEAR(p ? n.Tp : n.Ts, T, 1e-13) << th << " p " << p;
            EXPECT_NEAR(R + T, 1, 1e-13);
        }
    }
}

TEST(LayerStackIncoherent, EnergyAndReciprocityWithAbsorbingAndEvanescentLayers) {
    // Lossless stacks: R + T = 1. With absorbing layers R + T < 1, and T is the same from both
    // sides (T is reciprocal between lossless outer media in the coherent and incoherent sums
    // alike). An evanescent gap (frustrated total reflection) stays coherent: R ≤ 1.
    std::vector<Layer> lossy = SomeStack();
    lossy[1].n = Complex(2.3, 0.02);
    lossy[4].n = Complex(0.2, 3.0);  // a metal layer in the middle
    lossy[4].thickness = 12e-9;
    for (double th : {0.0, 0.45, 0.9, 1.4}) {
        const IncoherentStackResponse n = LayerStackIncoherent(Lambda, 1.0, CosIn(th), SomeStack(), Complex(1.52, 0));
        EXPECT_NEAR(n.Rs + n.Ts, 1, 1e-12) << th;
        EXPECT_NEAR(n.Rp + n.Tp, 1, 1e-12) << th;
        // Reciprocity: from the substrate at the angle that refracts to θ in air.
        const double cosSub = std::sqrt(1 - Sqr(std::sin(th) / 1.52));
        std::vector<Layer> up(lossy.rbegin(), lossy.rend());
        const IncoherentStackResponse down = LayerStackIncoherent(Lambda, 1.0, CosIn(th), lossy, Complex(1.52, 0));
        const IncoherentStackResponse back = LayerStackIncoherent(Lambda, 1.52, cosSub, up, Complex(1, 0));
        EXPECT_LT(down.R() + down.T(), 1 - 1e-3);
        EXPECT_NEAR(down.Ts, back.Ts, 1e-13) << th;
        EXPECT_NEAR(down.Tp, back.Tp, 1e-13) << th;
        const StackResponse cd = LayerStackResponse(Lambda, 1.0, CosIn(th), lossy, Complex(1.52, 0));
        const StackResponse cb = LayerStackResponse(Lambda, 1.52, cosSub, up, Complex(1, 0));
        EXPECT_NEAR(cd.Ts, cb.Ts, 1e-13) << th;
    }
    for (double gap : {50e-9, 1e-6}) {
        const Layer air[] = {{1.0, gap}, {1.9, 2e-6}};
        const IncoherentStackResponse f = LayerStackIncoherent(Lambda, 1.5, CosIn(1.0), air, Complex(1.5, 0));
        EXPECT_LE(f.Rs, 1 + 1e-12) << gap;
        EXPECT_NEAR(f.Rs + f.Ts, 1, 1e-12) << gap;
        EXPECT_NEAR(f.Rp + f.Tp, 1, 1e-12) << gap;
    }
}

TEST(LayerStackShear, TwiceTheThicknessTimesTheTangentPerPropagatingLayer) {
    // Σ 2 d_j tanθ_j (theory §4.4) for the propagating layers; metallic and evanescent ones add 0.
    const double th = 0.6, s = std::sin(th);
    const Layer layers[] = {{1.5, 100e-9}, {{0.2, 3.0}, 10e-9}, {2.0, 40e-9}};
    const double expected = 2 * 100e-9 * s / std::sqrt(1.5 * 1.5 - s * s) + 2 * 40e-9 * s / std::sqrt(4 - s * s);
    EXPECT_NEAR(LayerStackShear(1.0, CosIn(th), layers), expected, 1e-20);
    EXPECT_EQ(LayerStackShear(1.0, CosIn(0), layers), 0);
    const Layer gap[] = {{1.0, 1e-6}};  // from glass past the critical angle: evanescent
    EXPECT_EQ(LayerStackShear(1.5, CosIn(1.0), gap), 0);
}

}  // namespace
}  // namespace phasor
