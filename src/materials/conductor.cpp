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
// flipped normals). Never transmits; the rest (1 − R) is absorbed. The lobe is listed
// (ListNearDelta, id 0), so integrators measure delta sources through it in closed form (D14).
//
// Index: `ior`, a complex spectrum (core/spectrum/complex_spectrum.h): a named material (tabulated: Al from
// Rakić et al. 1998, Ag/Au/Cu from Johnson & Christy 1972; see core/spectrum/named_ior.h), a constant
// n + iκ, or nk(n = …, k = …) spectra. The index is relative to the medium outside
// (ScatterQuery::etaOutside).
#include <memory>
#include <sstream>

#include "core/spectrum/complex_spectrum.h"
#include "core/diagnostics.h"
#include "core/render/material.h"
#include "core/render/registry.h"
#include "materials/fresnel.h"
#include "materials/smooth_surface.h"

namespace phasor {

class ConductorMaterial final : public Material {
  public:
    explicit ConductorMaterial(std::shared_ptr<const ComplexSpectrum> ior) : ior_(ior), surface_(ior, 0, nullptr) {}

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

    unsigned Capabilities(const ScatterQuery &) const override { return CapNearDelta; }

    /// One lobe, id 0: the mirror direction (on wi's side: two-sided), weight R(λ).
    void ListNearDelta(const ScatterQuery &q, NearDeltaLobes &out) const override {
        if (q.wi.z == 0) return;
        NearDeltaLobe &l = out.Add();
        l.id = 0;
        l.flags = ScatterReflection | ScatterNearDelta;
        l.wo.fill(ReflectLocal(q.wi));
        l.weight = Reflectance(q);
        l.nIn.fill(q.etaOutside);
        l.nOut.fill(q.etaOutside);
        l.prob = 1;
    }

    /// Lobe 0 towards the mirror direction: Jones diag(r_s, r_p) (theory §4.1).
    std::optional<LobeResponse> EvalLobe(const ScatterQuery &q, int lobe, const Vec3 &wo) const override {
        if (lobe != 0 || q.wi.z == 0 || !SameDirection(wo, ReflectLocal(q.wi))) return std::nullopt;
        LobeResponse r;
        r.hasJones = true;
        for (int i = 0; i < q.wl->Count(); ++i) {
            const FresnelCoefficients c = FresnelAmplitudes(std::abs(q.wi.z), q.etaOutside, ior_->Eval(q.wl->lambda[i]));
            r.jones[i] = Jones::Diagonal(c.rs, c.rp);
            r.mueller[i] = Mueller::FromJones(r.jones[i]);
        }
        return r;
    }

    const SmoothSurface *Surface() const override { return &surface_; }

    std::string ToString() const override {
        std::ostringstream os;
        os << "ConductorMaterial[ ior = " << ior_->ToString() << " ]";
        return os.str();
    }

  private:
    std::optional<ScatterSample> SampleLobes(const ScatterQuery &q, double, const Vec2 &) const override {
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

    SampledSpectrum Reflectance(const ScatterQuery &q) const {
        SampledSpectrum r;
        const double cosI = std::abs(q.wi.z);
        for (int i = 0; i < q.wl->Count(); ++i) {
            r[i] = FresnelComplex(cosI, q.etaOutside, ior_->Eval(q.wl->lambda[i]));
        }
        return r;
    }

    std::shared_ptr<const ComplexSpectrum> ior_;  // n + iκ of the metal, relative to the outside
    SmoothSurface surface_;                       // the same interface, for kernels that name it `substrate`
};

PHASOR_EXPORT_PLUGIN(Material, ConductorMaterial)

}  // namespace phasor
