// SPDX-License-Identifier: Apache-2.0
// phasor — helpers shared by the light plug-ins that generalized rays measure in closed form
// (theory §2.4, §0 D4a, D14): per-wavelength evaluation of the Eq. 24 overlaps and the spectral
// normalisation of lights whose strength is given as a total ("spectrum gives the shape").
#pragma once

#include <cmath>
#include <optional>

#include "core/render/genray.h"
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

/// Factor turning a spectral shape into a spectrum of the given total: total / ∫S dλ.
inline double TotalScale(const Spectrum &s, double total) {
    const double integral = SpectrumIntegral(s);
    return integral > 0 ? total / integral : 0;
}

/// A `spectrum` parameter that only gives the shape of a total (irradiance, power): its integral
/// must be positive. `light` names the plug-in in the error.
inline std::shared_ptr<const Spectrum> ShapeSpectrumParam(const ParamDict &d, BuildContext &ctx,
                                                          const char *light) {
    auto spectrum = ctx.GetSpectrum(d, "spectrum");
    if (!(SpectrumIntegral(*spectrum) > 0))
        throw Error(d.Loc("spectrum"), std::string("the spectrum of a ") + light + " must have a positive integral");
    return spectrum;
}

/// A direction parameter: must not be zero; returned as given (callers normalise).
inline Vec3 DirectionParam(const ParamDict &d, const char *name) {
    Vec3 dir = d.GetVector(name);
    if (!(Length(dir) > 0)) throw Error(d.Loc(name), std::string("'") + name + "' must not be zero");
    return dir;
}

/// value[i] = k_i²·f(g_i)·emission[i] for each carried wavelength (radiance units, theory §0 D4).
template <typename F>
SampledSpectrum MeasurePerWavelength(const SpectralGenRay &g, const SampledSpectrum &emission, F &&f) {
    SampledSpectrum v(0.0);
    for (int i = 0; i < g.count; ++i)
        if (emission[i] != 0) {
            const GenRay gi = g.At(i);
            v[i] = gi.k * gi.k * f(gi) * emission[i];
        }
    return v;
}

/// The closed forms of a light at infinity with direction of travel `s`, per-wavelength
/// irradiance `e` (normal to s) and either a disc of half-angle alpha or a Gaussian of angular
/// covariance omega·I (alpha = omega = 0: a coherent plane wave).
inline std::optional<GrMeasurement> MeasureDistantGR(const SpectralGenRay &g, const Vec3 &s,
                                                     const SampledSpectrum &e, bool disc, double alpha,
                                                     double omega) {
    if (Dot(s, g.d) <= 0) return std::nullopt;
    GrMeasurement m;
    m.value = MeasurePerWavelength(g, e, [&](const GenRay &gi) {
        return disc ? MeasureDistantDisc(gi, s, 1.0, alpha) : MeasureDistantGaussian(gi, s, 1.0, omega);
    });
    m.wi = -s;
    m.dist = Infinity;
    if (disc && alpha > 0) m.profile = AngularProfile::Disc(std::sin(alpha));
    else if (!disc && omega > 0) m.profile = AngularProfile::Gaussian(omega);
    return m;
}

/// D4a for a light at infinity: the exact own-frame integral of the plane-wave measurement over the
/// hemisphere about s, E·(1 − e^{−β²k²}) (theory §0 D4); a distant source's angular profile only
/// widens the arrival directions (angularVariance += Ω) and is reported as `profile` (D15).
inline GrIncidence DistantIncidence(const SpectralGenRay &g, const Vec3 &s, const SampledSpectrum &e,
                                    double omega, const AngularProfile &profile = {}) {
    GrIncidence inc;
    inc.irradiance = SampledSpectrum(0.0);
    for (int i = 0; i < g.count; ++i) {
        const GenRay gi = g.At(i);
        inc.irradiance[i] = e[i] * -std::expm1(-gi.beta2 * gi.k * gi.k);
    }
    const GenRay g0 = g.At(0);
    inc.wi = -s;
    inc.dist = Infinity;
    inc.angularVariance = g0.AngularVariance() + omega;
    inc.profile = profile;
    return inc;
}

}  // namespace phasor
