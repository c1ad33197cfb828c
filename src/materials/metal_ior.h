// SPDX-License-Identifier: Apache-2.0
// phasor — complex refractive indices n + iκ of common metals (used by the `conductor` kernel).
//
// Sources (numeric data only):
//   Ag, Au, Cu: P. B. Johnson and R. W. Christy, "Optical constants of the noble metals",
//               Phys. Rev. B 6, 4370 (1972), Table I (photon energies 0.64–6.60 eV,
//               i.e. 188–1937 nm). Interpolated linearly in photon energy, clamped outside.
//   Al:         A. D. Rakić, A. B. Djurišić, J. M. Elazar, M. L. Majewski, "Optical properties of
//               metallic films for vertical-cavity optoelectronic devices", Appl. Opt. 37, 5271
//               (1998), Lorentz–Drude model with the paper's Al parameters, evaluated over 0.1–10 µm
//               (clamped outside).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/math.h"

namespace phasor {

enum class Metal { Al, Ag, Au, Cu };

inline const std::vector<std::string> &MetalNames() {
    static const std::vector<std::string> names = {"Al", "Ag", "Au", "Cu"};
    return names;
}

inline std::optional<Metal> MetalFromName(const std::string &name) {
    if (name == "Al") return Metal::Al;
    if (name == "Ag") return Metal::Ag;
    if (name == "Au") return Metal::Au;
    if (name == "Cu") return Metal::Cu;
    return std::nullopt;
}

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

}  // namespace phasor
