// SPDX-License-Identifier: Apache-2.0
// `point`: an isotropic point source (delta position). Emitted spectral intensity
// I(λ) = intensity · spectrum(λ) [W/sr per unit of the response-normalised wavelength measure].
// Generalized rays measure it in closed form as a coherent spherical wave (point_like.h).
#include "lights/point_like.h"
#include "core/render/registry.h"

namespace phasor {

class PointLight final : public PointLikeLight {
  public:
    PointLight(Vec3 p, double intensity, std::shared_ptr<const Spectrum> s)
        : PointLikeLight(p, intensity, std::move(s)) {}

    static const Schema &GetSchema() {
        static const Schema s{"light", "point", "Isotropic point source.",
                              {P::Vector("position", "position", Dim::Length()).Default(Value::Vector({0, 0, 0}, Dim::Length())),
                               P::Number("intensity", "radiant intensity scale", Dim::Intensity())
                                   .Default(Value::Number(1, Dim::Intensity()))
                                   .Min(0)
                                   .Max(MaxLightStrength),
                               P::Spectrum("spectrum", "spectral shape").Default(Value::Number(1))}};
        return s;
    }
    static std::unique_ptr<Light> Create(const ParamDict &d, BuildContext &ctx) {
        return std::make_unique<PointLight>(d.GetVector("position"), d.GetNumber("intensity"),
                                            ctx.GetSpectrum(d, "spectrum"));
    }

    double Falloff(const Vec3 &) const override { return 1; }
    bool IsIsotropic() const override { return true; }
    double PowerScale() const override { return 4 * Pi * intensity_; }
    std::string ToString() const override {
        return "point { position = " + phasor::ToString(p_) + ", intensity = " + std::to_string(intensity_) +
               ", spectrum = " + spectrum_->ToString() + " }";
    }
};

PHASOR_EXPORT_PLUGIN(Light, PointLight)

}  // namespace phasor
