// SPDX-License-Identifier: Apache-2.0
// `plane_wave`: a fully coherent plane wave (theory §2.2: 𝒲_s = E·δ(k⊥ − k_s⊥)), e.g. a collimated
// laser much wider than the scene. `irradiance` is the total irradiance [W/m²] measured on a plane
// normal to `direction` (the direction of travel) over the spectrum, whose shape is normalised
// (lights/strength.h; a line carries all of it). Delta direction: classical rays never
// hit it (the `ray` integrator sees it only through next-event estimation); generalized rays
// measure it in closed form (theory §2.4 item 2, §0 D4a/D14). Coherence: Ω = 0. Its field
// (CoherentSource) is U = √E(λ)·e^{ik d·x}, E(λ) the spectral irradiance; `rs` propagates it when
// the spectrum is a line.
#include "core/render/coherent_source.h"
#include "core/render/light.h"
#include "lights/closed_form.h"
#include "lights/strength.h"
#include "core/render/registry.h"

namespace phasor {

namespace {

/// The plane wave over a plane: constant amplitude, phase k·(d·e1·u + d·e2·v) from the plane's origin.
class PlaneWaveOnPlane final : public PlaneField {
  public:
    PlaneWaveOnPlane(double amplitude, double k, double du, double dv) : amp_(amplitude), k_(k), du_(du), dv_(dv) {}
    void At(double u, double v, double *amplitude, double *phase) const override {
        *amplitude = amp_;
        *phase = k_ * du_ * u + k_ * dv_ * v;
    }
    PhaseSlope Slope(int axis, const Bounds2 &) const override {
        const double d = axis == 0 ? du_ : dv_;
        return {d, d, 0};
    }

  private:
    double amp_, k_, du_, dv_;  // du, dv: the direction cosines along the plane's axes
};

}  // namespace

class PlaneWaveLight final : public Light, public CoherentSource {
  public:
    PlaneWaveLight(Vec3 dir, double e, LightEmission emission)
        : dir_(Normalize(dir)), irradiance_(e), scale_(emission.scale), spectrum_(std::move(emission.spectrum)) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "light",
            "plane_wave",
            "Coherent plane wave (delta direction); irradiance is the total, spectrum the shape.",
            {P::Vector("direction", "direction in which the wave travels").Default(Value::Vector({0, 0, -1})),
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
        return std::make_unique<PlaneWaveLight>(dir, d.GetNumber("irradiance"),
                                                ReadLightEmission(d, ctx, "plane_wave", "irradiance", false));
    }

    /// For the light contract suite: the default and an oblique line (its coherent field).
    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(2);
        p[1].Set("direction", Value::Vector({0.2, 0.1, -1})).Set("spectrum", Value::Call("line", {Value::Number(633e-9, Dim::Length())}, {""}));
        return p;
    }

    SampledSpectrum Emission(const SampledWavelengths &wl) const {
        return EvalEmission(*spectrum_, wl) * scale_;
    }
    std::optional<LightSample> SampleLi(const LightSampleContext &, const Vec2 &,
                                        const SampledWavelengths &wl) const override {
        return LightSample{Emission(wl), -dir_, Infinity, 1.0, true};
    }
    double PdfLi(const LightSampleContext &, const Vec3 &, const Vec3 &, const Vec3 &) const override {
        return 0;
    }
    LightType Type() const override { return LightType::DeltaDirection; }
    std::optional<GrMeasurement> MeasureGR(const SpectralGenRay &g,
                                           const SampledWavelengths &wl) const override {
        return MeasureDistantGR(g, dir_, Emission(wl), false, 0, 0);
    }
    bool MeasuresNothing(const SpectralGenRay &g) const override { return Dot(dir_, g.d) <= 0; }  // facing away
    std::optional<GrIncidence> IncidenceOnGR(const SpectralGenRay &g,
                                             const SampledWavelengths &wl) const override {
        return DistantIncidence(g, dir_, Emission(wl), 0);
    }
    LightCoherence Coherence(const Vec3 &) const override { return LightCoherence{-dir_, 0}; }
    double Reach(const LightSampleContext &ctx) const override { return scale_ * ReceiverCosine(ctx.n, dir_); }

    // ---- The field (core/render/coherent_source.h) -------------------------------------------
    const CoherentSource *Coherent() const override { return this; }
    /// √E(λ)·e^{ik d·x}: E(λ) = the spectral irradiance (a line: its irradiance, D10).
    Complex Field(const Vec3 &x, double lambda) const override {
        return std::polar(std::sqrt(scale_ * spectrum_->Eval(lambda)), 2 * Pi / lambda * Dot(dir_, x));
    }
    Vec3 Travel(const Vec3 &, double) const override { return dir_; }
    std::optional<Vec3> PlaneWaveDirection() const override { return dir_; }
    std::unique_ptr<PlaneField> OnPlane(const PlateFrame &plane, double lambda) const override {
        return std::make_unique<PlaneWaveOnPlane>(std::sqrt(scale_ * spectrum_->Eval(lambda)), 2 * Pi / lambda,
                                                  Dot(dir_, plane.e1), Dot(dir_, plane.e2));
    }
    void Preprocess(const Bounds3 &b) override { sceneArea_ = SceneCrossSection(b); }
    const Spectrum &EmissionSpectrum() const override { return *spectrum_; }
    double PowerScale() const override { return scale_ * sceneArea_; }
    std::string ToString() const override {
        return "plane_wave { direction = " + phasor::ToString(dir_) +
               ", irradiance = " + std::to_string(irradiance_) + " }";
    }

  private:
    Vec3 dir_;
    double irradiance_, scale_ = 0;
    std::shared_ptr<const Spectrum> spectrum_;
    double sceneArea_ = 1;
};

PHASOR_EXPORT_PLUGIN(Light, PlaneWaveLight)

}  // namespace phasor
