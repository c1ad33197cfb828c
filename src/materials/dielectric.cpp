// SPDX-License-Identifier: Apache-2.0
// phasor — `dielectric`: a smooth interface to a transparent medium (glass, water; theory §4.1),
// bare or coated.
//
// Two near-delta lobes (supplement S6.4): specular reflection with the unpolarised Fresnel
// reflectance R and refraction by Snell's law with T = 1 − R; lossless, so R + T = 1 exactly.
// With `coating = @film` R and T are those of the thin_film / multilayer stack on the glass
// (layer_stack.h, theory §4.4–4.5: an anti-reflection coating, a dichroic mirror), R + T ≤ 1
// (= 1 for lossless layers). The generalized ray keeps β and ρ; only its mean direction changes,
// so in the ray-optics limit both lobes are Dirac deltas (for a generalized ray their width is
// the ray's spread σ_k/k). Valid for an optically flat interface (roughness ≪ λ over the
// footprint) and a non-absorbing interior. The shading normal points outside: wi.z > 0 means the
// path arrives from the outside medium (index ScatterQuery::etaOutside) and enters the interior
// (index `ior`), wi.z < 0 that it is inside and leaves (through the coating's layers in reverse
// order). Lobe choice is ∝ R and T, half at the hero wavelength, half over the carried ones (smooth_kernel.h, theory §3.1); the refracted radiance
// carries the (η_i/η_t)² factor (camera paths transport radiance, whose basic invariant is L/n²).
// A wavelength-dependent index makes refraction dispersive: its direction is the hero's, and the
// integrator drops the companions (theory §0 D10). Both lobes are listed (ListNearDelta: ids 0
// reflection, 1 refraction) and measured in closed form by the integrator (D14). The optics are
// materials/smooth_kernel.h's, shared with conductor, thin_film and multilayer.
//
// Dispersion: `ior` is a complex spectrum (core/spectrum/complex_spectrum.h) with κ = 0: a constant, a named
// glass ("BK7", "fused_silica", "water", …; core/spectrum/named_ior.h), a `sellmeier` or `cauchy`
// spectrum, or any spectrum; `cauchy_b` adds Cauchy's term, η(λ) = ior(λ) + B/λ² (Cauchy 1836;
// e.g. BK7 ≈ 1.5046 + 4.20e-3 µm²/λ²).
#include <memory>
#include <string>

#include "core/spectrum/complex_spectrum.h"
#include "core/diagnostics.h"
#include "core/render/registry.h"
#include "materials/smooth_kernel.h"

namespace phasor {

class DielectricMaterial final : public SmoothKernel {
  public:
    DielectricMaterial(std::shared_ptr<const ComplexSpectrum> ior, double cauchyB, std::shared_ptr<const Coating> coating)
        : SmoothKernel(SmoothSurface(std::move(ior), cauchyB, std::move(coating)), /*transmits=*/true) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "material",
            "dielectric",
            "smooth dielectric interface: Fresnel-weighted specular reflection and Snell refraction, "
            "optionally under a thin-film or multilayer coating",
            {
                P::ComplexSpectrum("ior",
                                   "index of refraction η(λ) of the inside (real: κ = 0, n > 0; the outside "
                                   "is the query's medium, normally air = 1): a number, a glass such as "
                                   "\"BK7\", or a spectrum such as sellmeier(…) or cauchy(…)")
                    .Default(Value::Number(1.5)),
                P::Number("cauchy_b",
                          "Cauchy dispersion term B added to 'ior': η(λ) = ior(λ) + B/λ² "
                          "(e.g. 0.0042 um^2)",
                          Dim::Area())
                    .Default(Value::Number(0, Dim::Area())),
                CoatingSpec(),
            }};
        return s;
    }

    static std::unique_ptr<Material> Create(const ParamDict &dict, BuildContext &ctx) {
        auto ior = ctx.GetComplexSpectrum(dict, "ior");
        if (!IsTransparent(*ior))
            throw Error(dict.Loc("ior"), "dielectric 'ior' must be real (κ = 0: the interior does not "
                                         "absorb); it is " + ior->ToString() + " (use 'conductor' for metals)");
        const double b = dict.GetNumber("cauchy_b");
        for (double l = 360e-9; l <= 1000e-9; l += 5e-9) {
            const double n = ior->Eval(l).real() + b / (l * l);
            if (!(n > 0))
                throw Error(dict.Loc(dict.Has("ior") ? "ior" : "cauchy_b"),
                            "the index of refraction must be positive; it is " + std::to_string(n) + " at " +
                                std::to_string(l * 1e9) + " nm");
        }
        return std::make_unique<DielectricMaterial>(ior, b, ReadCoating(dict, ctx));
    }

    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(5);
        // p[0]: the default, η = 1.5.
        p[1].Set("ior", Value::Number(1.33)).Set("coating", Value::Ref("contract_stack"));  // coated
        p[2].Set("ior", Value::Number(2.42));  // diamond: strong reflection, early TIR
        p[3].Set("ior", Value::Number(1.5))
            .Set("cauchy_b", Value::Number(0.02e-12, Dim::Area()));  // dispersive
        p[4].Set("ior", Value::Number(1.0));                         // index matched: pure transmission
        return p;
    }

    std::string ToString() const override { return Describe("DielectricMaterial"); }
};

PHASOR_EXPORT_PLUGIN(Material, DielectricMaterial)

}  // namespace phasor
