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
// Sampling (Material's default SampleLobes): lobe 0 with probability ½·R/(R + T) at the hero plus
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

    unsigned Capabilities(const ScatterQuery &) const override { return CapNearDelta; }
    /// Lobe 0 (reflection: the mirror direction on wi's side, weight R(λ)) and, for a transmitting
    /// surface, lobe 1 (Snell's law, weight T(λ)·(η_i/η_t)², not listed under total internal
    /// reflection at the hero). A lobe that carries nothing at every wavelength is not listed.
    void ListNearDelta(const ScatterQuery &q, NearDeltaLobes &out) const override;
    /// The Jones / Mueller response of lobe 0 or 1 towards its hero direction (see the top of the
    /// file) and, for a coated surface, its coherence terms.
    std::optional<LobeResponse> EvalLobe(const ScatterQuery &q, int lobe, const Vec3 &wo) const override;
    const SmoothSurface *Surface() const override { return &surface_; }
    /// A coated surface reports the coating's coherence terms (EvalLobe).
    bool HasCoherenceTerms() const override { return surface_.LayerCount() > 0; }
    bool Transmits() const { return transmits_; }

  protected:
    /// "Name[ substrate = …, coating = …, transmits|opaque ]" for ToString.
    std::string Describe(const std::string &name) const;
    /// Picks lobe 0 or 1 ∝ its probability (ListNearDelta's lobes, without building a full list).
    std::optional<ScatterSample> SampleLobes(const ScatterQuery &q, double u0, const Vec2 &u) const override;

  private:
    /// The (at most two) lobes of a query, as ListNearDelta lists them; returns their count.
    int Lobes(const ScatterQuery &q, std::array<NearDeltaLobe, 2> &out) const;
    /// One carried wavelength of a query: the indices on wi's side and the far side, and the
    /// unpolarised R and T of the query's regime (coherent, or incoherent for rayOptics).
    struct Wave {
        bool ok = false;  // false: no valid index data here (the path is absorbed)
        Complex substrate;  // the substrate's index at λ
        double nI = 1, nT = 1, eta = 1;
        double R = 0, T = 0;
    };
    Wave Evaluate(const ScatterQuery &q, int i) const;
    /// Evaluate without R and T: only the indices (ok: the substrate has index data at λ).
    Wave Sides(const ScatterQuery &q, int i) const;
    /// From the substrate side: a transmitting surface hit from below.
    bool FromInside(const ScatterQuery &q) const { return transmits_ && q.wi.z < 0; }

    SmoothSurface surface_;
    bool transmits_ = false;
    bool dispersive_ = false;  // the refraction lobe's direction varies with λ
};

/// True if the index has κ = 0 over 360–1000 nm (the band GetComplexSpectrum checks): a substrate
/// a SmoothKernel can transmit into.
bool IsTransparent(const ComplexSpectrum &ior);

/// The `coating` parameter of a kernel with a smooth substrate (conductor, dielectric; the grating
/// and rough kernels take one the same way): a reference to a `thin_film` or `multilayer`
/// definition, whose layers go on the kernel's own substrate. Absent: a bare surface.
ParamSpec CoatingSpec();
/// Reads `coating` (nullptr if absent). Throws phasor::Error at the parameter if it names
/// something that is not a coating definition (naming what it is) or a definition that sets its
/// own `substrate_ior` (the host's index is the substrate).
std::shared_ptr<const Coating> ReadCoating(const ParamDict &dict, BuildContext &ctx);

/// A smooth kernel that is a coating definition over its own substrate (`thin_film`,
/// `multilayer`): usable as a surface on its own and, through AsCoating, as another kernel's
/// `coating`. Transmits when `substrate_ior` is transparent.
class CoatingKernel : public SmoothKernel {
  public:
    CoatingKernel(std::shared_ptr<const ComplexSpectrum> substrate, std::shared_ptr<const Coating> coating)
        : SmoothKernel(SmoothSurface(substrate, 0, coating), IsTransparent(*substrate)), coating_(std::move(coating)) {}
    std::shared_ptr<const Coating> AsCoating() const override { return coating_; }

    /// The `substrate_ior` parameter both definitions share (default 1: a free-standing film).
    static ParamSpec SubstrateSpec();

  private:
    std::shared_ptr<const Coating> coating_;
};

}  // namespace phasor
