// SPDX-License-Identifier: Apache-2.0
// `area`: a diffuse (Lambertian, spatially incoherent thermal) emitter on a shape. Emitted
// spectral radiance L(λ) = radiance · spectrum(λ), from the side the shape's normal points to
// (both sides if two_sided). Sampled uniformly by area for next-event estimation.
#include "core/render/light.h"
#include "core/render/registry.h"

namespace phasor {

class AreaLight final : public Light {
  public:
    AreaLight(std::shared_ptr<Shape> shape, double radiance, std::shared_ptr<const Spectrum> s, bool twoSided)
        : shape_(std::move(shape)), radiance_(radiance), spectrum_(std::move(s)), twoSided_(twoSided) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "light", "area", "Diffuse emitter on a shape (spatially incoherent, Lambertian).",
            {P::Ref("shape", "shape", "the emitting shape").Required(),
             P::Number("radiance", "emitted radiance scale", Dim::Radiance())
                 .Default(Value::Number(1, Dim::Radiance()))
                 .Min(0)
                 .Max(MaxLightStrength),
             P::Spectrum("spectrum", "spectral shape").Default(Value::Number(1)),
             P::Bool("two_sided", "emit from both sides").Default(Value::Bool(false))}};
        return s;
    }
    static std::unique_ptr<Light> Create(const ParamDict &d, BuildContext &ctx) {
        auto shape = ctx.GetRef<Shape>(d, "shape");
        if (shape->areaLight) throw Error(d.Loc("shape"), "shape '" + shape->name + "' already has an area light");
        auto light = std::make_unique<AreaLight>(shape, d.GetNumber("radiance"), ctx.GetSpectrum(d, "spectrum"),
                                                 d.GetBool("two_sided"));
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
        return EvalEmission(*spectrum_, wl) * radiance_;
    }
    std::optional<LightSample> SampleLi(const LightSampleContext &ctx, const Vec2 &u,
                                        const SampledWavelengths &wl) const override {
        ShapeSample ss = shape_->Sample(u);
        Vec3 d = ss.p - ctx.p;
        double r2 = LengthSquared(d);
        if (!(r2 > 0)) return std::nullopt;
        double r = std::sqrt(r2);
        Vec3 wi = d / r;
        double cosL = std::abs(Dot(ss.n, wi));
        if (cosL < 1e-12) return std::nullopt;
        SampledSpectrum Le = L(ss.p, ss.n, -wi, wl);
        if (Le.IsZero()) return std::nullopt;
        // Area density → solid-angle density: p_ω = p_A · r² / |cos θ_light|.
        return LightSample{Le, wi, r, ss.pdfArea * r2 / cosL, false};
    }
    double PdfLi(const LightSampleContext &ctx, const Vec3 &wi, const Vec3 &pLight, const Vec3 &nLight) const override {
        double cosL = std::abs(Dot(nLight, wi));
        if (cosL < 1e-12) return 0;
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
    const Spectrum &EmissionSpectrum() const override { return *spectrum_; }
    double PowerScale() const override { return radiance_ * Pi * shape_->Area() * (twoSided_ ? 2 : 1); }
    std::string ToString() const override { return "area { shape = " + shape_->ToString() + " }"; }

  private:
    std::shared_ptr<Shape> shape_;
    double radiance_;
    std::shared_ptr<const Spectrum> spectrum_;
    bool twoSided_;
};

PHASOR_EXPORT_PLUGIN(Light, AreaLight)

}  // namespace phasor
