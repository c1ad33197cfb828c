// SPDX-License-Identifier: Apache-2.0
// phasor — `plastic`: a Lambertian base under a smooth, clear dielectric coat (paint, glazed
// ceramic, plastic; the worked example of docs/kernels.md).
//
// Two lobes. Light reflected by the coat's top surface is a near-delta specular lobe with the
// dielectric Fresnel reflectance F(θ_i) (listed, id 0). Light refracted into the coat, scattered by
// the Lambertian base (albedo ρ) and reflected back and forth between base and coat until it
// escapes is a continuous lobe (id 1), f = ρ·(1 − F(θ_i))·(1 − F(θ_o)) / (π·η²·(1 − ρ·F̄_in)):
// (1 − F(θ_o))/η² carries the coat's inside radiance out (n² law), and the geometric series of
// inner reflections sums to 1/(1 − ρ·F̄_in), F̄_in the coat's hemispherical reflectance from
// inside (Saunderson 1942, J. Opt. Soc. Am. 32, 727; the smooth "plastic" of pbrt and Mitsuba).
// Integrating f·cosθ_o gives the total reflectance F + (1 − F)·ρ·(1 − F̄_in)/(1 − ρ·F̄_in): exactly
// 1 for ρ = 1. Valid for a coat thicker than the light's coherence length (its inner reflections
// add in power; a thin coat interferes: thin_film) and thin against the footprint (the diffuse
// light leaves where it entered), an optically flat coat and a non-absorbing coat index. Two-sided
// like `diffuse`: it reflects into wi's hemisphere and never transmits. Reciprocal. The lobe is
// picked ∝ its share of the hero's reflectance; the diffuse direction is cosine-weighted.
#include <memory>
#include <sstream>

#include "core/diagnostics.h"
#include "core/render/material.h"
#include "core/render/registry.h"
#include "core/render/sampling.h"
#include "core/spectrum/complex_spectrum.h"
#include "materials/fresnel.h"

namespace phasor {

class PlasticMaterial final : public Material {
  public:
    PlasticMaterial(SpectrumTexture albedo, std::shared_ptr<const ComplexSpectrum> ior)
        : albedo_(std::move(albedo)), ior_(std::move(ior)) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "material",
            "plastic",
            "Lambertian base under a smooth clear coat: Fresnel specular lobe + diffuse lobe with inner reflections",
            {
                P::SpectrumTexture("reflectance", "albedo ρ(λ) ∈ [0, 1] of the Lambertian base, or a texture")
                    .Default(Value::Number(0.5))
                    .Min(0)
                    .Max(1),
                P::ComplexSpectrum("ior", "real index of the coat (κ = 0): a number, a glass such as \"BK7\", or a spectrum")
                    .Default(Value::Number(1.5)),
            }};
        return s;
    }

    static std::unique_ptr<Material> Create(const ParamDict &d, BuildContext &ctx) {
        SpectrumTexture albedo = ctx.GetSpectrumTexture(d, "reflectance");  // a texture's range is checked here
        if (!albedo.IsTexture() && !(albedo.MaxValue() <= 1))
            throw Error(d.Loc("reflectance"), "'reflectance' must lie in [0, 1]; its maximum is " +
                                                  std::to_string(albedo.MaxValue()));
        auto ior = ctx.GetComplexSpectrum(d, "ior");  // n > 0, κ ≥ 0 checked here
        for (double l = 360e-9; l <= 1000e-9; l += 5e-9)
            if (ior->Eval(l).imag() != 0)
                throw Error(d.Loc("ior"), "the coat's 'ior' must be real (κ = 0); it is " + ior->ToString());
        return std::make_unique<PlasticMaterial>(std::move(albedo), std::move(ior));
    }

    /// Presets for the contract suite: the default, a lossless white base (reflects exactly 1),
    /// a dispersive BK7 coat over the fixture checkerboard, a black base (the coat alone).
    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(4);
        p[1].Set("reflectance", Value::Number(1.0));
        p[2].Set("reflectance", Value::Ref("contract_checker")).Set("ior", Value::String("BK7"));
        p[3].Set("reflectance", Value::Number(0.0)).Set("ior", Value::Number(2.0));
        return p;
    }

    const PreparedKernel &Prepare(const ScatterQuery &q, ScratchBuffer &scratch) const override {
        return *scratch.New<Prepared>(*this, q, scratch);
    }

    std::string ToString() const override {
        std::ostringstream os;
        os << "PlasticMaterial[ reflectance = " << albedo_.ToString() << ", ior = " << ior_->ToString() << " ]";
        return os.str();
    }

  private:
    /// The coat for one query, per carried wavelength: relative index η = n_coat/n_outside, the
    /// specular reflectance F(θ_i), the albedo ρ and the inner reflectance F̄_in; and the
    /// probability of picking the specular lobe, F/(F + diffuse reflectance), each the largest over
    /// the carried wavelengths (so that a base black at the hero still samples its colour).
    struct Coat {
        SampledSpectrum eta, fresnel, albedo, inner;
        double specProb = 0;
    };
    bool Evaluate(const ScatterQuery &q, Coat *c) const {
        if (q.wi.z == 0) return false;
        c->albedo = albedo_.Eval(q.tex, *q.wl);
        double spec = 0, diffuse = 0;
        for (int i = 0; i < q.wl->Count(); ++i) {
            c->eta[i] = ior_->Eval(q.wl->lambda[i]).real() / q.etaOutside;
            c->fresnel[i] = FresnelDielectric(std::abs(q.wi.z), c->eta[i]);
            c->inner[i] = FresnelDiffuseReflectance(1 / c->eta[i]);  // from inside the coat
            const double f = c->fresnel[i], rho = c->albedo[i], in = c->inner[i];
            spec = std::max(spec, f);
            diffuse = std::max(diffuse, (1 - f) * rho * (1 - in) / (1 - rho * in));  // Saunderson
        }
        if (!(spec + diffuse > 0)) return false;  // a black base under an index-matched coat
        c->specProb = spec / (spec + diffuse);
        return true;
    }

    /// The kernel at one hit: the coat evaluated there (lobe 0, the coat's mirror reflection, listed
    /// with weight F(θ_i, λ) and probability Coat::specProb; lobe 1, the diffuse light).
    class Prepared final : public PreparedKernel {
      public:
        Prepared(const PlasticMaterial &m, const ScatterQuery &q, ScratchBuffer &scratch) : PreparedKernel(q), m_(&m) {
            const bool diffuse = m.albedo_.MaxValue() > 0;
            caps_ = CapNearDelta | (diffuse ? CapContinuous : 0u);
            if (diffuse) continuous_.Add(1);
            ok_ = m.Evaluate(q, &c_);
            if (!ok_ || !(c_.specProb > 0)) return;
            LobeList list(scratch, 1);
            NearDeltaLobe &l = list.Add();
            l.id = 0;
            l.flags = ScatterReflection | ScatterNearDelta;
            l.wo.fill(ReflectLocal(q.wi));
            l.SetWeight(c_.fresnel);
            l.nIn.fill(q.etaOutside);
            l.nOut.fill(q.etaOutside);
            l.prob = c_.specProb;
            lobes_ = list.Lobes();
        }

        /// Lobe 0: Jones diag(r_s, r_p) of the coat's surface; lobe 1: the diffuse light, depolarised.
        std::optional<LobeResponse> EvalLobe(int lobe, const Vec3 &wo) const override {
            LobeResponse r;
            if (lobe == 0 && SameDirection(wo, ReflectLocal(q_.wi))) {
                r.hasJones = true;
                for (int i = 0; i < q_.wl->Count(); ++i) {
                    const double n = m_->ior_->Eval(q_.wl->lambda[i]).real();
                    const FresnelCoefficients f = FresnelAmplitudes(std::abs(q_.wi.z), q_.etaOutside, Complex(n, 0));
                    r.jones[i] = Jones::Diagonal(f.rs, f.rp);
                    r.mueller[i] = Mueller::FromJones(r.jones[i]);
                }
                return r;
            }
            if (lobe != 1 || q_.wi.z * wo.z <= 0) return std::nullopt;
            const SampledSpectrum f = EvalContinuous(wo) * std::abs(wo.z);
            for (int i = 0; i < q_.wl->Count(); ++i) r.mueller[i] = Mueller::Depolarizer(f[i]);
            return r;
        }

      private:
        std::optional<ScatterSample> SampleLobes(double u0, const Vec2 &u) const override {
            if (!ok_) return std::nullopt;
            ScatterSample s;
            s.eta = 1;
            if (u0 < c_.specProb) {  // the coat's mirror reflection
                s.wo = ReflectLocal(q_.wi);
                s.weight = c_.fresnel / c_.specProb;
                s.pdf = c_.specProb;
                s.lobe = 0;
                s.flags = ScatterReflection | ScatterNearDelta;
                return s;
            }
            // The diffuse lobe, cosine-weighted on wi's side (Malley's method).
            const Vec2 d = ConcentricDisc(u);
            const double z = SafeSqrt(1 - d.x * d.x - d.y * d.y);
            if (z == 0) return std::nullopt;
            s.wo = Vec3(d.x, d.y, q_.wi.z > 0 ? z : -z);
            s.pdf = (1 - c_.specProb) * z * InvPi;
            s.weight = Diffuse(z) * (z / s.pdf);
            s.lobe = 1;
            s.flags = ScatterReflection | ScatterDiffuse;
            return s;
        }
        SampledSpectrum EvalContinuous(const Vec3 &wo) const override {
            if (q_.wi.z * wo.z <= 0 || !ok_) return SampledSpectrum(0.0);
            return Diffuse(std::abs(wo.z));
        }
        double PdfContinuous(const Vec3 &wo) const override {
            if (q_.wi.z * wo.z <= 0 || !ok_) return 0;
            return (1 - c_.specProb) * std::abs(wo.z) * InvPi;
        }
        KernelValue EvalPdfContinuous(const Vec3 &wo, const IncidentWave &) const override {
            if (q_.wi.z * wo.z <= 0 || !ok_) return KernelValue{};
            return KernelValue{Diffuse(std::abs(wo.z)), (1 - c_.specProb) * std::abs(wo.z) * InvPi};
        }
        /// The diffuse lobe's f [1/sr] towards |cosθ_o| = cosO (file comment).
        SampledSpectrum Diffuse(double cosO) const {
            SampledSpectrum f(0.0);
            for (int i = 0; i < q_.wl->Count(); ++i) {
                const double e = c_.eta[i], rho = c_.albedo[i];
                f[i] = rho * (1 - c_.fresnel[i]) * (1 - FresnelDielectric(cosO, e)) / (Pi * e * e * (1 - rho * c_.inner[i]));
            }
            return f;
        }

        const PlasticMaterial *m_;
        Coat c_;
        bool ok_ = false;  // Evaluate succeeded: the coat reflects something
    };

    SpectrumTexture albedo_;
    std::shared_ptr<const ComplexSpectrum> ior_;
};

PHASOR_EXPORT_PLUGIN(Material, PlasticMaterial)

}  // namespace phasor
