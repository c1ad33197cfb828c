// SPDX-License-Identifier: Apache-2.0
// The generalized ray (core/render/genray.h) against theory §1–§2: moments, minimum uncertainty, the S6.3
// free-space law, ABCD composition, thin lens / mirror, time reversal, the wave function ↔
// phase-space density (WDF) pair, the oblique cut's norm, and the Eq. 24 closed forms against
// direct quadrature of their defining integrals.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>

#include "core/render/genray.h"

namespace phasor {
namespace {

constexpr double Lambda = 550e-9;
const double K = 2 * Pi / Lambda;

// ∫_a^b f by composite Simpson with n (even) intervals.
double Simpson(const std::function<double(double)> &f, double a, double b, int n) {
    const double h = (b - a) / n;
    double s = f(a) + f(b);
    for (int i = 1; i < n; ++i) s += f(a + i * h) * (i % 2 ? 4 : 2);
    return s * h / 3;
}

GenRay MakeRay(double beta, double rho) {
    GenRay g;
    g.o = Vec3(0.1, -0.2, 0.3);
    g.d = Normalize(Vec3(0.2, 0.1, 1));
    g.k = K;
    g.beta2 = beta * beta;
    g.rho = rho;
    return g;
}

// Per-axis marginal of g in (x, κ): (1/π)·exp(−x²/β² − (βκ − ρx/β)²) (theory §1.2).
TEST(GenRay, MomentsAndMinimumUncertainty) {
    for (double rho : {0.0, 0.7, -2.5}) {
        const double beta = 3e-6;
        GenRay g = MakeRay(beta, rho);
        const double sr = std::sqrt(g.SigmaR2()), sk = std::sqrt(g.SigmaK2());
        // Moments by 2-D quadrature of the per-axis density over ±10σ.
        auto moment = [&](int px, int pk) {
            return Simpson(
                [&](double x) {
                    return Simpson(
                        [&](double kk) {
                            // The 4-D density factorises; integrate the other axis out (factor π).
                            double d = g.PhaseSpaceDensity(Vec2(x, 0), Vec2(kk, 0)) * Pi;
                            return d * std::pow(x, px) * std::pow(kk, pk);
                        },
                        -12 * sk, 12 * sk, 400);
                },
                -12 * sr, 12 * sr, 400);
        };
        const double m0 = moment(0, 0);
        EXPECT_NEAR(m0, 1.0, 1e-9);
        const double vr = moment(2, 0) / m0, vk = moment(0, 2) / m0, crk = moment(1, 1) / m0;
        EXPECT_NEAR(vr / (beta * beta / 2), 1, 1e-9) << "σ_r² = β²/2";
        EXPECT_NEAR(vk / ((1 + rho * rho) / (2 * beta * beta)), 1, 1e-9) << "σ_k² = (1+ρ²)/(2β²)";
        EXPECT_NEAR(crk, rho / 2, 1e-9);
        EXPECT_NEAR((vr * vk - crk * crk), 0.25, 1e-9) << "det Σ = ¼";
        GrCovariance c = g.Covariance();
        EXPECT_NEAR(c.Det(), 0.25, 1e-15);
    }
}

// The WDF (S3.16) of the wave function (theory §1.3) is the phase-space density g (§1.2), per
// axis: (1/2π)∫ψ*(x−y/2)ψ(x+y/2)e^{−iyκ}dy = (1/π)exp(−x²/β² − (βκ − ρx/β)²). This pins the sign
// of ρ (diverging for ρ > 0) and the normalisation together.
TEST(GenRay, WaveFunctionWignerIsPhaseSpaceDensity) {
    const double beta = 2e-6, rho = 1.3;
    GenRay g = MakeRay(beta, rho);
    const Frame f = g.TransverseFrame();
    // 1-D ψ along the transverse axis s: the 2-D ψ factorises, ψ₁(0) = (πβ²)^{-1/4}.
    auto psi1 = [&](double x) { return g.WaveFunction(g.o + f.s * x) / std::pow(Pi * beta * beta, -0.25); };
    for (double x : {0.0, 0.8e-6, -1.7e-6}) {
        for (double kappa : {0.0, 2e5, -4e5}) {
            auto re = [&](double y) {
                Complex v = std::conj(psi1(x - y / 2)) * psi1(x + y / 2) * std::exp(Complex(0, -y * kappa));
                return v.real();
            };
            const double w = Simpson(re, -20 * beta, 20 * beta, 4000) / (2 * Pi);
            const double expected = g.PhaseSpaceDensity(Vec2(x, 0), Vec2(kappa, 0)) * Pi;
            EXPECT_NEAR(w, expected, 1e-9 * (1 / Pi)) << "x " << x << " κ " << kappa;
        }
    }
}

// S6.3 (supplement) is reproduced exactly, by the closed form and by Σ ← TΣTᵀ.
TEST(GenRay, FreeSpaceUpdateEqualsS63) {
    for (double rho : {0.0, 0.4, -3.0}) {
        GenRay g = MakeRay(5e-6, rho);
        const double z = 0.37, zb = z / g.k, b2 = g.beta2;
        const double beta2S63 = b2 + zb * (2 * rho + zb * (1 + rho * rho) / b2);
        const double rhoS63 = rho + 2 * zb * (1 + rho * rho) / (2 * b2);
        GenRay a = g;
        a.Propagate(z);
        EXPECT_NEAR(a.beta2 / beta2S63, 1, 1e-14);
        EXPECT_NEAR(a.rho / rhoS63, 1, 1e-14);
        GenRay m = g;
        m.Apply(Abcd::FreeSpace(z, g.k));
        EXPECT_NEAR(m.beta2 / beta2S63, 1, 1e-13);
        EXPECT_NEAR(m.rho / rhoS63, 1, 1e-13);
        EXPECT_NEAR(a.SigmaK2() / g.SigmaK2(), 1, 1e-13) << "σ_k is invariant";
        EXPECT_NEAR(LengthSquared(a.o - (g.o + z * g.d)), 0, 1e-30);
        EXPECT_NEAR(a.Covariance().Det(), 0.25, 1e-12);
    }
}

TEST(GenRay, PropagationComposes) {
    GenRay g = MakeRay(4e-6, 0.3);
    GenRay a = g, b = g;
    a.Propagate(0.12);
    a.Propagate(1.9);
    b.Propagate(0.12 + 1.9);
    EXPECT_NEAR(a.beta2 / b.beta2, 1, 1e-12);
    EXPECT_NEAR(a.rho / b.rho, 1, 1e-12);
    // Backwards by the same distance returns to the start (ABCD with −z is the inverse). Over a
    // few Rayleigh ranges (z_R = kβ² ≈ 0.18 mm) so that β² does not lose digits to cancellation.
    a = g;
    a.Propagate(1e-4);
    a.Propagate(3e-4);
    a.Propagate(-4e-4);
    EXPECT_NEAR(a.beta2 / g.beta2, 1, 1e-10);
    EXPECT_NEAR(a.rho - g.rho, 0, 1e-10);
}

// Thin lens: β kept, ρ ← ρ − β²k/f; a collimated beam focuses to its waist at
// z_w = f/(1 + (f/z_R)²), z_R = kβ²; a mirror of radius R is a lens of f = R/2.
TEST(GenRay, ThinLensAndMirror) {
    const double beta = 0.5e-3, f = 0.2;
    GenRay g = MakeRay(beta, 0);
    GenRay l = g;
    l.Apply(Abcd::ThinLens(f, g.k));
    EXPECT_NEAR(l.beta2 / g.beta2, 1, 1e-15);
    EXPECT_NEAR(l.rho, -g.beta2 * g.k / f, 1e-9 * g.beta2 * g.k / f);
    const double zR = g.k * g.beta2;
    const double zw = f / (1 + Sqr(f / zR));
    l.Propagate(zw);
    EXPECT_NEAR(l.rho, 0, 1e-9);
    // Waist radius²: β₀²/(1 + (z_R/f)²).
    EXPECT_NEAR(l.beta2 / (g.beta2 / (1 + Sqr(zR / f))), 1, 1e-9);
    GenRay m = g;
    m.Apply(Abcd::CurvedMirror(2 * f, g.k));
    EXPECT_NEAR(m.rho, -g.beta2 * g.k / f, 1e-9 * g.beta2 * g.k / f);
    // Compositions are symplectic: det T = 1 keeps det Σ = ¼.
    Abcd t =
        Abcd::FreeSpace(0.3, g.k) * Abcd::CurvedInterface(0.05, g.k, 1.5 * g.k) * Abcd::ThinLens(-0.1, g.k);
    EXPECT_NEAR(t.Det(), 1, 1e-12);
    g.Apply(t);
    EXPECT_NEAR(g.Covariance().Det(), 0.25, 1e-9);
}

TEST(GenRay, TimeReversalIsAnInvolution) {
    GenRay g = MakeRay(3e-6, 0.8);
    GenRay r = g.TimeReversed();
    EXPECT_EQ(r.d, -g.d);
    EXPECT_EQ(r.rho, -g.rho);
    GenRay rr = r.TimeReversed();
    EXPECT_EQ(rr.o, g.o);
    EXPECT_EQ(rr.d, g.d);
    EXPECT_EQ(rr.beta2, g.beta2);
    EXPECT_EQ(rr.rho, g.rho);
    // The physical field is the complex conjugate (D3), and a reversed GR propagated back by z
    // undoes the forward propagation's curvature: ρ(−z of the reverse) = −ρ(z).
    const Vec3 x = g.o + Vec3(1e-6, -2e-6, 0.5e-6);
    Complex a = g.WaveFunction(x), b = r.WaveFunction(x);
    EXPECT_NEAR(std::abs(b - std::conj(a)), 0, 1e-12 * std::abs(a));
    GenRay fwd = g, bwd = r;
    fwd.Propagate(0.4);
    bwd.Propagate(-0.4);
    EXPECT_NEAR(bwd.rho, -fwd.rho, 1e-9 * std::abs(fwd.rho));
    EXPECT_NEAR(bwd.beta2 / fwd.beta2, 1, 1e-12);
}

// The oblique cut has unit norm on the plane (theory §6.3 step 3), for any tilt and ρ.
TEST(GenRay, ObliqueCutIsUnitNorm) {
    const double beta = 2e-6;
    for (double tiltDeg : {0.0, 30.0, 60.0}) {
        GenRay g = MakeRay(beta, 0.9);
        const Frame f = g.TransverseFrame();
        const double th = Radians(tiltDeg);
        const Vec3 n = Normalize(f.n * std::cos(th) + f.s * std::sin(th));
        const Frame pf = Frame::FromNormal(n);
        const double reach = 8 * beta / std::cos(th);
        double norm = Simpson(
            [&](double u) {
                return Simpson([&](double v) { return std::norm(g.OnPlane(g.o + pf.s * u + pf.t * v, n)); },
                               -reach, reach, 600);
            },
            -reach, reach, 600);
        EXPECT_NEAR(norm, 1, 1e-8) << tiltDeg << " deg";
    }
}

// Plane wave (item 2): D4's sensor-plane integral ∫d²κ M = E·cosθ_s·(1 − e^{−β²k²}) by quadrature
// in polar coordinates about the source direction.
TEST(GenRayMeasure, PlaneWaveSensorIntegral) {
    const double E = 2.5;
    for (double thetaDeg : {0.0, 30.0}) {
        // At normal incidence a small βk makes the tail term visible (the formula is exact there);
        // at 30° the cap of directions around s leaves the hemisphere unless βk ≫ 1.
        const double beta = thetaDeg == 0 ? 0.25 * Lambda : 1.5 * Lambda;
        const double th = Radians(thetaDeg);
        const Vec3 n(0, 0, 1);
        const Vec3 s(std::sin(th), 0, -std::cos(th));  // light travels towards the plane
        // Integrate over physical GR directions d (= −tracing) on the sensor hemisphere, d·n < 0,
        // with d²κ = k² cosθ dω; parameterise d by the angle γ from s and azimuth φ.
        const Frame fs = Frame::FromNormal(s);
        auto integrand = [&](double gamma, double phi) {
            Vec3 d = fs.ToWorld(
                Vec3(std::sin(gamma) * std::cos(phi), std::sin(gamma) * std::sin(phi), std::cos(gamma)));
            if (Dot(d, n) >= 0) return 0.0;
            GenRay g{Vec3(), d, K, beta * beta, 0};
            return MeasurePlaneWave(g, s, E) * K * K * std::abs(Dot(d, n)) * std::sin(gamma);
        };
        double total = Simpson(
            [&](double gamma) {
                return Simpson([&](double phi) { return integrand(gamma, phi); }, 0, 2 * Pi, 256);
            },
            0, Pi / 2, 4000);
        const double expected = E * std::cos(th) * (1 - std::exp(-beta * beta * K * K));
        EXPECT_NEAR(total / expected, 1, 1e-7) << thetaDeg << " deg";
    }
}

// Point source (item 5): ∫d²k⊥ M over the GR's own transverse wavevectors is I/R² for any
// curvature, and M peaks where ρ matches the spherical wave (ρ = β²k/R).
TEST(GenRayMeasure, PointSourceIntegralAndCurvatureMatch) {
    const double I = 3, R = 0.01, beta = 20e-6;
    const Vec3 p(0, 0, 0);
    for (double rho : {0.0, beta * beta * K / R, -5.0}) {
        auto m = [&](double kx, double ky) {
            // Tilt the GR so that its transverse wavevector relative to the axis through the
            // source is (kx, ky) exactly: direction cosines (kx/k, ky/k).
            Vec3 d(kx / K, ky / K, SafeSqrt(1 - Sqr(kx / K) - Sqr(ky / K)));
            GenRay g{Vec3(0, 0, R), d, K, beta * beta, rho};
            return MeasurePointSource(g, p, I);
        };
        const double w =
            8 * std::sqrt(0.5 * (1 + Sqr(beta * K / R - rho / beta) * beta * beta) / (beta * beta));
        double total = Simpson(
            [&](double kx) { return Simpson([&](double ky) { return m(kx, ky); }, -w, w, 300); }, -w, w, 300);
        EXPECT_NEAR(total * R * R / I, 1, 1e-6) << "ρ " << rho;
    }
    GenRay matched{Vec3(0, 0, R), Vec3(0, 0, 1), K, beta * beta, beta * beta * K / R};
    GenRay flat = matched;
    flat.rho = 0;
    EXPECT_GT(MeasurePointSource(matched, p, I), MeasurePointSource(flat, p, I));
    // Matched: a = 0 ⇒ M = (I/R²)·β²/π.
    EXPECT_NEAR(MeasurePointSource(matched, p, I) / (I / (R * R) * beta * beta / Pi), 1, 1e-12);
}

// The one-test early exit of a distant disc (DistantDiscOutOfReach) claims "0" only where every
// wavelength the GR measures reads exactly 0, and does claim it once the disc is beyond the reach
// of every measured window (so it saves the work it is there for): a tilted GR, windows of
// different widths per slot (the widest not the last), every slot or some (SpectralGenRay::measured).
TEST(GenRayMeasure, DistantDiscOutOfReachOnlyWhereEveryWavelengthReadsZero) {
    const double lambdas[4] = {400e-9, 480e-9, 590e-9, 700e-9}, footprint[4] = {1.0, 0.35, 2.0, 0.7};
    const Vec3 d = Normalize(Vec3(0.3, -0.5, 0.8));
    const Frame f = Frame::FromNormal(d);
    int claimed = 0;
    for (const double beta : {0.05e-3, 0.3e-3, 2e-3})
        for (const double rho : {0.0, 0.7, -3.0})
            for (const double alpha : {1e-4, 4.65e-3, 0.1})
                for (const unsigned mask : {~0u, 1u, 0b0100u, 0b1010u}) {
                    SpectralGenRay g;
                    g.d = d;
                    g.count = 4;
                    g.measured = mask;
                    double sigmaMax = 0;  // over the measured slots
                    for (int i = 0; i < 4; ++i) {
                        const std::size_t k = std::size_t(i);
                        g.k[k] = 2 * Pi / lambdas[i];
                        g.beta2[k] = Sqr(beta * footprint[i]);
                        g.rho[k] = rho;
                        if (g.Measures(i)) sigmaMax = std::max(sigmaMax, std::sqrt(g.At(i).AngularVariance()));
                    }
                    const double sinAlpha = std::sin(alpha);
                    // Offsets across the threshold sin(alpha) + 11·σ_max, finely near it.
                    for (double x = -3; x <= 3; x += 0.01) {
                        const double sinTheta = sinAlpha + (11 + x) * sigmaMax;
                        if (!(sinTheta < 1)) continue;
                        const Vec3 s = d * std::sqrt(1 - sinTheta * sinTheta) + f.s * sinTheta;
                        if (DistantDiscOutOfReach(g, s, sinAlpha)) {
                            ++claimed;
                            for (int i = 0; i < 4; ++i) {
                                if (!g.Measures(i)) continue;
                                ASSERT_EQ(MeasureDistantDisc(g.At(i), s, 1.0, sinAlpha), 0.0)
                                    << "beta " << beta << ", rho " << rho << ", alpha " << alpha << ", mask " << mask
                                    << ", x " << x << ", slot " << i;
                            }
                        } else {
                            EXPECT_LT(x, 0.01) << "beyond every measured window's reach but not claimed: beta " << beta
                                               << ", mask " << mask << ", x " << x;
                        }
                    }
                }
    EXPECT_GT(claimed, 5000);
    // A plane wave (sinα = 0) is never exactly 0, however far: never claimed.
    SpectralGenRay g;
    g.d = d;
    g.k[0] = K;
    g.beta2[0] = Sqr(0.3e-3);
    EXPECT_FALSE(DistantDiscOutOfReach(g, d * std::cos(0.5) + f.s * std::sin(0.5), 0.0));
}

// Distant sources reduce to the plane wave; the disc's interior reads L/k² with L = E/(π sin²α).
TEST(GenRayMeasure, DistantSourcesLimits) {
    const double beta = 0.3e-3, E = 1.7;
    GenRay g{Vec3(), Vec3(0, 0, 1), K, beta * beta, 0.4};
    const Vec3 s = Normalize(Vec3(1e-4, -0.5e-4, 1));
    EXPECT_NEAR(MeasureDistantGaussian(g, s, E, 0) / MeasurePlaneWave(g, s, E), 1, 1e-12);
    EXPECT_NEAR(MeasureDistantDisc(g, s, E, 0) / MeasurePlaneWave(g, s, E), 1, 1e-12);
    // A disc much smaller than the GR's angular spread looks like the Gaussian of Ω = α²/4 (D5).
    const double sigTheta = std::sqrt(g.AngularVariance());
    const double alphaSmall = 1e-3 * sigTheta;
    EXPECT_NEAR(MeasureDistantDisc(g, s, E, std::sin(alphaSmall)) /
                    MeasureDistantGaussian(g, s, E, alphaSmall * alphaSmall / 4),
                1, 1e-9);
    // A disc much larger than the spread: interior = E/(π k² sin²α) exactly (to the tail).
    const double alpha = 4.65e-3;
    EXPECT_NEAR(MeasureDistantDisc(g, s, E, std::sin(alpha)) * K * K / (E / (Pi * Sqr(std::sin(alpha)))), 1, 1e-12);
}

// Gaussian beam (item 1): a GR against a beam of its own state gives the Moyal self-overlap
// (2π)^{-2} (pure state); a very wide beam becomes a plane wave of irradiance 2P/(πw₀²).
TEST(GenRayMeasure, GaussianBeamOverlaps) {
    GenRay g{Vec3(0.01, 0, 0.2), Vec3(0, 0, 1), K, Sqr(40e-6), 0.6};
    EXPECT_NEAR(MeasureGaussianBeam(g, g, 1.0) * 4 * Pi * Pi, 1, 1e-12);
    const double w0 = 0.2, P = 2;
    GenRay wide{Vec3(0.01, 0, 0), Vec3(0, 0, 1), K, w0 * w0 / 2, 0};
    const double E = 2 * P / (Pi * w0 * w0) * std::exp(-2 * Sqr(0.0) / (w0 * w0));
    GenRay gr = g;
    gr.rho = 0;
    const Vec3 s(0, 0, 1);
    EXPECT_NEAR(MeasureGaussianBeam(gr, wide, P) / MeasurePlaneWave(gr, s, E), 1, 1e-6);
}

TEST(GenRayMeasure, DiscGaussianProbability) {
    for (double c : {0.1, 1.0, 3.0, 7.0})
        EXPECT_NEAR(DiscGaussianProbability(0, c, 1), 1 - std::exp(-0.5 * c * c), 1e-13);
    // Scale invariance, monotonicity, limits.
    EXPECT_NEAR(DiscGaussianProbability(3e-3, 4e-3, 1e-3), DiscGaussianProbability(3, 4, 1), 1e-13);
    EXPECT_LT(DiscGaussianProbability(5, 4, 1), DiscGaussianProbability(4, 4, 1));
    EXPECT_EQ(DiscGaussianProbability(0, 100, 1), 1);
    EXPECT_EQ(DiscGaussianProbability(100, 1, 1), 0);
    // A huge disc with the centre on its rim: half the mass (flat edge limit).
    EXPECT_NEAR(DiscGaussianProbability(1e4, 1e4, 1), 0.5, 1e-4);
    // Against a Monte Carlo-free 2-D quadrature at an offset.
    const double t = 1.3, c = 2.1;
    // ∫ over x of N(x; t, 1)·P(|y| ≤ √(c² − x²)), with x = c·sinφ removing the square-root ends.
    double q = Simpson(
        [&](double phi) {
            const double x = c * std::sin(phi), h = c * std::cos(phi);
            return std::exp(-0.5 * Sqr(x - t)) / std::sqrt(2 * Pi) * std::erf(h / std::sqrt(2.0)) * h;
        },
        -Pi / 2, Pi / 2, 2000);
    EXPECT_NEAR(DiscGaussianProbability(t, c, 1), q, 1e-9);
}

}  // namespace
}  // namespace phasor
