// SPDX-License-Identifier: Apache-2.0
// phasor — generalized-ray maths (genray.h; theory §1–§2).
#include "core/render/genray.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/numerics/rice.h"

namespace phasor {

GrCovariance GrCovariance::Transformed(const Abcd &t) const {
    // Σ' = T Σ Tᵀ for T = [[a, b], [c, d]] (theory §1.6, S3.36).
    const double rrN = t.a * t.a * rr + 2 * t.a * t.b * rk + t.b * t.b * kk;
    const double rkN = t.a * t.c * rr + (t.a * t.d + t.b * t.c) * rk + t.b * t.d * kk;
    const double kkN = t.c * t.c * rr + 2 * t.c * t.d * rk + t.d * t.d * kk;
    return {rrN, rkN, kkN};
}

void GenRay::Propagate(double z) {
    // Supplement S6.3 in closed form; identical to Apply(Abcd::FreeSpace(z, k)) (theory §1.6).
    const double zb = z / k;
    const double q = (1 + rho * rho) / beta2;
    beta2 = beta2 + zb * (2 * rho + zb * q);
    rho = rho + zb * q;
    o += z * d;
}

void GenRay::Apply(const Abcd &t) {
    GrCovariance s = Covariance().Transformed(t);
    beta2 = s.Beta2();
    rho = s.Rho();
}

Complex GenRay::WaveFunction(const Vec3 &x) const {
    // Theory §1.3: ψ = (πβ²)^{-1/2} e^{ik d·Δ} e^{−(1−iρ)|Δ⊥|²/(2β²)}.
    const Vec3 delta = x - o;
    const double along = Dot(delta, d);
    const double perp2 = std::max(0.0, LengthSquared(delta) - along * along);
    const Complex expo(-perp2 / (2 * beta2), rho * perp2 / (2 * beta2) + k * along);
    return std::exp(expo) / std::sqrt(Pi * beta2);
}

Complex GenRay::OnPlane(const Vec3 &x, const Vec3 &n) const {
    // Theory §6.3 step 3: the oblique cut keeps the transverse profile at the projected offset
    // and gains √cosθ, which makes the plane-to-plane norm 1.
    const double c = std::abs(Dot(d, n));
    if (c == 0) return 0;
    return std::sqrt(c) * WaveFunction(x);
}

double GenRay::PhaseSpaceDensity(const Vec2 &dr, const Vec2 &dk) const {
    // Theory §1.2: g = π⁻² exp(−|Δr|²/β² − |βΔk − (ρ/β)Δr|²).
    const double beta = std::sqrt(beta2);
    const Vec2 m = dk * beta - dr * (rho / beta);
    return std::exp(-LengthSquared(dr) / beta2 - LengthSquared(m)) / (Pi * Pi);
}

void SpectralGenRay::Propagate(double z) {
    for (int i = 0; i < count; ++i) {
        GenRay g = At(i);
        g.Propagate(z);
        beta2[i] = g.beta2;
        rho[i] = g.rho;
    }
    o += z * d;
}

void SpectralGenRay::Redirect(const Vec3 &newDirection, double etaRatio) {
    d = newDirection;
    pixel.valid = false;
    for (int i = 0; i < count; ++i) k[i] *= etaRatio;
}

SpectralGenRay SpectralGenRay::TimeReversed() const {
    SpectralGenRay r = *this;
    r.d = -d;
    for (int i = 0; i < count; ++i) r.rho[i] = -rho[i];
    return r;
}

// ---- Closed-form measurements -----------------------------------------------------------------

Vec2 TransverseWavevector(const GenRay &g, const Vec3 &s) {
    if (Dot(s, g.d) <= 0) return {Infinity, Infinity};
    const Frame f = g.TransverseFrame();
    return Vec2(Dot(s, f.s), Dot(s, f.t)) * g.k;
}

double MeasurePlaneWave(const GenRay &g, const Vec3 &s, double irradiance) {
    // Theory §2.4 item 2.
    const Vec2 ks = TransverseWavevector(g, s);
    if (!std::isfinite(ks.x)) return 0;
    const double q = 1 + g.rho * g.rho;
    return irradiance * g.beta2 / (Pi * q) * std::exp(-g.beta2 * LengthSquared(ks) / q);
}

double MeasureDistantGaussian(const GenRay &g, const Vec3 &s, double irradiance, double omega) {
    // Theory §2.4 item 3: E·N₂(k_s⊥; 0, σ_k²I + k²Ω).
    const Vec2 ks = TransverseWavevector(g, s);
    if (!std::isfinite(ks.x)) return 0;
    return irradiance * Normal2(LengthSquared(ks), g.SigmaK2() + g.k * g.k * omega);
}

double MeasureDistantDisc(const GenRay &g, const Vec3 &s, double irradiance, double sinAlpha) {
    if (sinAlpha <= 0) return MeasurePlaneWave(g, s, irradiance);
    const Vec2 ks = TransverseWavevector(g, s);
    if (!std::isfinite(ks.x)) return 0;
    // Work in angle units (divide wavevectors by k) for a well-scaled Rice integral.
    const double p = DiscGaussianProbability(Length(ks) / g.k, sinAlpha, std::sqrt(g.AngularVariance()));
    return irradiance * p / (Pi * g.k * g.k * sinAlpha * sinAlpha);
}

bool DistantDiscOutOfReach(const SpectralGenRay &g, const Vec3 &s, double sinAlpha) {
    // |k_s⊥|/k = |s × d| (TransverseWavevector's length over k); 1e-9 rad covers the rounding of
    // the two computations (RiceCdf's t − c to ~1e-16·t).
    if (!(sinAlpha > 0)) return false;  // a plane wave (MeasurePlaneWave) is never exactly 0
    const double gap = Length(Cross(s, g.d)) - sinAlpha - 1e-9;
    if (!(gap > 0) || !(Dot(s, g.d) > 0)) return false;
    // gap ≥ RiceReach·σ_i, squared (a last-bit difference to the square-root form is far inside
    // the 1e-9 above).
    const double reach2 = Sqr(gap / RiceReach);
    // Each measured wavelength (the set bits of g.measured below g.count).
    static_assert(NumWavelengths < 32, "the measured mask is an unsigned of 32 bits");
    for (unsigned m = g.measured & ((1u << g.count) - 1); m != 0; m &= m - 1)
        if (!(g.At(std::countr_zero(m)).AngularVariance() <= reach2)) return false;
    return true;
}

double MeasurePointSource(const GenRay &g, const Vec3 &p, double intensity) {
    // Theory §2.4 item 5 (derivation: the far-zone WDF (I/R²)δ(k⊥ − k r⊥/R) against g).
    const Vec3 rel = g.o - p;
    const double r2 = LengthSquared(rel);
    if (!(r2 > 0)) return 0;
    const double r = std::sqrt(r2);
    if (Dot(rel, g.d) <= 0) return 0;  // the wave travels against the GR
    const Frame f = g.TransverseFrame();
    const Vec2 kappa = Vec2(Dot(rel, f.s), Dot(rel, f.t)) * (g.k / r);
    const double beta = std::sqrt(g.beta2);
    const double a = beta * g.k / r - g.rho / beta;
    const double ab2 = a * a * g.beta2;
    return intensity / r2 * std::exp(-g.beta2 * LengthSquared(kappa) / (1 + ab2)) /
           (Pi * (1 / g.beta2 + a * a));
}

namespace {
// N₂(u; 0, C) for a 2-vector u = (x, y) and symmetric C = [[cxx, cxy], [cxy, cyy]].
double Normal2Full(double x, double y, double cxx, double cxy, double cyy) {
    const double det = cxx * cyy - cxy * cxy;
    if (!(det > 0)) return 0;
    const double q = (cyy * x * x - 2 * cxy * x * y + cxx * y * y) / det;
    return std::exp(-0.5 * q) / (2 * Pi * std::sqrt(det));
}
}  // namespace

double GaussianBeamGeometry::Beta2At(double z, double k) const {
    const double zr = k * beta2;
    return beta2 * (1 + (z / zr) * (z / zr));
}

Complex GaussianBeamGeometry::Field(const Vec3 &p, double k, double zRef) const {
    const Vec3 dp = p - waist;
    const double z = Dot(dp, axis);
    const double r2 = std::max(0.0, LengthSquared(dp) - z * z);
    const Complex q = Q(z, k), q0 = Q(0, k);
    const Complex ik(0, k);
    return (q0 / q) * std::exp(ik * (z - zRef) + ik * r2 / (2.0 * q)) / std::sqrt(Pi * beta2);
}

double MeasureGaussianBeam(const GenRay &g, const GenRay &beam, double power) {
    // Theory §2.4 item 1 with the source WDF P·g_{β_s,ρ_s}: per axis N₂(ū_g − ū_s; 0, Σ_g + Σ_s).
    if (Dot(beam.d, g.d) <= 0) return 0;
    GenRay s = beam;
    s.k = g.k;
    // Carry the beam to the plane ⊥ g.d through g.o (along its own axis).
    const double z = Dot(g.o - beam.o, g.d) / Dot(beam.d, g.d);
    s.Propagate(z);
    const Frame f = g.TransverseFrame();
    const Vec3 dr = g.o - s.o;
    const Vec2 drT(Dot(dr, f.s), Dot(dr, f.t));
    const Vec2 dkT = Vec2(Dot(beam.d, f.s), Dot(beam.d, f.t)) * (-g.k);
    const GrCovariance c = g.Covariance() + s.Covariance();
    return power * Normal2Full(drT.x, dkT.x, c.rr, c.rk, c.kk) * Normal2Full(drT.y, dkT.y, c.rr, c.rk, c.kk);
}

AngularProfile GaussianBeamOverlapProfile(const GenRay &g, const GenRay &beam) {
    AngularProfile p;
    if (Dot(beam.d, g.d) <= 0) return p;
    GenRay s = beam;
    s.k = g.k;
    const double z = Dot(g.o - beam.o, g.d) / Dot(beam.d, g.d);
    s.Propagate(z);
    const Frame f = g.TransverseFrame();
    const Vec3 dr = s.o - g.o;  // the beam's mean relative to the GR's: (Δr, Δk)
    const Vec2 drT(Dot(dr, f.s), Dot(dr, f.t));
    const Vec2 dkT = Vec2(Dot(beam.d, f.s), Dot(beam.d, f.t)) * g.k;
    const GrCovariance a = g.Covariance(), b = s.Covariance();
    // Per axis: posterior covariance P = (A⁻¹ + B⁻¹)⁻¹ = A(A + B)⁻¹B, mean P·B⁻¹·Δu = A(A + B)⁻¹Δu.
    const GrCovariance c = a + b;
    const double det = c.Det();
    if (!(det > 0)) return p;
    // (A + B)⁻¹ = [[kk, −rk], [−rk, rr]]/det; P_kk = (A(A+B)⁻¹B)_kk.
    const double i_rr = c.kk / det, i_rk = -c.rk / det, i_kk = c.rr / det;
    // M = A·(A+B)⁻¹ (2×2, rows of A times the inverse).
    const double m_kr = a.rk * i_rr + a.kk * i_rk, m_kk = a.rk * i_rk + a.kk * i_kk;
    const double pkk = m_kr * b.rk + m_kk * b.kk;
    const Vec2 meanK = drT * m_kr + dkT * m_kk;
    const Vec3 dir = g.d + (f.s * meanK.x + f.t * meanK.y) / g.k;
    p = AngularProfile::Gaussian(std::max(pkk, 0.0) / (g.k * g.k), true);
    p.centre = Normalize(dir);
    return p;
}

AngularProfile GaussianBeamIncidenceProfile(const GenRay &g, const GenRay &beamAtG) {
    const double b2 = beamAtG.beta2, rho = beamAtG.rho, g2 = g.beta2, k = beamAtG.k;
    const double var = (0.5 / b2 + rho * rho * g2 / (2 * b2 * (b2 + g2))) / (k * k);
    AngularProfile p = AngularProfile::Gaussian(var);
    p.localized = true;
    return p;
}

double DiscGaussianProbability(double offset, double radius, double sigma) {
    if (radius <= 0) return 0;
    if (!(sigma > 0)) return offset <= radius ? 1.0 : 0.0;
    return RiceCdf(offset / sigma, radius / sigma);
}

double RectGaussianProbability(const Vec2 &mu, double sigma, const Vec2 &lo, const Vec2 &hi) {
    auto axis = [&](double m, double a, double b) {
        if (!(sigma > 0)) return (m >= a && m <= b) ? 1.0 : 0.0;
        const double s = sigma * std::sqrt(2.0);
        // Φ(b) − Φ(a) via erfc on the far tails for accuracy.
        return 0.5 * (std::erfc((a - m) / s) - std::erfc((b - m) / s));
    };
    return axis(mu.x, lo.x, hi.x) * axis(mu.y, lo.y, hi.y);
}

}  // namespace phasor
