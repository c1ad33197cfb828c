// SPDX-License-Identifier: Apache-2.0
// `directional`: light from a single direction at infinity (delta direction), e.g. an idealised
// sun. `irradiance` is measured on a plane normal to the direction of travel. For generalized rays
// it is a coherent plane wave (theory §2.4 item 2), like `plane_wave`, but its strength is
// irradiance × spectrum(λ) rather than a total.
#include "core/render/light.h"
#include "lights/closed_form.h"
#include "core/render/registry.h"

namespace phasor {

class DirectionalLight final : public Light {
  public:
    DirectionalLight(Vec3 dir, double e, std::shared_ptr<const Spectrum> s)
        : dir_(Normalize(dir)), irradiance_(e), spectrum_(std::move(s)) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "light", "directional", "Parallel light from one direction (delta direction).",
            {P::Vector("direction", "direction in which the light travels").Default(Value::Vector({0, 0, -1})),
             P::Number("irradiance",
                       "irradiance scale normal to the direction: the light's spectral distribution is "
                       "irradiance × spectrum(λ) (a scale times a shape, as for point, spot and area lights) — not "
                       "a total as for plane_wave and distant, whose spectrum is normalised to unit integral",
                       Dim::Irradiance())
                 .Default(Value::Number(1, Dim::Irradiance()))
                 .Min(0)
                 .Max(MaxLightStrength),
             P::Spectrum("spectrum", "spectral shape").Default(Value::Number(1))}};
        return s;
    }
    static std::unique_ptr<Light> Create(const ParamDict &d, BuildContext &ctx) {
        Vec3 dir = DirectionParam(d, "direction");
        return std::make_unique<DirectionalLight>(dir, d.GetNumber("irradiance"), ctx.GetSpectrum(d, "spectrum"));
    }

    /// For the light contract suite: the default and an oblique direction.
    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(2);
        p[1].Set("direction", Value::Vector({0.3, -0.2, -1}));
        return p;
    }

    std::optional<LightSample> SampleLi(const LightSampleContext &, const Vec2 &,
                                        const SampledWavelengths &wl) const override {
        return LightSample{EvalEmission(*spectrum_, wl) * irradiance_, -dir_, Infinity, 1.0, true};
    }
    double PdfLi(const LightSampleContext &, const Vec3 &, const Vec3 &, const Vec3 &) const override { return 0; }
    LightType Type() const override { return LightType::DeltaDirection; }
    std::optional<GrMeasurement> MeasureGR(const SpectralGenRay &g,
                                           const SampledWavelengths &wl) const override {
        return MeasureDistantGR(g, dir_, EvalEmission(*spectrum_, wl) * irradiance_, false, 0, 0);
    }
    std::optional<GrIncidence> IncidenceOnGR(const SpectralGenRay &g,
                                             const SampledWavelengths &wl) const override {
        return DistantIncidence(g, dir_, EvalEmission(*spectrum_, wl) * irradiance_, 0);
    }
    LightCoherence Coherence(const Vec3 &) const override { return LightCoherence{-dir_, 0}; }
    void Preprocess(const Bounds3 &b) override { sceneArea_ = SceneCrossSection(b); }
    const Spectrum &EmissionSpectrum() const override { return *spectrum_; }
    double PowerScale() const override { return irradiance_ * sceneArea_; }
    std::string ToString() const override { return "directional { direction = " + phasor::ToString(dir_) + " }"; }

  private:
    Vec3 dir_;
    double irradiance_;
    std::shared_ptr<const Spectrum> spectrum_;
    double sceneArea_ = 1;
};

PHASOR_EXPORT_PLUGIN(Light, DirectionalLight)

}  // namespace phasor
