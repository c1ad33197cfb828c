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
// Index: `ior` (a complex constant), or `eta` and `k` (spectra), or `metal` (tabulated: Al from
// Rakić et al. 1998, Ag/Au/Cu from Johnson & Christy 1972; see metal_ior.h). The index is relative
// to the medium outside (ScatterQuery::etaOutside).
#include <memory>
#include <sstream>

#include "core/diagnostics.h"
#include "core/material.h"
#include "core/registry.h"
#include "materials/fresnel.h"
#include "materials/metal_ior.h"

namespace phasor {

namespace {

// The real or imaginary part of a tabulated metal's index as a Spectrum.
class MetalIndexSpectrum final : public Spectrum {
  public:
    MetalIndexSpectrum(Metal m, bool imaginary, std::string name)
        : metal_(m), imaginary_(imaginary), name_(std::move(name)) {}
    double Eval(double lambda) const override {
        Complex n = MetalIndex(metal_, lambda);
        return imaginary_ ? n.imag() : n.real();
    }
    double MaxValue() const override {
        double m = 0;
        for (double l = 100e-9; l <= 10e-6; l *= 1.01) m = std::max(m, Eval(l));
        return m;
    }
    std::pair<double, double> Support() const override { return {0, Infinity}; }
    std::string ToString() const override {
        return std::string(imaginary_ ? "k" : "n") + "(\"" + name_ + "\")";
    }

  private:
    Metal metal_;
    bool imaginary_;
    std::string name_;
};

}  // namespace

class ConductorMaterial final : public Material {
  public:
    ConductorMaterial(std::shared_ptr<const Spectrum> eta, std::shared_ptr<const Spectrum> k,
                      std::optional<Metal> metal = std::nullopt)
        : eta_(std::move(eta)), k_(std::move(k)), metal_(metal) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "material",
            "conductor",
            "smooth metal: specular reflection with the exact Fresnel reflectance of a complex index n + iκ",
            {
                P::Complex("ior",
                           "constant complex index n + iκ relative to the outside (n > 0, κ ≥ 0), "
                           "e.g. 0.18+3.42i; replaces 'eta'/'k'/'metal'"),
                P::Spectrum("eta", "real part n(λ) of the index (> 0); needs 'k'"),
                P::Spectrum("k", "extinction coefficient κ(λ) ≥ 0; needs 'eta'"),
                P::String("metal",
                          "tabulated index used when neither 'ior' nor 'eta'/'k' is given: "
                          "Al (Rakić 1998), Ag, Au, Cu (Johnson & Christy 1972)")
                    .Default(Value::String("Al"))
                    .Choices(MetalNames()),
            }};
        return s;
    }

    static std::unique_ptr<Material> Create(const ParamDict &dict, BuildContext &ctx) {
        const bool hasIor = dict.Has("ior"), hasEta = dict.Has("eta"), hasK = dict.Has("k");
        const int ways = int(hasIor) + int(hasEta || hasK) + int(dict.Has("metal"));
        if (ways > 1)
            throw Error(dict.EntityLoc(), "conductor: give exactly one of 'ior', 'eta' with 'k', or 'metal'");
        if (hasIor) {
            Complex n = dict.GetComplex("ior");
            if (!(n.real() > 0) || !(n.imag() >= 0))
                throw Error(dict.Loc("ior"),
                            "'ior' must have a positive real part and a non-negative "
                            "imaginary part (n + iκ, κ ≥ 0)");
            return std::make_unique<ConductorMaterial>(std::make_shared<ConstantSpectrum>(n.real()),
                                                       std::make_shared<ConstantSpectrum>(n.imag()));
        }
        if (hasEta != hasK)
            throw Error(dict.Loc(hasEta ? "eta" : "k"), std::string("conductor: '") + (hasEta ? "eta" : "k") +
                                                            "' needs '" + (hasEta ? "k" : "eta") +
                                                            "' as well");
        if (hasEta) {
            auto eta = ctx.GetSpectrum(dict, "eta");
            auto k = ctx.GetSpectrum(dict, "k");
            // Check the physical range over the visible and near infrared.
            for (double l = 360e-9; l <= 1000e-9; l += 5e-9) {
                if (!(eta->Eval(l) > 0))
                    throw Error(dict.Loc("eta"), "'eta' must be positive; it is " +
                                                     std::to_string(eta->Eval(l)) + " at " +
                                                     std::to_string(l * 1e9) + " nm");
                if (!(k->Eval(l) >= 0))
                    throw Error(dict.Loc("k"), "'k' must be non-negative; it is " +
                                                   std::to_string(k->Eval(l)) + " at " +
                                                   std::to_string(l * 1e9) + " nm");
            }
            return std::make_unique<ConductorMaterial>(std::move(eta), std::move(k));
        }
        std::string name = dict.GetString("metal");
        std::optional<Metal> m = MetalFromName(name);
        if (!m)
            throw Error(dict.Loc("metal"),
                        "unknown metal '" + name + "'");  // schema choices catch this first
        return std::make_unique<ConductorMaterial>(std::make_shared<MetalIndexSpectrum>(*m, false, name),
                                                   std::make_shared<MetalIndexSpectrum>(*m, true, name), m);
    }

    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(4);
        // p[0]: the default (aluminium).
        p[1].Set("metal", Value::String("Au"));
        p[2].Set("ior", Value::ComplexNumber(Complex(0.2, 3.0)));
        p[3].Set("eta", Value::Number(1.8)).Set("k", Value::Number(0.4));  // weakly absorbing, low R
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
            const FresnelCoefficients c = FresnelAmplitudes(std::abs(q.wi.z), q.etaOutside, Index(q.wl->lambda[i]));
            r.jones[i] = Jones::Diagonal(c.rs, c.rp);
            r.mueller[i] = Mueller::FromJones(r.jones[i]);
        }
        return r;
    }

    std::string ToString() const override {
        std::ostringstream os;
        os << "ConductorMaterial[ eta = " << eta_->ToString() << ", k = " << k_->ToString() << " ]";
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

    /// The complex index at vacuum wavelength l [m]; a tabulated metal is evaluated once (not once
    /// for n and once for κ).
    Complex Index(double l) const { return metal_ ? MetalIndex(*metal_, l) : Complex(eta_->Eval(l), k_->Eval(l)); }

    SampledSpectrum Reflectance(const ScatterQuery &q) const {
        SampledSpectrum r;
        const double cosI = std::abs(q.wi.z);
        for (int i = 0; i < q.wl->Count(); ++i) r[i] = FresnelComplex(cosI, q.etaOutside, Index(q.wl->lambda[i]));
        return r;
    }

    std::shared_ptr<const Spectrum> eta_, k_;
    std::optional<Metal> metal_;  // set for `metal`: eta_/k_ are then views of MetalIndex()
};

PHASOR_EXPORT_PLUGIN(Material, ConductorMaterial)

}  // namespace phasor
