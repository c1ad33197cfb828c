// SPDX-License-Identifier: Apache-2.0
// phasor — `dielectric`: a smooth interface to a transparent medium (glass, water; theory §4.1).
//
// Two near-delta lobes (supplement S6.4): specular reflection with the unpolarised Fresnel
// reflectance R and refraction by Snell's law with T = 1 − R; lossless, so R + T = 1 exactly.
// The generalized ray keeps β and ρ; only its mean direction changes, so in the ray-optics limit
// both lobes are Dirac deltas (for a generalized ray their width is the ray's spread σ_k/k).
// Valid for an optically flat interface (roughness ≪ λ over the footprint) and a non-absorbing
// interior. The shading normal points outside: wi.z > 0 means the path arrives from the outside
// medium (index ScatterQuery::etaOutside) and enters the interior (index `ior`), wi.z < 0 that it
// is inside and leaves. Lobe choice is ∝ Fresnel at the hero wavelength (theory §3.1); the
// refracted radiance carries the (η_i/η_t)² factor (camera paths transport radiance, whose
// basic invariant is L/n²). A wavelength-dependent index makes refraction dispersive: its
// direction is the hero's, and the integrator drops the companions (theory §0 D10). For a
// generalized ray both lobes are listed (ListNearDelta: ids 0 reflection, 1 refraction) and
// measured in closed form by the integrator (D14).
//
// Dispersion: `ior` is a complex spectrum (core/spectrum/complex_spectrum.h) with κ = 0: a constant, a named
// glass ("BK7", "fused_silica", "water", …; core/spectrum/named_ior.h) or any spectrum; `cauchy_b` adds
// Cauchy's term, η(λ) = ior(λ) + B/λ² (Cauchy 1836; e.g. BK7 ≈ 1.5046 + 4.20e-3 µm²/λ²).
#include <memory>
#include <sstream>

#include "core/spectrum/complex_spectrum.h"
#include "core/diagnostics.h"
#include "core/render/material.h"
#include "core/render/registry.h"
#include "materials/fresnel.h"
#include "materials/smooth_surface.h"

namespace phasor {

class DielectricMaterial final : public Material {
  public:
    DielectricMaterial(std::shared_ptr<const ComplexSpectrum> ior, double cauchyB)
        : ior_(ior), cauchyB_(cauchyB), surface_(ior, cauchyB, nullptr) {
        // Dispersive if η varies over the band a path may carry (checked on a fine grid).
        const double eta0 = Index(550e-9);
        for (double l = 200e-9; l <= 3000e-9; l *= 1.005)
            if (std::abs(Index(l) - eta0) > 1e-12 * eta0) dispersive_ = true;
    }

    static const Schema &GetSchema() {
        static const Schema s{
            "material",
            "dielectric",
            "smooth dielectric interface: Fresnel-weighted specular reflection and Snell refraction",
            {
                P::ComplexSpectrum("ior",
                                   "index of refraction η(λ) of the inside (real: κ = 0, n > 0; the outside "
                                   "is the query's medium, normally air = 1): a number, a glass such as "
                                   "\"BK7\", or a spectrum")
                    .Default(Value::Number(1.5)),
                P::Number("cauchy_b",
                          "Cauchy dispersion term B added to 'ior': η(λ) = ior(λ) + B/λ² "
                          "(e.g. 0.0042 um^2)",
                          Dim::Area())
                    .Default(Value::Number(0, Dim::Area())),
            }};
        return s;
    }

    static std::unique_ptr<Material> Create(const ParamDict &dict, BuildContext &ctx) {
        auto ior = ctx.GetComplexSpectrum(dict, "ior");
        for (double l = 360e-9; l <= 1000e-9; l += 5e-9)
            if (ior->Eval(l).imag() != 0)
                throw Error(dict.Loc("ior"), "dielectric 'ior' must be real (κ = 0: the interior does not "
                                             "absorb); it is " + ior->ToString() + " (use 'conductor' for metals)");
        const double b = dict.GetNumber("cauchy_b");
        auto m = std::make_unique<DielectricMaterial>(ior, b);
        for (double l = 360e-9; l <= 1000e-9; l += 5e-9)
            if (!(m->Index(l) > 0))
                throw Error(dict.Loc(dict.Has("ior") ? "ior" : "cauchy_b"),
                            "the index of refraction must be positive; it is " + std::to_string(m->Index(l)) +
                                " at " + std::to_string(l * 1e9) + " nm");
        return m;
    }

    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(5);
        // p[0]: the default, η = 1.5.
        p[1].Set("ior", Value::Number(1.33));
        p[2].Set("ior", Value::Number(2.42));  // diamond: strong reflection, early TIR
        p[3].Set("ior", Value::Number(1.5))
            .Set("cauchy_b", Value::Number(0.02e-12, Dim::Area()));  // dispersive
        p[4].Set("ior", Value::Number(1.0));                         // index matched: pure transmission
        return p;
    }

    unsigned Capabilities(const ScatterQuery &) const override { return CapNearDelta; }

    /// Lobe 0: reflection, weight R(λ); lobe 1: refraction by Snell's law, weight T(λ)·(η_i/η_t)²,
    /// per wavelength along its own direction (dispersive when η varies); not listed under total
    /// internal reflection at the hero wavelength. Probabilities as in Sample: R and T at the hero.
    void ListNearDelta(const ScatterQuery &q, NearDeltaLobes &out) const override {
        Interface f;
        if (!Evaluate(q, &f)) return;
        // A lobe that carries nothing at any wavelength (index matched: R = 0) is not listed.
        bool reflects = false;
        for (int i = 0; i < q.wl->Count(); ++i) reflects = reflects || f.refl[i] > 0;
        NearDeltaLobe scratch;
        NearDeltaLobe &r = reflects ? out.Add() : scratch;
        r.id = 0;
        r.flags = ScatterReflection | ScatterNearDelta;
        r.wo.fill(ReflectLocal(q.wi));
        r.prob = f.refl[0];
        Vec3 wt;
        const bool refracts = f.refl[0] < 1 && RefractLocal(q.wi, f.eta[0], &wt);
        NearDeltaLobe *t = refracts ? &out.Add() : nullptr;
        if (t) {
            t->id = 1;
            t->flags = ScatterTransmission | ScatterNearDelta | (dispersive_ ? ScatterDispersive : 0u);
            t->prob = 1 - f.refl[0];
        }
        for (int i = 0; i < q.wl->Count(); ++i) {
            r.weight[i] = f.refl[i];
            r.nIn[i] = r.nOut[i] = f.nI[i];
            if (!t) continue;
            t->nIn[i] = f.nI[i];
            t->nOut[i] = f.nT[i];
            if (RefractLocal(q.wi, f.eta[i], &t->wo[i])) t->weight[i] = (1 - f.refl[i]) / (f.eta[i] * f.eta[i]);
            else t->wo[i] = wt;  // weight 0 at this companion (total internal reflection)
        }
    }

    /// Lobe 0 (mirror direction): Jones diag(r_s, r_p); lobe 1 (refracted direction at the hero):
    /// diag(t_s, t_p)·√(Re(n_t cosθ_t)/(n_i cosθ_i))·(η_i/η_t), so that M00 is the listed weight
    /// T·(η_i/η_t)² (theory §4.1: power factor and radiance scaling).
    std::optional<LobeResponse> EvalLobe(const ScatterQuery &q, int lobe, const Vec3 &wo) const override {
        Interface f;
        if ((lobe != 0 && lobe != 1) || !Evaluate(q, &f)) return std::nullopt;
        Vec3 dir = ReflectLocal(q.wi);
        if (lobe == 1 && !RefractLocal(q.wi, f.eta[0], &dir)) return std::nullopt;
        if (!SameDirection(wo, dir)) return std::nullopt;
        LobeResponse r;
        r.hasJones = true;
        const double cosI = std::abs(q.wi.z);
        for (int i = 0; i < q.wl->Count(); ++i) {
            const FresnelCoefficients c = FresnelAmplitudes(cosI, f.nI[i], Complex(f.nT[i], 0));
            if (lobe == 0) r.jones[i] = Jones::Diagonal(c.rs, c.rp);
            else {
                const double power = std::max(0.0, (f.nT[i] * c.cosThetaT).real()) / (f.nI[i] * cosI);
                r.jones[i] = Jones::Diagonal(c.ts, c.tp) * Complex(std::sqrt(power) / f.eta[i], 0);
            }
            r.mueller[i] = Mueller::FromJones(r.jones[i]);
        }
        return r;
    }

    const SmoothSurface *Surface() const override { return &surface_; }

    std::string ToString() const override {
        std::ostringstream os;
        os << "DielectricMaterial[ ior = " << ior_->ToString() << ", cauchy_b = " << cauchyB_
           << " m^2, dispersive = " << (dispersive_ ? "true" : "false") << " ]";
        return os.str();
    }

    /// Index of the interior at vacuum wavelength lambda [m].
    double Index(double lambda) const { return ior_->Eval(lambda).real() + cauchyB_ / (lambda * lambda); }

  private:
    /// The interface as seen from wi, per wavelength: indices of wi's side (nI) and the far side
    /// (nT), η = nT/nI and the unpolarised reflectance.
    struct Interface {
        std::array<double, NumWavelengths> nI{}, nT{}, eta{}, refl{};
    };
    /// False if wi is grazing or outside the index data (treated as absorbed).
    bool Evaluate(const ScatterQuery &q, Interface *f) const {
        if (q.wi.z == 0) return false;
        const bool entering = q.wi.z > 0;  // wi on the outside: the path crosses into the interior
        const double cosI = std::abs(q.wi.z);
        for (int i = 0; i < q.wl->Count(); ++i) {
            const double n = Index(q.wl->lambda[i]);
            if (!(n > 0)) return false;
            f->nI[i] = entering ? q.etaOutside : n;
            f->nT[i] = entering ? n : q.etaOutside;
            f->eta[i] = f->nT[i] / f->nI[i];
            f->refl[i] = FresnelDielectric(cosI, f->eta[i]);
        }
        return true;
    }

    std::optional<ScatterSample> SampleLobes(const ScatterQuery &q, double u0, const Vec2 &) const override {
        Interface f;
        if (!Evaluate(q, &f)) return std::nullopt;
        const int count = q.wl->Count();
        ScatterSample s;
        const double rHero = f.refl[0];
        if (u0 < rHero) {
            // Specular reflection, chosen with probability R(λ_hero): weight = R(λ)/R(λ_hero).
            s.wo = ReflectLocal(q.wi);
            for (int i = 0; i < count; ++i) s.weight[i] = f.refl[i] / rHero;
            s.pdf = rHero;
            s.lobe = 0;
            s.flags = ScatterReflection | ScatterNearDelta;
            s.eta = 1;
            return s;
        }
        // Refraction at the hero wavelength (total internal reflection has R = 1 and never gets
        // here), chosen with probability T(λ_hero) = 1 − R(λ_hero).
        if (!RefractLocal(q.wi, f.eta[0], &s.wo)) return std::nullopt;  // unreachable: R = 1 under TIR
        const double tHero = 1 - rHero;
        // weight = T(λ)/T(λ_hero) · (η_i/η_t)²: radiance scaling on crossing the interface.
        for (int i = 0; i < count; ++i) s.weight[i] = (1 - f.refl[i]) / tHero / (f.eta[i] * f.eta[i]);
        s.pdf = tHero;
        s.lobe = 1;
        s.flags = ScatterTransmission | ScatterNearDelta | (dispersive_ ? ScatterDispersive : 0u);
        s.eta = f.eta[0];
        return s;
    }

    std::shared_ptr<const ComplexSpectrum> ior_;  // κ = 0 (checked in Create)
    double cauchyB_ = 0;  // Cauchy B [m²]
    SmoothSurface surface_;  // the same interface, for kernels that name it `substrate`
    bool dispersive_ = false;
};

PHASOR_EXPORT_PLUGIN(Material, DielectricMaterial)

}  // namespace phasor
