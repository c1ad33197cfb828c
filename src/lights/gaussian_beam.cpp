// SPDX-License-Identifier: Apache-2.0
// `gaussian_beam`: a coherent TEM₀₀ laser beam (theory §2.2, Gaussian Schell model with full
// coherence). `waist_radius` w₀ is the 1/e² intensity radius at the waist, so in the GR convention
// β_s = w₀/√2 and the intensity is P/(πβ²)·exp(−r²/β²) with β²(z) = β_s²(1 + (z/z_R)²),
// z_R = kβ_s² = πw₀²/λ (theory §1.6: a GR with ρ = 0 at the waist). `position` is the centre of
// the waist, `direction` the direction of travel, `power` the total power [W] over the spectrum,
// whose shape is normalised (lights/strength.h). The beam fills its whole axis (upstream of the
// waist it converges); shadow rays run to infinity against the local direction of travel.
//
// Classical rays see it as a delta-direction source whose irradiance follows the Gaussian profile
// and whose local direction follows the wavefront (tilt ρr/(kβ²), the beam's mean k given r).
// Generalized rays measure it in closed form: the phase-space overlap of two Gaussians
// (theory §2.4 item 1). Coherence: Ω = 0. Footprint-aware kernels (apertures) integrate the beam's
// own field over the GR's footprint: light samples carry the beam's geometry and its on-axis
// irradiance (LightSample::beam, IncidentWave). Its field (CoherentSource) is the exact paraxial
// TEM₀₀ field √P(λ)·ψ (GaussianBeamGeometry), which `rs` propagates when the spectrum is a line.
#include "core/render/coherent_source.h"
#include "core/render/light.h"
#include "lights/closed_form.h"
#include "lights/strength.h"
#include "core/render/registry.h"

namespace phasor {

namespace {

// Openings farther than this many β(z) from the beam's axis carry no light (amplitude e^{−32} of
// the axis value there): a quadrature over a plane leaves them out.
constexpr double BeamCutoff = 8;

/// The beam over a plane: √P·ψ, its phase relative to k·z at the plane's origin (which keeps the
/// argument small far from the waist).
class BeamOnPlane final : public PlaneField {
  public:
    BeamOnPlane(const PlateFrame &plane, const GaussianBeamGeometry &beam, double amplitude, double k)
        : plane_(plane), beam_(beam), amp_(amplitude), k_(k), zRef_(beam.Axial(plane.origin)),
          du_(Dot(beam.axis, plane.e1)), dv_(Dot(beam.axis, plane.e2)) {
        // The box of the points within BeamCutoff·β(z) of the axis: β at the farthest z of the
        // box bounds the footprint (one refinement).
        const double cn = std::abs(Dot(beam_.axis, plane.n));
        if (!(cn > 1e-6)) throw Error("the Gaussian beam runs parallel to the plane");
        const double t = Dot(plane.origin - beam_.waist, plane.n) / Dot(beam_.axis, plane.n);
        const Vec3 hit = beam_.waist + beam_.axis * t;  // the axis meets the plane here
        const Vec2 c(Dot(hit - plane.origin, plane.e1), Dot(hit - plane.origin, plane.e2));
        double half = BeamCutoff * std::sqrt(beam_.Beta2At(t, k_)) / cn;
        const double slope = std::sqrt(std::max(0.0, 1 - cn * cn));  // |dz/ds| along the plane
        half = BeamCutoff * std::sqrt(beam_.Beta2At(std::abs(t) + half * slope, k_)) / cn;
        support_ = Bounds2{c - Vec2(half, half), c + Vec2(half, half)};
    }
    void At(double u, double v, double *amplitude, double *phase) const override {
        const Complex psi = beam_.Field(plane_.ToWorld(Vec2(u, v)), k_, zRef_);
        *amplitude = amp_ * std::abs(psi);
        *phase = std::arg(psi);
    }
    /// k times the axis' component along the plane axis, ± what the curvature, its change along the
    /// axis and the Gouy phase add: φ = k z + k r² z/(2(z² + z_R²)) − atan(z/z_R); along a plane
    /// axis |∂r/∂u| ≤ 1 and |∂z/∂u| ≤ a (the axis' largest component on the plane), so beyond k·∂z/∂u
    /// the gradient is at most k·r·max|z|/(z² + z_R²) + a·(k r²/(2 z_R²) + 1/z_R). r (distance from
    /// the axis, convex) and z (linear) take their extremes over the box at its corners.
    PhaseSlope Slope(int axis, const Bounds2 &box) const override {
        const double zr = k_ * beam_.beta2;
        const double a = std::max(std::abs(du_), std::abs(dv_));
        double rMax = 0, zLo = Infinity, zHi = -Infinity;
        for (int c = 0; c < 4; ++c) {
            const Vec3 p = plane_.ToWorld(Vec2((c & 1) ? box.hi.x : box.lo.x, (c & 2) ? box.hi.y : box.lo.y));
            const double z = beam_.Axial(p);
            rMax = std::max(rMax, std::sqrt(std::max(0.0, LengthSquared(p - beam_.waist) - z * z)));
            zLo = std::min(zLo, z);
            zHi = std::max(zHi, z);
        }
        auto f = [&](double z) { return std::abs(z) / (z * z + zr * zr); };
        double fMax = std::max(f(zLo), f(zHi));
        if (zLo <= zr && zHi >= zr) fMax = std::max(fMax, f(zr));
        if (zLo <= -zr && zHi >= -zr) fMax = std::max(fMax, f(-zr));
        const double d = axis == 0 ? du_ : dv_;
        return {d, d, k_ * rMax * fMax + a * (k_ * rMax * rMax / (2 * zr * zr) + 1 / zr)};
    }
    /// Panels no longer than the beam's radius β(z) anywhere in the box resolve its Gaussian
    /// envelope (β(z) is smallest at the z nearest 0).
    double PanelLimit(const Bounds2 &box) const override {
        double zLo = Infinity, zHi = -Infinity;
        for (int c = 0; c < 4; ++c) {
            const double z =
                beam_.Axial(plane_.ToWorld(Vec2((c & 1) ? box.hi.x : box.lo.x, (c & 2) ? box.hi.y : box.lo.y)));
            zLo = std::min(zLo, z);
            zHi = std::max(zHi, z);
        }
        const double zNear = (zLo <= 0 && zHi >= 0) ? 0.0 : std::min(std::abs(zLo), std::abs(zHi));
        return std::sqrt(beam_.Beta2At(zNear, k_));
    }
    Bounds2 Support() const override { return support_; }

  private:
    PlateFrame plane_;
    GaussianBeamGeometry beam_;
    double amp_, k_, zRef_;
    double du_, dv_;  // the axis' components along e1, e2
    Bounds2 support_;
};

}  // namespace

class GaussianBeamLight final : public Light, public CoherentSource {
  public:
    GaussianBeamLight(Vec3 pos, Vec3 dir, double w0, double power, LightEmission emission)
        : pos_(pos),
          dir_(Normalize(dir)),
          beta2_(0.5 * w0 * w0),
          power_(power),
          scale_(emission.scale),
          spectrum_(std::move(emission.spectrum)) {}

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
             P::Spectrum("spectrum",
                         "spectral shape (normalised to unit integral unless normalize_spectrum = false), e.g. "
                         "line(632.8 nm)")
                 .Default(Value::Call("line", {Value::Number(632.8e-9, Dim::Length())}, {""})),
             NormalizeSpectrumParam()}};
        return s;
    }
    static std::unique_ptr<Light> Create(const ParamDict &d, BuildContext &ctx) {
        Vec3 dir = DirectionParam(d, "direction");
        return std::make_unique<GaussianBeamLight>(d.GetVector("position"), dir, d.GetNumber("waist_radius"),
                                                   d.GetNumber("power"),
                                                   ReadLightEmission(d, ctx, "gaussian_beam", "power", false));
    }

    /// For the light contract suite (which passes the beam through the origin): the default, and a
    /// narrow tilted beam whose waist lies off the origin on its axis.
    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(2);
        p[1].Set("position", Value::Vector({-0.02, 0, -0.1}, Dim::Length()))
            .Set("direction", Value::Vector({0.2, 0, 1}))
            .Set("waist_radius", Value::Number(50e-6, Dim::Length()));
        return p;
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
    LightType Type() const override { return LightType::DeltaDirection; }
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

    // ---- The field (core/render/coherent_source.h) -------------------------------------------
    const CoherentSource *Coherent() const override { return this; }
    /// √P(λ)·ψ(x): P(λ) = the spectral power (a line: its power, D10), ψ the unit-power beam.
    Complex Field(const Vec3 &x, double lambda) const override {
        return std::sqrt(scale_ * spectrum_->Eval(lambda)) * Geometry().Field(x, 2 * Pi / lambda);
    }
    /// The normal of the wavefront: the axis tilted by ρr/(kβ²) (as SampleLi's direction).
    Vec3 Travel(const Vec3 &x, double lambda) const override {
        GenRay b = Beam(2 * Pi / lambda);
        b.Propagate(Dot(x - pos_, dir_));
        return Normalize(dir_ + (x - b.o) * (b.rho / (b.k * b.beta2)));
    }
    std::unique_ptr<PlaneField> OnPlane(const PlateFrame &plane, double lambda) const override {
        return std::make_unique<BeamOnPlane>(plane, Geometry(), std::sqrt(scale_ * spectrum_->Eval(lambda)),
                                             2 * Pi / lambda);
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
