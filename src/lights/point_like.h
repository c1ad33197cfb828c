// SPDX-License-Identifier: Apache-2.0
// Shared implementation of the point-like lights (`point`, `spot`): a delta-position source of
// spectral intensity I(λ)·Falloff(direction), I(λ) = scale · spectrum(λ) (lights/strength.h). Next-event estimation is the inverse-square law;
// generalized rays measure it in closed form as a coherent spherical wave (theory §2.4 item 5,
// §0 D4a/D14): the overlap depends on how well the GR's curvature matches the wave's.
#pragma once

#include <memory>

#include "core/render/light.h"
#include "lights/closed_form.h"
#include "lights/strength.h"

namespace phasor {

class PointLikeLight : public Light {
  public:
    PointLikeLight(Vec3 p, LightEmission emission)
        : p_(p), scale_(emission.scale), spectrum_(std::move(emission.spectrum)) {}

    /// Relative intensity towards unit direction `w` (pointing away from the light), in [0, 1].
    virtual double Falloff(const Vec3 &w) const = 0;

    std::optional<LightSample> SampleLi(const LightSampleContext &ctx, const Vec2 &,
                                        const SampledWavelengths &wl) const override {
        Vec3 d = p_ - ctx.p;
        double r2 = LengthSquared(d);
        if (!(r2 > 0)) return std::nullopt;
        double r = std::sqrt(r2);
        Vec3 wi = d / r;
        double f = Falloff(-wi);
        if (f == 0) return std::nullopt;
        return LightSample{EvalEmission(*spectrum_, wl) * (scale_ * f / r2), wi, r, 1.0, true};
    }
    double PdfLi(const LightSampleContext &, const Vec3 &, const Vec3 &, const Vec3 &) const override { return 0; }
    LightType Type() const override { return LightType::DeltaPosition; }
    std::optional<GrMeasurement> MeasureGR(const SpectralGenRay &g,
                                           const SampledWavelengths &wl) const override {
        const Vec3 toLight = p_ - g.o;
        const double r = Length(toLight);
        if (!(r > 0)) return std::nullopt;
        const double f = Falloff(-toLight / r);
        if (f == 0) return std::nullopt;
        GrMeasurement m;
        m.value = MeasurePerWavelength(g, EvalEmission(*spectrum_, wl) * (scale_ * f),
                                       [&](const GenRay &gi) { return MeasurePointSource(gi, p_, 1.0); });
        m.wi = toLight / r;
        m.dist = r;
        return m;
    }
    std::optional<GrIncidence> IncidenceOnGR(const SpectralGenRay &g,
                                             const SampledWavelengths &wl) const override {
        // ∫d²k⊥ of theory §2.4 item 5 is exactly I/R² for any (β, ρ); the arrival directions
        // spread with variance (1 + a²β²)/(2β²k²), a = βk/R − ρ/β.
        const Vec3 toLight = p_ - g.o;
        const double r2 = LengthSquared(toLight), r = std::sqrt(r2);
        if (!(r > 0)) return std::nullopt;
        const double f = Falloff(-toLight / r);
        if (f == 0) return std::nullopt;
        GrIncidence inc;
        inc.irradiance = EvalEmission(*spectrum_, wl) * (scale_ * f / r2);
        inc.wi = toLight / r;
        inc.dist = r;
        const GenRay g0 = g.At(0);
        const double beta = std::sqrt(g0.beta2), a = beta * g0.k / r - g0.rho / beta;
        inc.angularVariance = (1 + a * a * g0.beta2) / (2 * g0.beta2 * g0.k * g0.k);
        return inc;
    }
    LightCoherence Coherence(const Vec3 &p) const override { return LightCoherence{Normalize(p_ - p), 0}; }
    /// The irradiance itself: I·Falloff·|cosθ|/d² (no estimate at the light's own position).
    double Reach(const LightSampleContext &ctx) const override {
        const Vec3 d = p_ - ctx.p;
        const double r2 = LengthSquared(d);
        if (!(r2 > 0)) return std::numeric_limits<double>::quiet_NaN();
        const Vec3 wi = d / std::sqrt(r2);
        return scale_ * Falloff(-wi) * ReceiverCosine(ctx.n, wi) / r2;
    }
    const Spectrum &EmissionSpectrum() const override { return *spectrum_; }

  protected:
    Vec3 p_;
    double scale_;  // I(λ) = scale_ · spectrum(λ) [W/sr per m]
    std::shared_ptr<const Spectrum> spectrum_;
};

}  // namespace phasor
