// SPDX-License-Identifier: Apache-2.0
// phasor — `diffuse`: an ideal Lambertian reflector (theory §4.7).
//
// Models a matte surface whose scattered radiance is independent of direction: f = R/π per unit
// solid angle, R ∈ [0, 1] the directional-hemispherical reflectance (from a spectrum or a
// texture). Valid for surfaces rough on the scale of the wavelength and the footprint; in the
// generalized-ray picture it is a continuous lobe, so it is the same in the ray-optics limit and
// for generalized rays (the GR keeps β, ρ; coherence handling is the integrator's business,
// theory §4.7). Two-sided (pbrt's convention): it reflects into the hemisphere of wi, whichever
// side of the shading normal that is, and never transmits. Sampling: cosine-weighted hemisphere
// (Malley's method on Shirley & Chiu's concentric disc mapping), so the weight is exactly R.
#include <memory>
#include <sstream>

#include "core/diagnostics.h"
#include "core/render/material.h"
#include "core/render/registry.h"
#include "core/render/sampling.h"

namespace phasor {

class DiffuseMaterial final : public Material {
  public:
    explicit DiffuseMaterial(SpectrumTexture reflectance) : reflectance_(std::move(reflectance)) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "material",
            "diffuse",
            "Lambertian reflector (two-sided, no transmission): f = R/π, cosine-weighted sampling",
            {
                P::SpectrumTexture("reflectance",
                                   "directional-hemispherical reflectance R(λ) in [0, 1], or a spectral or "
                                   "dimensionless texture R(uv, λ)")
                    .Default(Value::Number(0.5))
                    .Min(0)
                    .Max(1),
                P::Ref("texture", "texture", "the same as reflectance = @texture; replaces 'reflectance'")
                    .Min(0)
                    .Max(1),
            }};
        return s;
    }

    static std::unique_ptr<Material> Create(const ParamDict &dict, BuildContext &ctx) {
        if (dict.Has("texture") && dict.Has("reflectance")) {
            ctx.Diag().Warning(dict.Loc("reflectance"), "ignoring 'reflectance' because 'texture' was given");
            dict.GetValue("reflectance");  // reported here, not again as unused
        }
        // A texture's range is checked against [0, 1] by the accessor; a spectrum's here.
        const std::string param = dict.Has("texture") ? "texture" : "reflectance";
        SpectrumTexture r = ctx.GetSpectrumTexture(dict, param);
        if (!r.IsTexture() && !(r.MaxValue() <= 1))
            throw Error(dict.Loc(param),
                        "'reflectance' must lie in [0, 1]; its maximum is " + std::to_string(r.MaxValue()));
        return std::make_unique<DiffuseMaterial>(std::move(r));
    }

    /// Presets for the generic contract suite (tests/materials/kernel_contract_test.cpp). The
    /// suite defines the fixture texture @contract_checker.
    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(3);
        p[0].Set("reflectance", Value::Number(0.5));
        p[1].Set("reflectance", Value::Number(1.0));
        p[2].Set("texture", Value::Ref("contract_checker"));
        return p;
    }

    const PreparedKernel &Prepare(const ScatterQuery &q, ScratchBuffer &scratch) const override {
        return *scratch.New<Prepared>(q, reflectance_.Eval(q.tex, *q.wl));
    }

    std::string ToString() const override {
        std::ostringstream os;
        os << "DiffuseMaterial[ reflectance = " << reflectance_.ToString() << " ]";
        return os.str();
    }

  private:
    static bool SameSide(const Vec3 &a, const Vec3 &b) { return a.z * b.z > 0; }

    /// The kernel at one hit: R evaluated there.
    class Prepared final : public PreparedKernel {
      public:
        Prepared(const ScatterQuery &q, const SampledSpectrum &r) : PreparedKernel(q), r_(r) {
            caps_ = CapContinuous;
            continuous_.Add(0);
        }
        /// Lobe 0 (the only one): a depolariser, M = (R/π)·|cosθo|·diag(1, 0, 0, 0) (theory §4.9).
        std::optional<LobeResponse> EvalLobe(int lobe, const Vec3 &wo) const override {
            if (lobe != 0 || !SameSide(q_.wi, wo)) return std::nullopt;
            const SampledSpectrum f = r_ * (InvPi * std::abs(wo.z));
            LobeResponse r;
            for (int i = 0; i < q_.wl->Count(); ++i) r.mueller[i] = Mueller::Depolarizer(f[i]);
            return r;
        }

      private:
        std::optional<ScatterSample> SampleLobes(double, const Vec2 &u) const override {
            if (q_.wi.z == 0) return std::nullopt;
            // Malley's method: project a uniform disc sample up to the hemisphere (pdf = cosθ/π).
            const Vec2 d = ConcentricDisc(u);
            const double z = SafeSqrt(1 - d.x * d.x - d.y * d.y);
            if (z == 0) return std::nullopt;  // exactly on the horizon: pdf 0
            ScatterSample s;
            s.wo = Vec3(d.x, d.y, q_.wi.z > 0 ? z : -z);  // mirrored to wi's side (two-sided)
            s.pdf = z * InvPi;
            s.weight = r_;  // f·|cosθo|/pdf = (R/π)·cosθ/(cosθ/π)
            s.lobe = 0;
            s.flags = ScatterReflection | ScatterDiffuse;
            s.eta = 1;
            return s;
        }
        SampledSpectrum EvalContinuous(const Vec3 &wo) const override {
            return SameSide(q_.wi, wo) ? r_ * InvPi : SampledSpectrum(0);
        }
        double PdfContinuous(const Vec3 &wo) const override { return SameSide(q_.wi, wo) ? std::abs(wo.z) * InvPi : 0; }
        KernelValue EvalPdfContinuous(const Vec3 &wo, const IncidentWave &) const override {
            if (!SameSide(q_.wi, wo)) return KernelValue{};
            return KernelValue{r_ * InvPi, std::abs(wo.z) * InvPi};
        }

        SampledSpectrum r_;  // R(λ) at the hit
    };

    SpectrumTexture reflectance_;
};

PHASOR_EXPORT_PLUGIN(Material, DiffuseMaterial)

}  // namespace phasor
