// SPDX-License-Identifier: Apache-2.0
// phasor — `harvey_shack`: a randomly rough surface in the (energy-normalised) Harvey–Shack
// smooth-surface scatter theory (theory §4.3, §0 D7), over the Fresnel response of a substrate.
//
// Model. A surface of rms height σ_h whose height statistics follow the K-correlation ("ABC") PSD
// (k_correlation_psd.h; parameters T [m²] and γ > 1, or a GGX-like roughness α_r with
// T = (1 − α_r²)/(4 k̄² α_r²), k̄ = 2π/0.55 µm, theory §4.3) reflects light of wavenumber k
// (in the medium it arrives from) into two lobes:
//   * a specular near-delta lobe (id 0, listed): the coherent part α_spec·F(θ), with the
//     Debye–Waller factor α_spec = exp(−(kσ_h(cosθ_i + cosθ_o))²) = exp(−(2kσ_h cosθ)²) at the
//     mirror direction (θ_i = θ_o = θ: the lobe is symmetric); Jones √α_spec·diag(r_s, r_p) (over a coated substrate, with the coating's
//     coherence terms times α_spec, LobeCoherence: sample_solve weights its interference by the
//     light's coherence);
//   * a continuous scattered lobe (id 1): theory §4.3's energy-normalised form, normalised for the
//     light's incident direction,
//         f(wi → wo) = (1 − α_spec(θ_o))·F(θ_o)·k²p_PSD(ζ)/V(θ_o, k²T),   ζ = k(wo∥ + wi∥)
//     (wi, wo pointing away from the surface; the mirror direction has ζ = 0). wo is where the
//     light comes from in a backward tracer (the sun, a lamp), wi where it goes (the camera), so
//     θ_o is the light's angle of incidence: F, α_spec and V are those of the light. V is the PSD
//     mass inside the visible disc (V = 0.96 / 0.88 / 0.49 at θ = 0 / 45 / 80° for α_r = 0.1):
//     without 1/V the evanescent part of the PSD would be lost. V is tabulated per γ over
//     (cosθ, ln k²T) (k_correlation_psd.h, error ≤ 2e-4, ≤ 2e-5 away from grazing).
// Energy (D7), per incident direction. Light arriving from d leaves into the specular lobe
// (α_spec(θ_d)·F(θ_d)) and into every wi with f(wi → d)·cosθ_i, whose integral over wi is
// (1 − α_spec(θ_d))·F(θ_d)/V(θ_d)·∫ k²p_PSD d²(wi∥) = (1 − α_spec(θ_d))·F(θ_d): the surface
// reflects exactly F(θ_d) of the light from any direction d — a sun, a laser, each direction of
// an area light — and loses nothing else. The kernel is therefore not reciprocal (f depends on
// θ_o alone besides ζ) and declares ConservesEnergyPerIncidentDirection(), as `grating` does: the
// lobes of one *query* (what a camera at wi gathers from every direction) need not sum to
// F(θ_i); a white furnace reads F only where F, α_spec and V vary little over the halo
// (docs/kernels.md quantifies it). F is the substrate's unpolarised (coated) reflectance
// R = (R_s + R_p)/2 (materials/smooth_surface.h), so this holds per wavelength; F at the half
// vector (as Holzschuch–Pacanowski use it) would break the exact sum. The *polarisation* of the
// scattered lobe is that of the local facet: EvalLobe returns Jones √(f|cosθo|/R(θ_h))·
// diag(r_s(θ_h), r_p(θ_h)) in the s/p frame of the plane through wi and wo (θ_h = the angle between
// wi and the half vector), so M00 = f·|cosθo| exactly.
//
// Sampling (theory §3.1, §4.3), from the query's wi: the specular lobe with probability α_spec(θ_i)
// (hero wavelength; kept within [0.01, 0.99] while both lobes carry something, so that neither is
// left to chance), else Holzschuch–Pacanowski: the radius |ζ|/k by the inverse radial CDF
// restricted to the visible bound 1 + sinθ_i (mass M), the azimuth uniform over the arc inside the
// visible disc (half-angle φ_max), giving the solid-angle pdf (π/φ_max)·k²p_PSD(ζ)·cosθ_o/M, times
// the lobe's probability; every sample propagates (the pdf integrates to that probability
// exactly). The weight f·cosθ_o/pdf = (1 − α_spec(θ_o))·F(θ_o)·M(θ_i)·(φ_max/π)/(V(θ_o)·(1 − p_spec))
// is finite and bounded (by F·M/(0.01·V), V > 0 for k²T > 0) but not by 1: the halo a camera at wi
// sees is lit from directions θ_o whose 1 − α_spec(θ_o) may far exceed 1 − α_spec(θ_i), which sets
// its sampling probability — most at a grazing wi on a very rough surface (the presets' largest
// hero weight is 141, σ_h = 400 nm at cosθ_i = 5e-6; 5.6 for σ_h = 20 nm; docs/kernels.md).
//
// Frames and sides. Reflection only: transmission through a rough dielectric is out of scope
// (the transmitted share 1 − F is lost). A path arriving from below the shading normal (wi.z < 0)
// sees, for a transparent substrate (a `dielectric`: κ = 0 over 360–1000 nm), the same rough
// interface from inside — the substrate's inside response (total internal reflection included)
// in a medium of index Re(n_substrate), whose wavenumber then sets k; for an absorbing substrate
// (a `conductor`) the kernel is two-sided like `conductor`, mirrored onto wi's side.
// The ray-optics limit (ScatterQuery::rayOptics) is the same rough surface (the specular lobe is
// then a true delta), whose F is the substrate's ray-optics response: for a coated substrate the
// incoherent sum of the coating (SmoothSurface::IncoherentResponse, as `conductor` and
// `dielectric` answer there), with Mueller matrices and no Jones matrix; a bare substrate answers
// the same in both regimes.
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
#include "core/render/lobe_average.h"
#include "core/render/registry.h"
#include "materials/fresnel.h"
#include "materials/k_correlation_psd.h"
#include "materials/smooth_surface.h"
#include "materials/validity.h"
#include "materials/smooth_kernel.h"

namespace phasor {

class HarveyShackMaterial final : public Material {
  public:
    /// Vacuum wavelength at which alpha_r defines T (theory §4.3: k̄ = 2π/0.55 µm).
    static constexpr double AlphaRWavelength = 0.55e-6;

    HarveyShackMaterial(std::shared_ptr<const SmoothKernel> substrate, double sigmaH, double corrT, double gamma)
        : substrate_(std::move(substrate)),
          surface_(&substrate_->Surface()),
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
            "and a scattered halo (1 − that)·F over a conductor or dielectric substrate; reflects exactly F of the "
            "light from any direction",
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
        std::shared_ptr<const SmoothKernel> substrate = ReadSubstrate(dict, ctx);
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
        const double sigma = dict.GetNumber("sigma_h");
        WarnIfBeyondVisible(dict, ctx, "sigma_h", sigma,
                            "Harvey–Shack's smooth-surface model needs σ_h ≪ λ (docs/kernels.md, harvey_shack)", 10,
                            "a surface this rough is a diffuse (Lambertian-like) scatterer");
        return std::make_unique<HarveyShackMaterial>(substrate, sigma, t, dict.GetNumber("gamma"));
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

    /// Lists lobe 0, the specular direction on wi's side, weight α_spec(λ)·F(λ) at θ_i (= θ_o),
    /// probability α_spec at the hero (the same as Sample's). EvalLobe: lobe 0 (mirror direction):
    /// √α_spec times the substrate's response at θ_i; lobe 1 (any wo on wi's side): the substrate's
    /// response at the facet angle θ_h, scaled so that M00 = f·|cosθo| (a depolariser of that value
    /// where R(θ_h) = 0), in the s/p frame of the plane through wi and wo. Jones matrices
    /// diag(r_s, r_p); in the ray-optics limit a coated substrate answers with its incoherent
    /// Mueller matrix and no Jones matrix (SubstrateResponse).
    const PreparedKernel &Prepare(const ScatterQuery &q, ScratchBuffer &scratch) const override {
        return *scratch.New<Prepared>(*this, q, scratch);
    }

    /// f(wi → wo) depends on wo's angle (the light's) besides ζ: see the file comment.
    bool IsReciprocal() const override { return false; }
    /// The light from one direction is reflected with exactly F (specular + halo).
    bool ConservesEnergyPerIncidentDirection() const override { return true; }
    /// The specular lobe carries a coated substrate's coherence terms.
    bool HasCoherenceTerms() const override { return surface_->LayerCount() > 0; }
    std::string ToString() const override {
        std::ostringstream os;
        os << "HarveyShackMaterial[ sigma_h = " << sigma_ << " m, correlation_t = " << corrT_
           << " m^2, gamma = " << table_->Psd().Gamma() << ", substrate: " << surface_->ToString()
           << (transparent_ ? " (transparent)" : " (absorbing)") << " ]";
        return os.str();
    }

    /// The PSD mass inside the visible disc, V(θ, k²T), as the kernel uses it (the table).
    double VisibleMass(double cosTheta, double t) const { return table_->Eval(cosTheta, t); }

  private:
    static constexpr int SpecularLobe = 0, ScatterLobe = 1;

    /// The query as the kernel sees it: wi mirrored onto the upper side and, per carried wavelength,
    /// the medium's index n and t = k²T (k = 2πn/λ, the wavenumber of the light on wi's side, which
    /// is also the light's: reflection only); the substrate's index and its coating's thicknesses
    /// at the hit, which every response of the substrate below reads.
    struct Local {
        Vec3 wi;             // wi with z > 0
        bool flip = false;   // wi.z < 0 in the shading frame
        bool inside = false; // seen from inside a transparent substrate
        double cosI = 0, s = 0;
        int count = 0;
        std::array<double, NumWavelengths> n{}, k{}, t{};
        std::array<Complex, NumWavelengths> substrate{};  // SmoothSurface::SubstrateIndex(λ_i)
        const double *thickness = nullptr;                 // SmoothSurface::Thicknesses at the hit
        double pSpec = 1;    // probability of the specular lobe (SpecularProbability of α_spec(θ_i))
        Vec3 ToUpper(const Vec3 &w) const { return flip ? Vec3(w.x, w.y, -w.z) : w; }
        Vec3 FromUpper(const Vec3 &w) const { return ToUpper(w); }
    };

    /// False if wi is grazing (cosθ_i = 0: nothing arrives). `thickness` holds LayerCount() values.
    bool Localize(const ScatterQuery &q, double *thickness, Local *l) const {
        surface_->Thicknesses(q.tex, thickness);
        l->thickness = thickness;
        if (!(q.wi.z != 0)) return false;
        l->flip = q.wi.z < 0;
        l->inside = l->flip && transparent_;
        l->wi = l->ToUpper(q.wi);
        l->cosI = std::min(1.0, l->wi.z);
        l->s = std::min(1.0, std::hypot(l->wi.x, l->wi.y));
        l->count = q.wl->Count();
        for (int i = 0; i < l->count; ++i) {
            const double lambda = q.wl->lambda[i];
            l->substrate[i] = surface_->SubstrateIndex(lambda);
            l->n[i] = l->inside ? l->substrate[i].real() : q.etaOutside;
            l->k[i] = 2 * Pi * l->n[i] / lambda;
            l->t[i] = l->k[i] * l->k[i] * corrT_;
        }
        l->pSpec = SpecularProbability(Alpha(*l, 0, l->cosI));
        return true;
    }

    /// α_spec = exp(−(2kσ_h cosθ)²) at wavelength slot i for light at cosθ (theory §4.3, Debye–Waller
    /// at the mirror direction); 1 − α_spec is OneMinusAlpha (no cancellation for small kσ_h).
    double Alpha(const Local &l, int i, double cosTheta) const {
        return std::exp(-Sqr(2 * l.k[i] * sigma_ * cosTheta));
    }
    double OneMinusAlpha(const Local &l, int i, double cosTheta) const {
        return -std::expm1(-Sqr(2 * l.k[i] * sigma_ * cosTheta));
    }

    /// The regime's answer is coherent (a Jones matrix): always for a bare substrate, and for a
    /// coated one except in the ray-optics limit (the incoherent sum of its layers).
    bool Coherent(const ScatterQuery &q) const { return !q.rayOptics || surface_->LayerCount() == 0; }

    /// The substrate's unpolarised reflectance F for light at cosθ on wi's side, wavelength slot i,
    /// in the query's regime (coherent, or incoherent for a coated substrate in the ray-optics limit).
    double Reflectance(const ScatterQuery &q, const Local &l, int i, double cosTheta) const {
        const double c = std::max(cosTheta, 1e-300), lambda = q.wl->lambda[i];
        return Coherent(q) ? surface_->Response(lambda, q.etaOutside, c, l.inside, l.thickness, l.substrate[i]).R()
                           : surface_->IncoherentResponse(lambda, q.etaOutside, c, l.inside, l.thickness, l.substrate[i]).R();
    }

    /// The substrate's reflection at cosθ as a lobe response: R, its Mueller matrix, and (coherent
    /// regime) the Jones matrix diag(r_s, r_p) it comes from.
    struct Facet {
        double R = 0;
        Jones jones;
        Mueller mueller;
    };
    Facet SubstrateResponse(const ScatterQuery &q, const Local &l, int i, double cosTheta) const {
        const double c = std::max(cosTheta, 1e-300), lambda = q.wl->lambda[i];
        Facet f;
        if (Coherent(q)) {
            const StackResponse s = surface_->Response(lambda, q.etaOutside, c, l.inside, l.thickness, l.substrate[i]);
            f.R = s.R();
            f.jones = Jones::Diagonal(s.rs, s.rp);
            f.mueller = Mueller::FromJones(f.jones);
        } else {
            const IncoherentStackResponse s =
                surface_->IncoherentResponse(lambda, q.etaOutside, c, l.inside, l.thickness, l.substrate[i]);
            f.R = s.R();
            f.mueller = Mueller::FromDiagonalSums(s.Rs, s.Rp, s.Rsp);
        }
        return f;
    }

    /// The specular lobe's weight α_spec(θ_i)·F(θ_i) per carried wavelength.
    SampledSpectrum SpecularWeight(const ScatterQuery &q, const Local &l) const {
        SampledSpectrum a(0.0);
        for (int i = 0; i < l.count; ++i) a[i] = Alpha(l, i, l.cosI) * Reflectance(q, l, i, l.cosI);
        return a;
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

    /// f of the scattered lobe towards o (upper side: the light's direction) per wavelength [1/sr]:
    /// (1 − α_spec(θ_o))·F(θ_o)·k²p_PSD(ζ)/V(θ_o, k²T) with k²p_PSD(ζ) = p(ξ), ξ = wo∥ + wi∥
    /// (k_correlation_psd.h).
    SampledSpectrum Scatter(const ScatterQuery &q, const Local &l, const Vec3 &o) const {
        SampledSpectrum f(0.0);
        const double r2 = Sqr(o.x + l.wi.x) + Sqr(o.y + l.wi.y);
        for (int i = 0; i < l.count; ++i) {
            const double v = std::max(table_->Eval(o.z, l.t[i]), 1e-300);
            f[i] = OneMinusAlpha(l, i, o.z) * Reflectance(q, l, i, o.z) * table_->Psd().Density(l.t[i], r2) / v;
        }
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

    /// The kernel at one hit: the query as the kernel sees it (Local) and the specular lobe.
    class Prepared final : public PreparedKernel {
      public:
        Prepared(const HarveyShackMaterial &m, const ScatterQuery &q, ScratchBuffer &scratch) : PreparedKernel(q), m_(&m) {
            caps_ = CapNearDelta | (m.sigma_ > 0 ? CapContinuous : 0u);
            if (m.sigma_ > 0) continuous_.Add(ScatterLobe);
            ok_ = m.Localize(q, scratch.Room<double>(std::size_t(m.surface_->LayerCount())), &l_);
            if (!ok_) return;
            spec_ = m.SpecularWeight(q, l_);
            if (spec_.IsZero()) return;
            lobe_.id = SpecularLobe;
            lobe_.flags = ScatterReflection | ScatterNearDelta;
            lobe_.wo.fill(ReflectLocal(q.wi));
            lobe_.SetWeight(spec_);
            for (int i = 0; i < l_.count; ++i) lobe_.nIn[i] = lobe_.nOut[i] = l_.n[i];
            lobe_.prob = l_.pSpec;
            lobes_ = std::span<const NearDeltaLobe>(&lobe_, 1);
        }

        /// The specular lobe's α_spec(κ)·F(κ): the coated substrate's bandwidth plus the rate of
        /// ln α_spec = −(2kσ_h)²(1 − κ²/n²), 8k²σ_h²κ/n² per unit κ (theory §0 D15).
        double AngularBandwidth(double kappaMax) const override {
            const HarveyShackMaterial &m = *m_;
            const bool inside = q_.wi.z < 0 && m.transparent_;
            const double lambda = q_.wl->lambda[0];
            const double k0 = 2 * Pi / lambda;
            return HeroToShortest(*q_.wl) *
                   (m.surface_->Bandwidth(lambda, q_.etaOutside, kappaMax, inside, l_.thickness, l_.substrate[0],
                                          LobeAverageTolerance) +
                    8 * k0 * k0 * m.sigma_ * m.sigma_ * kappaMax);
        }

        std::optional<LobeResponse> EvalLobe(int lobe, const Vec3 &wo) const override {
            const HarveyShackMaterial &m = *m_;
            const ScatterQuery &q = q_;
            const Local &l = l_;
            if (!ok_) return std::nullopt;
            LobeResponse r;
            r.hasJones = m.Coherent(q);
            if (lobe == SpecularLobe) {
                if (!SameDirection(wo, ReflectLocal(q.wi))) return std::nullopt;
                // A coated substrate's coherence terms, times the specular share α_spec (sample_solve).
                r.coherence.any = m.surface_->LayerCount() > 0;
                for (int i = 0; i < l.count; ++i) {
                    const Facet s = m.SubstrateResponse(q, l, i, l.cosI);
                    const double a = m.Alpha(l, i, l.cosI);
                    r.jones[i] = s.jones * Complex(std::sqrt(a), 0);
                    r.mueller[i] = s.mueller * a;
                    if (!r.coherence.any) continue;
                    const double lambda = q.wl->lambda[i];
                    const IncoherentStackResponse n =
                        m.surface_->IncoherentResponse(lambda, q.etaOutside, l.cosI, l.inside, l.thickness, l.substrate[i]);
                    r.coherence.incoherent[i] = Mueller::FromDiagonalSums(n.Rs, n.Rp, n.Rsp) * a;
                    r.coherence.shear[i] = m.surface_->ShearVector(lambda, q.etaOutside, l.wi, l.inside, l.thickness);
                }
                return r;
            }
            if (lobe != ScatterLobe || !(m.sigma_ > 0)) return std::nullopt;
            const Vec3 o = l.ToUpper(wo);
            if (!(o.z > 0)) return std::nullopt;
            const SampledSpectrum f = m.Scatter(q, l, o);
            const Vec3 h = Normalize(l.wi + o);
            const double cosH = Clamp(Dot(l.wi, h), 0.0, 1.0);
            for (int i = 0; i < l.count; ++i) {
                const double value = f[i] * o.z;
                const Facet s = m.SubstrateResponse(q, l, i, cosH);
                if (s.R > 0) {
                    r.jones[i] = s.jones * Complex(std::sqrt(value / s.R), 0);
                    r.mueller[i] = s.mueller * (value / s.R);
                } else {
                    r.hasJones = false;
                    r.mueller[i] = Mueller::Depolarizer(value);
                }
            }
            if (!r.hasJones)
                for (int i = 0; i < l.count; ++i) r.jones[i] = Jones();
            return r;
        }

      private:
        std::optional<ScatterSample> SampleLobes(double u0, const Vec2 &u) const override {
            const HarveyShackMaterial &m = *m_;
            const Local &l = l_;
            if (!ok_) return std::nullopt;
            ScatterSample s;
            s.eta = 1;
            if (u0 < l.pSpec) {
                // The specular lobe, chosen with probability p_spec ≈ α_spec(λ_hero): weight α_spec(λ)F(λ)/p_spec.
                s.wo = ReflectLocal(q_.wi);
                s.weight = spec_ / l.pSpec;
                s.pdf = l.pSpec;
                s.lobe = SpecularLobe;
                s.flags = ScatterReflection | ScatterNearDelta;
                return s;
            }
            // Holzschuch–Pacanowski (theory §4.3 steps 1–4) at the hero wavelength.
            const KCorrelationPsd &psd = m.table_->Psd();
            const double t = l.t[0];
            const double mass = psd.RadialCdf(t, 1 + l.s);
            const double r = psd.InverseRadialCdf(t, mass * u.x);
            const double phiMax = KCorrelationPsd::ArcHalfAngle(r, l.s);
            if (!(phiMax > 0)) return std::nullopt;  // r = 1 + s exactly: a set of measure zero
            const double phiI = l.s > 0 ? std::atan2(l.wi.y, l.wi.x) : 0.0;
            const double phi = phiI + (2 * u.y - 1) * phiMax;
            const double ox = r * std::cos(phi) - l.wi.x, oy = r * std::sin(phi) - l.wi.y;
            const double z2 = 1 - ox * ox - oy * oy;
            if (!(z2 > 0)) return std::nullopt;  // on the horizon (rounding): pdf 0
            const Vec3 o(ox, oy, std::sqrt(z2));
            const double pdf = m.ScatterPdf(l, o);
            if (!(pdf > 0) || !std::isfinite(pdf)) return std::nullopt;
            s.wo = l.FromUpper(o);
            s.pdf = pdf;
            s.weight = m.Scatter(q_, l, o) * (o.z / pdf);
            s.lobe = ScatterLobe;
            s.flags = ScatterReflection | ScatterDiffuse;
            return s;
        }
        SampledSpectrum EvalContinuous(const Vec3 &wo) const override {
            if (!(m_->sigma_ > 0) || !ok_) return SampledSpectrum(0.0);
            const Vec3 o = l_.ToUpper(wo);
            if (!(o.z > 0)) return SampledSpectrum(0.0);
            return m_->Scatter(q_, l_, o);
        }
        double PdfContinuous(const Vec3 &wo) const override {
            if (!(m_->sigma_ > 0) || !ok_) return 0;
            return m_->ScatterPdf(l_, l_.ToUpper(wo));
        }
        KernelValue EvalPdfContinuous(const Vec3 &wo, const IncidentWave &) const override {
            if (!(m_->sigma_ > 0) || !ok_) return KernelValue{};
            const Vec3 o = l_.ToUpper(wo);
            return KernelValue{o.z > 0 ? m_->Scatter(q_, l_, o) : SampledSpectrum(0.0), m_->ScatterPdf(l_, o)};
        }

        const HarveyShackMaterial *m_;
        Local l_;
        bool ok_ = false;        // wi is not grazing (Localize)
        SampledSpectrum spec_;   // the specular lobe's weight α_spec(θ_i)·F(θ_i)
        NearDeltaLobe lobe_;     // the specular lobe, listed when spec_ is not zero
    };

    std::shared_ptr<const SmoothKernel> substrate_;  // keeps surface_ alive
    const SmoothSurface *surface_;
    double sigma_;   // σ_h [m]
    double corrT_;   // T [m²]
    std::shared_ptr<const VisibleMassTable> table_;
    bool transparent_ = false;  // κ = 0 over 360–1000 nm: wi.z < 0 is the inside of the substrate
};

PHASOR_EXPORT_PLUGIN(Material, HarveyShackMaterial)

}  // namespace phasor
