// SPDX-License-Identifier: Apache-2.0
// phasor — `two_sided`: one reflecting kernel on both faces of a sheet, or a different one on each
// (Mitsuba 3's twosided).
//
// A query from the side the shading normal points to (wi.z ≥ 0) goes to `front` unchanged. A query
// from below (wi.z < 0) goes to `back` mirrored through the tangent plane: the child sees
// wi' = (wi.x, wi.y, −wi.z) in its usual upper hemisphere, and every direction it returns (sampled
// wo, listed lobe directions) and every direction it is asked about is mirrored the same way, so
// the back face is the mirror image of the child's surface (for the isotropic and groove-symmetric
// kernels of theory §4 the same surface). Tangential quantities (a lobe's shift, a film's shear)
// are unchanged by the mirror. Polarisation: in the s/p basis of core/polarization.h,
// ŝ = n̂ × k̂ maps to the mirror image of ŝ but p̂ = k̂ × ŝ to minus the mirror image of p̂ (a mirror
// reverses handedness), so the back's Jones matrix J becomes D·J·D with D = diag(1, −1) and its
// Mueller matrix M becomes M_D·M·M_D with M_D = diag(1, 1, −1, −1) (S2 and S3 change sign);
// diagonal responses (Fresnel, diffuse) are unchanged. With `material` alone, front and back are
// the same kernel.
// Children must not transmit (as in Mitsuba, whose twosided refuses transmitting BSDFs): light
// that crossed the sheet would meet the other face's kernel from its own side, so a transmitting
// front and back would not describe one consistent sheet. Create probes each child over incident
// directions on both sides, wavelengths 400–700 nm and a few uvs (listed lobes, samples across
// the lobe choice, Eval across the surface) and refuses one that sends light through; footprint-
// aware kernels (`aperture`) transmit and are refused as well. Energy (CombinedEnergySense, core/
// render/material.h): light from a direction d and every query that gathers it lie on one side, so
// each face keeps its child's sense: reciprocal if both children are, per incident direction if each
// is reciprocal or per incident direction (a grating on one face, a rough surface on the other), per
// query likewise; children that conserve energy only per query and only per incident direction
// are refused (one declaration cannot describe both faces).
#include <array>
#include <cmath>
#include <memory>
#include <sstream>

#include "core/diagnostics.h"
#include "core/render/material.h"
#include "core/render/registry.h"

namespace phasor {

namespace {

/// The mirror image through the tangent plane (z → −z).
Vec3 Mirror(const Vec3 &v) { return {v.x, v.y, -v.z}; }

/// The mirror's change of s/p basis on a Jones matrix, D·J·D with D = diag(1, −1).
Jones MirrorBasis(const Jones &j) {
    Jones r = j;
    r.m[0][1] = -j.m[0][1];
    r.m[1][0] = -j.m[1][0];
    return r;
}

/// The same on a Mueller matrix, M_D·M·M_D with M_D = diag(1, 1, −1, −1).
Mueller MirrorBasis(const Mueller &m) {
    Mueller r = m;
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
            if ((a >= 2) != (b >= 2)) r.m[a][b] = -m.m[a][b];
    return r;
}

/// A description of the first way the probe finds `m` sending light through the surface, or ""
/// if it finds none (see the file comment).
std::string FindTransmission(const Material &m) {
    if (m.IsFootprintAware()) return "it is footprint-aware (an aperture transmits)";
    SampledWavelengths wl;
    for (int i = 0; i < NumWavelengths; ++i) {
        wl.lambda[i] = 400e-9 + 300e-9 * i / std::max(1, NumWavelengths - 1);
        wl.pdf[i] = 1 / 300e-9;
    }
    constexpr std::array<double, 6> cosines = {1, 0.6, 0.15, -0.15, -0.6, -1};
    constexpr std::array<double, 2> phis = {0.3, 2.4};
    const std::array<Vec2, 2> uvs = {Vec2(0.13, 0.61), Vec2(0.77, 0.29)};
    ScratchBuffer scratch;
    for (const double c : cosines)
        for (const double phi : phis)
            for (const Vec2 &uv : uvs) {
                ScatterQuery q;
                const double s = std::sqrt(std::max(0.0, 1 - c * c));
                q.wi = Vec3(s * std::cos(phi), s * std::sin(phi), c);
                q.wl = &wl;
                q.tex.uv = uv;
                scratch.Reset();
                const PreparedKernel &k = m.Prepare(q, scratch);
                for (const NearDeltaLobe &l : k.ListNearDelta())
                    if (l.flags & ScatterTransmission) return "it lists a transmitted lobe";
                for (int i = 0; i < 16; ++i)
                    for (int j = 0; j < 2; ++j) {
                        auto smp = k.Sample((i + 0.5) / 16, Vec2(0.25 + 0.5 * j, 0.5));
                        if (smp && ((smp->flags & ScatterTransmission) || smp->wo.z * q.wi.z < 0))
                            return "it samples directions through the surface";
                    }
                for (int i = 0; i < 8; ++i) {
                    const double a = 2 * Pi * (i + 0.5) / 8, cz = i % 2 ? 0.3 : 0.9, sz = std::sqrt(1 - cz * cz);
                    const Vec3 wo(sz * std::cos(a), sz * std::sin(a), c > 0 ? -cz : cz);
                    if (!k.Eval(wo).IsZero()) return "it scatters into the far side (Eval)";
                }
            }
    return "";
}

}  // namespace

class TwoSidedMaterial final : public Material, public ReferenceDirection {
  public:
    /// The children must have a combined energy sense (CombinedEnergySense; Create checks it).
    TwoSidedMaterial(std::shared_ptr<const Material> front, std::shared_ptr<const Material> back)
        : front_(std::move(front)), back_(std::move(back)) {
        const Material *children[] = {front_.get(), back_.get()};
        sense_ = CombinedEnergySense(children).value_or(EnergySense::PerQuery);
    }

    static const Schema &GetSchema() {
        static const Schema s{
            "material",
            "two_sided",
            "a reflecting kernel on both faces of a sheet (or one per face); from below it is mirrored",
            {
                P::Ref("material", "material", "the kernel on both faces (instead of 'front' and 'back')"),
                P::Ref("front", "material", "the kernel on the face the shading normal points out of"),
                P::Ref("back", "material", "the kernel on the other face, seen mirrored (with 'front')"),
            }};
        return s;
    }

    static std::unique_ptr<Material> Create(const ParamDict &d, BuildContext &ctx) {
        const bool one = d.Has("material"), front = d.Has("front"), back = d.Has("back");
        if (one && (front || back))
            throw Error(d.Loc(front ? "front" : "back"), "give 'material' (both faces) or 'front' and 'back', not both");
        if (!one && !(front && back))
            throw Error(d.Loc(front ? "front" : back ? "back" : "material"),
                        front || back ? std::string("'") + (front ? "front" : "back") + "' needs '" +
                                            (front ? "back" : "front") + "' (or give 'material' for both faces)"
                                      : "two_sided needs 'material' (both faces) or 'front' and 'back'");
        auto child = [&](const char *name) {
            std::shared_ptr<const Material> m = ctx.GetRef<Material>(d, name);
            const std::string why = FindTransmission(*m);
            if (!why.empty())
                throw Error(d.Loc(name), std::string("'") + name + "' transmits: " + why + " (" + m->ToString() +
                                             "); two_sided takes reflecting kernels only (a sheet whose faces are "
                                             "seen from their own sides)");
            return m;
        };
        if (one) {
            std::shared_ptr<const Material> m = child("material");
            return std::make_unique<TwoSidedMaterial>(m, m);
        }
        std::shared_ptr<const Material> f = child("front"), b = child("back");
        const Material *children[] = {f.get(), b.get()};
        if (!CombinedEnergySense(children))
            throw Error(d.Loc("back"), std::string("'front' ") + Describe(EnergySenseOf(*f)) + " (" + f->ToString() +
                                           ") but 'back' " + Describe(EnergySenseOf(*b)) + " (" + b->ToString() +
                                           "): one kernel cannot declare both (Material::"
                                           "ConservesEnergyPerIncidentDirection)");
        return std::make_unique<TwoSidedMaterial>(f, b);
    }

    /// Presets for the contract suite (fixtures of tests/materials/material_test_util.h).
    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(3);
        p[0].Set("material", Value::Ref("contract_gold"));
        // A different kernel per face: a glint from above, a diffuser from below.
        p[1].Set("front", Value::Ref("contract_gold")).Set("back", Value::Ref("contract_matte"));
        // Kernels that conserve energy per incident direction on both faces: a rough surface above,
        // a grating (mirrored) below.
        p[2].Set("front", Value::Ref("contract_rough")).Set("back", Value::Ref("contract_grating"));
        return p;
    }

    /// The child of wi's side prepared for the query (mirrored from below): its lobes (same ids,
    /// shifts and indices; directions mirrored back from below) and continuous lobes (same ids).
    /// EvalLobe: the child's response; from below towards the mirrored wo, in the mirrored s/p basis.
    const PreparedKernel &Prepare(const ScatterQuery &q, ScratchBuffer &scratch) const override {
        return *scratch.New<Prepared>(*this, q, scratch);
    }

    bool IsReciprocal() const override { return sense_ == EnergySense::Reciprocal; }
    bool ConservesEnergyPerIncidentDirection() const override { return sense_ == EnergySense::PerIncidentDirection; }
    bool HasCoherenceTerms() const override { return front_->HasCoherenceTerms() || back_->HasCoherenceTerms(); }
    bool MayPassStraight() const override { return front_->MayPassStraight() || back_->MayPassStraight(); }
    /// The front face's reference direction (the side the shading frame describes).
    std::optional<double> ReferenceAngle(const TextureEvalContext &tex) const override {
        return ReferenceAngleOf(*front_, tex);
    }

    void CheckShape(const Shape &shape) const override {
        front_->CheckShape(shape);
        if (back_ != front_) back_->CheckShape(shape);
    }

    std::string ToString() const override {
        std::ostringstream os;
        if (front_ == back_) os << "TwoSidedMaterial[ material = " << front_->ToString() << " ]";
        else os << "TwoSidedMaterial[ front = " << front_->ToString() << ", back = " << back_->ToString() << " ]";
        return os.str();
    }

  private:
    /// The sheet at one hit: the child of wi's side, prepared for wi mirrored onto its upper side
    /// when wi is below.
    class Prepared final : public PreparedKernel {
      public:
        Prepared(const TwoSidedMaterial &m, const ScatterQuery &q, ScratchBuffer &scratch)
            : PreparedKernel(q), below_(q.wi.z < 0) {
            ScatterQuery local = q;
            if (below_) local.wi = Mirror(q.wi);
            child_ = &(below_ ? m.back_ : m.front_)->Prepare(local, scratch);
            caps_ = child_->Capabilities();
            continuous_ = child_->ContinuousLobes();
            const std::span<const NearDeltaLobe> lobes = child_->ListNearDelta();
            if (!below_ || lobes.empty()) {
                lobes_ = lobes;
                return;
            }
            LobeList mirrored(scratch, int(lobes.size()));
            for (const NearDeltaLobe &l : lobes) {
                NearDeltaLobe &c = mirrored.Add();
                c = l;
                for (Vec3 &w : c.wo) w = Mirror(w);
            }
            lobes_ = mirrored.Lobes();
        }

        /// The side's child's (mirroring keeps κ).
        double AngularBandwidth(double kappaMax) const override { return child_->AngularBandwidth(kappaMax); }
        std::optional<LobeResponse> EvalLobe(int lobe, const Vec3 &wo) const override {
            if (!below_) return child_->EvalLobe(lobe, wo);
            std::optional<LobeResponse> r = child_->EvalLobe(lobe, Mirror(wo));
            if (!r) return std::nullopt;
            for (int i = 0; i < q_.wl->Count(); ++i) {
                r->jones[i] = MirrorBasis(r->jones[i]);
                r->mueller[i] = MirrorBasis(r->mueller[i]);
                r->coherence.incoherent[i] = MirrorBasis(r->coherence.incoherent[i]);
            }
            return r;
        }
        /// The side's child's, at the mirrored wi′ from below; a wi′ on the other side (the other
        /// child) is not answered.
        std::optional<SampledSpectrum> LobeWeightAt(int lobe, const Vec3 &wiPrime, unsigned slots) const override {
            if ((wiPrime.z < 0) != below_) return std::nullopt;
            return child_->LobeWeightAt(lobe, below_ ? Mirror(wiPrime) : wiPrime, slots);
        }

      private:
        std::optional<ScatterSample> SampleLobes(double u0, const Vec2 &u) const override {
            std::optional<ScatterSample> s = child_->Sample(u0, u);
            if (s && below_) s->wo = Mirror(s->wo);
            return s;
        }
        SampledSpectrum EvalContinuous(const Vec3 &wo) const override { return child_->Eval(below_ ? Mirror(wo) : wo); }
        double PdfContinuous(const Vec3 &wo) const override { return child_->Pdf(below_ ? Mirror(wo) : wo); }
        KernelValue EvalPdfContinuous(const Vec3 &wo, const IncidentWave &w) const override {
            return child_->EvalPdf(below_ ? Mirror(wo) : wo, w);
        }

        bool below_;  // wi below the shading normal: the back, mirrored
        const PreparedKernel *child_ = nullptr;
    };

    std::shared_ptr<const Material> front_, back_;  // the same object for `material`
    EnergySense sense_ = EnergySense::Reciprocal;  // CombinedEnergySense of front and back
};

PHASOR_EXPORT_PLUGIN(Material, TwoSidedMaterial)

}  // namespace phasor
