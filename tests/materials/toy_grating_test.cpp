// SPDX-License-Identifier: Apache-2.0
// A toy reflection grating, written only against the kernel author's guide (docs/kernels.md) to
// prove that a many-lobe, dispersive kernel needs nothing outside its own file and its
// registration line: the contract suite (kernel_contract_test.cpp) picks it up from the registry
// and checks its listed orders against the vector grating equation, their weights, the lobe
// choice and EvalLobe. Not a physical model worth rendering (the real one is `grating`,
// src/materials/grating.cpp): orders j = −M…M of a sinusoidal phase grating (thin-phase amplitudes
// J_j(m)², m = k·h·cosθ_i, theory §4.2) on a grey mirror of reflectance R, grooves along the local
// y axis (grating vector along x), renormalised over the propagating orders of the *query's* wi.
// Registered only in the test executables.
// Unlike `grating` (whose orders carry the efficiencies of the light arriving along them) it
// conserves energy per query and is not reciprocal, which no other kernel that can be blended does
// (the `aperture` is footprint-aware): it is what exercises the contract suite's per-query energy
// checks on a non-reciprocal many-lobe kernel, and what mix_test.cpp and two_sided_test.cpp use for
// the per-query energy sense and for the refusal of a per-query child beside a per-incident-direction
// one (CombinedEnergySense, core/render/material.h).
#include <cmath>
#include <sstream>

#include "core/render/material.h"
#include "core/render/registry.h"

namespace phasor {

class ToyGratingMaterial final : public Material {
  public:
    ToyGratingMaterial(double period, double height, int maxOrder, double reflectance)
        : period_(period), height_(height), maxOrder_(maxOrder), reflectance_(reflectance) {}

    static const Schema &GetSchema() {
        static const Schema s{"material",
                              "toy_grating",
                              "test kernel: a thin-phase reflection grating on a grey mirror",
                              {P::Length("period", "groove period Λ").Default(Value::Number(1.6e-6, Dim::Length())).Min(0, true),
                               P::Length("height", "peak-to-peak groove height").Default(Value::Number(0.1e-6, Dim::Length())).Min(0),
                               P::Integer("max_order", "highest order |j| listed").Default(Value::Integer(3)).Min(0).Max(20),
                               P::Number("reflectance", "grey mirror reflectance R").Default(Value::Number(0.9)).Min(0).Max(1)}};
        return s;
    }
    static std::unique_ptr<Material> Create(const ParamDict &d, BuildContext &) {
        return std::make_unique<ToyGratingMaterial>(d.GetNumber("period"), d.GetNumber("height"), d.GetInt("max_order"),
                                                    d.GetNumber("reflectance"));
    }
    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(3);
        // p[0]: defaults (1.6 µm, a CD's pitch); p[1]: many orders; p[2]: the zeroth order only.
        p[1].Set("period", Value::Number(5e-6, Dim::Length())).Set("height", Value::Number(0.3e-6, Dim::Length()));
        p[2].Set("max_order", Value::Integer(0));
        return p;
    }

    const PreparedKernel &Prepare(const ScatterQuery &q, ScratchBuffer &scratch) const override {
        return *scratch.New<Prepared>(*this, q, scratch);
    }
    // m = k·h·cosθ_i and the renormalisation depend on the incident direction only.
    bool IsReciprocal() const override { return false; }

    std::string ToString() const override {
        std::ostringstream os;
        os << "ToyGratingMaterial[ period = " << period_ << ", height = " << height_ << ", max_order = " << maxOrder_
           << ", reflectance = " << reflectance_ << " ]";
        return os.str();
    }

  private:
    /// The orders of one query, listed once; the default Sample picks one ∝ its probability.
    class Prepared final : public PreparedKernel {
      public:
        Prepared(const ToyGratingMaterial &m, const ScatterQuery &q, ScratchBuffer &scratch) : PreparedKernel(q) {
            caps_ = CapNearDelta;
            if (q.wi.z == 0) return;
            const int count = q.wl->Count();
            LobeList out(scratch, 2 * m.maxOrder_ + 1);
            std::array<double, NumWavelengths> total{};  // Σ_j J_j² over the propagating orders, per λ
            for (int j = -m.maxOrder_; j <= m.maxOrder_; ++j) {
                const Vec2 shift(j * 2 * Pi / m.period_, 0);
                Vec3 wo0;
                if (!NearDeltaDirection(q.wi, q.etaOutside, q.etaOutside, shift, q.wl->lambda[0], false, &wo0))
                    continue;  // evanescent at the hero: not listed
                NearDeltaLobe &l = out.Add();
                l.id = j;
                l.flags = ScatterReflection | ScatterNearDelta | (j != 0 ? ScatterDispersive : 0u);
                l.shift = shift;
                l.nIn.fill(q.etaOutside);
                l.nOut.fill(q.etaOutside);
                for (int i = 0; i < count; ++i) {
                    l.wo[i] = wo0;
                    const double lambda = q.wl->lambda[i];
                    if (!NearDeltaDirection(q.wi, q.etaOutside, q.etaOutside, shift, lambda, false, &l.wo[i])) continue;
                    const double a = std::pow(std::cyl_bessel_j(double(std::abs(j)), m.Modulation(q, lambda)), 2);
                    l.SetWeight(i, a);
                    total[i] += a;
                }
            }
            // Renormalised over the propagating orders; lobes are picked ∝ their hero weight.
            for (int k = 0; k < out.Count(); ++k) {
                NearDeltaLobe &l = out[k];
                for (int i = 0; i < count; ++i) l.SetWeight(i, total[i] > 0 ? m.reflectance_ * l.Weight()[i] / total[i] : 0);
                l.prob = m.reflectance_ > 0 ? l.Weight()[0] / m.reflectance_ : 1.0 / out.Count();
            }
            lobes_ = out.Lobes();
        }

        std::optional<LobeResponse> EvalLobe(int lobe, const Vec3 &wo) const override {
            const NearDeltaLobe *l = FindLobe(lobe);
            if (!l || !SameDirection(wo, l->wo[0])) return std::nullopt;
            LobeResponse r;
            r.hasJones = true;
            for (int i = 0; i < q_.wl->Count(); ++i) {
                r.jones[i] = Jones::Identity() * Complex(std::sqrt(l->Weight()[i]), 0);
                r.mueller[i] = Mueller::Identity() * l->Weight()[i];
            }
            return r;
        }
    };

    // m = k·h·cosθ_i (theory §4.2, D6); h is peak-to-peak, the phase amplitude is k·h·cosθ_i.
    double Modulation(const ScatterQuery &q, double lambda) const {
        return 2 * Pi * q.etaOutside / lambda * height_ * std::abs(q.wi.z);
    }

    double period_, height_;
    int maxOrder_;
    double reflectance_;
};

PHASOR_REGISTER_PLUGIN(Material, ToyGratingMaterial, "toy_grating");

}  // namespace phasor
