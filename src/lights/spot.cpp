// SPDX-License-Identifier: Apache-2.0
// `spot`: a point source emitting into a cone, with a smooth falloff between
// cone_angle − cone_delta and cone_angle (smoothstep in cosθ, as in pbrt). Generalized rays
// measure it like `point` (theory §2.4 item 5) times the falloff towards the receiver.
#include "lights/point_like.h"
#include "core/render/registry.h"

namespace phasor {

class SpotLight final : public PointLikeLight {
  public:
    SpotLight(Vec3 from, Vec3 to, double cone, double delta, LightEmission emission)
        : PointLikeLight(from, std::move(emission)), dir_(Normalize(to - from)), cosMax_(std::cos(cone)),
          cosStart_(std::cos(std::max(0.0, cone - delta))) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "light", "spot", "Point source restricted to a cone with a smooth edge.",
            {P::Vector("from", "position", Dim::Length()).Default(Value::Vector({0, 0, 0}, Dim::Length())),
             P::Vector("to", "a point the cone axis passes through", Dim::Length())
                 .Default(Value::Vector({0, 0, 1}, Dim::Length())),
             P::Angle("cone_angle", "half-angle of the cone").Default(Value::Number(Radians(30), Dim::Angle())).Min(0, true).Max(Pi),
             P::Angle("cone_delta", "width of the smooth edge").Default(Value::Number(Radians(5), Dim::Angle())).Min(0),
             P::Number("intensity", "radiant intensity on the axis, the total over the spectrum", Dim::Intensity())
                 .Default(Value::Number(1, Dim::Intensity()))
                 .Min(0)
                 .Max(MaxLightStrength),
             P::Spectrum("spectrum", "spectral shape (normalised to unit integral unless normalize_spectrum = false)").Default(Value::Number(1)),
             NormalizeSpectrumParam()}};
        return s;
    }
    static std::unique_ptr<Light> Create(const ParamDict &d, BuildContext &ctx) {
        Vec3 from = d.GetVector("from"), to = d.GetVector("to");
        if (!(Length(to - from) > 0)) throw Error(d.Loc("to"), "'to' must differ from 'from'");
        return std::make_unique<SpotLight>(from, to, d.GetNumber("cone_angle"), d.GetNumber("cone_delta"),
                                           ReadLightEmission(d, ctx, "spot", "intensity", true));
    }

    /// For the light contract suite: the default cone, and a narrow one off the axes.
    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(2);
        p[1].Set("from", Value::Vector({0.1, 0.2, 0.8}, Dim::Length()))
            .Set("to", Value::Vector({0, 0, 0}, Dim::Length()))
            .Set("cone_angle", Value::Number(Radians(10), Dim::Angle()))
            .Set("cone_delta", Value::Number(Radians(3), Dim::Angle()));
        return p;
    }

    double Falloff(const Vec3 &w) const override {
        const double cosTheta = Dot(w, dir_);
        if (cosTheta >= cosStart_) return 1;
        if (cosTheta <= cosMax_) return 0;
        double t = (cosTheta - cosMax_) / (cosStart_ - cosMax_);
        return t * t * (3 - 2 * t);
    }
    double PowerScale() const override { return scale_ * 2 * Pi * (1 - 0.5 * (cosStart_ + cosMax_)); }
    std::string ToString() const override { return "spot { position = " + phasor::ToString(p_) + " }"; }

  private:
    Vec3 dir_;
    double cosMax_, cosStart_;
};

PHASOR_EXPORT_PLUGIN(Light, SpotLight)

}  // namespace phasor
