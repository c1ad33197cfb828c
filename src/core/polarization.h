// SPDX-License-Identifier: Apache-2.0
// phasor — polarisation algebra: Jones matrices (complex 2×2, field amplitudes), Stokes vectors
// and Mueller matrices (real 4×4, intensities), and the Mueller rotation (theory §4.1, §4.9).
//
// Basis and conventions (used by every kernel that reports a polarised response):
//   * A Jones vector (E_s, E_p) holds the field components along ŝ and p̂ of the plane of
//     incidence: ŝ = normalise(n̂ × k̂) is perpendicular to the plane of incidence, p̂ = k̂ × ŝ lies in
//     it, so (ŝ, p̂, k̂) is right-handed for the propagation direction k̂ of that wave. The incident
//     wave uses its own k̂_i and the outgoing one its k̂_o (ŝ is shared, p̂ differs); a Jones matrix
//     maps incident (E_s, E_p) to outgoing (E_s, E_p), so a Fresnel interface is
//     Diagonal(r_s, r_p) or Diagonal(t_s, t_p) with theory §4.1's coefficients (fresnel.h).
//     At normal incidence the plane of incidence is undefined; the caller picks ŝ.
//   * Stokes vectors (S0, S1, S2, S3) in that basis: S0 = I_s + I_p, S1 = I_s − I_p,
//     S2 = 2 Re(E_s E_p*), S3 = −2 Im(E_s E_p*) (x = s, y = p in the usual definitions with
//     time dependence e^{-iωt}). With these, a Fresnel interface's Mueller matrix is theory §4.1's
//     [[A, B, 0, 0], [B, A, 0, 0], [0, 0, C, S], [0, 0, −S, C]],
//     A = (|r_s|²+|r_p|²)/2, B = (|r_s|²−|r_p|²)/2, C = Re(r_s r_p*), S = Im(r_s r_p*).
//   * Mueller matrices act on Stokes vectors from the left; products compose right to left
//     (M2 * M1 applies M1 first), as for Jones matrices.
#pragma once

#include <array>

#include "core/math.h"

namespace phasor {

/// A complex 2×2 Jones matrix in the (s, p) basis above: m[row][col], outgoing = m · incident.
/// Amplitudes are dimensionless field ratios (no power factor: a transmission Jones matrix holds
/// t_s, t_p; the power factor Re(n₂cosθ_t)/Re(n₁cosθ_i) is applied to intensities by the caller).
struct Jones {
    Complex m[2][2] = {{0, 0}, {0, 0}};

    static Jones Identity() { return Diagonal(1, 1); }
    /// diag(s, p): an element that does not mix s and p (a planar interface).
    static Jones Diagonal(Complex s, Complex p) {
        Jones j;
        j.m[0][0] = s;
        j.m[1][1] = p;
        return j;
    }
    Jones operator*(const Jones &o) const;
    Jones operator*(Complex c) const;
    Jones operator+(const Jones &o) const;
};

/// (S0, S1, S2, S3) in the (s, p) basis above; S0 is the intensity (any radiometric unit).
using Stokes = std::array<double, 4>;

/// Stokes vector of the field (E_s, E_p) (same units squared as the field).
Stokes StokesFromField(Complex es, Complex ep);
/// Degree of polarisation √(S1²+S2²+S3²)/S0 (0 for S0 = 0).
double DegreeOfPolarization(const Stokes &s);

/// A real 4×4 Mueller matrix m[row][col] acting on Stokes vectors (S0..S3).
struct Mueller {
    double m[4][4] = {};

    static Mueller Identity();
    static Mueller Zero();
    /// a·diag(1, 0, 0, 0): keeps a fraction a of the intensity and depolarises it fully (diffuse).
    static Mueller Depolarizer(double a);
    /// The Mueller matrix of a Jones matrix (non-depolarising): M = A (J ⊗ J*) A⁻¹ with the Stokes
    /// convention above, so FromJones(Diagonal(r_s, r_p)) = theory §4.1's Fresnel matrix.
    static Mueller FromJones(const Jones &j);
    /// The Mueller matrix of an incoherent sum of elements that do not mix s and p, Σ_k
    /// FromJones(Diagonal(a_k, b_k)), from the sums ss = Σ|a_k|², pp = Σ|b_k|², sp = Σ a_k·conj(b_k):
    /// theory §4.1's [[A, B, 0, 0], [B, A, 0, 0], [0, 0, C, S], [0, 0, −S, C]] with A = (ss + pp)/2,
    /// B = (ss − pp)/2, C = Re sp, S = Im sp. One term gives FromJones(Diagonal(a, b)); more terms
    /// depolarise partially (|sp|² < ss·pp). Used for a layer stack's incoherent sum.
    static Mueller FromDiagonalSums(double ss, double pp, Complex sp);
    /// Rotation of the Stokes reference frame by theta [rad] (theory §4.9):
    /// [[1,0,0,0],[0,cos2θ,−sin2θ,0],[0,sin2θ,cos2θ,0],[0,0,0,1]]. Rotation(a)·Rotation(b) =
    /// Rotation(a + b); Rotation(π) = identity. An element M whose s axis is at angle θ to the
    /// current frame acts as Rotation(θ)·M·Rotation(−θ).
    static Mueller Rotation(double theta);

    Mueller operator*(const Mueller &o) const;
    Mueller operator*(double s) const;
    Mueller operator+(const Mueller &o) const;
    Stokes operator*(const Stokes &s) const;
};

// ---- implementation (small and hot: inline) -------------------------------------------------

inline Jones Jones::operator*(const Jones &o) const {
    Jones r;
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) r.m[i][j] = m[i][0] * o.m[0][j] + m[i][1] * o.m[1][j];
    return r;
}
inline Jones Jones::operator*(Complex c) const {
    Jones r;
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) r.m[i][j] = m[i][j] * c;
    return r;
}
inline Jones Jones::operator+(const Jones &o) const {
    Jones r;
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) r.m[i][j] = m[i][j] + o.m[i][j];
    return r;
}

inline Stokes StokesFromField(Complex es, Complex ep) {
    const Complex c = es * std::conj(ep);  // E_s E_p*
    return {std::norm(es) + std::norm(ep), std::norm(es) - std::norm(ep), 2 * c.real(), -2 * c.imag()};
}

inline double DegreeOfPolarization(const Stokes &s) {
    if (s[0] == 0) return 0;
    return std::sqrt(s[1] * s[1] + s[2] * s[2] + s[3] * s[3]) / s[0];
}

inline Mueller Mueller::Zero() { return Mueller{}; }
inline Mueller Mueller::Identity() {
    Mueller r;
    for (int i = 0; i < 4; ++i) r.m[i][i] = 1;
    return r;
}
inline Mueller Mueller::Depolarizer(double a) {
    Mueller r;
    r.m[0][0] = a;
    return r;
}

inline Mueller Mueller::FromJones(const Jones &j) {
    if (j.m[0][1] == Complex(0, 0) && j.m[1][0] == Complex(0, 0)) {
        // diag(a, b) (every planar interface): theory §4.1's [[A, B, 0, 0], [B, A, 0, 0],
        // [0, 0, C, S], [0, 0, −S, C]] with A, B = (|a|² ± |b|²)/2, C + iS = a·b*.
        const Complex a = j.m[0][0], b = j.m[1][1], c = a * std::conj(b);
        Mueller r;
        r.m[0][0] = r.m[1][1] = 0.5 * (std::norm(a) + std::norm(b));
        r.m[0][1] = r.m[1][0] = 0.5 * (std::norm(a) - std::norm(b));
        r.m[2][2] = r.m[3][3] = c.real();
        r.m[2][3] = c.imag();
        r.m[3][2] = -c.imag();
        return r;
    }
    // Stokes S_k = tr(σ_k E E†) with σ0 = I, σ1 = diag(1, −1), σ2 = [[0,1],[1,0]],
    // σ3 = [[0,−i],[i,0]] (the convention above); E E† = ½ Σ_k S_k σ_k, so the outgoing
    // S'_i = tr(σ_i J E E† J†) gives M_ij = ½ Re tr(σ_i J σ_j J†).
    const Complex I(0, 1);
    const Complex sigma[4][2][2] = {
        {{1, 0}, {0, 1}}, {{1, 0}, {0, -1}}, {{0, 1}, {1, 0}}, {{0, -I}, {I, 0}}};
    Jones jd;  // J†
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) jd.m[a][b] = std::conj(j.m[b][a]);
    auto asJones = [&](int k) {
        Jones s;
        for (int a = 0; a < 2; ++a)
            for (int b = 0; b < 2; ++b) s.m[a][b] = sigma[k][a][b];
        return s;
    };
    Mueller r;
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 4; ++k) {
            const Jones p = asJones(i) * j * asJones(k) * jd;
            r.m[i][k] = 0.5 * (p.m[0][0] + p.m[1][1]).real();
        }
    return r;
}

inline Mueller Mueller::FromDiagonalSums(double ss, double pp, Complex sp) {
    Mueller r;
    r.m[0][0] = r.m[1][1] = 0.5 * (ss + pp);
    r.m[0][1] = r.m[1][0] = 0.5 * (ss - pp);
    r.m[2][2] = r.m[3][3] = sp.real();
    r.m[2][3] = sp.imag();
    r.m[3][2] = -sp.imag();
    return r;
}

inline Mueller Mueller::Rotation(double theta) {
    // theory §4.9
    const double c = std::cos(2 * theta), s = std::sin(2 * theta);
    Mueller r = Identity();
    r.m[1][1] = c;
    r.m[1][2] = -s;
    r.m[2][1] = s;
    r.m[2][2] = c;
    return r;
}

inline Mueller Mueller::operator*(const Mueller &o) const {
    Mueller r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k) r.m[i][j] += m[i][k] * o.m[k][j];
    return r;
}
inline Mueller Mueller::operator*(double s) const {
    Mueller r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = m[i][j] * s;
    return r;
}
inline Mueller Mueller::operator+(const Mueller &o) const {
    Mueller r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = m[i][j] + o.m[i][j];
    return r;
}
inline Stokes Mueller::operator*(const Stokes &s) const {
    Stokes r{};
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 4; ++k) r[i] += m[i][k] * s[k];
    return r;
}

}  // namespace phasor
