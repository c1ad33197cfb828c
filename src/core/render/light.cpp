// SPDX-License-Identifier: Apache-2.0
#include "core/render/light.h"

namespace phasor {

SampledSpectrum Light::L(const Vec3 &, const Vec3 &, const Vec3 &, const SampledWavelengths &) const {
    return SampledSpectrum(0.0);
}

SampledSpectrum Light::Le(const Vec3 &, const SampledWavelengths &) const { return SampledSpectrum(0.0); }

std::optional<GrMeasurement> Light::MeasureGR(const SpectralGenRay &, const SampledWavelengths &) const {
    return std::nullopt;
}

std::optional<GrIncidence> Light::IncidenceOnGR(const SpectralGenRay &, const SampledWavelengths &) const {
    return std::nullopt;
}

LightCoherence Light::Coherence(const Vec3 &) const { return LightCoherence{}; }

const char *Describe(LightType t) {
    switch (t) {
        case LightType::DeltaPosition: return "delta position";
        case LightType::DeltaDirection: return "delta direction";
        case LightType::Distant: return "distant";
        case LightType::Area: return "area";
    }
    return "?";
}

double SceneCrossSection(const Bounds3 &b) {
    const double r = b.Empty() ? 1 : 0.5 * Length(b.Diagonal());
    return Pi * r * r;
}

}  // namespace phasor
