// SPDX-License-Identifier: Apache-2.0
// phasor — `harvey_shack`: a randomly rough surface in the (energy-normalised) Harvey–Shack
// smooth-surface scatter theory (theory §4.3, §0 D7), over the Fresnel response of a substrate.
//
// Model. A surface of rms height σ_h whose height statistics follow the K-correlation ("ABC") PSD
// (k_correlation_psd.h; parameters T [m²] and γ > 1, or a GGX-like roughness α_r with
// T = (1 − α_r²)/(4 k̄² α_r²), k̄ = 2π/0.55 µm, theory §4.3) reflects light of wavenumber k
// (in the medium it arrives from) into two lobes:
//   * a specular near-delta lobe (id 0, listed): the coherent part α_spec·F(θ_i), with the
//     Debye–Waller factor α_spec = exp(−(kσ_h(cosθ_i + cosθ_o))²) = exp(−(2kσ_h cosθ_i)²) at the
//     mirror direction; Jones √α_spec·diag(r_s, r_p) (over a coated substrate, with the coating's
//     coherence terms times α_spec, LobeCoherence: sample_solve weights its interference by the
//     light's coherence);
//   * a continuous scattered lobe (id 1): theory §4.3's energy-normalised form
//         f(wi → wo) = (1 − α_spec)·F(θ_i)·k²p_PSD(ζ)/V(θ_i, k²T),   ζ = k(wo∥ + wi∥)
//     (wi, wo pointing away from the surface; the mirror direction has ζ = 0), where V is the PSD
//     mass inside the visible disc (V = 0.96 / 0.88 / 0.49 at θ_i = 0 / 45 / 80° for α_r = 0.1):
//     without 1/V the evanescent part of the PSD would be lost. V is tabulated per γ over
//     (cosθ_i, ln k²T) (k_correlation_psd.h, error ≤ 2e-4, ≤ 2e-5 away from grazing).
// So the kernel reflects exactly ∫(specular + scatter) = α_spec·F + (1 − α_spec)·F = F(θ_i) (D7):
// the white furnace of a lossless substrate is exact. F is the substrate's unpolarised (coated)
// reflectance R = (R_s + R_p)/2 at θ_i (materials/smooth_surface.h), so this holds per
// wavelength; using F at the half vector instead (as Holzschuch–Pacanowski do) would break the
// exact sum. The *polarisation* of the scattered lobe is that of the local facet: EvalLobe returns
// Jones √(f|cosθo|/R(θ_h))·diag(r_s(θ_h), r_p(θ_h)) in the s/p frame of the plane through wi and wo
// (θ_h = the angle between wi and the half vector), so M00 = f·|cosθo| exactly.
//
// Sampling (theory §3.1, §4.3): the specular lobe with probability α_spec (hero wavelength; kept
// within [0.01, 0.99] while both lobes carry something, so that neither is left to chance), else
// Holzschuch–Pacanowski: the radius |ζ|/k by the inverse radial CDF restricted to the visible
// bound 1 + sinθ_i (mass M), the azimuth uniform over the arc inside the visible disc (half-angle
// φ_max), giving the solid-angle pdf (π/φ_max)·k²p_PSD(ζ)·cosθ_o/M, times the lobe's probability;
// every sample propagates (the pdf integrates to that probability exactly).
//
// Frames and sides. Reflection only: transmission through a rough dielectric is out of scope
// (the transmitted share 1 − F is lost). A path arriving from below the shading normal (wi.z < 0)
// sees, for a transparent substrate (a `dielectric`: κ = 0 over 360–1000 nm), the same rough
// interface from inside — the substrate's inside response (total internal reflection included)
// in a medium of index Re(n_substrate), whose wavenumber then sets k; for an absorbing substrate
// (a `conductor`) the kernel is two-sided like `conductor`, mirrored onto wi's side.
// The ray-optics limit is the same kernel (a rough surface stays rough; the specular lobe is then
// a true delta).
//
// Non-reciprocal: the 1/V(θ_i) and F(θ_i) factors make f(wi → wo) ≠ f(wo → wi); that is the price
// of the exact sum over wo (the integral a backward tracer samples). The flux a collimated source
// at θ_s sends into all directions, ∫ f(wo ← ω_s) dω, is then F(θ_s) only where V, F and α_spec
// vary little over the scattered lobe (docs/kernels.md quantifies it).
//
// Validity: Harvey–Shack's smooth-surface regime, σ_h ≪ λ for the scattered lobe's shape (the
// specular fraction is right for any σ_h with Gaussian heights); no shadowing or multiple
// scattering; statistics stationary over the footprint (no speckle, no glints: theory §4).
// References: Krywonos, PhD thesis, U. Central Florida 2006 (generalised Harvey–Shack); Church,
// Jenkinson & Zavada, Opt. Eng. 18 (1979) (K-correlation PSD); Holzschuch & Pacanowski, "A
// two-scale microfacet reflectance model combining reflection and diffraction", ACM TOG 36(4) 2017.
#include <memory>
#include <sstream>

#include "core/diagnostics.h"
#include "core/render/material.h"
#include "core/render/registry.h"
#include "materials/fresnel.h"
#include "materials/k_correlation_psd.h"
#include "materials/smooth_surface.h"

namespace phasor {

class HarveyShackMaterial final : public Material {
  public:
    /// Vacuum wavelength at which alpha_r defines T (theory §4.3: k̄ = 2π/0.55 µm).
    static constexpr double AlphaRWavelength = 0.55e-6;

    HarveyShackMaterial(std::shared_ptr<const Material> substrate, double sigmaH, double corrT, double gamma)
        : substrate_(std::move(substrate)),
          surface_(substrate_->Surface()),
          sigma_(sigmaH),
          corrT_(corrT),
          table_(VisibleMassTable::For(gamma)) {
        transparent_ = true;
        for (double l = 360e-9; l <= 1000e-9; l += 5e-9) transparent_ = transparent_ && !surface_->Absorbing(l);
    }

    static const Schema &GetSchema() {
        static const Schema s{
            "material",
            "harvey_shack",
            "randomly rough surface (Harvey–Shack, K-correlation PSD): a specular lobe exp(−(2kσ_h cosθ)²)·F "
            "and a scattered halo (1 − that)·F over a conductor or dielectric substrate; reflects exactly F",
            {
                P::Length("sigma_h", "rms height σ_h of the surface (≥ 0; 0 is the smooth substrate)")
                    .Required()
                    .Min(0),
                P::Number("correlation_t",
                          "K-correlation PSD parameter T [area]: p(ζ) ∝ (1 + T|ζ|²)^(−(γ+1)/2), ζ the surface "
                          "spatial frequency; larger T = narrower halo. Give this or 'alpha_r'",
                          Dim::Area())
                    .Min(0, true),
                P::Number("alpha_r",
                          "roughness α_r ∈ (0, 1) from which T = (1 − α_r²)/(4 k̄² α_r²), k̄ = 2π/0.55 µm "
                          "(Holzschuch–Pacanowski's GGX-like width). Give this or 'correlation_t'")
                    .Min(0, true),
                P::Number("gamma", "K-correlation PSD exponent γ > 1 (tail (1 + T|ζ|²)^(−(γ+1)/2))")
                    .Default(Value::Number(3))
                    .Min(1, true)
                    .Max(100),
                P::Ref("substrate", "material",
                       "the smooth surface underneath: a `conductor` or `dielectric` (with its coating), "
                       "whose Fresnel reflectance multiplies both lobes")
                    .Required(),
            }};
        return s;
    }

    static std::unique_ptr<Material> Create(const ParamDict &dict, BuildContext &ctx) {
        auto substrate = ctx.GetRef<Material>(dict, "substrate");
        if (!substrate || !substrate->Surface())
            throw Error(dict.Loc("substrate"),
                        "'substrate' must be a smooth kernel with a Fresnel response (conductor or dielectric); "
                        "it is " + (substrate ? substrate->ToString() : std::string("null")));
        const bool hasT = dict.Has("correlation_t"), hasAlpha = dict.Has("alpha_r");
        if (hasT && hasAlpha)
            throw Error(dict.Loc("alpha_r"), "give either 'correlation_t' or 'alpha_r', not both");
        if (!hasT && !hasAlpha)
            throw Error(dict.Loc("sigma_h"),
                        "harvey_shack needs the PSD width: 'correlation_t' (an area, e.g. 0.2 um^2) or "
                        "'alpha_r' (a roughness in (0, 1))");
        double t;
        if (hasT) t = dict.GetNumber("correlation_t");
        else {
            const double a = dict.GetNumber("alpha_r");
            if (!(a < 1)) throw Error(dict.Loc("alpha_r"), "'alpha_r' must lie in (0, 1); it is " + std::to_string(a));
            t = TFromAlphaR(a);
        }
        return std::make_unique<HarveyShackMaterial>(substrate, dict.GetNumber("sigma_h"), t, dict.GetNumber("gamma"));
    }

    /// theory §4.3: T = (1 − α_r²)/(4 k̄² α_r²), k̄ = 2π/0.55 µm [m²].
    static double TFromAlphaR(double a) {
        const double kbar = 2 * Pi / AlphaRWavelength;
        return (1 - a * a) / (4 * kbar * kbar * a * a);
    }

    /// Presets for the contract suite: gold and glass substrates, small to large roughness,
    /// narrow and wide halos, light and heavy PSD tails.
    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(5);
        auto nm = [](double v) { return Value::Number(v * 1e-9, Dim::Length()); };
        // The suite's χ² grid resolves a halo at normal incidence only down to k²T ≈ 50 (a narrower
        // one lies inside one Simpson step of cosθ): narrower halos are tested in
        // harvey_shack_test.cpp with a χ² in the tangent plane.
        // p0: gold, moderate roughness, α_r = 0.1 (D7's V values; k²T = 47 at 400 nm).
        p[0].Set("substrate", Value::Ref("contract_gold")).Set("sigma_h", nm(20)).Set("alpha_r", Value::Number(0.1));
        // p1: glass, σ_h = 50 nm, T = 0.05 µm², heavier tail γ = 2.5 (seen from inside too).
        p[1].Set("substrate", Value::Ref("contract_glass"))
            .Set("sigma_h", nm(50))
            .Set("correlation_t", Value::Number(0.05e-12, Dim::Area()))
            .Set("gamma", Value::Number(2.5));
        // p2: gold, very rough (no specular lobe left except near grazing), wide halo α_r = 0.4.
        p[2].Set("substrate", Value::Ref("contract_gold")).Set("sigma_h", nm(400)).Set("alpha_r", Value::Number(0.4));
        // p3: gold, slightly rough (σ_h = 5 nm: mostly specular), α_r = 0.15.
        p[3].Set("substrate", Value::Ref("contract_gold")).Set("sigma_h", nm(5)).Set("alpha_r", Value::Number(0.15));
        // p4: glass, steep tail γ = 6 (the halo stays compact near the horizon: grazing-friendly),
        // σ_h = 100 nm, α_r = 0.2.
        p[4].Set("substrate", Value::Ref("contract_glass"))
            .Set("sigma_h", nm(100))
            .Set("alpha_r", Value::Number(0.2))
            .Set("gamma", Value::Number(6));
        return p;
    }

    unsigned Capabilities(const ScatterQuery &) const override {
        return CapNearDelta | (sigma_ > 0 ? CapContinuous : 0u);
    }
    void ContinuousLobes(const ScatterQuery &, ContinuousLobeIds &out) const override {
        if (sigma_ > 0) out.Add(ScatterLobe);
    }

    /// Lobe 0: the specular direction on wi's side, weight α_spec(λ)·F(λ), probability α_spec at
    /// the hero (the same as Sample's).
    void ListNearDelta(const ScatterQuery &q, NearDeltaLobes &out) const override {
        Local l;
        if (!Prepare(q, &l)) return;
        SampledSpectrum a;
        for (int i = 0; i < l.count; ++i) a[i] = l.alpha[i] * l.F[i];
        if (a.IsZero()) return;
        NearDeltaLobe &d = out.Add();
        d.id = SpecularLobe;
        d.flags = ScatterReflection | ScatterNearDelta;
        d.wo.fill(ReflectLocal(q.wi));
        d.weight = a;
        for (int i = 0; i < l.count; ++i) d.nIn[i] = d.nOut[i] = l.n[i];
        d.prob = l.pSpec;
    }

    /// Lobe 0 (mirror direction): Jones √α_spec·diag(r_s, r_p) at θ_i. Lobe 1 (any wo on wi's side):
    /// Jones √(f|cosθo|/R(θ_h))·diag(r_s, r_p)(θ_h) in the s/p frame of the plane through wi and wo,
    /// or a depolariser of value f|cosθo| where R(θ_h) = 0.
    std::optional<LobeResponse> EvalLobe(const ScatterQuery &q, int lobe, const Vec3 &wo) const override {
        Local l;
        if (!Prepare(q, &l)) return std::nullopt;
        LobeResponse r;
        if (lobe == SpecularLobe) {
            if (!SameDirection(wo, ReflectLocal(q.wi))) return std::nullopt;
            r.hasJones = true;
            // A coated substrate's coherence terms, times the specular share α_spec (sample_solve).
            r.coherence.any = surface_->LayerCount() > 0;
            for (int i = 0; i < l.count; ++i) {
                const StackResponse s = Response(q, l, i, l.cosI);
                r.jones[i] = Jones::Diagonal(s.rs, s.rp) * Complex(std::sqrt(l.alpha[i]), 0);
                r.mueller[i] = Mueller::FromJones(r.jones[i]);
                if (!r.coherence.any) continue;
                const double lambda = q.wl->lambda[i];
                const IncoherentStackResponse n = surface_->IncoherentResponse(lambda, q.etaOutside, l.cosI, l.inside, q.tex);
                r.coherence.incoherent[i] = Mueller::FromDiagonalSums(n.Rs, n.Rp, n.Rsp) * l.alpha[i];
                r.coherence.shear[i] = surface_->ShearVector(lambda, q.etaOutside, l.wi, l.inside, q.tex);
            }
            return r;
        }
        if (lobe != ScatterLobe || !(sigma_ > 0)) return std::nullopt;
        const Vec3 o = l.ToUpper(wo);
        if (!(o.z > 0)) return std::nullopt;
        const SampledSpectrum f = Scatter(l, o);
        const Vec3 h = Normalize(l.wi + o);
        const double cosH = Clamp(Dot(l.wi, h), 0.0, 1.0);
        r.hasJones = true;
        for (int i = 0; i < l.count; ++i) {
            const double value = f[i] * o.z;
            const StackResponse s = Response(q, l, i, cosH);
            if (s.R() > 0) {
                r.jones[i] = Jones::Diagonal(s.rs, s.rp) * Complex(std::sqrt(value / s.R()), 0);
                r.mueller[i] = Mueller::FromJones(r.jones[i]);
            } else {
                r.hasJones = false;
                r.mueller[i] = Mueller::Depolarizer(value);
            }
        }
        if (!r.hasJones)
            for (int i = 0; i < l.count; ++i) r.mueller[i] = Mueller::Depolarizer(f[i] * o.z);
        return r;
    }

    bool IsReciprocal() const override { return false; }  // 1/V(θ_i), F(θ_i): see the file comment
    /// The specular lobe carries a coated substrate's coherence terms.
    bool HasCoherenceTerms() const override { return surface_->LayerCount() > 0; }

    std::string ToString() const override {
        std::ostringstream os;
        os << "HarveyShackMaterial[ sigma_h = " << sigma_ << " m, correlation_t = " << corrT_
           << " m^2, gamma = " << table_->Psd().Gamma() << ", substrate: " << surface_->ToString()
           << (transparent_ ? " (transparent)" : " (absorbing)") << " ]";
        return os.str();
    }

    /// The PSD mass inside the visible disc, V(θ_i, k²T), as the kernel uses it (the table).
    double VisibleMass(double cosTheta, double t) const { return table_->Eval(cosTheta, t); }

  private:
    static constexpr int SpecularLobe = 0, ScatterLobe = 1;

    /// The query as the kernel sees it: wi mirrored onto the upper side, per carried wavelength
    /// the medium's index n and k²T, α_spec, F(θ_i) and V.
    struct Local {
        Vec3 wi;             // wi with z > 0
        bool flip = false;   // wi.z < 0 in the shading frame
        bool inside = false; // seen from inside a transparent substrate
        double cosI = 0, s = 0;
        int count = 0;
        std::array<double, NumWavelengths> n{}, t{}, alpha{}, F{}, V{};
        double pSpec = 1;    // probability of the specular lobe (SpecularProbability)
        Vec3 ToUpper(const Vec3 &w) const { return flip ? Vec3(w.x, w.y, -w.z) : w; }
        Vec3 FromUpper(const Vec3 &w) const { return ToUpper(w); }
    };

    StackResponse Response(const ScatterQuery &q, const Local &l, int i, double cosTheta) const {
        return surface_->Response(q.wl->lambda[i], q.etaOutside, std::max(cosTheta, 1e-300), l.inside, q.tex);
    }

    /// False if wi is grazing (cosθ_i = 0: nothing arrives). With pdfOnly, only what ScatterPdf
    /// reads (the hero's k²T and the lobe probability), not F and V (Pdf is called ~10× as often).
    bool Prepare(const ScatterQuery &q, Local *l, bool pdfOnly = false) const {
        if (!(q.wi.z != 0)) return false;
        l->flip = q.wi.z < 0;
        l->inside = l->flip && transparent_;
        l->wi = l->ToUpper(q.wi);
        l->cosI = std::min(1.0, l->wi.z);
        l->s = std::min(1.0, std::hypot(l->wi.x, l->wi.y));
        l->count = pdfOnly ? 1 : q.wl->Count();
        for (int i = 0; i < l->count; ++i) {
            const double lambda = q.wl->lambda[i];
            l->n[i] = l->inside ? surface_->SubstrateIndex(lambda).real() : q.etaOutside;
            const double k = 2 * Pi * l->n[i] / lambda;
            l->t[i] = k * k * corrT_;
            l->alpha[i] = std::exp(-Sqr(2 * k * sigma_ * l->cosI));  // theory §4.3 Debye–Waller
            if (pdfOnly) continue;
            l->F[i] = Response(q, *l, i, l->cosI).R();
            l->V[i] = sigma_ > 0 ? std::max(table_->Eval(l->cosI, l->t[i]), 1e-300) : 1;
        }
        l->pSpec = SpecularProbability(l->alpha[0]);
        return true;
    }

    /// Least probability of a lobe that carries anything (0 < α_spec < 1 at the hero).
    static constexpr double MinLobeProbability = 0.01;
    /// Theory §3.1 picks the specular lobe with probability α_spec (∝ its share). Each lobe of
    /// non-zero share is kept at ≥ 1 % of the samples: near grazing the halo's share 1 − α_spec
    /// falls to ~1e-5, and a lobe that is almost never sampled leaves its (small) part of every
    /// estimate to chance. The weights a_j/p_j stay exact.
    static double SpecularProbability(double alpha) {
        if (!(alpha > 0)) return 0;
        if (!(alpha < 1)) return 1;
        return Clamp(alpha, MinLobeProbability, 1 - MinLobeProbability);
    }

    /// f of the scattered lobe towards o (upper side) per wavelength [1/sr]: D7's
    /// (1 − α_spec)·F·k²p_PSD(ζ)/V with k²p_PSD(ζ) = p(ξ), ξ = wo∥ + wi∥ (k_correlation_psd.h).
    SampledSpectrum Scatter(const Local &l, const Vec3 &o) const {
        SampledSpectrum f(0.0);
        const double r2 = Sqr(o.x + l.wi.x) + Sqr(o.y + l.wi.y);
        for (int i = 0; i < l.count; ++i)
            f[i] = (1 - l.alpha[i]) * l.F[i] * table_->Psd().Density(l.t[i], r2) / l.V[i];
        return f;
    }

    /// Solid-angle density of the scattered lobe's sampling at o (upper side), hero wavelength,
    /// including its selection probability 1 − p_spec: theory §4.3 step 5.
    double ScatterPdf(const Local &l, const Vec3 &o) const {
        if (!(o.z > 0)) return 0;
        const KCorrelationPsd &psd = table_->Psd();
        const double t = l.t[0];
        const double m = psd.RadialCdf(t, 1 + l.s);
        const double r = std::hypot(o.x + l.wi.x, o.y + l.wi.y);
        const double phiMax = KCorrelationPsd::ArcHalfAngle(r, l.s);
        if (!(m > 0) || !(phiMax > 0)) return 0;
        return (1 - l.pSpec) * (Pi / phiMax) * psd.Density(t, r * r) * o.z / m;
    }

    std::optional<ScatterSample> SampleLobes(const ScatterQuery &q, double u0, const Vec2 &u) const override {
        Local l;
        if (!Prepare(q, &l)) return std::nullopt;
        ScatterSample s;
        s.eta = 1;
        if (u0 < l.pSpec) {
            // The specular lobe, chosen with probability p_spec ≈ α_spec(λ_hero): weight α_spec(λ)F(λ)/p_spec.
            s.wo = ReflectLocal(q.wi);
            for (int i = 0; i < l.count; ++i) s.weight[i] = l.alpha[i] * l.F[i] / l.pSpec;
            s.pdf = l.pSpec;
            s.lobe = SpecularLobe;
            s.flags = ScatterReflection | ScatterNearDelta;
            return s;
        }
        // Holzschuch–Pacanowski (theory §4.3 steps 1–4) at the hero wavelength.
        const KCorrelationPsd &psd = table_->Psd();
        const double t = l.t[0];
        const double m = psd.RadialCdf(t, 1 + l.s);
        const double r = psd.InverseRadialCdf(t, m * u.x);
        const double phiMax = KCorrelationPsd::ArcHalfAngle(r, l.s);
        if (!(phiMax > 0)) return std::nullopt;  // r = 1 + s exactly: a set of measure zero
        const double phiI = l.s > 0 ? std::atan2(l.wi.y, l.wi.x) : 0.0;
        const double phi = phiI + (2 * u.y - 1) * phiMax;
        const double ox = r * std::cos(phi) - l.wi.x, oy = r * std::sin(phi) - l.wi.y;
        const double z2 = 1 - ox * ox - oy * oy;
        if (!(z2 > 0)) return std::nullopt;  // on the horizon (rounding): pdf 0
        const Vec3 o(ox, oy, std::sqrt(z2));
        const double pdf = ScatterPdf(l, o);
        if (!(pdf > 0) || !std::isfinite(pdf)) return std::nullopt;
        const SampledSpectrum f = Scatter(l, o);
        s.wo = l.FromUpper(o);
        s.pdf = pdf;
        s.weight = f * (o.z / pdf);
        s.lobe = ScatterLobe;
        s.flags = ScatterReflection | ScatterDiffuse;
        return s;
    }

    SampledSpectrum EvalContinuous(const ScatterQuery &q, const Vec3 &wo) const override {
        Local l;
        if (!(sigma_ > 0) || !Prepare(q, &l)) return SampledSpectrum(0.0);
        const Vec3 o = l.ToUpper(wo);
        if (!(o.z > 0)) return SampledSpectrum(0.0);
        return Scatter(l, o);
    }

    double PdfContinuous(const ScatterQuery &q, const Vec3 &wo) const override {
        Local l;
        if (!(sigma_ > 0) || !Prepare(q, &l, true)) return 0;
        return ScatterPdf(l, l.ToUpper(wo));
    }

    std::shared_ptr<const Material> substrate_;  // keeps surface_ alive
    const SmoothSurface *surface_;
    double sigma_;   // σ_h [m]
    double corrT_;   // T [m²]
    std::shared_ptr<const VisibleMassTable> table_;
    bool transparent_ = false;  // κ = 0 over 360–1000 nm: wi.z < 0 is the inside of the substrate
};

PHASOR_EXPORT_PLUGIN(Material, HarveyShackMaterial)

}  // namespace phasor
