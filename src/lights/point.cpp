// SPDX-License-Identifier: Apache-2.0
// `point`: an isotropic point source (delta position). `intensity` is the total radiant intensity
// over the spectrum, whose shape is normalised (lights/strength.h): I(λ) = intensity ·
// spectrum(λ) / ∫spectrum dλ [W/sr per m].
// Generalized rays measure it in closed form as a coherent spherical wave (point_like.h).
#include "lights/point_like.h"
#include "core/render/registry.h"

namespace phasor {

class PointLight final : public PointLikeLight {
  public:
    PointLight(Vec3 p, LightEmission emission) : PointLikeLight(p, std::move(emission)) {}

    static const Schema &GetSchema() {
        static const Schema s{"light", "point", "Isotropic point source.",
                              {P::Vector("position", "position", Dim::Length()).Default(Value::Vector({0, 0, 0}, Dim::Length())),
                               P::Number("intensity", "radiant intensity, the total over the spectrum",
                                         Dim::Intensity())
                                   .Default(Value::Number(1, Dim::Intensity()))
                                   .Min(0)
                                   .Max(MaxLightStrength),
                               P::Spectrum("spectrum", "spectral shape (normalised to unit integral unless normalize_spectrum = false)").Default(Value::Number(1)),
                               NormalizeSpectrumParam()}};
        return s;
    }
    static std::unique_ptr<Light> Create(const ParamDict &d, BuildContext &ctx) {
        return std::make_unique<PointLight>(d.GetVector("position"),
                                            ReadLightEmission(d, ctx, "point", "intensity", true));
    }

    double Falloff(const Vec3 &) const override { return 1; }
    bool IsIsotropic() const override { return true; }
    double PowerScale() const override { return 4 * Pi * scale_; }
    std::string ToString() const override {
        return "point { position = " + phasor::ToString(p_) + ", intensity scale = " + std::to_string(scale_) +
               " W/sr per m" +
               ", spectrum = " + spectrum_->ToString() + " }";
    }
};

PHASOR_EXPORT_PLUGIN(Light, PointLight)

}  // namespace phasor
