// SPDX-License-Identifier: Apache-2.0
// phasor — `conductor`: a smooth (optically flat) metal surface (theory §4.1), bare or coated.
//
// One near-delta lobe: specular reflection with the exact unpolarised Fresnel reflectance of a
// complex index n + iκ, R = (|r_s|² + |r_p|²)/2 (fresnel.h), or, with `coating = @film`, the
// reflectance of that thin_film / multilayer stack on the metal (layer_stack.h: Airy /
// characteristic matrix per polarisation, theory §4.4–4.5). The generalized ray keeps β and ρ
// and only its mean direction is mirrored (supplement S6.4), so in the ray-optics limit the lobe
// is a Dirac delta and for a generalized ray its angular width is the ray's own spread σ_k/k.
// Valid when the surface roughness is ≪ λ over the footprint (otherwise use a rough kernel).
// Two-sided like pbrt's conductor: a ray arriving from below the shading normal is mirrored on
// that side too, with the same (coated) response (the inside of a metal is unreachable, so this
// only matters for thin sheets and flipped normals). Never transmits; the rest (1 − R) is
// absorbed. The lobe is listed (ListNearDelta, id 0), so integrators measure delta sources
// through it in closed form (D14). The optics are materials/smooth_kernel.h's, shared with
// dielectric, thin_film and multilayer; in the ray-optics limit a coating gives its incoherent sum.
//
// Index: `ior`, a complex spectrum (core/spectrum/complex_spectrum.h): a named material (tabulated: Al from
// Rakić et al. 1998, Ag/Au/Cu from Johnson & Christy 1972; see core/spectrum/named_ior.h), a constant
// n + iκ, or nk(n = …, k = …) spectra. The index is relative to the medium outside
// (ScatterQuery::etaOutside).
#include <memory>

#include "core/spectrum/complex_spectrum.h"
#include "core/render/registry.h"
#include "materials/smooth_kernel.h"

namespace phasor {

class ConductorMaterial final : public SmoothKernel {
  public:
    ConductorMaterial(std::shared_ptr<const ComplexSpectrum> ior, std::shared_ptr<const Coating> coating)
        : SmoothKernel(SmoothSurface(std::move(ior), 0, std::move(coating)), /*transmits=*/false) {}

    static const Schema &GetSchema() {
        static const Schema s{
            "material",
            "conductor",
            "smooth metal: specular reflection with the exact Fresnel reflectance of a complex index n + iκ, "
            "optionally under a thin-film or multilayer coating",
            {
                P::ComplexSpectrum("ior",
                                   "complex index n + iκ(λ) relative to the outside (n > 0, κ ≥ 0): a "
                                   "material (Al: Rakić 1998; Ag, Au, Cu: Johnson & Christy 1972), a "
                                   "constant such as 0.18+3.42i, a spectrum, or nk(n = …, k = …)")
                    .Default(Value::String("Al")),
                CoatingSpec(),
            }};
        return s;
    }

    static std::unique_ptr<Material> Create(const ParamDict &dict, BuildContext &ctx) {
        return std::make_unique<ConductorMaterial>(ctx.GetComplexSpectrum(dict, "ior"), ReadCoating(dict, ctx));
    }

    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(5);
        // p[0]: the default (aluminium).
        p[1].Set("ior", Value::String("Au"));
        p[2].Set("ior", Value::ComplexNumber(Complex(0.2, 3.0)));
        p[3].Set("ior", Value::Call("nk", {Value::Number(1.8), Value::Number(0.4)}, {"n", "k"}));  // weakly absorbing, low R
        p[4].Set("ior", Value::String("Cu")).Set("coating", Value::Ref("contract_film"));  // oxidised copper
        return p;
    }

    std::string ToString() const override { return Describe("ConductorMaterial"); }
};

PHASOR_EXPORT_PLUGIN(Material, ConductorMaterial)

}  // namespace phasor
