// SPDX-License-Identifier: Apache-2.0
// phasor — sampled wavelengths, spectrum evaluation at them, and Planck's law (spectrum.h).
#include "core/spectrum/spectrum.h"

#include <cmath>
#include <cstdio>

namespace phasor {

// ---- SampledWavelengths -------------------------------------------------------------------

void SampledWavelengths::TerminateSecondary() {
    if (SecondaryTerminated()) return;
    // The film averages L/pdf over all NumWavelengths entries and skips those with pdf 0
    // (film.cpp). Keeping only the hero therefore needs its pdf divided by NumWavelengths so
    // that the average still estimates the integral without bias (theory §0 D10; the same
    // bookkeeping as pbrt-v4's hero wavelength termination).
    for (int i = 1; i < NumWavelengths; ++i) pdf[i] = 0;
    pdf[0] /= NumWavelengths;
}

bool SampledWavelengths::SecondaryTerminated() const {
    if (delta) return true;  // a line sample never carries companions
    for (int i = 1; i < NumWavelengths; ++i)
        if (pdf[i] != 0) return false;
    return true;
}

// ---- Spectrum -----------------------------------------------------------------------------

SampledSpectrum Spectrum::Sample(const SampledWavelengths &wl) const {
    SampledSpectrum s;
    for (int i = 0; i < wl.Count(); ++i) s[i] = Eval(wl.lambda[i]);
    return s;
}

namespace {

// A line matches a delta sample if the wavelengths agree to round-off (the sampler copies the
// line wavelength verbatim, so this only guards against a float round trip).
bool SameWavelength(double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(a, b); }

}  // namespace

SampledSpectrum EvalEmission(const Spectrum &s, const SampledWavelengths &wl) {
    SampledSpectrum r;
    if (std::optional<double> line = s.LineWavelength()) {
        // A discrete line only exists for a delta sample at its own wavelength; its value there is
        // the line's integrated strength (theory §0 D10).
        if (wl.delta && SameWavelength(wl.lambda[0], *line)) r[0] = s.Eval(*line);
        return r;
    }
    // A continuous spectrum has no mass at a single wavelength: a delta sample estimates only the
    // lines, the continuous samples only the continuum (the sampler picks one or the other).
    if (wl.delta) return r;
    for (int i = 0; i < NumWavelengths; ++i) r[i] = s.Eval(wl.lambda[i]);
    return r;
}

std::string ConstantSpectrum::ToString() const {
    char buf[64];
    std::snprintf(buf, sizeof buf, "constant(%.17g)", c_);
    return buf;
}

// ---- Planck's law -------------------------------------------------------------------------

double Blackbody(double lambda, double T) {
    if (!(lambda > 0) || !(T > 0)) return 0;
    // Planck's law, spectral radiance per unit wavelength:
    //   B(λ, T) = 2hc² / λ⁵ / (exp(hc / (λ k T)) − 1)   [W/(m²·sr·m)]
    // with the exact SI 2019 constants.
    constexpr double h = 6.62607015e-34;  // Planck constant [J·s]
    constexpr double c = 299792458.0;     // speed of light [m/s]
    constexpr double kB = 1.380649e-23;   // Boltzmann constant [J/K]
    const double x = h * c / (lambda * kB * T);
    const double denom = std::expm1(x);
    if (!std::isfinite(denom)) return 0;  // deep Wien tail underflows to 0
    const double l2 = lambda * lambda;
    return 2 * h * c * c / (l2 * l2 * lambda) / denom;
}

}  // namespace phasor
