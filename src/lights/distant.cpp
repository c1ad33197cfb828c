// SPDX-License-Identifier: Apache-2.0
// `distant`: a partially coherent source at infinity of small angular extent, e.g. the sun
// (theory §2.2: 𝒲_s = E·N(k⊥; k_s⊥, k²Ω); §0 D5, D14). `irradiance` is the total irradiance
// [W/m²] on a plane normal to `direction` (the direction of travel of the central ray) over the
// spectrum, whose shape is normalised (lights/strength.h).
//
// Angular profile (`profile`):
//   * "disc": uniform radiance L = E/(π sin²α) over a cone of half-angle α = `angular_radius`
//     (the sun: α ≈ 4.65 mrad); coherence Ω = α²/4·I (D5).
//   * "gaussian": radiance E·N₂(u; 0, Ω) over the direction cosines u transverse to the central
//     ray, with Ω = `omega`·I [rad²], or α²/4 from `angular_radius` (the disc's equal-variance
//     Gaussian).
// α = 0 (or Ω = 0) is a delta-direction source: a coherent plane wave.
//
// Classical rays see the profile through Le() and SampleLi() (uniform in the cone, or the Gaussian
// in direction cosines). Generalized rays after a detector or a near-delta lobe measure it in
// closed form (theory §2.4 item 3; disc: the Gaussian's mass inside the disc, D14) — a 4.65 mrad sun
// against a 1e-4 rad mirror lobe would otherwise need light sampling with enormous variance.
#include "core/render/light.h"
#include "lights/closed_form.h"
#include "lights/strength.h"
#include "core/render/registry.h"

namespace phasor {

class DistantLight final : public Light {
  public:
    DistantLight(Vec3 dir, double e, LightEmission emission, bool disc, double alpha, double omega)
        : dir_(Normalize(dir)),
          frame_(Frame::FromNormal(-Normalize(dir))),
          irradiance_(e),
          scale_(emission.scale),
          spectrum_(std::move(emission.spectrum)),
          disc_(disc),
          alpha_(alpha),
          omega_(omega) {
        cosAlpha_ = std::cos(alpha_);
        sinAlpha_ = std::sin(alpha_);
    }

    static const Schema &GetSchema() {
        static const Schema s{
            "light",
            "distant",
            "Source at infinity with a small angular extent (sun, sky patch): disc or Gaussian profile.",
            {P::Vector("direction", "direction in which the light travels (central ray)")
                 .Default(Value::Vector({0, 0, -1})),
             P::Number("irradiance", "total irradiance on a plane normal to the direction", Dim::Irradiance())
                 .Default(Value::Number(1, Dim::Irradiance()))
                 .Min(0)
                 .Max(MaxLightStrength),
             P::String("profile", "angular profile: uniform disc or Gaussian")
                 .Default(Value::String("disc"))
                 .Choices({"disc", "gaussian"}),
             P::Angle("angular_radius", "disc: half-angle of the cone; gaussian: sets Ω = α²/4 (D5)")
                 .Default(Value::Number(4.65e-3, Dim::Angle()))
                 .Min(0)
                 .Max(Radians(30)),
             P::Number("omega",
                       "gaussian profile: angular covariance Ω per axis [rad^2]; replaces angular_radius",
                       Dim::Angle().Pow(2))
                 .Min(0)
                 .Max(0.1),
             P::Spectrum("spectrum", "spectral shape (normalised to unit integral unless normalize_spectrum = false)").Default(Value::Number(1)),
             NormalizeSpectrumParam()}};
        return s;
    }
    static std::unique_ptr<Light> Create(const ParamDict &d, BuildContext &ctx) {
        Vec3 dir = DirectionParam(d, "direction");
        const bool disc = d.GetString("profile") == "disc";
        double alpha = d.GetNumber("angular_radius"), omega = alpha * alpha / 4;
        if (d.Has("omega")) {
            if (disc)
                throw Error(d.Loc("omega"),
                            "'omega' needs profile = \"gaussian\" (a disc takes angular_radius)");
            if (d.Has("angular_radius"))
                throw Error(d.Loc("omega"), "give either 'omega' or 'angular_radius', not both");
            omega = d.GetNumber("omega");
            alpha = 2 * std::sqrt(omega);
        }
        return std::make_unique<DistantLight>(dir, d.GetNumber("irradiance"),
                                              ReadLightEmission(d, ctx, "distant", "irradiance", false), disc, alpha,
                                              omega);
    }

    /// For the light contract suite: the sun's disc, a Gaussian profile, and zero extent (a delta
    /// direction).
    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(3);
        p[0].Set("direction", Value::Vector({0.1, 0.3, -1}));
        p[1].Set("profile", Value::String("gaussian")).Set("omega", Value::Number(1e-4, Dim::Angle().Pow(2)));
        p[2].Set("angular_radius", Value::Number(0, Dim::Angle()));
        return p;
    }

    SampledSpectrum Emission(const SampledWavelengths &wl) const {
        return EvalEmission(*spectrum_, wl) * scale_;
    }
    /// A profile of zero extent is a plane wave: a delta direction.
    LightType Type() const override {
        return (disc_ ? alpha_ == 0 : omega_ == 0) ? LightType::DeltaDirection : LightType::Distant;
    }

    // Radiance arriving from direction w (towards the light) relative to the spectrum: the profile.
    double Profile(const Vec3 &w) const {
        const Vec3 l = frame_.ToLocal(w);
        if (l.z <= 0) return 0;
        if (disc_) return l.z >= cosAlpha_ ? 1 / (Pi * Sqr(sinAlpha_)) : 0;
        return Normal2(l.x * l.x + l.y * l.y, omega_);
    }
    std::optional<LightSample> SampleLi(const LightSampleContext &, const Vec2 &u,
                                        const SampledWavelengths &wl) const override {
        if (IsDelta()) return LightSample{Emission(wl), -dir_, Infinity, 1.0, true};
        Vec3 l;
        if (disc_) {
            // Uniform in the cone: cosθ uniform in [cosα, 1].
            const double cosT = 1 - u.x * (1 - cosAlpha_), sinT = SafeSqrt(1 - cosT * cosT),
                         phi = 2 * Pi * u.y;
            l = Vec3(sinT * std::cos(phi), sinT * std::sin(phi), cosT);
        } else {
            // Box–Muller in direction cosines.
            const double r = std::sqrt(-2 * omega_ * std::log(std::max(1e-300, 1 - u.x))), phi = 2 * Pi * u.y;
            const double ux = r * std::cos(phi), uy = r * std::sin(phi), z2 = 1 - ux * ux - uy * uy;
            if (!(z2 > 0)) return std::nullopt;
            l = Vec3(ux, uy, std::sqrt(z2));
        }
        const Vec3 w = frame_.ToWorld(l);
        const double pdf = PdfDirection(w);
        if (!(pdf > 0)) return std::nullopt;
        return LightSample{Emission(wl) * Profile(w), w, Infinity, pdf, false};
    }
    double PdfDirection(const Vec3 &w) const {
        const Vec3 l = frame_.ToLocal(w);
        if (l.z <= 0) return 0;
        if (disc_) return l.z >= cosAlpha_ ? 1 / (2 * Pi * (1 - cosAlpha_)) : 0;
        return Normal2(l.x * l.x + l.y * l.y, omega_) * l.z;  // d²u = cosθ dω
    }
    double PdfLi(const LightSampleContext &, const Vec3 &wi, const Vec3 &, const Vec3 &) const override {
        return IsDelta() ? 0 : PdfDirection(wi);
    }
    SampledSpectrum Le(const Vec3 &d, const SampledWavelengths &wl) const override {
        if (IsDelta()) return SampledSpectrum(0.0);
        const double p = Profile(d);
        return p > 0 ? Emission(wl) * p : SampledSpectrum(0.0);
    }

    std::optional<GrMeasurement> MeasureGR(const SpectralGenRay &g,
                                           const SampledWavelengths &wl) const override {
        // The geometry first: most GRs see none of a small source (and half face away from it), so
        // the emission spectrum is evaluated only for a measurement that is not zero.
        std::optional<GrMeasurement> m = MeasureDistantGR(g, dir_, SampledSpectrum(1.0), disc_, sinAlpha_, omega_);
        if (m && !m->value.IsZero()) m->value *= Emission(wl);
        return m;
    }
    /// MeasureDistantGR's two zeros: facing away, and a disc out of reach.
    bool MeasuresNothing(const SpectralGenRay &g) const override {
        return Dot(dir_, g.d) <= 0 || (disc_ && DistantDiscOutOfReach(g, dir_, sinAlpha_));
    }
    std::optional<GrIncidence> IncidenceOnGR(const SpectralGenRay &g,
                                             const SampledWavelengths &wl) const override {
        const AngularProfile profile = IsDelta() ? AngularProfile{}
                                       : disc_  ? AngularProfile::Disc(sinAlpha_)
                                                : AngularProfile::Gaussian(omega_);
        return DistantIncidence(g, dir_, Emission(wl), disc_ ? alpha_ * alpha_ / 4 : omega_, profile);
    }
    LightCoherence Coherence(const Vec3 &) const override {
        return LightCoherence{-dir_, disc_ ? alpha_ * alpha_ / 4 : omega_};
    }

    void Preprocess(const Bounds3 &b) override { sceneArea_ = SceneCrossSection(b); }
    const Spectrum &EmissionSpectrum() const override { return *spectrum_; }
    double PowerScale() const override { return scale_ * sceneArea_; }
    /// The irradiance scale times the receiver's cosine towards the disc, reduced by its angular
    /// radius (a Gaussian profile reaches every direction in front: no cosine).
    double Reach(const LightSampleContext &ctx) const override {
        return scale_ * (disc_ ? ReceiverCosine(ctx.n, dir_, cosAlpha_, sinAlpha_) : 1.0);
    }
    std::string ToString() const override {
        return "distant { direction = " + phasor::ToString(dir_) +
               ", profile = " + (disc_ ? "disc" : "gaussian") +
               ", angular_radius = " + std::to_string(alpha_) + " rad, omega = " + std::to_string(omega_) +
               " rad^2 }";
    }

  private:
    Vec3 dir_;
    Frame frame_;  // n = −dir (towards the light)
    double irradiance_, scale_ = 0;
    std::shared_ptr<const Spectrum> spectrum_;
    bool disc_;
    double alpha_, omega_, cosAlpha_ = 1, sinAlpha_ = 0;
    double sceneArea_ = 1;
};

PHASOR_EXPORT_PLUGIN(Light, DistantLight)

}  // namespace phasor
