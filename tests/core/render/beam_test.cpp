// SPDX-License-Identifier: Apache-2.0
// The PLT beam of sample-solve (core/render/beam.h) against an independent reference: the
// electric field as a complex 3-D vector ⊥ the direction of travel, whose Stokes vector in any
// frame is computed from its components (core/polarization.h's StokesFromField), and which an
// interface reflects by decomposing it on ŝ = n̂ × k̂ and p̂ = k̂ × ŝ itself. Tolerances: 1e-12
// (double-precision round-off of a handful of trigonometric operations on unit quantities).
#include <gtest/gtest.h>

#include <random>

#include "core/render/beam.h"

namespace phasor {
namespace {

using CVec3 = std::array<Complex, 3>;

CVec3 Scale(const Vec3 &v, Complex a) { return {v.x * a, v.y * a, v.z * a}; }
CVec3 Add(const CVec3 &a, const CVec3 &b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Complex Dot(const CVec3 &e, const Vec3 &v) { return e[0] * v.x + e[1] * v.y + e[2] * v.z; }

/// The Stokes vector of field e in the basis (x, d × x).
Stokes StokesIn(const CVec3 &e, const Vec3 &x, const Vec3 &d) {
    return StokesFromField(Dot(e, x), Dot(e, Cross(d, x)));
}

Vec3 RandomUnit(std::mt19937_64 &rng) {
    std::normal_distribution<double> n;
    return Normalize(Vec3(n(rng), n(rng), n(rng)));
}
Complex RandomComplex(std::mt19937_64 &rng) {
    std::normal_distribution<double> n;
    return Complex(n(rng), n(rng));
}

void ExpectStokesNear(const Stokes &a, const Stokes &b, double tol, const std::string &what) {
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(a[std::size_t(c)], b[std::size_t(c)], tol) << what << ", S" << c;
}

// A beam's Stokes vector re-expressed in another frame equals the field's Stokes vector computed in
// that frame directly; rotating x → x' → x'' equals x → x'' (rotations compose).
TEST(PltBeam, FrameRotationMatchesTheFieldAndComposes) {
    std::mt19937_64 rng(7);
    for (int trial = 0; trial < 50; ++trial) {
        const Vec3 d = RandomUnit(rng);
        const Vec3 x0 = PerpendicularTo(d, RandomUnit(rng)), x1 = PerpendicularTo(d, RandomUnit(rng)),
                   x2 = PerpendicularTo(d, RandomUnit(rng));
        const CVec3 e = Add(Scale(x0, RandomComplex(rng)), Scale(Cross(d, x0), RandomComplex(rng)));
        PltBeam b = PltBeam::Source(d, 1);
        b.t = x0;
        b.S[0] = StokesIn(e, x0, d);
        b.RotateFrame(x1);
        ExpectStokesNear(b.S[0], StokesIn(e, x1, d), 1e-12 * b.S[0][0], "x0 → x1");
        b.RotateFrame(x2);
        ExpectStokesNear(b.S[0], StokesIn(e, x2, d), 1e-12 * b.S[0][0], "x0 → x1 → x2");
        ExpectStokesNear(RotateStokesFrame(StokesIn(e, x0, d), x0, x2, d), StokesIn(e, x2, d), 1e-12 * b.S[0][0],
                         "x0 → x2");
        // Measure re-expresses too.
        ExpectStokesNear(b.Measure(0, x0, std::nullopt), StokesIn(e, x0, d), 1e-12 * b.S[0][0], "Measure");
    }
}

// Malus: linear light at angle a through a polariser at θ keeps cos²(a − θ) of its intensity and
// leaves linear at θ; the polariser is idempotent.
TEST(PltBeam, LinearPolarizerObeysMalusLaw) {
    for (double a : {0.0, 0.3, 1.1, -0.7})
        for (double th : {0.0, 0.25, Pi / 4, 2.0, -1.0}) {
            const Stokes in{1, std::cos(2 * a), std::sin(2 * a), 0};
            const Stokes out = LinearPolarizer(th) * in;
            EXPECT_NEAR(out[0], Sqr(std::cos(a - th)), 1e-14) << a << " " << th;
            EXPECT_NEAR(out[1], out[0] * std::cos(2 * th), 1e-14);
            EXPECT_NEAR(out[2], out[0] * std::sin(2 * th), 1e-14);
            EXPECT_NEAR(out[3], 0, 1e-14);
            const Stokes twice = LinearPolarizer(th) * out;
            ExpectStokesNear(twice, out, 1e-14, "idempotent");
        }
    // Unpolarised light: half.
    EXPECT_NEAR((LinearPolarizer(0.4) * Stokes{1, 0, 0, 0})[0], 0.5, 1e-15);
}

// Reciprocity: the Mueller matrix of D·Jᵀ·D is P·Mᵀ·P (P = diag(1, 1, −1, 1)) for any Jones matrix;
// a diagonal (interface) response is its own reverse.
TEST(PltBeam, ReciprocalMuellerIsTheTransposedJones) {
    std::mt19937_64 rng(11);
    for (int trial = 0; trial < 20; ++trial) {
        Jones j;
        for (auto &row : j.m)
            for (Complex &c : row) c = RandomComplex(rng);
        Jones rev;  // D·Jᵀ·D
        rev.m[0][0] = j.m[0][0];
        rev.m[1][1] = j.m[1][1];
        rev.m[0][1] = -j.m[1][0];
        rev.m[1][0] = -j.m[0][1];
        const Mueller a = ReciprocalMueller(Mueller::FromJones(j)), b = Mueller::FromJones(rev);
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) EXPECT_NEAR(a.m[r][c], b.m[r][c], 1e-12 * (1 + std::abs(b.m[0][0])));
    }
    const Mueller f = Mueller::FromJones(Jones::Diagonal(Complex(0.3, -0.8), Complex(-0.2, 0.5)));
    const Mueller g = ReciprocalMueller(f);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) EXPECT_NEAR(g.m[r][c], f.m[r][c], 1e-15);
}

// Reflection of an arbitrary field by an interface with complex r_s, r_p (a metal): the beam's
// Interact (frame into ŝ, the Mueller matrix, out along the reflected direction) gives the Stokes
// vector of the reflected field computed component by component, for any frames and either sign
// of ŝ. A linear state at 45° to the plane of incidence leaves elliptical, with
// S3/S0 = −Im(r_s r_p*)/A', A' = (|r_s|² + |r_p|²)/2 (the Fresnel phases).
TEST(PltBeam, InterfaceReflectionMatchesTheFieldReference) {
    std::mt19937_64 rng(3);
    const Complex rs(-0.83, -0.41), rp(0.61, 0.52);  // a metal's r_s, r_p (an oblique gold-like pair)
    const Mueller m = Mueller::FromJones(Jones::Diagonal(rs, rp));
    std::array<Mueller, NumWavelengths> ms;
    ms.fill(m);
    for (int trial = 0; trial < 30; ++trial) {
        const Vec3 n = RandomUnit(rng);
        Vec3 kIn = RandomUnit(rng);
        if (Dot(kIn, n) > 0) kIn = -kIn;  // travelling into the surface
        const Vec3 kOut = kIn - n * (2 * Dot(kIn, n));
        const Vec3 s = Normalize(Cross(n, kIn)), pIn = Cross(kIn, s), pOut = Cross(kOut, s);
        const Vec3 t0 = PerpendicularTo(kIn, RandomUnit(rng));
        const CVec3 e = Add(Scale(t0, RandomComplex(rng)), Scale(Cross(kIn, t0), RandomComplex(rng)));
        const CVec3 eOut = Add(Scale(s, rs * Dot(e, s)), Scale(pOut, rp * Dot(e, pIn)));
        for (double sign : {1.0, -1.0}) {
            PltBeam b = PltBeam::Source(kIn, 1);
            b.t = t0;
            b.S[0] = StokesIn(e, t0, kIn);
            b.Interact(s * sign, kOut, ms);
            const Vec3 x = PerpendicularTo(kOut, RandomUnit(rng));
            ExpectStokesNear(b.Measure(0, x, std::nullopt), StokesIn(eOut, x, kOut), 1e-12 * b.S[0][0], "reflection");
        }
    }
    // Linear at 45° → elliptical by the Fresnel phases.
    const Vec3 n(0, 0, 1), kIn = Normalize(Vec3(1, 0, -1)), kOut = Normalize(Vec3(1, 0, 1));
    const Vec3 s = Normalize(Cross(n, kIn));
    PltBeam b = PltBeam::Source(kIn, 1);
    b.t = s;
    b.S[0] = Stokes{1, 0, 1, 0};
    b.Interact(s, kOut, ms);
    const double aOut = 0.5 * (std::norm(rs) + std::norm(rp));
    EXPECT_NEAR(b.S[0][0], aOut, 1e-14);
    EXPECT_NEAR(b.S[0][3] / b.S[0][0], -(rs * std::conj(rp)).imag() / aOut, 1e-14);
    EXPECT_NEAR(b.S[0][2] / b.S[0][0], (rs * std::conj(rp)).real() / aOut, 1e-14);
}

// A source is unpolarised at every wavelength; the distance accumulates.
TEST(PltBeam, SourceIsUnpolarisedAndPropagationCountsTheDistance) {
    PltBeam c = PltBeam::Source(Vec3(1, 0, 0), 4);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(DegreeOfPolarization(c.S[std::size_t(i)]), 0.0);
    c.Propagate(2.5);
    c.Propagate(0.5);
    EXPECT_DOUBLE_EQ(c.dist, 3.0);
}

}  // namespace
}  // namespace phasor
