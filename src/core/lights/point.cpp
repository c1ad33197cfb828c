// SPDX-License-Identifier: Apache-2.0
// `point`: an isotropic point source (delta position). Emitted spectral intensity
// I(λ) = intensity · spectrum(λ) [W/sr per unit of the response-normalised wavelength measure].
// Generalized rays measure it in closed form as a coherent spherical wave (theory §2.4 item 5,
// §0 D4a/D14): the overlap depends on how well the GR's curvature matches the wave's.
#include "core/light.h"
#include "core/lights/closed_form.h"
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
    bool MeasuredInClosedForm() const override { return true; }
    std::optional<GrMeasurement> MeasureGR(const SpectralGenRay &g,
                                           const SampledWavelengths &wl) const override {
        const Vec3 toLight = p_ - g.o;
        const double r = Length(toLight);
        if (!(r > 0)) return std::nullopt;
        const double f = 1.0;
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
        const double f = 1.0;
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
