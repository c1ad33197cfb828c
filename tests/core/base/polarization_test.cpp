// SPDX-License-Identifier: Apache-2.0
// Jones / Stokes / Mueller algebra (core/polarization.h) against theory §4.1 and §4.9.
#include <gtest/gtest.h>

#include <random>

#include "core/polarization.h"

namespace phasor {
namespace {

// All quantities here are O(1) products of a few doubles: 1e-14 is ~50 ulp of headroom for
// the 4×4 products and the trace formula, far below any convention error (which is O(1)).
constexpr double Tol = 1e-14;

void ExpectMuellerNear(const Mueller &a, const Mueller &b, double tol, const char *what) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) EXPECT_NEAR(a.m[i][j], b.m[i][j], tol) << what << " [" << i << "][" << j << "]";
}

// The Fresnel r_s, r_p of theory §4.1 written out here (not via fresnel.h: core must not depend on
// materials) for real n1 and complex n2.
std::pair<Complex, Complex> Fresnel(double cosI, double n1, Complex n2) {
    const Complex cosT = std::sqrt(1.0 - Sqr(n1 / n2) * (1 - cosI * cosI));
    const Complex rs = (n1 * cosI - n2 * cosT) / (n1 * cosI + n2 * cosT);
    const Complex rp = (n2 * cosI - n1 * cosT) / (n2 * cosI + n1 * cosT);
    return {rs, rp};
}

Mueller TheoryFresnelMueller(Complex rs, Complex rp) {
    // theory §4.1: [[A,B,0,0],[B,A,0,0],[0,0,C,S],[0,0,−S,C]]
    const double A = 0.5 * (std::norm(rs) + std::norm(rp)), B = 0.5 * (std::norm(rs) - std::norm(rp));
    const Complex x = rs * std::conj(rp);
    Mueller m;
    m.m[0][0] = m.m[1][1] = A;
    m.m[0][1] = m.m[1][0] = B;
    m.m[2][2] = m.m[3][3] = x.real();
    m.m[2][3] = x.imag();
    m.m[3][2] = -x.imag();
    return m;
}

Jones RandomJones(std::mt19937 &rng) {
    std::normal_distribution<double> g;
    Jones j;
    for (auto &row : j.m)
        for (auto &e : row) e = Complex(g(rng), g(rng));
    return j;
}

TEST(Polarization, FresnelMuellerOfDielectricAndMetalMatchesTheory) {
    struct Case {
        const char *what;
        double n1;
        Complex n2;
    } cases[] = {{"glass", 1.0, {1.5, 0}}, {"glass from inside (TIR at large angles)", 1.5, {1.0, 0}},
                 {"gold at 550 nm", 1.0, {0.43, 2.455}}, {"aluminium", 1.0, {0.96, 6.69}}};
    for (const Case &c : cases)
        for (double cosI : {1.0, 0.8, 0.5, 0.2, 0.05}) {
            auto [rs, rp] = Fresnel(cosI, c.n1, c.n2);
            SCOPED_TRACE(std::string(c.what) + " cosI = " + std::to_string(cosI));
            ExpectMuellerNear(Mueller::FromJones(Jones::Diagonal(rs, rp)), TheoryFresnelMueller(rs, rp), Tol,
                              c.what);
        }
    // The metal case has S ≠ 0 (a retarder), so the sign of S3 is tested, not only |S|.
    auto [rs, rp] = Fresnel(0.5, 1.0, {0.43, 2.455});
    EXPECT_GT(std::abs((rs * std::conj(rp)).imag()), 0.05);
}

TEST(Polarization, FromJonesIsAHomomorphism) {
    std::mt19937 rng(7);
    for (int t = 0; t < 50; ++t) {
        const Jones a = RandomJones(rng), b = RandomJones(rng);
        // Entries are O(10) for products of normal(0,1) matrices: scale the tolerance.
        ExpectMuellerNear(Mueller::FromJones(a * b), Mueller::FromJones(a) * Mueller::FromJones(b), 1e-12,
                          "FromJones(A·B)");
    }
    ExpectMuellerNear(Mueller::FromJones(Jones::Identity()), Mueller::Identity(), 0, "identity");
    // A scalar factor c scales intensities by |c|².
    const Jones j = RandomJones(rng);
    ExpectMuellerNear(Mueller::FromJones(j * Complex(0, 2)), Mueller::FromJones(j) * 4, 1e-13, "scalar");
}

TEST(Polarization, StokesOfAFieldIsTheMuellerActionOnIt) {
    std::mt19937 rng(3);
    std::normal_distribution<double> g;
    for (int t = 0; t < 20; ++t) {
        const Jones j = RandomJones(rng);
        const Complex es(g(rng), g(rng)), ep(g(rng), g(rng));
        const Stokes out = StokesFromField(j.m[0][0] * es + j.m[0][1] * ep, j.m[1][0] * es + j.m[1][1] * ep);
        const Stokes viaMueller = Mueller::FromJones(j) * StokesFromField(es, ep);
        for (int i = 0; i < 4; ++i) EXPECT_NEAR(out[i], viaMueller[i], 1e-12 * (1 + std::abs(out[i])));
    }
    // Convention: s-polarised light has S1 = +S0.
    const Stokes s = StokesFromField(1, 0);
    EXPECT_EQ(s[1], 1);
}

TEST(Polarization, RotationsCompose) {
    for (double a : {0.0, 0.3, -1.1, 2.0})
        for (double b : {0.0, 0.7, 1.9, -0.4})
            ExpectMuellerNear(Mueller::Rotation(a) * Mueller::Rotation(b), Mueller::Rotation(a + b), Tol, "R(a)R(b)");
    // cos 2π, sin 2π are exact to ~2e-16.
    ExpectMuellerNear(Mueller::Rotation(Pi), Mueller::Identity(), Tol, "R(pi)");
    ExpectMuellerNear(Mueller::Rotation(0), Mueller::Identity(), 0, "R(0)");
    // R(θ) takes linear polarisation along s to linear polarisation at θ: (1, cos2θ, sin2θ, 0),
    // the Stokes vector of the field (cosθ, sinθ).
    const double th = 0.4;
    const Stokes rotated = Mueller::Rotation(th) * Stokes{1, 1, 0, 0};
    const Stokes direct = StokesFromField(std::cos(th), std::sin(th));
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(rotated[i], direct[i], Tol);
}

TEST(Polarization, RotatedLinearPolariserObeysMalusLaw) {
    const Mueller polariser = Mueller::FromJones(Jones::Diagonal(1, 0));  // transmits s
    const Stokes sPolarised{1, 1, 0, 0};
    for (double th : {0.0, 0.2, Pi / 4, 1.0, Pi / 2, 2.5}) {
        const Mueller rotated = Mueller::Rotation(th) * polariser * Mueller::Rotation(-th);
        EXPECT_NEAR((rotated * sPolarised)[0], Sqr(std::cos(th)), Tol) << "theta = " << th;
        // Unpolarised light loses half whatever the angle.
        EXPECT_NEAR((rotated * Stokes{1, 0, 0, 0})[0], 0.5, Tol);
    }
}

TEST(Polarization, PhysicalMuellerMatricesKeepDegreeOfPolarisationAtMostOne) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int t = 0; t < 200; ++t) {
        // A physical Mueller matrix: a non-negative mixture of non-depolarising ones and a depolariser.
        Mueller m = Mueller::FromJones(RandomJones(rng)) * 0.3 + Mueller::FromJones(RandomJones(rng)) * 0.7;
        if (t % 2) m = m + Mueller::Depolarizer(0.5);
        // A random physical Stokes vector (DOP ≤ 1).
        Stokes s{1, u(rng), u(rng), u(rng)};
        const double p = std::sqrt(s[1] * s[1] + s[2] * s[2] + s[3] * s[3]);
        if (p > 1) s = {1, s[1] / p, s[2] / p, s[3] / p};
        const Stokes out = m * s;
        EXPECT_GE(out[0], 0);
        EXPECT_LE(DegreeOfPolarization(out), 1 + 1e-12);
        // Non-depolarising (one Jones matrix) on fully polarised light stays fully polarised.
        const Stokes full = Mueller::FromJones(RandomJones(rng)) * StokesFromField({u(rng), u(rng)}, {u(rng), u(rng)});
        EXPECT_NEAR(DegreeOfPolarization(full), 1, 1e-12);
    }
    EXPECT_EQ(DegreeOfPolarization((Mueller::Depolarizer(0.3) * Stokes{1, 1, 0, 0})), 0);
    EXPECT_EQ((Mueller::Depolarizer(0.3) * Stokes{2, 1, 0, 0})[0], 0.6);
}


TEST(Mueller, FromDiagonalSumsIsTheSumOfTheTermsMuellerMatrices) {
    // One term: FromJones(Diagonal(a, b)). Several: the sum of their Mueller matrices (an
    // incoherent sum), which depolarises partially.
    const Complex a[] = {{0.3, -0.4}, {-0.2, 0.1}, {0.05, 0.6}}, b[] = {{0.7, 0.2}, {0.1, -0.3}, {-0.4, 0.0}};
    ExpectMuellerNear(Mueller::FromDiagonalSums(std::norm(a[0]), std::norm(b[0]), a[0] * std::conj(b[0])),
                      Mueller::FromJones(Jones::Diagonal(a[0], b[0])), Tol, "one term");
    double ss = 0, pp = 0;
    Complex sp;
    Mueller sum = Mueller::Zero();
    for (int k = 0; k < 3; ++k) {
        ss += std::norm(a[k]);
        pp += std::norm(b[k]);
        sp += a[k] * std::conj(b[k]);
        sum = sum + Mueller::FromJones(Jones::Diagonal(a[k], b[k]));
    }
    const Mueller m = Mueller::FromDiagonalSums(ss, pp, sp);
    ExpectMuellerNear(m, sum, Tol, "three terms");
    const Stokes out = m * Stokes{1, 0, 1, 0};  // 45° linear light in
    EXPECT_LT(DegreeOfPolarization(out), 1 - 1e-3);
}

}  // namespace
}  // namespace phasor
