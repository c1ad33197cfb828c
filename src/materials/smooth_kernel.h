// SPDX-License-Identifier: Apache-2.0
// phasor — the one kernel of a smooth (optically flat) surface, shared by `conductor`,
// `dielectric`, `thin_film` and `multilayer` (docs/kernels.md "Layer stacks and coatings": one layer stack,
// several geometries). Each of those files only declares its schema and builds a SmoothSurface — a
// coating (possibly none) over a substrate — in Create; everything optical is here.
//
// Lobes (all near-delta and listed, theory §4.1, S6.4): id 0, specular reflection with the
// surface's R(λ); id 1, only if the substrate transmits, refraction by Snell's law into (or out
// of) the substrate with T(λ)·(η_i/η_t)² (radiance), dispersive when the substrate's index varies
// with λ (its direction is the hero's; the integrator drops the companions, D10). R and T come
// from SmoothSurface (layer_stack.h), per polarisation:
//   * generalized rays (ScatterQuery::rayOptics false): the coherent response — a film's Airy
//     formula, a stack's characteristic matrix (theory §4.4–4.5, D8) — with EvalLobe's Jones
//     matrices diag(r_s, r_p) and diag(t_s, t_p)·√(power factor)·(η_i/η_t);
//   * the ray-optics limit (rayOptics true: `ray`, spread-free GRs): the incoherent sum of the
//     coating (multiple reflections inside each layer summed in power; theory §4.4–4.5, D8: "a film's
//     incoherent sum"), a partially depolarising Mueller matrix without a Jones matrix. A bare
//     surface has one response in both regimes: the Fresnel equations, with their Jones matrix.
// EvalLobe also fills LobeCoherence for a coated surface: `incoherent` (that incoherent sum)
// and `shear`, the lateral shear of the coating's deepest reflection (2·d·tanθ_t for one film,
// theory §4.4; LayerStackShear) along the incident wave's tangential direction of travel.
//
// Sides. A transmitting surface (`transmits`: the substrate does not absorb, κ = 0) is the
// interface of a solid: wi.z > 0 arrives from the outside (ScatterQuery::etaOutside), wi.z < 0
// from the substrate and meets the layers in reverse order (SmoothSurface::Response fromInside),
// with total internal reflection where the outside is evanescent. An opaque surface (absorbing
// substrate: a metal, a dark base) is two-sided like pbrt's conductor: from below it reflects as
// from above, mirrored on wi's side (the inside of a metal is unreachable; this only matters for
// thin sheets and flipped normals), and never transmits.
//
// Sampling (PreparedKernel's default SampleLobes over the listed lobes): lobe 0 with probability ½·R/(R + T) at the hero plus
// ½·R̄/(R̄ + T̄) over the carried wavelengths (R̄, T̄ their means), lobe 1 likewise with T: a film whose
// reflectance is dark at the hero and bright at a companion still reflects often (no fireflies),
// and no weight exceeds twice that of either rule alone. For a surface whose R and T vary little
// with λ a sample's weight is ≈ R + T (1 for a lossless surface); the rest, 1 − R − T, is absorbed
// by the substrate or the layers.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>

#include "core/render/material.h"
#include "core/render/registry.h"
#include "materials/smooth_surface.h"

namespace phasor {

class SmoothKernel : public Material {
  public:
    /// `transmits`: a refraction lobe into the substrate and the substrate side below (see above);
    /// the substrate must then have κ = 0 (IsTransparent).
    SmoothKernel(SmoothSurface surface, bool transmits);

    /// Lists lobe 0 (reflection: the mirror direction on wi's side, weight R(λ)) and, for a
    /// transmitting surface, lobe 1 (Snell's law, weight T(λ)·(η_i/η_t)², not listed under total
    /// internal reflection at the hero); a lobe that carries nothing at every wavelength is not
    /// listed. EvalLobe: the Jones / Mueller response of lobe 0 or 1 towards its hero direction (see
    /// the top of the file) and, for a coated surface, its coherence terms. AngularBandwidth: the
    /// coating's LayerStackBandwidth (its fringes' rate in κ, theory §0 D15; bare: the Fresnel
    /// coefficients' branch points only), at the hero and scaled to the shortest carried wavelength.
    const PreparedKernel &Prepare(const ScatterQuery &q, ScratchBuffer &scratch) const override;
    /// A coated surface reports the coating's coherence terms (EvalLobe).
    bool HasCoherenceTerms() const override { return surface_.LayerCount() > 0; }
    /// The plane-wave optics, a coating over a substrate (materials/smooth_surface.h): what
    /// `grating` and `harvey_shack` multiply their lobes by when they name this kernel as their
    /// `substrate` (ReadSubstrate).
    const SmoothSurface &Surface() const { return surface_; }
    bool Transmits() const { return transmits_; }
    /// A transmitting surface on a substrate of index 1 (a free-standing film, `substrate_ior = 1`):
    /// from the air, lobe 1 goes straight on.
    bool MayPassStraight() const override { return passesStraight_; }

  protected:
    /// "Name[ substrate = …, coating = …, transmits|opaque ]" for ToString.
    std::string Describe(const std::string &name) const;

  private:
    class Prepared;
    /// One carried wavelength of a query: the indices on wi's side and the far side, and the
    /// unpolarised R and T of the query's regime (coherent, or incoherent for rayOptics).
    struct Wave {
        bool ok = false;  // false: no valid index data here (the path is absorbed)
        Complex substrate;  // the substrate's index at λ
        double nI = 1, nT = 1, eta = 1;
        double R = 0, T = 0;
    };
    /// With the layers' thicknesses at the hit (SmoothSurface::Thicknesses).
    Wave Evaluate(const ScatterQuery &q, int i, const double *thickness) const;
    /// Evaluate without R and T: only the indices (ok: the substrate has index data at λ).
    Wave Sides(const ScatterQuery &q, int i) const;
    /// From the substrate side: a transmitting surface hit from below.
    bool FromInside(const ScatterQuery &q) const { return transmits_ && q.wi.z < 0; }

    SmoothSurface surface_;
    bool transmits_ = false;
    bool dispersive_ = false;  // the refraction lobe's direction varies with λ
    bool passesStraight_ = false;  // MayPassStraight
};

/// True if the index has κ = 0 over 360–1000 nm (the band GetComplexSpectrum checks): a substrate
/// a SmoothKernel can transmit into.
bool IsTransparent(const ComplexSpectrum &ior);

/// The `coating` parameter of a kernel with a smooth substrate (conductor, dielectric; the grating
/// and rough kernels take one the same way): a reference to a `thin_film` or `multilayer`
/// definition, whose layers go on the kernel's own substrate. Absent: a bare surface.
ParamSpec CoatingSpec();
/// Reads `coating` (nullptr if absent): the layers of the CoatingKernel it names. Throws
/// phasor::Error at the parameter if it names something that is not a coating definition (naming
/// what it is) or a definition that sets its own `substrate_ior` (the host's index is the substrate).
std::shared_ptr<const Coating> ReadCoating(const ParamDict &dict, BuildContext &ctx);
/// Reads `substrate` (required; `grating`, `harvey_shack`): the smooth kernel it names. Throws
/// phasor::Error at the parameter if it names another kind of kernel (naming what it is).
std::shared_ptr<const SmoothKernel> ReadSubstrate(const ParamDict &dict, BuildContext &ctx);

/// The thickest a layer stack is taken to be coherent: above it the model is far outside its range
/// (docs/kernels.md "Layer stacks": thinner than the light's coherence length) and a definition
/// gets a warning (WarnIfBeyondCoherence).
inline constexpr double MaxCoherentStack = 1e-3;  // [m]
/// Warns at `param` of `dict` when the stack's largest total thickness exceeds MaxCoherentStack.
void WarnIfBeyondCoherence(const Coating &coating, const ParamDict &dict, const std::string &param,
                           BuildContext &ctx);

/// A smooth kernel that is a coating definition over its own substrate (`thin_film`,
/// `multilayer`): usable as a surface on its own and, through Layers (ReadCoating), as another
/// kernel's `coating`. Transmits when `substrate_ior` is transparent.
class CoatingKernel : public SmoothKernel {
  public:
    CoatingKernel(std::shared_ptr<const ComplexSpectrum> substrate, std::shared_ptr<const Coating> coating)
        : SmoothKernel(SmoothSurface(substrate, 0, coating), IsTransparent(*substrate)), coating_(std::move(coating)) {}
    /// The layers, which `coating = @name` puts on another kernel's substrate.
    const std::shared_ptr<const Coating> &Layers() const { return coating_; }

    /// The `substrate_ior` parameter both definitions share (default 1: a free-standing film).
    static ParamSpec SubstrateSpec();

  private:
    std::shared_ptr<const Coating> coating_;
};

}  // namespace phasor
