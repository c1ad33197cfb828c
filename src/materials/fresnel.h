// SPDX-License-Identifier: Apache-2.0
// phasor — Fresnel equations for planar interfaces and the reflection / refraction laws
// (theory §4.1). Shared by every kernel with a smooth interface (dielectric, conductor, and
// later the grating substrate, Harvey–Shack base, thin films).
//
// Conventions: indices are n + iκ with κ ≥ 0 (time dependence e^{-iωt}: a wave with κ > 0 decays
// into the medium); cosThetaI is the cosine of the incidence angle measured in the incident medium
// (0 = grazing, 1 = normal); all results are for unpolarised light unless the name says s or p.
#pragma once

#include <limits>

#include "core/math.h"
#include "core/numerics/gauss_legendre.h"

namespace phasor {

/// Complex amplitude reflection and transmission coefficients of a planar interface between an
/// incident medium of index n1 and a medium of index n2 (theory §4.1):
///   r_s = (n₁cosθ_i − n₂cosθ_t)/(n₁cosθ_i + n₂cosθ_t),  r_p = (n₂cosθ_i − n₁cosθ_t)/(n₂cosθ_i + n₁cosθ_t),
///   t_s = 2n₁cosθ_i/(n₁cosθ_i + n₂cosθ_t),              t_p = 2n₁cosθ_i/(n₂cosθ_i + n₁cosθ_t).
/// r and t are ratios of electric-field amplitudes in the (s, p) basis of core/polarization.h
/// (Jones::Diagonal(r_s, r_p) is the interface's Jones matrix). Power transmittances need the
/// factors of FresnelPowerFactorS/P below.
struct FresnelCoefficients {
    Complex rs, rp, ts, tp;
    Complex cosThetaT;  // cosine of the (complex) refraction angle
};

/// cosθ_t in a medium of index n2 for a wave whose tangential wave-vector is that of cosθ_i in n1
/// (Snell's invariant n₁sinθ_i = n₂sinθ_t, all complex): cosθ_t = ±√(1 − (n₁/n₂)² sin²θ_i), the sign
/// chosen so that the wave decays away from the interface, Im(n₂cosθ_t) > 0, or, when
/// n₂cosθ_t is real (lossless and propagating), travels away from it, Re(n₂cosθ_t) ≥ 0.
/// "Real" means |Im| ≤ 100 ε·|n₂cosθ_t|: round-off leaves such imaginary parts of either sign
/// on a propagating wave in a lossless medium, and their sign must not flip the direction.
/// For real n1 and κ₂ ≥ 0 this is the principal branch (Re cosθ_t ≥ 0); under total internal
/// reflection it picks the evanescent wave that decays (cosθ_t = +i·a for real n₂ > 0).
inline Complex RefractedCos(Complex n1, Complex cosThetaI, Complex n2) {
    // 1 − (n₁/n₂)²·sin²θ_i written as (1 − (n₁/n₂)²) + (n₁/n₂)²·cos²θ_i: no cancellation near
    // grazing incidence, and an index-matched interface gives cosθ_t = cosθ_i exactly (r = 0).
    const Complex ratio2 = (n1 / n2) * (n1 / n2);
    Complex cosT = SqrtFinite((1.0 - ratio2) + ratio2 * cosThetaI * cosThetaI);
    const Complex q = n2 * cosT;  // normal wave-vector component / k₀
    // |Im q| ≤ 100ε·|q|, squared (no hypot)
    const double tol = 100 * std::numeric_limits<double>::epsilon();
    const bool real = q.imag() * q.imag() <= tol * tol * std::norm(q);
    if (real ? q.real() < 0 : q.imag() < 0) cosT = -cosT;
    return cosT;
}

/// The coefficients above for complex indices n1, n2 (n + iκ, κ ≥ 0) and a complex cosθ_i in
/// the incident medium, as inside an absorbing layer stack (layer_stack.h). cosθ_t follows
/// RefractedCos. Stokes' relations hold exactly in this normalisation: swapping the media gives
/// r' = −r and t·t' − r·r' = 1 per polarisation.
/// The same with cosθ_t given (it must be RefractedCos's for this interface): a layer stack
/// computes every medium's cosθ from the incident medium by Snell's invariant, so round-off in
/// complex layers does not accumulate down the stack.
/// S = double: lossless media and propagating waves, the same formulas in real arithmetic (complex
/// division is several times slower).
template <typename S>
inline FresnelCoefficients FresnelAmplitudes(S n1, S cosThetaI, S n2, S cosThetaT) {
    FresnelCoefficients c;
    const S cosI = cosThetaI, cosT = cosThetaT;
    c.cosThetaT = cosT;
    const S a = n1 * cosI, b = n2 * cosT;    // s-polarisation terms
    const S ap = n2 * cosI, bp = n1 * cosT;  // p-polarisation terms
    c.rs = (a - b) / (a + b);
    c.rp = (ap - bp) / (ap + bp);
    c.ts = 2.0 * a / (a + b);
    c.tp = 2.0 * a / (ap + bp);
    return c;
}
inline FresnelCoefficients FresnelAmplitudes(Complex n1, Complex cosThetaI, Complex n2) {
    if (n1.imag() == 0 && n2.imag() == 0 && cosThetaI.imag() == 0 && n2.real() > 0) {
        // Lossless media and a propagating transmitted wave: real arithmetic (a dielectric's hot path).
        const double r = n1.real() / n2.real(), c = cosThetaI.real();
        const double cos2T = (1 - r * r) + r * r * c * c;
        if (cos2T >= 0) return FresnelAmplitudes(n1.real(), c, n2.real(), std::sqrt(cos2T));
    }
    return FresnelAmplitudes(n1, cosThetaI, n2, RefractedCos(n1, cosThetaI, n2));
}

/// The interface n1 (real, incident side) → n2 = n + iκ for a real cosθ_i (clamped to [0, 1]);
/// the complex overload above with Im(n₁) = Im(cosθ_i) = 0.
inline FresnelCoefficients FresnelAmplitudes(double cosThetaI, double n1, Complex n2) {
    return FresnelAmplitudes(Complex(n1, 0), Complex(Clamp(cosThetaI, 0.0, 1.0), 0), n2);
}

/// Power factors that turn |t|² into a transmittance, T = factor·|t|² (Born & Wolf §1.5 for
/// absorbing media): s: Re(n₂cosθ_t)/Re(n₁cosθ_i), p: Re(n₂·conj(cosθ_t))/Re(n₁·conj(cosθ_i)).
/// Both reduce to theory §4.1's n₂cosθ_t/(n₁cosθ_i) for lossless media; 0 for an evanescent
/// transmitted wave. Defined for an incident medium with Re(n₁cosθ_i) > 0.
inline double FresnelPowerFactorS(Complex n1, Complex cosI, Complex n2, Complex cosT) {
    return (n2 * cosT).real() / (n1 * cosI).real();
}
inline double FresnelPowerFactorP(Complex n1, Complex cosI, Complex n2, Complex cosT) {
    return (n2 * std::conj(cosT)).real() / (n1 * std::conj(cosI)).real();
}

/// Unpolarised reflectance of the interface n1 (real) → n2 = n + iκ: (|r_s|² + |r_p|²)/2
/// (theory §4.1, Mueller element A). Exact for any complex n2 with κ ≥ 0; returns 0 for a
/// vanishing index contrast and 1 at grazing incidence.
inline double FresnelComplex(double cosThetaI, double n1, Complex n2) {
    if (n2 == Complex(n1, 0)) return 0;  // no interface (also avoids 0/0 at grazing)
    const double cosI = Clamp(cosThetaI, 0.0, 1.0);
    if (cosI == 0) return 1;
    FresnelCoefficients c = FresnelAmplitudes(cosI, n1, n2);
    return 0.5 * (std::norm(c.rs) + std::norm(c.rp));
}

/// The same reflectance in real arithmetic: the conductor equations in terms of a² + b² = |η² − sin²θ|
/// (η = n2/n1, a + ib = √(η² − sin²θ); Born & Wolf, Principles of Optics, §14.2), exact for any
/// κ ≥ 0 including total internal reflection (κ = 0, a = 0: R = 1), with a = ηκ/b where a² + b²
/// nearly cancels η² − sin²θ (beyond a critical angle in a weakly absorbing medium). For callers that
/// need only the unpolarised power many times (a grating order's efficiency at its source angle):
/// several times cheaper than the complex coefficients; equal to FresnelComplex to round-off
/// (tests/materials/fresnel_test.cpp).
inline double FresnelReflectanceReal(double cosThetaI, double n1, Complex n2) {
    if (n2 == Complex(n1, 0)) return 0;  // no interface
    const double c = Clamp(cosThetaI, 0.0, 1.0);
    if (c == 0) return 1;
    const double er = n2.real() / n1, ek = n2.imag() / n1, s2 = 1 - c * c;
    const double t0 = er * er - ek * ek - s2, cross = 2 * er * ek;
    const double sum = std::sqrt(t0 * t0 + cross * cross);  // a² + b²
    const double a = t0 >= 0 ? std::sqrt(0.5 * (sum + t0)) : (cross > 0 ? 0.5 * cross / std::sqrt(0.5 * (sum - t0)) : 0.0);
    const double rs = (sum - 2 * a * c + c * c) / (sum + 2 * a * c + c * c);
    const double pc = c * c * sum, ps = 2 * a * c * s2, s4 = s2 * s2;  // R_p/R_s's terms (B&W's with tanθ·cos²θ)
    const double rp = rs * (pc - ps + s4) / (pc + ps + s4);
    return 0.5 * (rs + rp);
}

/// The unpolarised transmittance (power, |t|² times the power factor n₂c_t/(n₁c)) of a lossless
/// interface n1 → n2 (both real) from FresnelAmplitudes's real-arithmetic coefficients, with its
/// c_t² = (1 − r²) + r²c², r = n₁/n₂ (0 under total internal reflection) — directly, not as 1 − R,
/// which loses every digit of a T ~ 1e-7 next to the critical angle (there c_t is round-off of that
/// expression, so the same expression keeps this T equal to the complex path's, EvalLobe's).
inline double FresnelTransmittanceReal(double cosThetaI, double n1, double n2) {
    if (n2 == n1) return 1;
    const double c = Clamp(cosThetaI, 0.0, 1.0), r = n1 / n2;
    const double cos2T = (1 - r * r) + r * r * c * c;
    if (!(cos2T > 0) || c == 0) return 0;
    const double ct = std::sqrt(cos2T);
    const FresnelCoefficients f = FresnelAmplitudes(n1, c, n2, ct);
    return 0.5 * (n2 * ct) / (n1 * c) * (std::norm(f.ts) + std::norm(f.tp));
}

/// Reflectance of a conductor with relative complex index eta = (n + iκ)/n_outside.
inline double FresnelConductor(double cosThetaI, Complex eta) { return FresnelComplex(cosThetaI, 1.0, eta); }

/// s- and p-reflectances of a dielectric interface with real relative index eta = n_t/n_i
/// (Hecht, Optics §4.6). Total internal reflection (sinθ_t ≥ 1) gives R_s = R_p = 1.
struct FresnelSP {
    double rs2 = 1, rp2 = 1;  // |r_s|², |r_p|²
    double Unpolarised() const { return 0.5 * (rs2 + rp2); }
};
inline FresnelSP FresnelDielectricSP(double cosThetaI, double eta) {
    const double cosI = Clamp(cosThetaI, 0.0, 1.0);
    if (eta == 1) return {0, 0};
    const double sin2T = std::max(0.0, 1 - cosI * cosI) / (eta * eta);  // Snell's law
    if (sin2T >= 1) return {1, 1};
    const double cosT = std::sqrt(1 - sin2T);
    const double rs = (cosI - eta * cosT) / (cosI + eta * cosT);
    const double rp = (eta * cosI - cosT) / (eta * cosI + cosT);
    return {rs * rs, rp * rp};
}

/// Unpolarised reflectance of a dielectric interface with real relative index eta = n_t/n_i
/// (η > 1: entering the denser medium). 1 under total internal reflection. T = 1 − R.
inline double FresnelDielectric(double cosThetaI, double eta) {
    return FresnelDielectricSP(cosThetaI, eta).Unpolarised();
}

/// Hemispherical (diffuse) reflectance of a dielectric interface with real relative index
/// eta = n_t/n_i for light arriving from the n_i side with a Lambertian (cosine-weighted) angular
/// distribution: F̄(η) = 2∫₀¹ F(μ, η) μ dμ (unpolarised Fresnel, μ = cosθ_i; total internal
/// reflection included). E.g. F̄(1.5) = 0.09178 (air → glass), F̄(1/1.5) = 0.59635 (glass → air).
///   * η ≥ 1.01: the exact closed form (Stern 1964, Appl. Opt. 3, 111); it matches the integral to
///     1e-13 (tests/materials/plastic_test.cpp) but cancels catastrophically as η → 1 (1e-9 at
///     η = 1.0001);
///   * 1 ≤ η < 1.01: the integral by 32-node Gauss–Legendre in t = √μ (F̄ < 3.2e-3 there; the rule
///     errs by < 3e-11 for η − 1 ≥ 1e-5 and < 4e-10 closer to 1, measured);
///   * η < 1: étendue (n²cosθ dω is invariant across the interface) and the reciprocity of the
///     transmittance give 1 − F̄(η) = η²·(1 − F̄(1/η)), free of the kink at the critical angle.
inline double FresnelDiffuseReflectance(double eta) {
    if (eta < 1) return 1 - eta * eta * (1 - FresnelDiffuseReflectance(1 / eta));
    if (eta < 1.01)  // μ = t²: F varies on the scale √(η² − 1) near μ = 0, i.e. (η² − 1)^¼ in t
        return 4 * IntegrateGaussLegendre([eta](double t) { return FresnelDielectric(t * t, eta) * t * t * t; },
                                          0.0, 1.0, 32);
    const double n = eta, n2 = n * n, n4 = n2 * n2;
    return 0.5 + (n - 1) * (3 * n + 1) / (6 * (n + 1) * (n + 1)) +
           n2 * (n2 - 1) * (n2 - 1) / ((n2 + 1) * (n2 + 1) * (n2 + 1)) * std::log((n - 1) / (n + 1)) -
           2 * n2 * n * (n2 + 2 * n - 1) / ((n2 + 1) * (n4 - 1)) +
           8 * n4 * (n4 + 1) / ((n2 + 1) * (n4 - 1) * (n4 - 1)) * std::log(n);
}

/// Mirror direction of w about the local normal (0, 0, 1): both directions point away from the
/// surface, on the same side (law of reflection).
inline Vec3 ReflectLocal(const Vec3 &w) { return {-w.x, -w.y, w.z}; }

/// Refracts w (local frame, pointing away from the surface, either side) through the interface
/// at z = 0 into the other half space. eta = n_t/n_i, the index of the side the refracted
/// direction lies on over the index of w's side. Returns false under total internal reflection.
/// Snell's law in vector form: wt = −w/η + (cosθ_i/η − cosθ_t)·n with n on w's side, which keeps
/// the tangential wave-vector component: n_t·wt_xy = −n_i·w_xy.
inline bool RefractLocal(const Vec3 &w, double eta, Vec3 *wt) {
    const double cosI = std::abs(w.z);
    const double sin2T = std::max(0.0, 1 - cosI * cosI) / (eta * eta);
    if (sin2T >= 1) return false;
    const double cosT = std::sqrt(1 - sin2T);
    const double side = w.z >= 0 ? 1.0 : -1.0;  // normal on w's side
    *wt = Vec3(-w.x / eta, -w.y / eta, -side * cosT);
    return true;
}

}  // namespace phasor
