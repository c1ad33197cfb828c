// SPDX-License-Identifier: Apache-2.0
// phasor — the free-space diffraction lobe of one event (theory §4.8, docs/fsd.md §4): the
// generalized ray's wave function on the event plane, cut by the shadow of the local geometry,
// overlapped with the incident wave — the aperture kernel's integral (theory §9) with the mask
// made of the scene's own edges:
//     A(s) = (πβ²)^{−1/2} ∫_open exp(−(1−iρ)|x|²/(2β²)) · U_inc(x) d²x,
// evaluated per carried wavelength with its own k, β², ρ, over the open trapezoids of the box or,
// when that is shorter, as the box minus the covered ones (Babinet); one axis in closed form
// (Faddeeva), the other by Gauss–Legendre (materials/aperture_integral.h). As a density per
// steradian for light arriving along −wo (the event plane's normal is the GR's direction d):
//     f(wo) = |A(s = −wo)|² / (λ²·(wo·d)),
// so that next-event estimation f·(wo·d)·E gives the radiance E·|A|²/λ², an unobstructed GR passes
// radiance unchanged and ∫ f·(wo·d) dω = ∫_open |ψ|² ≤ 1 (Parseval): FSD never creates light.
// The GR leaving an event is spread-free (theory §9 item 5).
#pragma once

#include <optional>
#include <vector>

#include "core/render/material.h"
#include "integrators/fsd/fsd_geometry.h"

namespace phasor::fsd {

/// A direction drawn from the FSD lobe: world direction, f·(wo·d)/pdf per wavelength, solid-angle pdf.
struct LobeSample {
    Vec3 wo;
    SampledSpectrum weight;
    double pdf = 0;
};

/// The FSD lobe of an event for the GR that arrives there.
class Lobe {
  public:
    /// `g`: the GR at the event (traced direction d = ev.frame.n; per-wavelength k, β², ρ there).
    Lobe(const Event &ev, const SpectralGenRay &g, const SampledWavelengths &wl, const Settings &s);

    /// f(wo) [1/sr] per carried wavelength for light arriving along −wo as the wave `w` (a plane
    /// wave, a spherical wave from distance w.dist, or a Gaussian beam per unit on-axis irradiance,
    /// as Material::EvalFrom). 0 for wo·d ≤ 0 (only transmission through the event plane).
    SampledSpectrum Eval(const Vec3 &wo, const IncidentWave &w = {}) const;
    /// Solid-angle density of Sample at wo.
    double Pdf(const Vec3 &wo) const;
    /// A direction from the proxy (below), with weight Eval(wo)·(wo·d)/pdf. nullopt for an
    /// evanescent draw.
    std::optional<LobeSample> Sample(double u0, const Vec2 &u) const;
    /// The direction of Sample alone (no Eval: the proxy is cheap, the amplitude is not).
    std::optional<Vec3> SampleDirection(double u0, const Vec2 &u) const;

    /// The amplitude A(s) of carried wavelength i (tests).
    Complex Amplitude(int i, const Vec3 &s, const IncidentWave &w = {}) const;

  private:
    // The sampling proxy (hero wavelength) in the plane's transverse wavevector q [rad/m]: the
    // GR's own angular Gaussian about straight through, one lobe per edge in the footprint
    // (Gaussian along the edge, Cauchy across it: an edge diffracts with |A|² ∝ 1/q² across,
    // centred on the GR's local wavevector at the edge), and a cosine lobe on the far side.
    struct EdgeLobe {
        Vec2 c, t, m;  // centre [rad/m], unit tangent and normal
        double prob;
    };
    double ProxyPdfQ(const Vec2 &q) const;

    const Event &ev_;
    const SampledWavelengths &wl_;
    int count_ = 0;
    std::array<double, NumWavelengths> k_{}, beta2_{}, rho_{}, window_{};
    bool babinet_ = false;  // integrate the box minus the covered trapezoids
    double k0_ = 0, sigmaF_ = 0, gamma_ = 0;
    double probForward_ = 0, probEdges_ = 0, probCosine_ = 0;
    std::vector<EdgeLobe> edges_;
};

/// Draws a point of the event's covered region (plane coordinates) with density ∝ the hero's
/// |ψ|² restricted to it, relative to coveredFraction: `weight` = |ψ|²(x)·coveredFraction /
/// (coveredFraction · density(x)), ≈ 1 (exactly 1 for exact trapezoid masses). nullopt if there
/// is no covered mass.
std::optional<Vec2> SampleCovered(const Event &ev, double u0, const Vec2 &u, double *weight);

}  // namespace phasor::fsd
