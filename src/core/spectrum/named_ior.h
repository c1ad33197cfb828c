// SPDX-License-Identifier: Apache-2.0
// phasor — complex refractive indices n + iκ (κ ≥ 0, e^{-iωt} convention as in
// materials/fresnel.h) of named materials, as a function of vacuum wavelength λ [m]. These are the
// strings a `complex spectrum` parameter accepts (ior = "Au"; core/spectrum/complex_spectrum.h).
//
// Sources (numeric data only):
//   Ag, Au, Cu: P. B. Johnson and R. W. Christy, "Optical constants of the noble metals",
//               Phys. Rev. B 6, 4370 (1972), Table I (photon energies 0.64–6.60 eV,
//               i.e. 188–1937 nm). Interpolated linearly in photon energy, clamped outside.
//   Al:         A. D. Rakić, A. B. Djurišić, J. M. Elazar, M. L. Majewski, "Optical properties of
//               metallic films for vertical-cavity optoelectronic devices", Appl. Opt. 37, 5271
//               (1998), Lorentz–Drude model with the paper's Al parameters, evaluated over 0.1–10 µm
//               (clamped outside).
//   BK7:        Schott N-BK7 data sheet, Sellmeier coefficients (n_d = 1.5168 at 587.6 nm).
//   fused_silica: I. H. Malitson, "Interspecimen comparison of the refractive index of fused
//               silica", J. Opt. Soc. Am. 55, 1205 (1965), three-term Sellmeier, 0.21–3.71 µm
//               (n_d = 1.4585).
//   water:      constant n_D = 1.333 (CRC Handbook, 20 °C: 1.33299); not dispersive (give a
//               table for rainbows).
//   chitin:     constant 1.56, the value commonly used for insect cuticle (theory §4.5 uses
//               1.55); not dispersive.
// Sellmeier glasses are evaluated with λ clamped to 0.2–3.7 µm (outside, the formula's poles are
// near). All glasses here are lossless (κ = 0).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/math.h"

namespace phasor {

enum class Metal { Al, Ag, Au, Cu };

namespace metal_detail {

// hc [eV·m]: photon energy E [eV] = HcEvM / λ [m].
inline constexpr double HcEvM = 1.23984193e-6;

// Johnson & Christy (1972), Table I: E [eV], then n, κ for Cu, Ag, Au.
struct JcRow {
    double e, nCu, kCu, nAg, kAg, nAu, kAu;
};
inline constexpr std::array<JcRow, 49> JohnsonChristy = {{
    {0.64, 1.09, 13.43, 0.24, 14.08, 0.92, 13.78}, {0.77, 0.76, 11.12, 0.15, 11.85, 0.56, 11.21},
    {0.89, 0.60, 9.439, 0.13, 10.10, 0.43, 9.519}, {1.02, 0.48, 8.245, 0.09, 8.828, 0.35, 8.145},
    {1.14, 0.36, 7.217, 0.04, 7.795, 0.27, 7.150}, {1.26, 0.32, 6.421, 0.04, 6.992, 0.22, 6.350},
    {1.39, 0.30, 5.768, 0.04, 6.312, 0.17, 5.663}, {1.51, 0.26, 5.180, 0.04, 5.727, 0.16, 5.083},
    {1.64, 0.24, 4.665, 0.03, 5.242, 0.14, 4.542}, {1.76, 0.21, 4.205, 0.04, 4.838, 0.13, 4.103},
    {1.88, 0.22, 3.747, 0.05, 4.483, 0.14, 3.697}, {2.01, 0.30, 3.205, 0.06, 4.152, 0.21, 3.272},
    {2.13, 0.70, 2.704, 0.05, 3.858, 0.29, 2.863}, {2.26, 1.02, 2.577, 0.06, 3.586, 0.43, 2.455},
    {2.38, 1.18, 2.608, 0.05, 3.324, 0.62, 2.081}, {2.50, 1.22, 2.564, 0.05, 3.093, 1.04, 1.833},
    {2.63, 1.25, 2.483, 0.05, 2.869, 1.31, 1.849}, {2.75, 1.24, 2.397, 0.04, 2.657, 1.38, 1.914},
    {2.88, 1.25, 2.305, 0.04, 2.462, 1.45, 1.948}, {3.00, 1.28, 2.207, 0.05, 2.275, 1.46, 1.958},
    {3.12, 1.32, 2.116, 0.05, 2.070, 1.47, 1.952}, {3.25, 1.33, 2.045, 0.05, 1.864, 1.46, 1.933},
    {3.37, 1.36, 1.975, 0.07, 1.657, 1.48, 1.895}, {3.50, 1.37, 1.916, 0.10, 1.419, 1.50, 1.866},
    {3.62, 1.36, 1.864, 0.14, 1.142, 1.48, 1.871}, {3.74, 1.34, 1.821, 0.17, 0.829, 1.48, 1.883},
    {3.87, 1.38, 1.783, 0.81, 0.392, 1.54, 1.898}, {3.99, 1.38, 1.729, 1.13, 0.616, 1.53, 1.893},
    {4.12, 1.40, 1.679, 1.34, 0.964, 1.53, 1.889}, {4.24, 1.42, 1.633, 1.39, 1.161, 1.49, 1.878},
    {4.36, 1.45, 1.633, 1.41, 1.264, 1.47, 1.869}, {4.49, 1.46, 1.646, 1.41, 1.331, 1.43, 1.847},
    {4.61, 1.45, 1.668, 1.38, 1.372, 1.38, 1.803}, {4.74, 1.41, 1.691, 1.35, 1.387, 1.35, 1.749},
    {4.86, 1.41, 1.741, 1.33, 1.393, 1.33, 1.688}, {4.98, 1.37, 1.783, 1.31, 1.389, 1.33, 1.631},
    {5.11, 1.34, 1.799, 1.30, 1.378, 1.32, 1.577}, {5.23, 1.28, 1.802, 1.28, 1.367, 1.32, 1.536},
    {5.36, 1.23, 1.792, 1.28, 1.357, 1.30, 1.497}, {5.48, 1.18, 1.768, 1.26, 1.344, 1.31, 1.460},
    {5.60, 1.13, 1.737, 1.25, 1.342, 1.30, 1.427}, {5.73, 1.08, 1.699, 1.22, 1.336, 1.30, 1.387},
    {5.85, 1.04, 1.651, 1.20, 1.325, 1.30, 1.350}, {5.98, 1.01, 1.599, 1.18, 1.312, 1.30, 1.304},
    {6.10, 0.99, 1.550, 1.15, 1.296, 1.33, 1.277}, {6.22, 0.98, 1.493, 1.14, 1.277, 1.33, 1.251},
    {6.35, 0.97, 1.440, 1.12, 1.255, 1.34, 1.226}, {6.47, 0.95, 1.388, 1.10, 1.232, 1.32, 1.203},
    {6.60, 0.94, 1.337, 1.07, 1.212, 1.28, 1.188},
}};

inline Complex JcColumn(const JcRow &r, Metal m) {
    switch (m) {
        case Metal::Cu:
            return {r.nCu, r.kCu};
        case Metal::Ag:
            return {r.nAg, r.kAg};
        default:
            return {r.nAu, r.kAu};
    }
}

// Linear interpolation in photon energy, clamped to the table's ends.
inline Complex JohnsonChristyIndex(Metal m, double lambda) {
    const double e = HcEvM / lambda;
    const auto &t = JohnsonChristy;
    if (!(e > t.front().e)) return JcColumn(t.front(), m);
    if (e >= t.back().e) return JcColumn(t.back(), m);
    std::size_t i = 1;
    while (t[i].e < e) ++i;
    const double f = (e - t[i - 1].e) / (t[i].e - t[i - 1].e);
    return (1 - f) * JcColumn(t[i - 1], m) + f * JcColumn(t[i], m);
}

// Rakić et al. (1998) Lorentz–Drude model for Al: ε(ω) = 1 − f₀ω_p²/(ω(ω + iΓ₀))
// + Σ_j f_j ω_p²/(ω_j² − ω² − iωΓ_j), all energies in eV (e^{-iωt} convention, Im ε ≥ 0).
inline Complex RakicAluminiumIndex(double lambda) {
    const double w = HcEvM / Clamp(lambda, 1e-7, 1e-5);
    constexpr double wp = 14.98;
    constexpr double f0 = 0.523, g0 = 0.047;
    constexpr double f[4] = {0.227, 0.050, 0.166, 0.030};
    constexpr double g[4] = {0.333, 0.312, 1.351, 3.382};
    constexpr double w0[4] = {0.162, 1.544, 1.808, 3.473};
    Complex eps = 1.0 - f0 * wp * wp / (w * Complex(w, g0));
    for (int j = 0; j < 4; ++j) eps += f[j] * wp * wp / Complex(w0[j] * w0[j] - w * w, -w * g[j]);
    return std::sqrt(eps);  // principal root: n > 0, κ ≥ 0
}

}  // namespace metal_detail

/// Complex index n + iκ of `m` at vacuum wavelength lambda [m].
inline Complex MetalIndex(Metal m, double lambda) {
    if (m == Metal::Al) return metal_detail::RakicAluminiumIndex(lambda);
    return metal_detail::JohnsonChristyIndex(m, lambda);
}

namespace glass_detail {

// Sellmeier: n² = 1 + Σ B_j λ²/(λ² − C_j), λ in µm, C_j in µm².
inline double Sellmeier(double lambda, const double (&b)[3], const double (&c)[3]) {
    const double l2 = Sqr(Clamp(lambda, 0.2e-6, 3.7e-6) * 1e6);
    double n2 = 1;
    for (int j = 0; j < 3; ++j) n2 += b[j] * l2 / (l2 - c[j]);
    return std::sqrt(n2);
}
inline Complex Bk7Index(double lambda) {
    constexpr double b[3] = {1.03961212, 0.231792344, 1.01046945};
    constexpr double c[3] = {0.00600069867, 0.0200179144, 103.560653};
    return Sellmeier(lambda, b, c);
}
inline Complex FusedSilicaIndex(double lambda) {
    constexpr double b[3] = {0.6961663, 0.4079426, 0.8974794};
    constexpr double c[3] = {0.0684043 * 0.0684043, 0.1162414 * 0.1162414, 9.896161 * 9.896161};
    return Sellmeier(lambda, b, c);
}

}  // namespace glass_detail

/// A named material: its scene name, a one-line source, and its index n + iκ at λ [m].
struct NamedIndex {
    const char *name;
    const char *source;
    Complex (*index)(double lambda);
};

/// Every named material, in the order docs list them.
inline const std::vector<NamedIndex> &NamedIndices() {
    static const std::vector<NamedIndex> table = {
        {"Al", "aluminium, Rakić et al. 1998 (Lorentz–Drude)", [](double l) { return MetalIndex(Metal::Al, l); }},
        {"Ag", "silver, Johnson & Christy 1972", [](double l) { return MetalIndex(Metal::Ag, l); }},
        {"Au", "gold, Johnson & Christy 1972", [](double l) { return MetalIndex(Metal::Au, l); }},
        {"Cu", "copper, Johnson & Christy 1972", [](double l) { return MetalIndex(Metal::Cu, l); }},
        {"BK7", "Schott N-BK7 crown glass (Sellmeier)", glass_detail::Bk7Index},
        {"fused_silica", "fused silica, Malitson 1965 (Sellmeier)", glass_detail::FusedSilicaIndex},
        {"water", "water, constant n_D = 1.333", [](double) { return Complex(1.333, 0); }},
        {"chitin", "insect chitin, constant 1.56", [](double) { return Complex(1.56, 0); }},
    };
    return table;
}

inline const NamedIndex *FindNamedIndex(const std::string &name) {
    for (const NamedIndex &m : NamedIndices())
        if (name == m.name) return &m;
    return nullptr;
}

inline std::vector<std::string> NamedIndexNames() {
    std::vector<std::string> names;
    for (const NamedIndex &m : NamedIndices()) names.push_back(m.name);
    return names;
}

}  // namespace phasor
