// SPDX-License-Identifier: Apache-2.0
// `spot`: a point source emitting into a cone, with a smooth falloff between
// cone_angle − cone_delta and cone_angle (smoothstep in cosθ, as in pbrt). Generalized rays
// measure it like `point` (theory §2.4 item 5) times the falloff towards the receiver.
#include "core/light.h"
#include "core/lights/closed_form.h"
#include "core/registry.h"

namespace phasor {

class SpotLight final : public Light {
  public:
    SpotLight(Vec3 from, Vec3 to, double cone, double delta, double intensity, std::shared_ptr<const Spectrum> s)
        : p_(from), dir_(Normalize(to - from)), cosMax_(std::cos(cone)),
          cosStart_(std::cos(std::max(0.0, cone - delta))), intensity_(intensity), spectrum_(std::move(s)) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "light", "spot", "Point source restricted to a cone with a smooth edge.",
            {P::Vector("from", "position", Dim::Length()).Default(Value::Vector({0, 0, 0}, Dim::Length())),
             P::Vector("to", "a point the cone axis passes through", Dim::Length())
                 .Default(Value::Vector({0, 0, 1}, Dim::Length())),
             P::Angle("cone_angle", "half-angle of the cone").Default(Value::Number(Radians(30), Dim::Angle())).Min(0, true).Max(Pi),
             P::Angle("cone_delta", "width of the smooth edge").Default(Value::Number(Radians(5), Dim::Angle())).Min(0),
             P::Number("intensity", "radiant intensity on the axis", Dim::Intensity())
                 .Default(Value::Number(1, Dim::Intensity()))
                 .Min(0),
             P::Spectrum("spectrum", "spectral shape").Default(Value::Number(1))}};
        return s;
    }
    static std::unique_ptr<Light> Create(const ParamDict &d, BuildContext &ctx) {
        Vec3 from = d.GetVector("from"), to = d.GetVector("to");
        if (!(Length(to - from) > 0)) throw Error(d.Loc("to"), "'to' must differ from 'from'");
        return std::make_unique<SpotLight>(from, to, d.GetNumber("cone_angle"), d.GetNumber("cone_delta"),
                                           d.GetNumber("intensity"), ctx.GetSpectrum(d, "spectrum"));
    }

    double Falloff(double cosTheta) const {
        if (cosTheta >= cosStart_) return 1;
        if (cosTheta <= cosMax_) return 0;
        double t = (cosTheta - cosMax_) / (cosStart_ - cosMax_);
        return t * t * (3 - 2 * t);
    }
    std::optional<LightSample> SampleLi(const LightSampleContext &ctx, const Vec2 &,
                                        const SampledWavelengths &wl) const override {
        Vec3 d = p_ - ctx.p;
        double r2 = LengthSquared(d);
        if (!(r2 > 0)) return std::nullopt;
        double r = std::sqrt(r2);
        Vec3 wi = d / r;
        double f = Falloff(Dot(-wi, dir_));
        if (f == 0) return std::nullopt;
        return LightSample{EvalEmission(*spectrum_, wl) * (intensity_ * f / r2), wi, r, 1.0, true};
    }
    double PdfLi(const LightSampleContext &, const Vec3 &, const Vec3 &, const Vec3 &) const override { return 0; }
    bool IsDelta() const override { return true; }
    bool MeasuredInClosedForm() const override { return true; }
    std::optional<GrMeasurement> MeasureGR(const SpectralGenRay &g,
                                           const SampledWavelengths &wl) const override {
        const Vec3 toLight = p_ - g.o;
        const double r = Length(toLight);
        if (!(r > 0)) return std::nullopt;
        const double f = Falloff(Dot(-toLight / r, dir_));
        if (f == 0) return std::nullopt;
        GrMeasurement m;
        m.value = MeasurePerWavelength(g, EvalEmission(*spectrum_, wl) * (intensity_ * f),
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
        const double f = Falloff(Dot(-toLight / r, dir_));
        if (f == 0) return std::nullopt;
        GrIncidence inc;
        inc.irradiance = EvalEmission(*spectrum_, wl) * (intensity_ * f / r2);
        inc.wi = toLight / r;
        inc.dist = r;
        const GenRay g0 = g.At(0);
        const double beta = std::sqrt(g0.beta2), a = beta * g0.k / r - g0.rho / beta;
        inc.angularVariance = (1 + a * a * g0.beta2) / (2 * g0.beta2 * g0.k * g0.k);
        return inc;
    }
    LightCoherence Coherence(const Vec3 &p) const override { return LightCoherence{Normalize(p_ - p), 0}; }
    const Spectrum &EmissionSpectrum() const override { return *spectrum_; }
    double PowerScale() const override { return intensity_ * 2 * Pi * (1 - 0.5 * (cosStart_ + cosMax_)); }
    std::string ToString() const override { return "spot { position = " + phasor::ToString(p_) + " }"; }

  private:
    Vec3 p_, dir_;
    double cosMax_, cosStart_, intensity_;
    std::shared_ptr<const Spectrum> spectrum_;
};

PHASOR_EXPORT_PLUGIN(Light, SpotLight)

}  // namespace phasor
