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
//   BK7:        Schott N-BK7 data sheet, Sellmeier coefficients (n_d = 1.5168 at 587.6 nm),
//               0.3–2.5 µm.
//   fused_silica, SiO2: I. H. Malitson, "Interspecimen comparison of the refractive index of fused
//               silica", J. Opt. Soc. Am. 55, 1205 (1965), three-term Sellmeier, 0.21–3.71 µm
//               (n_d = 1.4585). "SiO2" is the same amorphous silica (sputtered and evaporated
//               SiO₂ coating layers are close to it), named as coating designs name it.
//   MgF2:       M. J. Dodge, "Refractive properties of magnesium fluoride", Appl. Opt. 23, 1980
//               (1984), three-term Sellmeier of the ordinary ray, 0.2–7 µm (n_o = 1.3777 at
//               589.3 nm). Coating layers are polycrystalline and nearly isotropic; the ordinary
//               index is the one thin-film designs use.
//   TiO2:       J. R. DeVore, "Refractive indices of rutile and sphalerite", J. Opt. Soc. Am. 41,
//               416 (1951), rutile, ordinary ray: n² = 5.913 + 0.2441/(λ² − 0.0803) (λ in µm),
//               0.43–1.53 µm (n_o = 2.613 at 589.3 nm). Rutile absorbs below ≈ 410 nm; the formula
//               is held constant below 430 nm.
//   water:      M. Daimon and A. Masumura, "Measurement of the refractive index of distilled water
//               from the near-infrared region to the ultraviolet region", Appl. Opt. 46, 3811
//               (2007), four-term Sellmeier at 20 °C, 0.182–1.129 µm (n_D = 1.3330).
//   chitin:     H. L. Leertouwer, B. D. Wilts, D. G. Stavenga, "Refractive index and dispersion of
//               butterfly chitin and bird keratin measured by polarizing interference microscopy",
//               Opt. Express 19, 24061 (2011): Cauchy n = A + B/λ², A = 1.517, B = 8.80·10³ nm²
//               (1.572, 1.552, 1.541 at 400, 500, 600 nm), measured over 400–700 nm (theory §4.5
//               uses 1.55).
//   Cu2O:       cuprous oxide (cuprite; the film on tarnished copper and the bornite ore of the
//               paper's Fig. 1): the SOPRA S.A. optical-constants database, file CU2O.MAT
//               (n, κ at 75 wavelengths, 295–2480 nm; as distributed with the Solcore project),
//               interpolated linearly in wavelength, clamped outside. Absorbing in the blue
//               (κ ≈ 0.99 at 400 nm, 0.19 at 551 nm, 0.06 at 800 nm), n ≈ 3.1 at 500 nm.
// Outside the band of a dispersion formula, its value at the nearer end is used
// (core/spectrum/dispersion.h). All glasses and liquids here are lossless (κ = 0).
#pragma once

#include <algorithm>
#include <array>
#include <iterator>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/spectrum/dispersion.h"

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
    // The first row at or above e (binary search: the kernels ask at every node and facet).
    const std::size_t i = std::size_t(
        std::lower_bound(std::begin(t) + 1, std::end(t), e, [](const auto &row, double v) { return row.e < v; }) -
        std::begin(t));
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

constexpr double Um = 1e-6, Um2 = 1e-12;  // µm and µm² in SI

// Sellmeier fits: B_j, C_j [µm²] as published, and the band [µm] they were made on.
inline Complex Bk7Index(double lambda) {
    static const double b[] = {1.03961212, 0.231792344, 1.01046945};
    static const double c[] = {0.00600069867 * Um2, 0.0200179144 * Um2, 103.560653 * Um2};
    return dispersion::Sellmeier(lambda, b, c, 0.3 * Um, 2.5 * Um);
}
inline Complex FusedSilicaIndex(double lambda) {
    static const double b[] = {0.6961663, 0.4079426, 0.8974794};
    static const double c[] = {Sqr(0.0684043) * Um2, Sqr(0.1162414) * Um2, Sqr(9.896161) * Um2};
    return dispersion::Sellmeier(lambda, b, c, 0.21 * Um, 3.71 * Um);
}
inline Complex MgF2Index(double lambda) {
    static const double b[] = {0.48755108, 0.39875031, 2.3120353};
    static const double c[] = {Sqr(0.04338408) * Um2, Sqr(0.09461442) * Um2, Sqr(23.793604) * Um2};
    return dispersion::Sellmeier(lambda, b, c, 0.2 * Um, 7.0 * Um);
}
inline Complex WaterIndex(double lambda) {
    static const double b[] = {5.684027565e-1, 1.726177391e-1, 2.086189578e-2, 1.130748688e-1};
    static const double c[] = {5.101829712e-3 * Um2, 1.821153936e-2 * Um2, 2.620722293e-2 * Um2,
                               1.069792721e1 * Um2};
    return dispersion::Sellmeier(lambda, b, c, 0.182 * Um, 1.129 * Um);
}
// DeVore's rutile formula (a constant background and one resonance, not Sellmeier's form).
inline Complex TiO2Index(double lambda) {
    const double l2 = Sqr(Clamp(lambda, 0.43 * Um, 1.53 * Um) / Um);  // µm²
    return std::sqrt(5.913 + 0.2441 / (l2 - 0.0803));
}
inline Complex ChitinIndex(double lambda) {
    return dispersion::Cauchy(lambda, 1.517, 8.80e3 * 1e-18, 0, 0.4 * Um, 0.7 * Um);
}

// SOPRA CU2O.MAT: λ [nm], n, κ.
struct NkRow {
    double lambdaNm, n, k;
};
inline constexpr NkRow Cu2OTable[] = {
    {295.20, 1.97885, 1.87676}, {298.76, 1.99401, 1.85723}, {302.40, 2.01278, 1.83512},
    {306.14, 2.03492, 1.81051}, {309.96, 2.06021, 1.7835}, {313.89, 2.08844, 1.75418},
    {317.91, 2.11937, 1.72264}, {322.04, 2.15279, 1.68896}, {326.28, 2.18847, 1.65325},
    {330.63, 2.22618, 1.61559}, {335.10, 2.26571, 1.57607}, {339.69, 2.30683, 1.53478},
    {344.40, 2.34931, 1.49182}, {349.25, 2.39293, 1.44727}, {354.24, 2.43747, 1.40123},
    {359.38, 2.48270, 1.35378}, {364.66, 2.52841, 1.30502}, {370.11, 2.57436, 1.25504},
    {375.71, 2.62034, 1.20393}, {381.49, 2.66611, 1.15178}, {387.45, 2.71146, 1.09868},
    {393.60, 2.75617, 1.04472}, {399.95, 2.80000, 0.99}, {406.51, 2.84520, 0.931971},
    {413.28, 2.88866, 0.873808}, {420.29, 2.92990, 0.815873}, {427.54, 2.96844, 0.758531},
    {435.04, 3.00380, 0.702145}, {442.80, 3.03551, 0.647078}, {450.86, 3.06254, 0.593956},
    {459.20, 3.08137, 0.544624}, {467.87, 3.09623, 0.49716}, {476.87, 3.10732, 0.451581},
    {486.22, 3.11489, 0.407908}, {495.94, 3.11916, 0.366157}, {506.06, 3.12144, 0.324937},
    {516.60, 3.12120, 0.285244}, {527.60, 3.11748, 0.248678}, {539.07, 3.11004, 0.215848},
    {551.05, 3.09867, 0.187747}, {563.57, 3.08304, 0.167556}, {576.68, 3.06309, 0.1511},
    {590.41, 3.03867, 0.137625}, {604.81, 3.00765, 0.126046}, {619.93, 2.96953, 0.115553},
    {635.82, 2.93087, 0.106566}, {652.55, 2.89540, 0.09885}, {670.19, 2.86855, 0.092196},
    {688.81, 2.84388, 0.086246}, {708.49, 2.82001, 0.080571}, {729.32, 2.79539, 0.074987},
    {751.43, 2.76796, 0.069686}, {774.91, 2.73311, 0.064633}, {799.90, 2.70000, 0.06},
    {826.57, 2.67644, 0.055959}, {855.07, 2.65635, 0.052422}, {885.61, 2.63745, 0.049348},
    {918.41, 2.62139, 0.046008}, {953.73, 2.60902, 0.042744}, {991.88, 2.60120, 0.040443},
    {1033.21, 2.59590, 0.037691}, {1078.13, 2.59181, 0.034515}, {1127.14, 2.58731, 0.031347},
    {1180.81, 2.58195, 0.02815}, {1239.85, 2.57522, 0.024451}, {1305.11, 2.56987, 0.020754},
    {1377.61, 2.56977, 0.017827}, {1458.65, 2.57005, 0.014585}, {1549.81, 2.56923, 0.011237},
    {1653.14, 2.56696, 0.008159}, {1771.22, 2.56412, 0.005417}, {1907.46, 2.56136, 0.003119},
    {2066.42, 2.55930, 0.001376}, {2254.28, 2.55857, 0.000296}, {2479.70, 2.55980, 1.2e-05},
};
inline Complex Cu2OIndex(double lambda) {
    const double nm = lambda * 1e9;
    const auto &t = Cu2OTable;
    const std::size_t count = std::size(t);
    if (!(nm > t[0].lambdaNm)) return {t[0].n, t[0].k};
    if (nm >= t[count - 1].lambdaNm) return {t[count - 1].n, t[count - 1].k};
    const std::size_t i = std::size_t(std::lower_bound(std::begin(t) + 1, std::end(t), nm,
                                                       [](const NkRow &row, double v) { return row.lambdaNm < v; }) -
                                      std::begin(t));
    const double f = (nm - t[i - 1].lambdaNm) / (t[i].lambdaNm - t[i - 1].lambdaNm);
    return {(1 - f) * t[i - 1].n + f * t[i].n, (1 - f) * t[i - 1].k + f * t[i].k};
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
        {"SiO2", "amorphous silica (coating layers), Malitson 1965 (Sellmeier)", glass_detail::FusedSilicaIndex},
        {"MgF2", "magnesium fluoride, ordinary ray, Dodge 1984 (Sellmeier)", glass_detail::MgF2Index},
        {"TiO2", "titanium dioxide (rutile), ordinary ray, DeVore 1951", glass_detail::TiO2Index},
        {"Cu2O", "cuprous oxide, SOPRA database (absorbing in the blue)", glass_detail::Cu2OIndex},
        {"water", "water at 20 °C, Daimon & Masumura 2007 (Sellmeier)", glass_detail::WaterIndex},
        {"chitin", "insect chitin, Leertouwer et al. 2011 (Cauchy)", glass_detail::ChitinIndex},
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
