// SPDX-License-Identifier: Apache-2.0
// `area`: a diffuse (Lambertian, spatially incoherent thermal) emitter on a shape. `radiance` is the
// total radiance over the spectrum, whose shape is normalised (lights/strength.h): L(λ) =
// radiance · spectrum(λ) / ∫spectrum dλ, from the side the shape's normal points to (both sides if
// two_sided). Next-event estimation samples it by solid angle where the shape offers that (a
// rectangle: uniformly over the solid angle it subtends, Shape::SampleSolidAngle), else uniformly
// by area.
#include "core/render/light.h"
#include "core/render/registry.h"
#include "lights/strength.h"

namespace phasor {

class AreaLight final : public Light {
  public:
    AreaLight(std::shared_ptr<Shape> shape, LightEmission emission, bool twoSided)
        : shape_(std::move(shape)),
          scale_(emission.scale),
          spectrum_(std::move(emission.spectrum)),
          twoSided_(twoSided),
          bounds_(shape_->Bounds()),
          normals_(shape_->Normals()) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "light", "area",
            "Diffuse emitter on a shape (spatially incoherent, Lambertian); next-event estimation samples a "
            "rectangle uniformly by its solid angle, other shapes by area.",
            {P::Ref("shape", "shape", "the emitting shape").Required(),
             P::Number("radiance", "emitted radiance, the total over the spectrum", Dim::Radiance())
                 .Default(Value::Number(1, Dim::Radiance()))
                 .Min(0)
                 .Max(MaxLightStrength),
             P::Spectrum("spectrum", "spectral shape (normalised to unit integral unless normalize_spectrum = false)").Default(Value::Number(1)),
             NormalizeSpectrumParam(),
             P::Bool("two_sided", "emit from both sides").Default(Value::Bool(false))}};
        return s;
    }
    static std::unique_ptr<Light> Create(const ParamDict &d, BuildContext &ctx) {
        auto shape = ctx.GetRef<Shape>(d, "shape");
        if (shape->areaLight) throw Error(d.Loc("shape"), "shape '" + shape->name + "' already has an area light");
        auto light =
            std::make_unique<AreaLight>(shape, ReadLightEmission(d, ctx, "area", "radiance", true), d.GetBool("two_sided"));
        shape->areaLight = light.get();
        return light;
    }

    /// For the light contract suite, whose fixtures these name: a one-sided square, a two-sided
    /// one, a sphere.
    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(3);
        p[0].Set("shape", Value::Ref("contract_panel"));
        p[1].Set("shape", Value::Ref("contract_panel")).Set("two_sided", Value::Bool(true));
        p[2].Set("shape", Value::Ref("contract_ball"));
        return p;
    }

    SampledSpectrum L(const Vec3 &, const Vec3 &n, const Vec3 &w, const SampledWavelengths &wl) const override {
        if (!twoSided_ && Dot(n, w) <= 0) return SampledSpectrum(0.0);
        return EvalEmission(*spectrum_, wl) * scale_;
    }
    std::optional<LightSample> SampleLi(const LightSampleContext &ctx, const Vec2 &u,
                                        const SampledWavelengths &wl) const override {
        const std::optional<ShapeSolidAngleSample> sa = shape_->SampleSolidAngle(ctx.p, u);
        const ShapeSample ss = sa ? ShapeSample{sa->p, sa->n, 0} : shape_->Sample(u);
        Vec3 d = ss.p - ctx.p;
        double r2 = LengthSquared(d);
        if (!(r2 > 0)) return std::nullopt;
        double r = std::sqrt(r2);
        Vec3 wi = d / r;
        double cosL = std::abs(Dot(ss.n, wi));
        if (cosL < 1e-12) return std::nullopt;
        SampledSpectrum Le = L(ss.p, ss.n, -wi, wl);
        if (Le.IsZero()) return std::nullopt;
        // By area: area density → solid-angle density, p_ω = p_A · r² / |cos θ_light|.
        return LightSample{Le, wi, r, sa ? sa->pdf : ss.pdfArea * r2 / cosL, false};
    }
    double PdfLi(const LightSampleContext &ctx, const Vec3 &wi, const Vec3 &pLight, const Vec3 &nLight) const override {
        double cosL = std::abs(Dot(nLight, wi));
        if (cosL < 1e-12) return 0;
        if (const double pdf = shape_->PdfSolidAngle(ctx.p); pdf > 0) return pdf;
        return LengthSquared(pLight - ctx.p) / (cosL * shape_->Area());
    }
    LightType Type() const override { return LightType::Area; }
    /// Coherence (theory §0 D5, §2.2): a thermal emitter subtending the solid angle Ω_src ≈ A/r²
    /// (r to the centre of its bounds, orientation ignored) is treated as a disc of that solid angle,
    /// πα² = Ω_src, so Ω = α²/4 = Ω_src/(4π) per axis. GRs measure it as L_e (theory §2.4 item 4).
    LightCoherence Coherence(const Vec3 &p) const override {
        const Vec3 c = shape_->Bounds().Center() - p;
        const double r2 = LengthSquared(c);
        if (!(r2 > 0)) return LightCoherence{Vec3(0, 0, 1), 0.25};
        return LightCoherence{c / std::sqrt(r2), std::min(0.25, shape_->Area() / r2 * Inv4Pi)};
    }
    /// L·A·cosθ'_light·cosθ'_receiver/d² (pbrt-v4's LightBounds::Importance): the angles from the
    /// shape's normal cone and the receiver's normal to the direction between the bounds' centre
    /// and ctx.p, each reduced by the half-angle of the bounds' sphere seen from ctx.p (θ_b), and d
    /// at least that sphere's radius. 0 where every normal of the cone faces away from ctx.p.
    double Reach(const LightSampleContext &ctx) const override {
        const Vec3 toP = ctx.p - bounds_.Center();
        const double d2 = LengthSquared(toP), r2 = 0.25 * LengthSquared(bounds_.Diagonal());
        const double strength = scale_ * shape_->Area();
        if (!(d2 > r2)) return strength / std::max(r2, 1e-300);  // inside the bounds' sphere: θ_b = π
        const Vec3 wi = toP / std::sqrt(d2);
        const double sinB = std::sqrt(r2 / d2), cosB = std::sqrt(1 - r2 / d2);
        double cosW = Clamp(Dot(normals_.w, wi), -1, 1);
        if (twoSided_) cosW = std::abs(cosW);
        const double sinW = std::sqrt(1 - cosW * cosW);
        const double cosO = Clamp(normals_.cosTheta, -1, 1), sinO = std::sqrt(1 - cosO * cosO);
        // θ' = max(0, θ_w − θ_o − θ_b): the cone's nearest normal, widened by the bounds.
        const double cosX = CosOfReduced(cosW, sinW, cosO, sinO), sinX = SinOfReduced(cosW, sinW, cosO, sinO);
        const double cosL = CosOfReduced(cosX, sinX, cosB, sinB);
        if (cosL <= 0) return 0;  // θ' ≥ π/2: a Lambertian side emits into its hemisphere only
        return strength * cosL * ReceiverCosine(ctx.n, wi, cosB, sinB) / d2;
    }
    const Spectrum &EmissionSpectrum() const override { return *spectrum_; }
    double PowerScale() const override { return scale_ * Pi * shape_->Area() * (twoSided_ ? 2 : 1); }
    std::string ToString() const override { return "area { shape = " + shape_->ToString() + " }"; }

  private:
    std::shared_ptr<Shape> shape_;
    double scale_;  // L(λ) = scale_ · spectrum(λ) [W/m²/sr per m]
    std::shared_ptr<const Spectrum> spectrum_;
    bool twoSided_;
    Bounds3 bounds_;              // the shape's, for Reach
    Shape::NormalCone normals_;  // the shape's
};

PHASOR_EXPORT_PLUGIN(Light, AreaLight)

}  // namespace phasor
