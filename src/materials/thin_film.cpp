// SPDX-License-Identifier: Apache-2.0
// phasor — `thin_film`: one homogeneous film on a smooth substrate (theory §4.4, D8) — a soap
// film, an oxide layer on a metal (the bornite ore's Cu₂O on copper), an anti-reflection coat.
//
// Physics: the exact plane-wave response of the film, per polarisation, with complex indices, in
// double precision — Airy's summation of the multiply reflected waves,
//   r = (r₀₁ + r₁₂e^{2iδ}) / (1 + r₀₁r₁₂e^{2iδ}),  δ = (2π/λ)·n_f·d·cosθ_f,  R = |r|²
// (Born & Wolf, Principles of Optics, §1.6.4; Heavens, Optical Properties of Thin Solid Films,
// 1955), evaluated by layer_stack.h. Lobes, sides, sampling and the ray-optics limit are
// materials/smooth_kernel.h's: a specular reflection lobe; a refraction lobe into the substrate
// when it does not absorb (κ = 0; the default substrate_ior = 1 is a free-standing film in air);
// from below, the film seen from the substrate. Generalized rays get the coherent response (the
// interference colours), the ray-optics limit (`ray`) the incoherent sum, the film's reflections
// added in power. EvalLobe gives Jones diag(r_s, r_p) and, in LobeCoherence, that incoherent sum
// and the shear 2·d·tanθ_f between the waves reflected at the film's two faces.
//
// Validity: optically flat faces (roughness ≪ λ), a film thinner than the light's coherence
// length for the coherent response to hold (a few µm for sunlight; `sample_solve` will weight
// coherent and incoherent by the beam's coherence through the shear), and a thickness that
// varies slowly over the footprint when given as a texture (a thickness texture is evaluated at
// the hit point, like a local plane film).
//
// As a coating: `coating = @film` on a conductor or dielectric puts this film (its `ior` and
// thickness) on that kernel's index; the definition must then not set `substrate_ior`.
#include <memory>

#include "core/diagnostics.h"
#include "core/render/registry.h"
#include "materials/smooth_kernel.h"

namespace phasor {

class ThinFilmMaterial final : public CoatingKernel {
  public:
    using CoatingKernel::CoatingKernel;

    static const Schema &GetSchema() {
        static const Schema s{
            "material",
            "thin_film",
            "one film on a smooth substrate: Airy interference per polarisation (soap films, oxide layers, "
            "anti-reflection coats); a surface of its own or another kernel's `coating`",
            {
                P::Length("thickness", "geometric film thickness along the normal (or give thickness_texture)").Min(0),
                P::FloatTexture("thickness_texture",
                                "@name of a scalar texture of a length: a thickness varying over the surface "
                                "(instead of 'thickness')",
                                Dim::Length())
                    .Min(0),
                P::ComplexSpectrum("ior",
                                   "film index n + iκ(λ): a number, n+ik (e.g. 2.9+0.1i), a named material "
                                   "(\"Cu2O\", \"MgF2\", \"water\", …), a spectrum or nk(…)")
                    .Required(),
                SubstrateSpec(),
            }};
        return s;
    }

    static std::unique_ptr<Material> Create(const ParamDict &d, BuildContext &ctx) {
        const bool constant = d.Has("thickness"), textured = d.Has("thickness_texture");
        if (constant && textured)
            throw Error(d.Loc("thickness_texture"), "give either 'thickness' or 'thickness_texture', not both");
        if (!constant && !textured)
            throw Error(d.EntityLoc(), "thin_film needs 'thickness' (a length, e.g. 120 nm) or 'thickness_texture' "
                                       "(@name of a texture of a length)");
        if (textured && d.GetValue("thickness_texture").kind != Value::Kind::Ref)
            throw Error(d.Loc("thickness_texture"), "'thickness_texture' expects @name of a texture; give a constant "
                                                    "thickness as 'thickness'");
        const FloatTexture thickness = constant ? FloatTexture(d.GetNumber("thickness"), Dim::Length())
                                                : ctx.GetFloatTexture(d, "thickness_texture");
        auto coating = std::make_shared<Coating>();
        coating->layers.push_back({ctx.GetComplexSpectrum(d, "ior"), thickness});
        WarnIfBeyondCoherence(*coating, d, constant ? "thickness" : "thickness_texture", ctx);
        return std::make_unique<ThinFilmMaterial>(ctx.GetComplexSpectrum(d, "substrate_ior"), std::move(coating));
    }

    static std::vector<ParamDict> TestPresets() {
        std::vector<ParamDict> p(5);
        // A soap film in air: transparent on both sides, R + T = 1.
        p[0].Set("ior", Value::Number(1.33)).Set("thickness", Value::Number(300e-9, Dim::Length()));
        // Cu₂O on copper (theory §4.4's bornite): an absorbing film on an opaque metal.
        p[1].Set("ior", Value::String("Cu2O"))
            .Set("thickness", Value::Number(120e-9, Dim::Length()))
            .Set("substrate_ior", Value::String("Cu"));
        // A MgF₂ anti-reflection coat on dispersive BK7 (refraction is dispersive; TIR from inside).
        p[2].Set("ior", Value::String("MgF2"))
            .Set("thickness", Value::Number(100e-9, Dim::Length()))
            .Set("substrate_ior", Value::String("BK7"));
        // An absorbing high-index film of textured thickness (80–250 nm) on glass.
        p[3].Set("ior", Value::ComplexNumber(Complex(2.0, 0.3)))
            .Set("thickness_texture", Value::Ref("contract_thickness"))
            .Set("substrate_ior", Value::Number(1.5));
        // A thick (5 µm) film: fast spectral fringes.
        p[4].Set("ior", Value::String("TiO2"))
            .Set("thickness", Value::Number(5e-6, Dim::Length()))
            .Set("substrate_ior", Value::String("fused_silica"));
        return p;
    }

    std::string ToString() const override { return Describe("ThinFilmMaterial"); }
};

PHASOR_EXPORT_PLUGIN(Material, ThinFilmMaterial)

}  // namespace phasor
