// SPDX-License-Identifier: Apache-2.0
// phasor — `multilayer`: a stack of homogeneous layers on a smooth substrate (theory §4.5, D8) —
// the interference reflector of a beetle's elytron (Chrysomelidae), a Bragg mirror, a dichroic
// or anti-reflection stack.
//
// Physics: the exact plane-wave response of the stack, per polarisation, with complex indices,
// in double precision: the characteristic-matrix (Abelès) product, evaluated as Rouard's
// recursion Γ_{j−1} = (r_{j−1,j} + Γ_j e^{2iδ_j})/(1 + r_{j−1,j}Γ_j e^{2iδ_j}), R = |Γ₀|²
// (Macleod, Thin-Film Optical Filters, ch. 2; Born & Wolf §1.6.5), by layer_stack.h. The layers
// are `layers = [layer(ior = …, thickness = …), …]`, top (incident side) first, or N repeated
// bilayers (n_a, d_a), (n_b, d_b) with `pairs = N` — a quarter-wave pair at λ₀ has
// d = λ₀/(4n) and its N-pair peak reflectance is ((1 − (n_s/n₀)(n_b/n_a)^{2N})/(1 + …))².
// Everything else — lobes, sides, sampling, the incoherent ray-optics limit, Jones matrices and
// coherence terms (the shear Σ 2·d_j·tanθ_j of the deepest reflection) — is materials/
// smooth_kernel.h's, exactly as for `thin_film` (one layer here is a thin_film).
//
// Validity: optically flat, parallel layers (roughness ≪ λ), a stack thinner than the light's
// coherence length for the coherent response, at most SmoothSurface::MaxLayers layers.
//
// As a coating: `coating = @stack` on a conductor or dielectric puts these layers on that
// kernel's index; the definition must then not set `substrate_ior`.
#include <memory>
#include <string>

#include "core/diagnostics.h"
#include "core/render/registry.h"
#include "materials/smooth_kernel.h"

namespace phasor {

class MultilayerMaterial final : public CoatingKernel {
  public:
    using CoatingKernel::CoatingKernel;

    static const Schema &GetSchema() {
        static const Schema s{
            "material",
            "multilayer",
            "a stack of layers on a smooth substrate: characteristic-matrix interference per polarisation "
            "(beetle elytra, Bragg mirrors); a surface of its own or another kernel's `coating`",
            {
                P::RecordList("layers", "the layers, top (incident side) first (or give n_a, n_b, d_a, d_b, pairs)",
                              "layer", "one homogeneous layer",
                              {P::ComplexSpectrum("ior", "layer index n + iκ(λ)").Required(),
                               P::Length("thickness", "geometric thickness along the normal").Required().Min(0)}),
                P::ComplexSpectrum("n_a", "index of the first layer of each repeated pair (top layer of the stack)"),
                P::ComplexSpectrum("n_b", "index of the second layer of each repeated pair"),
                P::Length("d_a", "thickness of the first layer of each pair").Min(0),
                P::Length("d_b", "thickness of the second layer of each pair").Min(0),
                P::Integer("pairs", "number N of repeated (a, b) pairs: 2N layers a, b, a, b, …")
                    .Min(1)
                    .Max(SmoothSurface::MaxLayers / 2),
                SubstrateSpec(),
            }};
        return s;
    }

    static std::unique_ptr<Material> Create(const ParamDict &d, BuildContext &ctx) {
        static const char *const PairParams[] = {"n_a", "n_b", "d_a", "d_b", "pairs"};
        const char *firstPair = nullptr;
        for (const char *p : PairParams)
            if (!firstPair && d.Has(p)) firstPair = p;
        if (d.Has("layers") && firstPair)
            throw Error(d.Loc(firstPair), "give either 'layers' or the repeated pair (n_a, n_b, d_a, d_b, pairs), "
                                          "not both");
        auto coating = std::make_shared<Coating>();
        if (firstPair) {
            for (const char *p : PairParams)
                if (!d.Has(p))
                    throw Error(d.EntityLoc(), std::string("missing '") + p +
                                                   "': the repeated pair needs n_a, n_b, d_a, d_b and pairs");
            const CoatingLayer a{ctx.GetComplexSpectrum(d, "n_a"), FloatTexture(d.GetNumber("d_a"), Dim::Length())};
            const CoatingLayer b{ctx.GetComplexSpectrum(d, "n_b"), FloatTexture(d.GetNumber("d_b"), Dim::Length())};
            for (int k = 0; k < d.GetInt("pairs"); ++k) {
                coating->layers.push_back(a);
                coating->layers.push_back(b);
            }
        } else {
            if (!d.Has("layers"))
                throw Error(d.EntityLoc(), "multilayer needs 'layers' = [layer(ior = …, thickness = …), …] or the "
                                           "repeated pair n_a, n_b, d_a, d_b, pairs");
            const std::vector<ParamDict> records = d.GetRecords("layers");
            if (records.empty()) throw Error(d.Loc("layers"), "'layers' is empty: a multilayer needs at least one layer");
            if (records.size() > std::size_t(SmoothSurface::MaxLayers))
                throw Error(d.Loc("layers"), "'layers' has " + std::to_string(records.size()) + " layers; at most " +
                                                 std::to_string(SmoothSurface::MaxLayers) + " are supported");
            for (const ParamDict &l : records)
                coating->layers.push_back(
                    {ctx.GetComplexSpectrum(l, "ior"), FloatTexture(l.GetNumber("thickness"), Dim::Length())});
        }
        WarnIfBeyondCoherence(*coating, d, firstPair ? "d_a" : "layers", ctx);
        return std::make_unique<MultilayerMaterial>(ctx.GetComplexSpectrum(d, "substrate_ior"), std::move(coating));
    }

    static std::vector<ParamDict> TestPresets() {
        auto nm = [](double v) { return Value::Number(v * 1e-9, Dim::Length()); };
        auto layer = [&](Value ior, double d) { return Value::Call("layer", {std::move(ior), nm(d)}, {"ior", "thickness"}); };
        std::vector<ParamDict> p(4);
        // The beetle reflector of theory §4.5: quarter-wave chitin-like pairs at 530 nm on a
        // transparent base (R + T = 1, a narrow green peak); 6 pairs keep the suite fast (the
        // cost per query grows with the layer count, the code paths do not).
        p[0].Set("n_a", Value::Number(1.55))
            .Set("n_b", Value::Number(1.70))
            .Set("d_a", nm(85))
            .Set("d_b", nm(78))
            .Set("pairs", Value::Integer(6))
            .Set("substrate_ior", Value::String("chitin"));
        // The same on a dark absorbing base (opaque, two-sided).
        p[1].Set("n_a", Value::Number(1.55))
            .Set("n_b", Value::Number(1.70))
            .Set("d_a", nm(85))
            .Set("d_b", nm(78))
            .Set("pairs", Value::Integer(3))
            .Set("substrate_ior", Value::ComplexNumber(Complex(1.6, 0.6)));
        // A two-layer broadband AR stack of named materials on BK7, with a weakly absorbing layer.
        p[2].Set("layers", Value::List({layer(Value::String("MgF2"), 100), layer(Value::ComplexNumber(Complex(2.1, 0.01)), 65)}))
            .Set("substrate_ior", Value::String("BK7"));
        // A silver–dielectric stack (a metallic layer stays coherent even in the ray-optics limit).
        p[3].Set("layers", Value::List({layer(Value::String("SiO2"), 90), layer(Value::String("Ag"), 15),
                                        layer(Value::String("TiO2"), 40)}))
            .Set("substrate_ior", Value::String("fused_silica"));
        return p;
    }

    std::string ToString() const override { return Describe("MultilayerMaterial"); }
};

PHASOR_EXPORT_PLUGIN(Material, MultilayerMaterial)

}  // namespace phasor
