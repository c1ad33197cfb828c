// SPDX-License-Identifier: Apache-2.0
// `gaussian_beam`: a coherent TEM₀₀ laser beam (theory §2.2, Gaussian Schell model with full
// coherence). `waist_radius` w₀ is the 1/e² intensity radius at the waist, so in the GR convention
// β_s = w₀/√2 and the intensity is P/(πβ²)·exp(−r²/β²) with β²(z) = β_s²(1 + (z/z_R)²),
// z_R = kβ_s² = πw₀²/λ (theory §1.6: a GR with ρ = 0 at the waist). `position` is the centre of
// the waist, `direction` the direction of travel, `power` the total power [W]; `spectrum` gives the
// spectral shape (normalised to unit integral). The beam fills its whole axis (upstream of the
// waist it converges); shadow rays run to infinity against the local direction of travel.
//
// Classical rays see it as a delta-direction source whose irradiance follows the Gaussian profile
// and whose local direction follows the wavefront (tilt ρr/(kβ²), the beam's mean k given r).
// Generalized rays measure it in closed form: the phase-space overlap of two Gaussians
// (theory §2.4 item 1). Coherence: Ω = 0. Footprint-aware kernels (apertures) integrate the beam's
// own field over the GR's footprint: light samples carry the beam's geometry and its on-axis
// irradiance (LightSample::beam, IncidentWave). `rs` gets the exact paraxial field (CoherentField).
#include "core/render/light.h"
#include "lights/closed_form.h"
#include "core/render/registry.h"

namespace phasor {

class GaussianBeamLight final : public Light {
  public:
    GaussianBeamLight(Vec3 pos, Vec3 dir, double w0, double power, std::shared_ptr<const Spectrum> s)
        : pos_(pos), dir_(Normalize(dir)), beta2_(0.5 * w0 * w0), power_(power), spectrum_(std::move(s)) {
        scale_ = TotalScale(*spectrum_, power_);
    }

    static const Schema &GetSchema() {
        static const Schema s{
            "light",
            "gaussian_beam",
            "Coherent Gaussian laser beam (TEM00): waist radius, waist position, direction, power.",
            {P::Vector("position", "centre of the waist", Dim::Length())
                 .Default(Value::Vector({0, 0, 0}, Dim::Length())),
             P::Vector("direction", "direction of travel").Default(Value::Vector({0, 0, 1})),
             P::Length("waist_radius", "1/e² intensity radius w0 at the waist (beta = w0/sqrt(2))")
                 .Default(Value::Number(0.5e-3, Dim::Length()))
                 .Min(0, true),
             P::Number("power", "total power", Dim::Power())
                 .Default(Value::Number(1e-3, Dim::Power()))
                 .Min(0)
                 .Max(MaxLightStrength),
             P::Spectrum("spectrum", "spectral shape (normalised to unit integral), e.g. line(632.8 nm)")
                 .Default(Value::Call("line", {Value::Number(632.8e-9, Dim::Length())}, {""}))}};
        return s;
    }
    static std::unique_ptr<Light> Create(const ParamDict &d, BuildContext &ctx) {
        Vec3 dir = DirectionParam(d, "direction");
        auto spectrum = ShapeSpectrumParam(d, ctx, "gaussian_beam");
        return std::make_unique<GaussianBeamLight>(d.GetVector("position"), dir, d.GetNumber("waist_radius"),
                                                   d.GetNumber("power"), spectrum);
    }

    GaussianBeamGeometry Geometry() const { return GaussianBeamGeometry{pos_, dir_, beta2_}; }
    /// The beam as a physical GR at its waist for wavenumber k.
    GenRay Beam(double k) const { return GenRay{pos_, dir_, k, beta2_, 0}; }
    SampledSpectrum Emission(const SampledWavelengths &wl) const {
        return EvalEmission(*spectrum_, wl) * scale_;
    }

    std::optional<LightSample> SampleLi(const LightSampleContext &ctx, const Vec2 &,
                                        const SampledWavelengths &wl) const override {
        SampledSpectrum e = Emission(wl);
        if (e.IsZero()) return std::nullopt;
        SampledSpectrum axis = e;
        Vec3 local = dir_;
        for (int i = 0; i < wl.Count(); ++i) {
            if (e[i] == 0) continue;
            GenRay b = Beam(2 * Pi / wl.lambda[i]);
            const double z = Dot(ctx.p - pos_, dir_);
            b.Propagate(z);
            const Vec3 r = ctx.p - b.o;  // ⊥ dir
            const double r2 = LengthSquared(r);
            axis[i] *= 1 / (Pi * b.beta2);
            e[i] = axis[i] * std::exp(-r2 / b.beta2);
            if (i == 0) local = Normalize(dir_ + r * (b.rho / (b.k * b.beta2)));
        }
        LightSample ls{e, -local, Infinity, 1.0, true};
        ls.beam = Geometry();
        ls.beamAxisIrradiance = axis;
        return ls;
    }
    double PdfLi(const LightSampleContext &, const Vec3 &, const Vec3 &, const Vec3 &) const override {
        return 0;
    }
    bool IsDelta() const override { return true; }
    bool IsInfinite() const override { return true; }

    bool MeasuredInClosedForm() const override { return true; }
    std::optional<GrMeasurement> MeasureGR(const SpectralGenRay &g,
                                           const SampledWavelengths &wl) const override {
        if (Dot(dir_, g.d) <= 0) return std::nullopt;
        GrMeasurement m;
        m.value = MeasurePerWavelength(
            g, Emission(wl), [&](const GenRay &gi) { return MeasureGaussianBeam(gi, Beam(gi.k), 1.0); });
        m.wi = -dir_;
        m.dist = Infinity;
        const GenRay g0 = g.At(0);
        m.profile = GaussianBeamOverlapProfile(g0, Beam(g0.k));
        return m;
    }
    std::optional<GrIncidence> IncidenceOnGR(const SpectralGenRay &g,
                                             const SampledWavelengths &wl) const override {
        // ∫d²k⊥ of theory §2.4 item 1 = P·N₂(Δr; (β_g² + β_s²(z))/2): the beam profile seen
        // through the GR's spatial footprint (a Gaussian pixel for a sensor plane).
        GrIncidence inc;
        inc.irradiance = Emission(wl);
        Vec3 local = dir_;
        for (int i = 0; i < g.count; ++i) {
            const GenRay gi = g.At(i);
            GenRay b = Beam(gi.k);
            b.Propagate(Dot(gi.o - pos_, dir_));
            const Vec3 r = gi.o - b.o;
            const double s2 = gi.beta2 + b.beta2;
            inc.irradiance[i] *= std::exp(-LengthSquared(r) / s2) / (Pi * s2);
            if (i == 0) {
                local = Normalize(dir_ + r * (b.rho / (b.k * b.beta2)));
                inc.angularVariance = gi.AngularVariance() + 0.5 / (b.beta2 * b.k * b.k);
                inc.profile = GaussianBeamIncidenceProfile(gi, b);
            }
        }
        inc.wi = -local;
        inc.dist = Infinity;
        return inc;
    }
    LightCoherence Coherence(const Vec3 &) const override { return LightCoherence{-dir_, 0}; }
    /// The `rs` field: only a line spectrum is monochromatic (the line carries all the power).
    std::optional<CoherentWave> CoherentField() const override {
        const auto line = spectrum_->LineWavelength();
        if (!line) return std::nullopt;
        CoherentWave w;
        w.kind = CoherentWave::Kind::GaussianBeam;
        w.dir = dir_;
        w.pos = pos_;
        w.strength = scale_ * spectrum_->Eval(*line);  // = power
        w.lambda = *line;
        w.beta2 = beta2_;
        return w;
    }

    const Spectrum &EmissionSpectrum() const override { return *spectrum_; }
    double PowerScale() const override { return scale_; }
    std::string ToString() const override {
        return "gaussian_beam { position = " + phasor::ToString(pos_) +
               ", direction = " + phasor::ToString(dir_) +
               ", waist_radius = " + std::to_string(std::sqrt(2 * beta2_)) +
               " m, power = " + std::to_string(power_) + " W }";
    }

  private:
    Vec3 pos_, dir_;
    double beta2_, power_, scale_ = 0;
    std::shared_ptr<const Spectrum> spectrum_;
};

PHASOR_EXPORT_PLUGIN(Light, GaussianBeamLight)

}  // namespace phasor
