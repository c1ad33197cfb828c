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
// generalized ray (!ScatterQuery::rayOptics) Eval reports both lobes as the GR's angular Gaussians
// (near_delta.h).
//
// Dispersion: `ior` is a complex spectrum (core/complex_spectrum.h) with κ = 0: a constant, a named
// glass ("BK7", "fused_silica", "water", …; core/named_ior.h) or any spectrum; `cauchy_b` adds
// Cauchy's term, η(λ) = ior(λ) + B/λ² (Cauchy 1836; e.g. BK7 ≈ 1.5046 + 4.20e-3 µm²/λ²).
#include <memory>
#include <sstream>

#include "core/complex_spectrum.h"
#include "core/diagnostics.h"
#include "core/material.h"
#include "core/registry.h"
#include "materials/fresnel.h"
#include "materials/near_delta.h"

namespace phasor {

class DielectricMaterial final : public Material {
  public:
    DielectricMaterial(std::shared_ptr<const ComplexSpectrum> ior, double cauchyB)
        : ior_(std::move(ior)), cauchyB_(cauchyB) {
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

    std::optional<ScatterSample> Sample(const ScatterQuery &q, double u0, const Vec2 &) const override {
        const Vec3 &wi = q.wi;
        if (wi.z == 0) return std::nullopt;
        const bool entering = wi.z > 0;  // wi on the outside: the path crosses into the interior
        const double cosI = std::abs(wi.z);
        const int count = q.wl->Count();

        // Relative index η = n_(far side)/n_(wi side) and Fresnel reflectance per wavelength.
        std::array<double, NumWavelengths> eta{}, refl{};
        for (int i = 0; i < count; ++i) {
            const double n = Index(q.wl->lambda[i]);
            if (!(n > 0)) return std::nullopt;  // outside the index data: treat as absorbed
            eta[i] = entering ? n / q.etaOutside : q.etaOutside / n;
            refl[i] = FresnelDielectric(cosI, eta[i]);
        }

        ScatterSample s;
        const double rHero = refl[0];
        if (u0 < rHero) {
            // Specular reflection, chosen with probability R(λ_hero): weight = R(λ)/R(λ_hero).
            s.wo = ReflectLocal(wi);
            for (int i = 0; i < count; ++i) s.weight[i] = refl[i] / rHero;
            s.pdf = rHero;
            s.lobe = 0;
            s.flags = ScatterReflection | ScatterNearDelta;
            s.eta = 1;
            return s;
        }
        // Refraction at the hero wavelength (total internal reflection has R = 1 and never gets
        // here), chosen with probability T(λ_hero) = 1 − R(λ_hero).
        if (!RefractLocal(wi, eta[0], &s.wo)) return std::nullopt;  // unreachable: R = 1 under TIR
        const double tHero = 1 - rHero;
        // weight = T(λ)/T(λ_hero) · (η_i/η_t)²: radiance scaling on crossing the interface.
        for (int i = 0; i < count; ++i) s.weight[i] = (1 - refl[i]) / tHero / (eta[i] * eta[i]);
        s.pdf = tHero;
        s.lobe = 1;
        s.flags = ScatterTransmission | ScatterNearDelta | (dispersive_ ? ScatterDispersive : 0u);
        s.eta = eta[0];
        return s;
    }

    SampledSpectrum Eval(const ScatterQuery &q, const Vec3 &wo) const override {
        // Ray-optics limit: both lobes are Dirac deltas with no finite density. For a generalized
        // ray each lobe is the GR's angular Gaussian about its direction (near_delta.h), in the
        // medium the lobe travels in: f·|cosθo| = R·N(wo; wr, σ_k²/k_i²) + (T/η²)·N(wo; wt, σ_k²/k_t²)
        // per wavelength (β and ρ are kept, only |k| follows the medium, S6.4).
        const Vec3 &wi = q.wi;
        if (!SpreadNearDelta(q) || wi.z == 0 || wo.z == 0) return SampledSpectrum(0);
        const bool entering = wi.z > 0;
        const double cosI = std::abs(wi.z);
        const Vec3 wr = ReflectLocal(wi);
        SampledSpectrum f(0.0);
        for (int i = 0; i < q.wl->Count(); ++i) {
            const double lambda = q.wl->lambda[i], n = Index(lambda);
            if (!(n > 0)) continue;
            const double etaI = entering ? q.etaOutside : n, etaT = entering ? n : q.etaOutside;
            const double eta = etaT / etaI, refl = FresnelDielectric(cosI, eta);
            double v = refl * NearDeltaDensity(wo, wr, NearDeltaAngularVariance(q, etaI, lambda));
            Vec3 wt;
            if (refl < 1 && RefractLocal(wi, eta, &wt))
                v += (1 - refl) / (eta * eta) *
                     NearDeltaDensity(wo, wt, NearDeltaAngularVariance(q, etaT, lambda));
            f[i] = v / std::abs(wo.z);
        }
        return f;
    }

    double Pdf(const ScatterQuery &, const Vec3 &) const override { return 0; }

    bool IsDeltaOnly() const override { return true; }

    std::string ToString() const override {
        std::ostringstream os;
        os << "DielectricMaterial[ ior = " << ior_->ToString() << ", cauchy_b = " << cauchyB_
           << " m^2, dispersive = " << (dispersive_ ? "true" : "false") << " ]";
        return os.str();
    }

    /// Index of the interior at vacuum wavelength lambda [m].
    double Index(double lambda) const { return ior_->Eval(lambda).real() + cauchyB_ / (lambda * lambda); }

  private:
    std::shared_ptr<const ComplexSpectrum> ior_;  // κ = 0 (checked in Create)
    double cauchyB_ = 0;  // Cauchy B [m²]
    bool dispersive_ = false;
};

PHASOR_EXPORT_PLUGIN(Material, DielectricMaterial)

}  // namespace phasor
