// SPDX-License-Identifier: Apache-2.0
// phasor — Fresnel equations for planar interfaces and the reflection / refraction laws
// (theory §4.1). Shared by every kernel with a smooth interface (dielectric, conductor, and
// later the grating substrate, Harvey–Shack base, thin films).
//
// Conventions: indices are n + iκ with κ ≥ 0 (time dependence e^{-iωt}: a wave with κ > 0 decays
// into the medium); cosThetaI is the cosine of the incidence angle measured in the incident medium
// (0 = grazing, 1 = normal); all results are for unpolarised light unless the name says s or p.
#pragma once

#include "core/math.h"

namespace phasor {

/// Complex amplitude reflection and transmission coefficients of a planar interface between a
/// medium of real index n1 (incident side) and a medium of index n2 = n + iκ (theory §4.1):
///   r_s = (n₁cosθ_i − n₂cosθ_t)/(n₁cosθ_i + n₂cosθ_t),  r_p = (n₂cosθ_i − n₁cosθ_t)/(n₂cosθ_i + n₁cosθ_t),
///   t_s = 2n₁cosθ_i/(n₁cosθ_i + n₂cosθ_t),              t_p = 2n₁cosθ_i/(n₂cosθ_i + n₁cosθ_t),
/// with cosθ_t = √(1 − (n₁/n₂)² sin²θ_i) on the principal branch (Re ≥ 0, and Im ≥ 0 for κ ≥ 0:
/// the transmitted or evanescent wave decays away from the interface).
struct FresnelCoefficients {
    Complex rs, rp, ts, tp;
    Complex cosThetaT;  // cosine of the (complex) refraction angle
};

inline FresnelCoefficients FresnelAmplitudes(double cosThetaI, double n1, Complex n2) {
    const double cosI = Clamp(cosThetaI, 0.0, 1.0);
    const double sin2I = std::max(0.0, 1 - cosI * cosI);
    // Principal branch (Re ≥ 0). For κ > 0 the argument has Im > 0, far from the cut; for real n₂
    // under total internal reflection it is a negative real and cosθ_t = ±i·a: |r_s| = |r_p| = 1
    // on either sign, so the reflectances do not depend on how the cut is approached.
    const Complex cosT = std::sqrt(1.0 - (n1 / n2) * (n1 / n2) * sin2I);
    FresnelCoefficients c;
    c.cosThetaT = cosT;
    const Complex a = n1 * cosI, b = n2 * cosT;    // s-polarisation terms
    const Complex ap = n2 * cosI, bp = n1 * cosT;  // p-polarisation terms
    c.rs = (a - b) / (a + b);
    c.rp = (ap - bp) / (ap + bp);
    c.ts = 2.0 * a / (a + b);
    c.tp = 2.0 * a / (ap + bp);
    return c;
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
