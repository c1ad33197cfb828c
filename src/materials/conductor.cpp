// SPDX-License-Identifier: Apache-2.0
// phasor — `conductor`: a smooth (optically flat) metal surface (theory §4.1).
//
// One near-delta lobe: specular reflection with the exact unpolarised Fresnel reflectance of a
// complex index n + iκ, R = (|r_s|² + |r_p|²)/2 (fresnel.h). The generalized ray keeps β and ρ
// and only its mean direction is mirrored (supplement S6.4), so in the ray-optics limit the lobe
// is a Dirac delta and for a generalized ray its angular width is the ray's own spread σ_k/k.
// Valid when the surface roughness is ≪ λ over the footprint (otherwise use a rough kernel).
// Two-sided like pbrt's conductor: a ray arriving from below the shading normal is mirrored on
// that side too (the inside of a metal is unreachable, so this only matters for thin sheets and
// flipped normals). Never transmits; the rest (1 − R) is absorbed. For a generalized ray
// (!ScatterQuery::rayOptics) Eval reports the lobe as the GR's angular Gaussian (near_delta.h).
//
// Index: `ior`, a complex spectrum (core/complex_spectrum.h): a named material (tabulated: Al from
// Rakić et al. 1998, Ag/Au/Cu from Johnson & Christy 1972; see core/named_ior.h), a constant
// n + iκ, or nk(n = …, k = …) spectra. The index is relative to the medium outside
// (ScatterQuery::etaOutside).
#include <memory>
#include <sstream>

#include "core/complex_spectrum.h"
#include "core/diagnostics.h"
#include "core/material.h"
#include "core/registry.h"
#include "materials/fresnel.h"
#include "materials/near_delta.h"

namespace phasor {

class ConductorMaterial final : public Material {
  public:
    explicit ConductorMaterial(std::shared_ptr<const ComplexSpectrum> ior) : ior_(std::move(ior)) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "material",
            "conductor",
            "smooth metal: specular reflection with the exact Fresnel reflectance of a complex index n + iκ",
            {
                P::ComplexSpectrum("ior",
                                   "complex index n + iκ(λ) relative to the outside (n > 0, κ ≥ 0): a "
                                   "material (Al: Rakić 1998; Ag, Au, Cu: Johnson & Christy 1972), a "
                                   "constant such as 0.18+3.42i, a spectrum, or nk(n = …, k = …)")
                    .Default(Value::String("Al")),
            }};
        return s;
    }

    static std::unique_ptr<Material> Create(const ParamDict &dict, BuildContext &ctx) {
        return std::make_unique<ConductorMaterial>(ctx.GetComplexSpectrum(dict, "ior"));
    }

    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(4);
        // p[0]: the default (aluminium).
        p[1].Set("ior", Value::String("Au"));
        p[2].Set("ior", Value::ComplexNumber(Complex(0.2, 3.0)));
        p[3].Set("ior", Value::Call("nk", {Value::Number(1.8), Value::Number(0.4)}, {"n", "k"}));  // weakly absorbing, low R
        return p;
    }

    std::optional<ScatterSample> Sample(const ScatterQuery &q, double, const Vec2 &) const override {
        if (q.wi.z == 0) return std::nullopt;
        ScatterSample s;
        s.wo = ReflectLocal(q.wi);  // mirrored on wi's side (two-sided)
        s.weight = Reflectance(q);  // a/p = R/1
        s.pdf = 1;                  // the only lobe
        s.lobe = 0;
        s.flags = ScatterReflection | ScatterNearDelta;
        s.eta = 1;
        return s;
    }

    SampledSpectrum Eval(const ScatterQuery &q, const Vec3 &wo) const override {
        // Ray-optics limit: a Dirac delta has no finite density. A generalized ray's mirror lobe
        // is its own angular Gaussian about the mirror direction (near_delta.h), so
        // f·|cosθo| = R·N(wo; wr, σ_k²/k²): NEE to a delta-direction source then yields the glint
        // R·E·k²·N₂(Δk⊥; 0, σ_k²I) of theory §2.4 item 2.
        if (!SpreadNearDelta(q) || q.wi.z == 0 || wo.z == 0) return SampledSpectrum(0);
        const Vec3 wr = ReflectLocal(q.wi);
        const SampledSpectrum r = Reflectance(q);
        SampledSpectrum f(0.0);
        for (int i = 0; i < q.wl->Count(); ++i) {
            const double var = NearDeltaAngularVariance(q, q.etaOutside, q.wl->lambda[i]);
            f[i] = r[i] * NearDeltaDensity(wo, wr, var) / std::abs(wo.z);
        }
        return f;
    }

    double Pdf(const ScatterQuery &, const Vec3 &) const override { return 0; }

    bool IsDeltaOnly() const override { return true; }

    std::string ToString() const override {
        std::ostringstream os;
        os << "ConductorMaterial[ ior = " << ior_->ToString() << " ]";
        return os.str();
    }

  private:
    SampledSpectrum Reflectance(const ScatterQuery &q) const {
        SampledSpectrum r;
        const double cosI = std::abs(q.wi.z);
        for (int i = 0; i < q.wl->Count(); ++i) {
            r[i] = FresnelComplex(cosI, q.etaOutside, ior_->Eval(q.wl->lambda[i]));
        }
        return r;
    }

    std::shared_ptr<const ComplexSpectrum> ior_;  // n + iκ of the metal, relative to the outside
};

PHASOR_EXPORT_PLUGIN(Material, ConductorMaterial)

}  // namespace phasor
