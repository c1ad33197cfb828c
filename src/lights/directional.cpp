// SPDX-License-Identifier: Apache-2.0
// `directional`: light from a single direction at infinity (delta direction), e.g. an idealised
// sun. `irradiance` is the total over the spectrum (lights/strength.h), measured on a plane normal
// to the direction of travel. For generalized rays it is a coherent plane wave (theory §2.4 item 2),
// like `plane_wave`.
#include "core/render/light.h"
#include "lights/closed_form.h"
#include "lights/strength.h"
#include "core/render/registry.h"

namespace phasor {

class DirectionalLight final : public Light {
  public:
    DirectionalLight(Vec3 dir, LightEmission emission)
        : dir_(Normalize(dir)), scale_(emission.scale), spectrum_(std::move(emission.spectrum)) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "light", "directional", "Parallel light from one direction (delta direction).",
            {P::Vector("direction", "direction in which the light travels").Default(Value::Vector({0, 0, -1})),
             P::Number("irradiance", "total irradiance on a plane normal to the direction", Dim::Irradiance())
                 .Default(Value::Number(1, Dim::Irradiance()))
                 .Min(0)
                 .Max(MaxLightStrength),
             P::Spectrum("spectrum", "spectral shape (normalised to unit integral unless normalize_spectrum = false)").Default(Value::Number(1)),
             NormalizeSpectrumParam()}};
        return s;
    }
    static std::unique_ptr<Light> Create(const ParamDict &d, BuildContext &ctx) {
        Vec3 dir = DirectionParam(d, "direction");
        return std::make_unique<DirectionalLight>(dir, ReadLightEmission(d, ctx, "directional", "irradiance", true));
    }

    /// For the light contract suite: the default and an oblique direction.
    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(2);
        p[1].Set("direction", Value::Vector({0.3, -0.2, -1}));
        return p;
    }

    std::optional<LightSample> SampleLi(const LightSampleContext &, const Vec2 &,
                                        const SampledWavelengths &wl) const override {
        return LightSample{EvalEmission(*spectrum_, wl) * scale_, -dir_, Infinity, 1.0, true};
    }
    double PdfLi(const LightSampleContext &, const Vec3 &, const Vec3 &, const Vec3 &) const override { return 0; }
    LightType Type() const override { return LightType::DeltaDirection; }
    std::optional<GrMeasurement> MeasureGR(const SpectralGenRay &g,
                                           const SampledWavelengths &wl) const override {
        return MeasureDistantGR(g, dir_, EvalEmission(*spectrum_, wl) * scale_, false, 0, 0);
    }
    bool MeasuresNothing(const SpectralGenRay &g) const override { return Dot(dir_, g.d) <= 0; }  // facing away
    std::optional<GrIncidence> IncidenceOnGR(const SpectralGenRay &g,
                                             const SampledWavelengths &wl) const override {
        return DistantIncidence(g, dir_, EvalEmission(*spectrum_, wl) * scale_, 0);
    }
    LightCoherence Coherence(const Vec3 &) const override { return LightCoherence{-dir_, 0}; }
    double Reach(const LightSampleContext &ctx) const override { return scale_ * ReceiverCosine(ctx.n, dir_); }
    void Preprocess(const Bounds3 &b) override { sceneArea_ = SceneCrossSection(b); }
    const Spectrum &EmissionSpectrum() const override { return *spectrum_; }
    double PowerScale() const override { return scale_ * sceneArea_; }
    std::string ToString() const override { return "directional { direction = " + phasor::ToString(dir_) + " }"; }

  private:
    Vec3 dir_;
    double scale_;  // the spectral irradiance is scale_ · spectrum(λ) [W/m² per m]
    std::shared_ptr<const Spectrum> spectrum_;
    double sceneArea_ = 1;
};

PHASOR_EXPORT_PLUGIN(Light, DirectionalLight)

}  // namespace phasor
