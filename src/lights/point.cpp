// SPDX-License-Identifier: Apache-2.0
// `point`: an isotropic point source (delta position). `intensity` is the total radiant intensity
// over the spectrum, whose shape is normalised (lights/strength.h): I(λ) = intensity ·
// spectrum(λ) / ∫spectrum dλ [W/sr per m].
// Generalized rays measure it in closed form as a coherent spherical wave (point_like.h).
// Its field (CoherentSource) is that wave, U = √I(λ)·e^{ikρ}/ρ, which `rs` propagates when the
// spectrum is a line.
#include "core/render/coherent_source.h"
#include "lights/point_like.h"
#include "core/render/registry.h"

namespace phasor {

namespace {

/// A spherical wave over a plane: the source at (su, sv) in plane coordinates, at distance sz > 0
/// from the plane; amplitude √I/ρ, phase kρ relative to k·sz.
class SphericalWaveOnPlane final : public PlaneField {
  public:
    SphericalWaveOnPlane(double amplitude, double k, double su, double sv, double sz)
        : amp_(amplitude), k_(k), su_(su), sv_(sv), sz_(sz) {}
    void At(double u, double v, double *amplitude, double *phase) const override {
        const double du = u - su_, dv = v - sv_, q = du * du + dv * dv;
        const double rho = std::sqrt(q + sz_ * sz_);
        *amplitude = amp_ / rho;
        *phase = k_ * q / (rho + sz_);  // k(ρ − sz), without cancellation
    }
    PhaseSlope Slope(int axis, const Bounds2 &box) const override {
        return SphericalSlope(axis, box, Vec2(su_, sv_), sz_);
    }
    /// Panels of at most half the source's distance resolve the 1/ρ amplitude.
    double PanelLimit(const Bounds2 &) const override { return 0.5 * sz_; }

  private:
    double amp_, k_, su_, sv_, sz_;
};

}  // namespace

class PointLight final : public PointLikeLight, public CoherentSource {
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

    /// For the light contract suite (tests/lights/light_contract_test.cpp): the default, an
    /// off-centre blackbody, a line (its coherent field).
    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(3);
        p[1].Set("position", Value::Vector({0.2, -0.1, 0.3}, Dim::Length()))
            .Set("spectrum", Value::Call("blackbody", {Value::Number(3000, Dim::Temperature())}, {""}));
        p[2].Set("spectrum", Value::Call("line", {Value::Number(550e-9, Dim::Length())}, {""}));
        return p;
    }

    double Falloff(const Vec3 &) const override { return 1; }

    // ---- The field (core/render/coherent_source.h) -------------------------------------------
    const CoherentSource *Coherent() const override { return this; }
    /// √I(λ)·e^{ikρ}/ρ, ρ = |x − p|: I(λ) = intensity × spectrum (a line: its strength, D10).
    Complex Field(const Vec3 &x, double lambda) const override {
        const double rho = Length(x - p_);
        return std::polar(std::sqrt(scale_ * spectrum_->Eval(lambda)) / rho, 2 * Pi / lambda * rho);
    }
    Vec3 Travel(const Vec3 &x, double) const override { return Normalize(x - p_); }
    std::unique_ptr<PlaneField> OnPlane(const PlateFrame &plane, double lambda) const override {
        const Vec3 d = p_ - plane.origin;
        return std::make_unique<SphericalWaveOnPlane>(std::sqrt(scale_ * spectrum_->Eval(lambda)), 2 * Pi / lambda,
                                                      Dot(d, plane.e1), Dot(d, plane.e2), std::abs(Dot(d, plane.n)));
    }
    double PowerScale() const override { return 4 * Pi * scale_; }
    std::string ToString() const override {
        return "point { position = " + phasor::ToString(p_) + ", intensity scale = " + std::to_string(scale_) +
               " W/sr per m" +
               ", spectrum = " + spectrum_->ToString() + " }";
    }
};

PHASOR_EXPORT_PLUGIN(Light, PointLight)

}  // namespace phasor
