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
    // A substrate of index 1 (a film in air): the refraction lobe goes straight on from the air.
    passesStraight_ = !dispersive_ && n0 == 1;
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

SmoothKernel::Wave SmoothKernel::Evaluate(const ScatterQuery &q, int i, const double *thickness) const {
    Wave w = Sides(q, i);
    if (!w.ok) return w;
    const double lambda = q.wl->lambda[i], cosI = std::abs(q.wi.z);
    if (q.rayOptics) {
        const IncoherentStackResponse r =
            surface_.IncoherentResponse(lambda, q.etaOutside, cosI, FromInside(q), thickness, w.substrate);
        w.R = r.R();
        w.T = transmits_ ? r.T() : 0;
    } else {
        const StackResponse r = surface_.Response(lambda, q.etaOutside, cosI, FromInside(q), thickness, w.substrate);
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

/// The kernel at one hit: the layers' thicknesses there, R and T per carried wavelength and the (at
/// most two) lobes.
class SmoothKernel::Prepared final : public PreparedKernel {
  public:
    Prepared(const SmoothKernel &k, const ScatterQuery &q, ScratchBuffer &scratch) : PreparedKernel(q), k_(&k) {
        caps_ = CapNearDelta;
        if (const int layers = k.surface_.LayerCount(); layers > 0) {
            thickness_ = scratch.Room<double>(std::size_t(layers));
            k.surface_.Thicknesses(q.tex, thickness_);  // once per hit (a textured film)
        }
        if (q.wi.z == 0) return;
        const int count = q.wl->Count();
        for (int i = 0; i < count; ++i) w_[i] = k.Evaluate(q, i, thickness_);
        if (!w_[0].ok) return;
        lobes_ = std::span<const NearDeltaLobe>(lobe_.data(), std::size_t(List(q)));
    }

    std::optional<LobeResponse> EvalLobe(int lobe, const Vec3 &wo) const override;
    std::optional<SampledSpectrum> LobeWeightAt(int id, const Vec3 &wiPrime, unsigned slots) const override;
    double AngularBandwidth(double kappaMax) const override {
        return HeroToShortest(*q_.wl) * k_->surface_.Bandwidth(q_.wl->lambda[0], q_.etaOutside, kappaMax,
                                                              k_->FromInside(q_), thickness_, w_[0].substrate,
                                                              LobeAverageTolerance);
    }

  private:
    /// Fills lobe_ as the header describes; returns how many lobes it lists.
    int List(const ScatterQuery &q);

    const SmoothKernel *k_;
    double *thickness_ = nullptr;            // the layers' thicknesses at the hit (none: bare)
    std::array<Wave, NumWavelengths> w_;     // Evaluate per carried wavelength (w_[0].ok false: no lobe)
    std::array<NearDeltaLobe, 2> lobe_;      // lobes_ views the first List() of them
};

const PreparedKernel &SmoothKernel::Prepare(const ScatterQuery &q, ScratchBuffer &scratch) const {
    return *scratch.New<Prepared>(*this, q, scratch);
}

int SmoothKernel::Prepared::List(const ScatterQuery &q) {
    const int count = q.wl->Count();
    const std::array<Wave, NumWavelengths> &w = w_;
    int listed = 0;

    bool reflects = false, transmits = false;
    for (int i = 0; i < count; ++i) {
        reflects = reflects || w[i].R > 0;
        transmits = transmits || w[i].T > 0;
    }
    Vec3 hero;
    transmits = transmits && k_->transmits_ && RefractLocal(q.wi, w[0].eta, &hero);
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
        NearDeltaLobe &r = lobe_[listed++];
        r.id = 0;
        r.flags = ScatterReflection | ScatterNearDelta;
        r.wo.fill(ReflectLocal(q.wi));
        r.prob = probability(w[0].R, meanR);
        for (int i = 0; i < count; ++i) {
            r.SetWeight(i, w[i].R);
            r.nIn[i] = r.nOut[i] = w[i].nI;
        }
    }
    if (transmits) {
        NearDeltaLobe &t = lobe_[listed++];
        t.id = 1;
        t.flags = ScatterTransmission | ScatterNearDelta | (k_->dispersive_ ? ScatterDispersive : 0u);
        t.prob = probability(w[0].T, meanT);
        for (int i = 0; i < count; ++i) {
            t.nIn[i] = w[i].nI;
            t.nOut[i] = w[i].nT;
            // Radiance scaling (η_i/η_t)² on crossing (camera paths carry L/n², dielectric.cpp).
            if (w[i].ok && RefractLocal(q.wi, w[i].eta, &t.wo[i])) t.SetWeight(i, w[i].T / (w[i].eta * w[i].eta));
            else t.wo[i] = hero;  // weight 0 at this companion (total internal reflection, no data)
        }
    }
    return listed;
}

/// List's weight of one lobe at wiPrime in the slots asked for, with the hit's layer thicknesses (no
/// texture evaluation); the hero is evaluated in any case (no lobe is listed where it has no response).
std::optional<SampledSpectrum> SmoothKernel::Prepared::LobeWeightAt(int id, const Vec3 &wiPrime, unsigned slots) const {
    SampledSpectrum out;
    if (wiPrime.z == 0 || (id != 0 && id != 1)) return out;
    ScatterQuery q = q_;
    q.wi = wiPrime;
    const Wave hero = k_->Evaluate(q, 0, thickness_);
    Vec3 wo;
    if (!hero.ok || (id == 1 && (!k_->transmits_ || !RefractLocal(q.wi, hero.eta, &wo)))) return out;
    for (int i = 0; i < q.wl->Count(); ++i) {
        if (!((slots >> i) & 1u)) continue;
        const Wave w = i == 0 ? hero : k_->Evaluate(q, i, thickness_);
        if (id == 0) out[i] = w.R;  // 0 at every slot where List lists no reflection
        else if (w.ok && w.T > 0 && RefractLocal(q.wi, w.eta, &wo)) out[i] = w.T / (w.eta * w.eta);
    }
    return out;
}

std::optional<LobeResponse> SmoothKernel::Prepared::EvalLobe(int lobe, const Vec3 &wo) const {
    const ScatterQuery &q = q_;
    const SmoothSurface &surface = k_->surface_;
    if (q.wi.z == 0 || (lobe != 0 && lobe != 1) || (lobe == 1 && !k_->transmits_)) return std::nullopt;
    const Wave &hero = w_[0];  // as the listing: no lobe where the hero has no response
    if (!hero.ok) return std::nullopt;
    Vec3 dir = ReflectLocal(q.wi);
    if (lobe == 1 && !RefractLocal(q.wi, hero.eta, &dir)) return std::nullopt;
    if (!SameDirection(wo, dir)) return std::nullopt;

    const bool inside = k_->FromInside(q);
    const double cosI = std::abs(q.wi.z);
    LobeResponse r;
    // A bare surface has one response, a Jones matrix in both regimes; a coated one in the
    // ray-optics limit answers with the incoherent sum, which has none.
    const bool coherent = !q.rayOptics || surface.LayerCount() == 0;
    r.hasJones = coherent;
    r.coherence.any = surface.LayerCount() > 0;
    for (int i = 0; i < q.wl->Count(); ++i) {
        const Wave w = k_->Sides(q, i);
        if (!w.ok) continue;  // zero response
        const double lambda = q.wl->lambda[i];
        const StackResponse c = surface.Response(lambda, q.etaOutside, cosI, inside, thickness_, w.substrate);
        // A bare interface has one response: its incoherent matrix is FromJones(j) (set below).
        const bool layered = surface.LayerCount() > 0;
        IncoherentStackResponse n{};
        if (layered) n = surface.IncoherentResponse(lambda, q.etaOutside, cosI, inside, thickness_, w.substrate);
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
        if (r.coherence.any) r.coherence.shear[i] = surface.ShearVector(lambda, q.etaOutside, q.wi, inside, thickness_);
    }
    return r;
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
    const auto *c = dynamic_cast<const CoatingKernel *>(m.get());
    if (!c)
        throw Error(dict.Loc("coating"), "'coating' must name a thin_film or multilayer definition; '@" + name +
                                             "' is a " + (e ? e->type : std::string("other")) + " material");
    if (e && e->params.Has("substrate_ior"))
        throw Error(dict.Loc("coating"), "coating '@" + name + "' sets its own 'substrate_ior'; as a coating it lies "
                                         "on this kernel's 'ior' (remove 'substrate_ior' from '" + name + "')");
    return c->Layers();
}

std::shared_ptr<const SmoothKernel> ReadSubstrate(const ParamDict &dict, BuildContext &ctx) {
    std::shared_ptr<Material> m = ctx.GetRef<Material>(dict, "substrate");
    if (auto smooth = std::dynamic_pointer_cast<const SmoothKernel>(m)) return smooth;
    const SceneEntity *e = ctx.EntityOf(m.get());
    throw Error(dict.Loc("substrate"), "'substrate' must be a smooth kernel with a Fresnel response (a conductor or a "
                                       "dielectric); '" + dict.GetValue("substrate").ToString() + "' is a '" +
                                           (e ? e->type : std::string("?")) + "' material");
}

void WarnIfBeyondCoherence(const Coating &coating, const ParamDict &dict, const std::string &param,
                           BuildContext &ctx) {
    double total = 0;  // the largest total thickness (each layer at its thickest) [m]
    for (const CoatingLayer &l : coating.layers) total += l.thickness.MaxValue();
    if (!(total > MaxCoherentStack)) return;
    // The interference fringes' spacing in wavelength at 550 nm for an index of 1.5: λ²/(2nd).
    const double fringe = 550e-9 * 550e-9 / (2 * 1.5 * total);
    ctx.Diag().Warning(dict.Loc(param),
                       "the layers are " + Value::Number(total, Dim::Length()).ToString() +
                           " thick, far outside the thin-film model's range: its coherent response assumes a stack "
                           "thinner than the light's coherence length (about a micrometre for sunlight, at most "
                           "metres for a stabilised laser; docs/kernels.md, layer stacks); at this thickness the "
                           "fringes are " + Value::Number(fringe, Dim::Length()).ToString() +
                           " apart in wavelength, finer than any real source's line. Keep a layer below " +
                           Value::Number(MaxCoherentStack, Dim::Length()).ToString() +
                           ", or model a thick slab as a plain dielectric");
}

ParamSpec CoatingKernel::SubstrateSpec() {
    return P::ComplexSpectrum("substrate_ior",
                              "index n + iκ(λ) of the substrate under the layers: a number, n+ik, a named glass or "
                              "metal (\"BK7\", \"Cu\"), a spectrum or nk(…); κ = 0 transmits into it, κ > 0 is "
                              "opaque. Default 1: a free-standing film in air (a soap film)")
        .Default(Value::Number(1));
}

}  // namespace phasor
