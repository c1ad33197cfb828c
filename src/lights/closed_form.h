// SPDX-License-Identifier: Apache-2.0
// phasor — helpers shared by the light plug-ins that generalized rays measure in closed form
// (theory §2.4, §0 D4a, D14): per-wavelength evaluation of the Eq. 24 overlaps (what a light's
// strength means: lights/strength.h).
#pragma once

#include <cmath>
#include <optional>

#include "core/render/genray.h"
#include "core/render/registry.h"
#include "core/spectrum/spectrum.h"

namespace phasor {

/// A direction parameter: must not be zero; returned as given (callers normalise).
inline Vec3 DirectionParam(const ParamDict &d, const char *name) {
    Vec3 dir = d.GetVector(name);
    if (!(Length(dir) > 0)) throw Error(d.Loc(name), std::string("'") + name + "' must not be zero");
    return dir;
}

/// value[i] = k_i²·f(g_i)·emission[i] for each carried wavelength g measures (radiance units,
/// theory §0 D4; 0 in the slots g.Measures not).
template <typename F>
SampledSpectrum MeasurePerWavelength(const SpectralGenRay &g, const SampledSpectrum &emission, F &&f) {
    SampledSpectrum v(0.0);
    for (int i = 0; i < g.count; ++i)
        if (emission[i] != 0 && g.Measures(i)) {
            const GenRay gi = g.At(i);
            v[i] = gi.k * gi.k * f(gi) * emission[i];
        }
    return v;
}

/// The closed forms of a light at infinity with direction of travel `s`, per-wavelength
/// irradiance `e` (normal to s) and either a disc of half-angle α (given as sinα) or a Gaussian of
/// angular covariance omega·I (sinα = omega = 0: a coherent plane wave).
inline std::optional<GrMeasurement> MeasureDistantGR(const SpectralGenRay &g, const Vec3 &s,
                                                     const SampledSpectrum &e, bool disc, double sinAlpha,
                                                     double omega) {
    if (Dot(s, g.d) <= 0) return std::nullopt;
    GrMeasurement m;
    if (disc && DistantDiscOutOfReach(g, s, sinAlpha)) m.value = SampledSpectrum(0.0);
    else
        m.value = MeasurePerWavelength(g, e, [&](const GenRay &gi) {
            return disc ? MeasureDistantDisc(gi, s, 1.0, sinAlpha) : MeasureDistantGaussian(gi, s, 1.0, omega);
        });
    m.wi = -s;
    m.dist = Infinity;
    if (disc && sinAlpha > 0) m.profile = AngularProfile::Disc(sinAlpha);
    else if (!disc && omega > 0) m.profile = AngularProfile::Gaussian(omega);
    return m;
}

/// D4a for a light at infinity: E, the plane wave's irradiance (normal to s), which a sensor turns
/// into the flux E·cosθ_s. The pixel's states summed over every label u ∈ ℝ² measure the flux
/// weighted by the pixel's Gaussian exactly (genray.h PixelState; docs/narrow_pixels.md) — the
/// own-frame integral of the plane-wave measurement over the propagating hemisphere alone,
/// E·(1 − e^{−β²k²}), leaves out the states labelled beyond it (19 % of E for a pixel of pitch
/// λ/2). A distant source's angular profile only widens the arrival directions
/// (angularVariance += Ω), which the sensor's acceptance and aim fractions use,
/// and is reported as `profile` (the plane waves a lobe's weight is averaged over, D15).
inline GrIncidence DistantIncidence(const SpectralGenRay &g, const Vec3 &s, const SampledSpectrum &e,
                                    double omega, const AngularProfile &profile = {}) {
    GrIncidence inc;
    inc.irradiance = e;
    const GenRay g0 = g.At(0);
    inc.wi = -s;
    inc.dist = Infinity;
    inc.angularVariance = g0.AngularVariance() + omega;
    inc.profile = profile;
    return inc;
}

}  // namespace phasor
