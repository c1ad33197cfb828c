// SPDX-License-Identifier: Apache-2.0
// phasor — the plane-wave optics of a smooth surface: an optional coating (a stack of thin
// layers) over a substrate half-space (reflectance and geometry are separate: docs/kernels.md,
// "Layer stacks and coatings").
//
// One implementation serves every kernel whose *geometry* (a flat interface, a sinusoidal grating,
// a rough surface) multiplies a *reflectance*: `conductor` and `dielectric` are a SmoothSurface
// (bare, or with `coating = @film`), `thin_film` and `multilayer` are one with their own layers,
// and `grating` / `harvey_shack` take one through `substrate = @conductor_or_dielectric`, whose
// Fresnel response (and coating) multiplies their lobes. The response is the exact
// characteristic-matrix result of layer_stack.h (theory §4.4–4.5, D8): per polarisation, complex
// indices, double precision.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/render/texture.h"
#include "core/spectrum/complex_spectrum.h"
#include "materials/layer_stack.h"

namespace phasor {

/// One coating layer: its index n + iκ(λ) and its geometric thickness along the normal [m]
/// (a constant or a scalar texture of a length).
struct CoatingLayer {
    std::shared_ptr<const ComplexSpectrum> ior;
    FloatTexture thickness;
};

/// The layers of a `thin_film` or `multilayer` definition, outer (incident) side first: what a
/// `coating = @name` parameter refers to. Immutable once built.
struct Coating {
    std::vector<CoatingLayer> layers;
    std::string ToString() const;
};

/// A smooth, planar surface: `coating` (may be null: a bare interface) on a substrate of index
/// `substrate`(λ) + cauchyB/λ². The outside medium is the query's (ScatterQuery::etaOutside).
class SmoothSurface {
  public:
    /// Most layers a coating may have (multilayer's `pairs` are bounded so that 2·pairs fit).
    static constexpr int MaxLayers = 256;

    SmoothSurface(std::shared_ptr<const ComplexSpectrum> substrate, double cauchyB,
                  std::shared_ptr<const Coating> coating)
        : substrate_(std::move(substrate)), cauchyB_(cauchyB), coating_(std::move(coating)) {}

    /// n + iκ of the substrate at vacuum wavelength lambda [m] (including the Cauchy term).
    Complex SubstrateIndex(double lambda) const {
        return substrate_->Eval(lambda) + Complex(cauchyB_ / (lambda * lambda), 0);
    }
    /// True if the substrate absorbs (κ > 0 at lambda): nothing is transmitted into it as a lobe.
    bool Absorbing(double lambda) const { return SubstrateIndex(lambda).imag() > 0; }
    const Coating *GetCoating() const { return coating_.get(); }
    int LayerCount() const { return coating_ ? int(coating_->layers.size()) : 0; }

    /// The layers' thicknesses at one hit [m], outer layer first: the `thickness` the responses
    /// below take. A kernel prepared for a hit evaluates textured thicknesses once this way (a
    /// bubble's noise-driven film), instead of once per wavelength and response.
    void Thicknesses(const TextureEvalContext &tex, double *thickness) const;

    /// The response to a plane wave of vacuum wavelength lambda [m] that arrives with
    /// cosθ = cosI ∈ (0, 1] from the outside (index etaOutside; then the layers, then the
    /// substrate) or, if fromInside, from the substrate (then the layers in reverse order, then
    /// the outside). Textured thicknesses are evaluated at `tex`. r, t and R, T as in
    /// layer_stack.h (fresnel.h's sign conventions, T with the power factor between the incident
    /// and the exit medium, so a lossless stack has R + T = 1 per polarisation).
    StackResponse Response(double lambda, double etaOutside, double cosI, bool fromInside,
                           const TextureEvalContext &tex) const;
    /// The same with the layers' thicknesses (Thicknesses; nullptr for a bare surface) and the
    /// substrate's index at lambda (SubstrateIndex(lambda)) given, as a caller that already has them
    /// passes them.
    StackResponse Response(double lambda, double etaOutside, double cosI, bool fromInside, const double *thickness,
                           Complex substrate) const;
    /// Response(…).R() or, with `transmitted`, .T() alone (unpolarised power): for a bare surface
    /// (κ ≥ 0) lit from a real medium in real arithmetic (FresnelReflectanceReal; T by FresnelTransmittanceReal
    /// into a lossless medium), else from Response. Equal to Response's to round-off (1e-13); for callers that need
    /// the power many times per hit (a grating order's efficiency at each order's source angle).
    double Power(double lambda, double etaOutside, double cosI, bool fromInside, const double *thickness,
                 Complex substrate, bool transmitted) const;
    /// The same wave's incoherent response (layer_stack.h's LayerStackIncoherent: multiple
    /// reflections inside every propagating layer summed in power), the ray-optics limit of a
    /// coated surface. Equals Response's R and T for a bare surface.
    IncoherentStackResponse IncoherentResponse(double lambda, double etaOutside, double cosI, bool fromInside,
                                               const TextureEvalContext &tex) const;
    IncoherentStackResponse IncoherentResponse(double lambda, double etaOutside, double cosI, bool fromInside,
                                               const double *thickness, Complex substrate) const;
    /// Lateral shear [m] of the coating for that wave (LayerStackShear: 2·d·tanθ_t for one film);
    /// 0 for a bare surface.
    double Shear(double lambda, double etaOutside, double cosI, bool fromInside, const TextureEvalContext &tex) const;
    /// The same shear as a vector in the local tangent plane (z = normal) for the wave arriving
    /// along −wi: Shear(|wi.z|) along −wi.xy, where the deeper reflections exit (LobeCoherence::shear);
    /// zero at normal incidence and for a bare surface.
    Vec2 ShearVector(double lambda, double etaOutside, const Vec3 &wi, bool fromInside,
                     const TextureEvalContext &tex) const;
    Vec2 ShearVector(double lambda, double etaOutside, const Vec3 &wi, bool fromInside, const double *thickness) const;

    /// PreparedKernel::AngularBandwidth of the surface for light arriving with tangential wave-vector
    /// κ = kappa (units of k₀) from the outside (index etaOutside) or, if fromInside, from the
    /// substrate, with the layers' thicknesses at the hit (Thicknesses; nullptr for a bare surface)
    /// and the substrate's index at lambda (SubstrateIndex(lambda), as the caller has it):
    /// LayerStackBandwidth at vacuum wavelength lambda, tolerance tol (theory §0 D15).
    double Bandwidth(double lambda, double etaOutside, double kappa, bool fromInside, const double *thickness,
                     Complex substrate, double tol) const;

    std::string ToString() const;

  private:
    /// Calls f(span of the coating's layers at lambda, in the order the wave meets them), their
    /// thicknesses from `thickness` (outer first).
    template <typename F>
    auto WithLayers(double lambda, bool fromInside, const double *thickness, F &&f) const;
    /// Calls f(thicknesses at tex) (Thicknesses into a buffer of its own).
    template <typename F>
    auto WithThicknesses(const TextureEvalContext &tex, F &&f) const;
    double Shear(double lambda, double etaOutside, double cosI, bool fromInside, const double *thickness) const;

    std::shared_ptr<const ComplexSpectrum> substrate_;
    double cauchyB_ = 0;  // [m²]
    std::shared_ptr<const Coating> coating_;
};

}  // namespace phasor
