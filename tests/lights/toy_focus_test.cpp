// SPDX-License-Identifier: Apache-2.0
// A toy coherent source, written only against the light interface (core/render/light.h,
// core/render/coherent_source.h), to prove that a new source `rs` can propagate needs nothing
// outside its own file and its registration line (issue 25 §4): a spherical wave converging on a
// focus — the light behind a lens — that `rs` sends through a disc onto a sensor in the focal
// plane, where it must give the exact on-axis value and the Airy pattern. The light contract suite
// (light_contract_test.cpp) picks it up from the registry and checks its sampling, power, field and
// closed-form measurement. Registered only in this test executable.
//
// The field: U = √I(λ)·e^{−ikρ}/ρ, ρ = |x − focus|, within a cone of half-angle `cone_angle` about
// `direction` (the direction of travel of its axis) and upstream of the focus; 0 elsewhere. I(λ) =
// intensity × spectrum [W/sr]: the irradiance at ρ is I/ρ², as for a point source (it is the time
// reverse of one), so a GR measures it as a point source measures the time-reversed GR.
#include <gtest/gtest.h>

#include <cmath>

#include "core/render/coherent_source.h"
#include "core/render/light.h"
#include "core/render/registry.h"
#include "lights/closed_form.h"
#include "parser/parser.h"
#include "support/scene_builder.h"

namespace phasor {

namespace {

/// The converging wave over a plane: the focus at (fu, fv) in plane coordinates, at distance fz > 0
/// from the plane; amplitude √I/ρ, phase −k(ρ − fz).
class ConvergingOnPlane final : public PlaneField {
  public:
    ConvergingOnPlane(double amplitude, double k, double fu, double fv, double fz, double cosCone, const Vec2 &axisFoot,
                      double footRadius)
        : amp_(amplitude), k_(k), fu_(fu), fv_(fv), fz_(fz), cosCone_(cosCone), foot_(axisFoot), footR_(footRadius) {}
    void At(double u, double v, double *amplitude, double *phase) const override {
        const double du = u - fu_, dv = v - fv_, q = du * du + dv * dv;
        const double rho = std::sqrt(q + fz_ * fz_);
        *amplitude = fz_ / rho >= cosCone_ ? amp_ / rho : 0.0;  // (a plane ⊥ the axis)
        *phase = -k_ * q / (rho + fz_);
    }
    PhaseSlope Slope(int axis, const Bounds2 &box) const override {
        const PhaseSlope diverging = SphericalSlope(axis, box, Vec2(fu_, fv_), fz_);
        return {-diverging.hi, -diverging.lo, 0};
    }
    double PanelLimit(const Bounds2 &) const override { return 0.5 * fz_; }
    Bounds2 Support() const override { return Bounds2{foot_ - Vec2(footR_, footR_), foot_ + Vec2(footR_, footR_)}; }

  private:
    double amp_, k_, fu_, fv_, fz_, cosCone_;
    Vec2 foot_;
    double footR_;
};

}  // namespace

class ToyFocusLight final : public Light, public CoherentSource {
  public:
    ToyFocusLight(Vec3 focus, Vec3 dir, double cone, double intensity, std::shared_ptr<const Spectrum> s)
        : focus_(focus), dir_(Normalize(dir)), cosCone_(std::cos(cone)), intensity_(intensity), spectrum_(std::move(s)) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "light", "toy_focus", "test light: a coherent spherical wave converging on a focus within a cone",
            {P::Vector("focus", "the point the wave converges on", Dim::Length()).Default(Value::Vector({0, 0, -1}, Dim::Length())),
             P::Vector("direction", "direction of travel of the cone's axis").Default(Value::Vector({0, 0, -1})),
             P::Angle("cone_angle", "half-angle of the cone").Default(Value::Number(0.2, Dim::Angle())).Min(0, true).Max(1.5),
             P::Number("intensity", "I: the irradiance at distance ρ is I/ρ²", Dim::Intensity())
                 .Default(Value::Number(1, Dim::Intensity()))
                 .Min(0),
             P::Spectrum("spectrum", "spectral shape").Default(Value::Number(1))}};
        return s;
    }
    static std::unique_ptr<Light> Create(const ParamDict &d, BuildContext &ctx) {
        return std::make_unique<ToyFocusLight>(d.GetVector("focus"), d.GetVector("direction"), d.GetNumber("cone_angle"),
                                               d.GetNumber("intensity"), ctx.GetSpectrum(d, "spectrum"));
    }
    /// Cones whose axes pass through the origin (the light contract suite measures a delta
    /// direction's flux through the scene's centre).
    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(2);
        p[1].Set("focus", Value::Vector({0.1, 0, -1}, Dim::Length()))
            .Set("direction", Value::Vector({0.1, 0, -1}))
            .Set("spectrum", Value::Call("line", {Value::Number(600e-9, Dim::Length())}, {""}));
        return p;
    }

    /// The wave reaches x if x lies upstream of the focus inside the cone.
    bool Reaches(const Vec3 &x) const {
        const Vec3 to = focus_ - x;
        const double r = Length(to);
        return r > 0 && Dot(to, dir_) >= cosCone_ * r;
    }
    double Spectral(double lambda) const { return intensity_ * spectrum_->Eval(lambda); }

    std::optional<LightSample> SampleLi(const LightSampleContext &ctx, const Vec2 &,
                                        const SampledWavelengths &wl) const override {
        if (!Reaches(ctx.p)) return std::nullopt;
        const Vec3 from = ctx.p - focus_;  // towards where the light comes from
        const double r2 = LengthSquared(from);
        return LightSample{EvalEmission(*spectrum_, wl) * (intensity_ / r2), from / std::sqrt(r2), Infinity, 1.0, true};
    }
    double PdfLi(const LightSampleContext &, const Vec3 &, const Vec3 &, const Vec3 &) const override { return 0; }
    LightType Type() const override { return LightType::DeltaDirection; }
    /// The time reverse of a point source at the focus: measured as the point source measures the
    /// time-reversed GR (theory §2.4 item 5; |⟨ψ, Ū⟩|² = |⟨ψ̄, U⟩|²).
    std::optional<GrMeasurement> MeasureGR(const SpectralGenRay &g, const SampledWavelengths &wl) const override {
        if (!Reaches(g.o)) return std::nullopt;
        const SpectralGenRay reversed = g.TimeReversed();
        GrMeasurement m;
        m.value = MeasurePerWavelength(reversed, EvalEmission(*spectrum_, wl) * intensity_,
                                       [&](const GenRay &gi) { return MeasurePointSource(gi, focus_, 1.0); });
        m.wi = Normalize(g.o - focus_);
        m.dist = Infinity;
        return m;
    }
    LightCoherence Coherence(const Vec3 &p) const override { return LightCoherence{Normalize(p - focus_), 0}; }
    const Spectrum &EmissionSpectrum() const override { return *spectrum_; }
    double PowerScale() const override { return intensity_ * 2 * Pi * (1 - cosCone_); }
    std::string ToString() const override { return "toy_focus"; }

    // ---- The field --------------------------------------------------------------------------------
    const CoherentSource *Coherent() const override { return this; }
    Complex Field(const Vec3 &x, double lambda) const override {
        if (!Reaches(x)) return 0;
        const double rho = Length(x - focus_);
        return std::polar(std::sqrt(Spectral(lambda)) / rho, -2 * Pi / lambda * rho);
    }
    Vec3 Travel(const Vec3 &x, double) const override { return Normalize(focus_ - x); }
    std::unique_ptr<PlaneField> OnPlane(const PlateFrame &plane, double lambda) const override {
        if (std::abs(Dot(dir_, plane.n)) < 1 - 1e-12)
            throw Error("toy_focus: the plane must be normal to the cone's axis");
        const Vec3 d = focus_ - plane.origin;
        const double fz = std::abs(Dot(d, plane.n));
        const Vec2 foot(Dot(d, plane.e1), Dot(d, plane.e2));
        return std::make_unique<ConvergingOnPlane>(std::sqrt(Spectral(lambda)), 2 * Pi / lambda, foot.x, foot.y, fz,
                                                   cosCone_, foot, fz * std::tan(std::acos(cosCone_)));
    }

  private:
    Vec3 focus_, dir_;
    double cosCone_, intensity_;
    std::shared_ptr<const Spectrum> spectrum_;
};

PHASOR_REGISTER_PLUGIN(Light, ToyFocusLight, "toy_focus");

namespace test {
namespace {

// A disc of radius a in a plate at z = 0, the wave converging on (0, 0, −f): in the focal plane the
// field is exactly, on the axis (every path in phase; theory §6.2's 3-D RS-I integral in closed form),
//     U(focus) = f√I [½(1/f² − 1/R_a²) − ik(1/f − 1/R_a)],   R_a² = f² + a²,
// and around it the Airy pattern I₀[2J₁(v)/v]², v = k·a·r/f (paraxial; NA = a/f = 0.01 here).
TEST(ToyFocus, RsPropagatesItThroughADiscToTheAiryPattern) {
    const double lambda = 633e-9, k = 2 * Pi / lambda, a = 0.5e-3, f = 50e-3, I = 2.0, sigma = 0.5e-6;
    const std::string text = R"(wscene 1
Light "toy_focus" "lens" { focus = [0 0 -50] mm  direction = [0 0 -1]  cone_angle = 0.05 rad  intensity = 2 W/sr
                          spectrum = line(633 nm) }
Material "aperture" "hole" { discs = [0 0 0.5] mm }
Shape "rectangle" "plate" { width = 10 mm  height = 10 mm  material = @hole }
Detector "virtual_plane" "focal" { to_world = translate([0 0 -50] mm)  extent = [123 3] um  pitch = 3 um
                                   sigma = 0.5 um }
Integrator "rs" "rs" { mode = "3d" }
)";
    Diagnostics diag;
    auto desc = ParseSceneString(text, "toy_focus.wscene", DefineList{}, diag);
    ASSERT_TRUE(desc);
    auto scene = Scene::Build(*desc, diag);
    std::ostringstream log;
    diag.Print(log);
    ASSERT_TRUE(scene) << log.str();
    const Image img = RenderImage(*scene, 1);
    ASSERT_EQ(img.width, 41);
    const int c = img.ChannelIndex("intensity");
    const double Ra = std::hypot(f, a);
    const Complex u0 = f * std::sqrt(I) * Complex(0.5 * (1 / (f * f) - 1 / (Ra * Ra)), -k * (1 / f - 1 / Ra));
    // The pixel averages the pattern over N(0, σ²I): near the axis 1 − v²/4 loses (k a σ/f)²/2.
    const double centre = std::norm(u0) * (1 - Sqr(k * a * sigma / f) / 2);
    const double got = img.At(20, 0, c);  // reference_irradiance = 1 W/m²
    std::printf("toy_focus through a disc, focal-plane centre: rs %.8e, closed form %.8e (relative %.2e)\n", got,
                centre, got / centre - 1);
    EXPECT_NEAR(got / centre, 1, 2e-4);
    for (int i = 0; i < 41; ++i) {
        const double r = std::abs(i - 20) * 3e-6, v = k * a * r / f;
        const double airy = v > 0 ? Sqr(2 * std::cyl_bessel_j(1.0, v) / v) : 1.0;
        EXPECT_NEAR(img.At(i, 0, c) / std::norm(u0), airy, 5e-3) << "pixel " << i << " (r = " << r * 1e6 << " um)";
    }
}

}  // namespace
}  // namespace test
}  // namespace phasor
