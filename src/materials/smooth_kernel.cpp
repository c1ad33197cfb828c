// SPDX-License-Identifier: Apache-2.0
// phasor — the smooth-surface kernel (smooth_kernel.h).
#include "materials/smooth_kernel.h"

#include <sstream>

#include "core/diagnostics.h"
#include "core/render/lobe_average.h"
#include "materials/fresnel.h"

namespace phasor {

SmoothKernel::SmoothKernel(SmoothSurface surface, bool transmits)
    : surface_(std::move(surface)), transmits_(transmits) {
    // Dispersive if the substrate's index varies over the band a path may carry (fine grid).
    if (!transmits_) return;
    const double n0 = surface_.SubstrateIndex(550e-9).real();
    for (double l = 200e-9; l <= 3000e-9; l *= 1.005)
        if (std::abs(surface_.SubstrateIndex(l).real() - n0) > 1e-12 * n0) dispersive_ = true;
}

SmoothKernel::Wave SmoothKernel::Sides(const ScatterQuery &q, int i) const {
    Wave w;
    const Complex sub = surface_.SubstrateIndex(q.wl->lambda[i]);
    if (!(sub.real() > 0) || !std::isfinite(sub.real()) || !std::isfinite(sub.imag())) return w;  // outside the data
    w.substrate = sub;
    const bool inside = FromInside(q);
    w.nI = inside ? sub.real() : q.etaOutside;
    w.nT = inside ? q.etaOutside : sub.real();
    w.eta = w.nT / w.nI;
    w.ok = true;
    return w;
}

SmoothKernel::Wave SmoothKernel::Evaluate(const ScatterQuery &q, int i) const {
    Wave w = Sides(q, i);
    if (!w.ok) return w;
    const double lambda = q.wl->lambda[i], cosI = std::abs(q.wi.z);
    if (q.rayOptics) {
        const IncoherentStackResponse r = surface_.IncoherentResponse(lambda, q.etaOutside, cosI, FromInside(q), q.tex, w.substrate);
        w.R = r.R();
        w.T = transmits_ ? r.T() : 0;
    } else {
        const StackResponse r = surface_.Response(lambda, q.etaOutside, cosI, FromInside(q), q.tex, w.substrate);
        w.R = r.R();
        w.T = transmits_ ? r.T() : 0;
    }
    // A layer index outside its data (n = 0) poisons the recursion: treat the wave as absorbed.
    // Round-off may leave an evanescent transmission at −1e-16: that is 0.
    w.ok = std::isfinite(w.R) && std::isfinite(w.T) && w.R > -1e-12 && w.T > -1e-12;
    w.R = w.ok ? std::max(0.0, w.R) : 0;
    w.T = w.ok ? std::max(0.0, w.T) : 0;
    return w;
}

void SmoothKernel::ListNearDelta(const ScatterQuery &q, NearDeltaLobes &out) const {
    std::array<NearDeltaLobe, 2> lobes;
    const int count = Lobes(q, lobes);
    for (int k = 0; k < count; ++k) out.Add() = lobes[k];
}

std::optional<ScatterSample> SmoothKernel::SampleLobes(const ScatterQuery &q, double u0, const Vec2 &) const {
    std::array<NearDeltaLobe, 2> lobes;
    const int count = Lobes(q, lobes);
    return SampleListedLobe(std::span<const NearDeltaLobe>(lobes.data(), count), u0);
}

int SmoothKernel::Lobes(const ScatterQuery &q, std::array<NearDeltaLobe, 2> &out) const {
    if (q.wi.z == 0) return 0;
    const int count = q.wl->Count();
    std::array<Wave, NumWavelengths> w;
    for (int i = 0; i < count; ++i) w[i] = Evaluate(q, i);
    if (!w[0].ok) return 0;
    int listed = 0;

    bool reflects = false, transmits = false;
    for (int i = 0; i < count; ++i) {
        reflects = reflects || w[i].R > 0;
        transmits = transmits || w[i].T > 0;
    }
    Vec3 hero;
    transmits = transmits && transmits_ && RefractLocal(q.wi, w[0].eta, &hero);
    // Lobe probabilities: half ∝ the energy each carries at the hero, half ∝ its mean over the
    // carried wavelengths. A film's reflectance swings with λ: by the hero alone a lobe that is dark
    // at the hero but bright at a companion would be picked rarely and weighted by up to 1/1e-6
    // (fireflies on a soap bubble); by the mean alone a path that carries only the hero (after a
    // dispersive lobe) could lose its likely lobe. The mixture bounds each weight by twice the better
    // of the two.
    double meanR = 0, meanT = 0;
    for (int i = 0; i < count; ++i) {
        meanR += w[i].R;
        meanT += transmits ? w[i].T : 0;
    }
    const double heroTotal = w[0].R + (transmits ? w[0].T : 0), meanTotal = meanR + meanT;
    auto probability = [&](double hero, double mean) {
        const double a = heroTotal > 0 ? hero / heroTotal : 0, b = meanTotal > 0 ? mean / meanTotal : 0;
        return heroTotal > 0 && meanTotal > 0 ? 0.5 * (a + b) : a + b;
    };
    if (reflects) {
        NearDeltaLobe &r = out[listed++];
        r.id = 0;
        r.flags = ScatterReflection | ScatterNearDelta;
        r.wo.fill(ReflectLocal(q.wi));
        r.prob = probability(w[0].R, meanR);
        for (int i = 0; i < count; ++i) {
            r.weight[i] = w[i].R;
            r.nIn[i] = r.nOut[i] = w[i].nI;
        }
    }
    if (transmits) {
        NearDeltaLobe &t = out[listed++];
        t.id = 1;
        t.flags = ScatterTransmission | ScatterNearDelta | (dispersive_ ? ScatterDispersive : 0u);
        t.prob = probability(w[0].T, meanT);
        for (int i = 0; i < count; ++i) {
            t.nIn[i] = w[i].nI;
            t.nOut[i] = w[i].nT;
            // Radiance scaling (η_i/η_t)² on crossing (camera paths carry L/n², dielectric.cpp).
            if (w[i].ok && RefractLocal(q.wi, w[i].eta, &t.wo[i])) t.weight[i] = w[i].T / (w[i].eta * w[i].eta);
            else t.wo[i] = hero;  // weight 0 at this companion (total internal reflection, no data)
        }
    }
    return listed;
}

std::optional<LobeResponse> SmoothKernel::EvalLobe(const ScatterQuery &q, int lobe, const Vec3 &wo) const {
    if (q.wi.z == 0 || (lobe != 0 && lobe != 1) || (lobe == 1 && !transmits_)) return std::nullopt;
    const Wave hero = Evaluate(q, 0);  // as ListNearDelta: no lobe where the hero has no response
    if (!hero.ok) return std::nullopt;
    Vec3 dir = ReflectLocal(q.wi);
    if (lobe == 1 && !RefractLocal(q.wi, hero.eta, &dir)) return std::nullopt;
    if (!SameDirection(wo, dir)) return std::nullopt;

    const bool inside = FromInside(q);
    const double cosI = std::abs(q.wi.z);
    LobeResponse r;
    // A bare surface has one response, a Jones matrix in both regimes; a coated one in the
    // ray-optics limit answers with the incoherent sum, which has none.
    const bool coherent = !q.rayOptics || surface_.LayerCount() == 0;
    r.hasJones = coherent;
    r.coherence.any = surface_.LayerCount() > 0;
    for (int i = 0; i < q.wl->Count(); ++i) {
        const Wave w = Sides(q, i);
        if (!w.ok) continue;  // zero response
        const double lambda = q.wl->lambda[i];
        const StackResponse c = surface_.Response(lambda, q.etaOutside, cosI, inside, q.tex, w.substrate);
        // A bare interface has one response: its incoherent matrix is FromJones(j) (set below).
        const bool layered = surface_.LayerCount() > 0;
        IncoherentStackResponse n{};
        if (layered) n = surface_.IncoherentResponse(lambda, q.etaOutside, cosI, inside, q.tex, w.substrate);
        if (!std::isfinite(c.R() + c.T() + (layered ? n.R() + n.T() : 0.0))) continue;  // as Evaluate: absorbed
        Jones j;
        Mueller incoherent;
        if (lobe == 0) {
            j = Jones::Diagonal(c.rs, c.rp);
            if (layered) incoherent = Mueller::FromDiagonalSums(n.Rs, n.Rp, n.Rsp);
        } else {
            // diag(t_s, t_p) with the power factors between the two media (theory §4.1) and the
            // radiance factor η_i/η_t, so that M00 = T·(η_i/η_t)², the listed weight.
            const Complex nI(w.nI, 0), nT(w.nT, 0), cosIn(cosI, 0);
            const double ps = std::max(0.0, FresnelPowerFactorS(nI, cosIn, nT, c.cosSubstrate));
            const double pp = std::max(0.0, FresnelPowerFactorP(nI, cosIn, nT, c.cosSubstrate));
            j = Jones::Diagonal(c.ts * std::sqrt(ps), c.tp * std::sqrt(pp)) * Complex(1 / w.eta, 0);
            if (layered) incoherent = Mueller::FromDiagonalSums(n.Ts, n.Tp, n.Tsp) * (1 / (w.eta * w.eta));
        }
        if (!layered) incoherent = Mueller::FromJones(j);
        if (!coherent) {
            r.mueller[i] = incoherent;  // the ray-optics limit of a coating: no Jones matrix
        } else {
            r.jones[i] = j;
            r.mueller[i] = Mueller::FromJones(j);
        }
        r.coherence.incoherent[i] = incoherent;
        // The deeper reflections exit displaced along the incident wave's tangential travel, −wi.xy.
        if (r.coherence.any) r.coherence.shear[i] = surface_.ShearVector(lambda, q.etaOutside, q.wi, inside, q.tex);
    }
    return r;
}

double SmoothKernel::AngularBandwidth(const ScatterQuery &q, double kappaMax) const {
    return HeroToShortest(*q.wl) *
           surface_.Bandwidth(q.wl->lambda[0], q.etaOutside, kappaMax, FromInside(q), q.tex, LobeAverageTolerance);
}

std::string SmoothKernel::Describe(const std::string &name) const {
    std::ostringstream os;
    os << name << "[ " << surface_.ToString() << (transmits_ ? ", transmits" : ", opaque")
       << (dispersive_ ? ", dispersive" : "") << " ]";
    return os.str();
}

bool IsTransparent(const ComplexSpectrum &ior) {
    for (double l = 360e-9; l <= 1000e-9; l += 5e-9)
        if (ior.Eval(l).imag() != 0) return false;
    return true;
}

ParamSpec CoatingSpec() {
    return P::Ref("coating", "material",
                  "layers on the surface: @name of a thin_film or multilayer definition (without its own "
                  "substrate_ior: this kernel's index is the substrate); absent: bare");
}

std::shared_ptr<const Coating> ReadCoating(const ParamDict &dict, BuildContext &ctx) {
    if (!dict.Has("coating")) return nullptr;
    const std::string name = dict.GetValue("coating").text;
    std::shared_ptr<Material> m = ctx.GetRef<Material>(dict, "coating");
    const SceneEntity *e = ctx.EntityOf(m.get());
    std::shared_ptr<const Coating> c = m->AsCoating();
    if (!c)
        throw Error(dict.Loc("coating"), "'coating' must name a thin_film or multilayer definition; '@" + name +
                                             "' is a " + (e ? e->type : std::string("other")) + " material");
    if (e && e->params.Has("substrate_ior"))
        throw Error(dict.Loc("coating"), "coating '@" + name + "' sets its own 'substrate_ior'; as a coating it lies "
                                         "on this kernel's 'ior' (remove 'substrate_ior' from '" + name + "')");
    return c;
}

ParamSpec CoatingKernel::SubstrateSpec() {
    return P::ComplexSpectrum("substrate_ior",
                              "index n + iκ(λ) of the substrate under the layers: a number, n+ik, a named glass or "
                              "metal (\"BK7\", \"Cu\"), a spectrum or nk(…); κ = 0 transmits into it, κ > 0 is "
                              "opaque. Default 1: a free-standing film in air (a soap film)")
        .Default(Value::Number(1));
}

}  // namespace phasor
