// SPDX-License-Identifier: Apache-2.0
// phasor — what a light's strength means, the same for every light (docs/wscene.md "Lights"):
// its strength parameter (area `radiance` W/m²/sr, point and spot `intensity` W/sr, plane_wave,
// distant and directional `irradiance` W/m², gaussian_beam `power` W) is the total over its
// spectrum, whose shape is normalised to unit integral: the spectral distribution is
// strength · spectrum(λ) / ∫spectrum dλ [unit per metre of wavelength]. A line carries all of it.
// `normalize_spectrum = false` reads the spectrum as absolute instead: strength · spectrum(λ) per
// metre of wavelength (a blackbody(T, normalize = false) emitter of emissivity `strength`).
//
// In a `wscene 1` file the strengths of area, point, spot and directional lights scaled their
// spectrum (the second meaning); such a light is a located error naming the equivalent total,
// unless both meanings agree (a spectrum of unit integral, e.g. a line of power 1).
#pragma once

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "core/render/registry.h"
#include "core/spectrum/spectrum.h"

namespace phasor {

/// ∫ S(λ) dλ [m·(unit of S)]: a line's strength, else Simpson's rule over the support (an
/// unbounded side is replaced by the 360–830 nm band, as the wavelength sampler does).
inline double SpectrumIntegral(const Spectrum &s) {
    if (auto line = s.LineWavelength()) return s.Eval(*line);
    auto [a, b] = s.Support();
    if (!(a > 0) || !std::isfinite(a)) a = 360e-9;
    if (!std::isfinite(b)) b = 830e-9;
    if (!(b > a)) return 0;
    const int n = 20000;  // even; ≤ 0.05 nm steps over the visible band
    const double h = (b - a) / n;
    double sum = s.Eval(a) + s.Eval(b);
    for (int i = 1; i < n; ++i) sum += s.Eval(a + i * h) * (i % 2 ? 4 : 2);
    return sum * h / 3;
}

/// A light strength as a scene writes it, to 6 significant digits with an SI prefix on its watts
/// ("3.91721 uW/m^2/sr").
inline std::string StrengthText(double v, Dim dim) {
    const std::string full = Value::Number(1, dim).ToString();  // "1 W/m^2/sr"
    const std::string unit = full.substr(full.find(' ') + 1);
    double scale = 1;
    std::string prefix;
    if (std::abs(v) < 1)  // the largest prefix not above the value: 1 ≤ |v|/scale < 1000
        for (const auto &[f, p] : {std::pair<double, const char *>{1e-3, "m"}, {1e-6, "u"}, {1e-9, "n"}, {1e-12, "p"}})
            if (std::abs(v) >= f) {
                scale = f;
                prefix = p;
                break;
            }
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.6g ", v / scale);
    return buf + prefix + unit;
}

/// The `normalize_spectrum` parameter every light has.
inline ParamSpec NormalizeSpectrumParam() {
    return P::Bool("normalize_spectrum",
                   "true: the strength is the total over the spectrum, whose shape is normalised to unit integral; "
                   "false: the spectral distribution is strength × spectrum(λ) per metre of wavelength")
        .Default(Value::Bool(true));
}

/// A light's spectrum and the factor its values are multiplied by: the spectral distribution is
/// scale · spectrum(λ) [strength's unit per metre of wavelength].
struct LightEmission {
    std::shared_ptr<const Spectrum> spectrum;
    double scale = 0;
};

/// Reads `spectrum`, `normalize_spectrum` and the strength parameter `strength` of light type
/// `light`. `scaledInVersion1`: the strength scaled the spectrum in `wscene 1` files (area,
/// point, spot, directional), so such a file is refused at the strength with the equivalent
/// total (see the file comment). Throws phasor::Error at the parameter.
inline LightEmission ReadLightEmission(const ParamDict &d, BuildContext &ctx, const char *light,
                                       const char *strength, bool scaledInVersion1) {
    LightEmission e;
    e.spectrum = ctx.GetSpectrum(d, "spectrum");
    const double value = d.GetNumber(strength);
    const bool normalize = d.GetBool("normalize_spectrum");
    if (!normalize) {
        e.scale = value;
        return e;
    }
    const double integral = SpectrumIntegral(*e.spectrum);
    if (!(integral > 0))
        throw Error(d.Loc("spectrum"), std::string("the spectrum of a ") + light +
                                           " light must have a positive integral (its shape is normalised to 1)");
    if (scaledInVersion1 && d.FormatVersion() == 1 && !d.Has("normalize_spectrum") &&
        std::abs(integral - 1) > 1e-9) {
        const Dim dim = d.GetSchema() ? d.GetSchema()->Find(strength)->dim : Dim::None();
        const bool vowel = std::string("aeiou").find(light[0]) != std::string::npos;
        throw Error(d.Loc(strength),
                    std::string("in a 'wscene 1' file the '") + strength + "' of " + (vowel ? "an " : "a ") + light +
                        " light scaled its spectrum (" + StrengthText(value, dim) +
                        " × spectrum(λ) per metre of wavelength); from 'wscene 2' on it is the total over the "
                        "spectrum, like every light's. The same light is '" + strength + " = " +
                        StrengthText(value * integral, dim) +
                        "' (the old value × ∫spectrum dλ), or keep the old meaning with "
                        "'normalize_spectrum = false'; then make the file's header 'wscene 2'");
    }
    e.scale = value / integral;
    return e;
}

}  // namespace phasor
