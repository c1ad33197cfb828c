// SPDX-License-Identifier: Apache-2.0
// `point`: an isotropic point source (delta position). Emitted spectral intensity
// I(λ) = intensity · spectrum(λ) [W/sr per unit of the response-normalised wavelength measure].
#include "core/light.h"
#include "core/registry.h"

namespace phasor {

class PointLight final : public Light {
  public:
    PointLight(Vec3 p, double intensity, std::shared_ptr<const Spectrum> s)
        : p_(p), intensity_(intensity), spectrum_(std::move(s)) {}

    static const Schema &GetSchema() {
        static const Schema s{"light", "point", "Isotropic point source.",
                              {P::Vector("position", "position", Dim::Length()).Default(Value::Vector({0, 0, 0}, Dim::Length())),
                               P::Number("intensity", "radiant intensity scale", Dim::Intensity())
                                   .Default(Value::Number(1, Dim::Intensity()))
                                   .Min(0),
                               P::Spectrum("spectrum", "spectral shape").Default(Value::Number(1))}};
        return s;
    }
    static std::unique_ptr<Light> Create(const ParamDict &d, BuildContext &ctx) {
        return std::make_unique<PointLight>(d.GetVector("position"), d.GetNumber("intensity"),
                                            ctx.GetSpectrum(d, "spectrum"));
    }

    std::optional<LightSample> SampleLi(const LightSampleContext &ctx, const Vec2 &,
                                        const SampledWavelengths &wl) const override {
        Vec3 d = p_ - ctx.p;
        double r2 = LengthSquared(d);
        if (!(r2 > 0)) return std::nullopt;
        double r = std::sqrt(r2);
        // Irradiance normal to wi: I / r² (inverse-square law).
        return LightSample{EvalEmission(*spectrum_, wl) * (intensity_ / r2), d / r, r, 1.0, true};
    }
    double PdfLi(const LightSampleContext &, const Vec3 &, const Vec3 &, const Vec3 &) const override { return 0; }
    bool IsDelta() const override { return true; }
    const Spectrum &EmissionSpectrum() const override { return *spectrum_; }
    double PowerScale() const override { return 4 * Pi * intensity_; }
    std::string ToString() const override {
        return "point { position = " + phasor::ToString(p_) + ", intensity = " + std::to_string(intensity_) +
               ", spectrum = " + spectrum_->ToString() + " }";
    }

  private:
    Vec3 p_;
    double intensity_;
    std::shared_ptr<const Spectrum> spectrum_;
};

PHASOR_EXPORT_PLUGIN(Light, PointLight)

}  // namespace phasor
