// SPDX-License-Identifier: Apache-2.0
// phasor — a generalized ray's response is its angular-spectrum average (theory §0 D15).
//
// A GR is a Gaussian beam: by Parseval the power it carries through a near-delta lobe is
// ∫ a_j(k)·|A(k)|² d²k — the lobe's efficiency averaged over the GR's angular spectrum
// N(k⊥; k̄⊥, σ_k²I) — and at a closed-form measurement of a light (D4a, D14) over the product of
// that spectrum with the light's angular profile (the overlap the measurement computes). A film's
// efficiency oscillates with the direction at 2k₀·d·tanθ_f per unit of sinθ: a 10 µm film runs
// through a fringe within 1–2°, so its value at the mean direction can be anything between the
// fringe's extremes under a 2° source. This file averages a listed lobe's efficiency (and, for
// `sample_solve`, its Mueller matrix) over such an ensemble:
//
//   ⟨a_j⟩ = ∫ a_j(ω)·P(u)·W(u) d²u / ∫ P(u)·W(u) d²u,
//
// u the direction cosines of the light's arrival direction ω transverse to the profile's centre,
// P the light's profile (a point, a uniform disc of radius sin α, a Gaussian; AngularProfile) and
// W the measuring GR's window, an isotropic Gaussian of variance σ_k²/k² about its mean direction
// (taken in the same coordinates: its anisotropy there, 1 − cos ε for an axis ε away from the
// profile's, changes ⟨a_j⟩ at O(ε²) of a_j's variation). The integral is the quadrature of
// core/numerics/ensemble_quadrature.h, with node counts from the prepared kernel's AngularBandwidth (its
// remainder bounds hold for the band-limited model stated there) at a tolerance of 1e-5 of sup a_j.
// At each node the kernel is asked for the lobe at the query direction wi′ whose lobe j points at ω
// (the vector grating equation inverted: n_in·wi′.xy = −n_out·ω.xy + shift·λ/2π), so every kernel
// — films, stacks, coatings on any substrate, grating orders through J_j(m(θ))² and F(θ), the
// specular lobe of a rough surface — is averaged the same way.
//
// Where: every closed-form measurement through a listed lobe — D14 at a path vertex (the light's
// profile times the outgoing GR's spectrum) and D4a through lobes at a sensor plane (the profile
// alone, weighted by the lobe's irradiance transfer; the sensor integrates the GR's spectrum out).
// A *sampled* lobe keeps its weight at the GR's mean direction: what follows it is measured by the
// mean ray (an emitter, an escape, NEE after a continuous lobe), and the detector's own direction
// sampling integrates the GR's spectrum over that product — averaging the lobe again would smooth it
// twice (an area lamp seen in a 10 µm film through a sensor plane read 10 % low that way).
//
// Cost: one rule per ensemble and distinct wavelength footprint, and one kernel evaluation per node —
// the lobe's weight alone where the prepared kernel answers PreparedKernel::LobeWeightAt (the smooth
// kernels, grating, mix, two_sided: one order of a grating instead of its whole listing, the hit's
// textures not evaluated again), else the material prepared again for the node's direction. An
// ensemble whose spread meets the bound with one node (a camera pixel's ~1e-4 rad spectrum on a
// film of a few µm) is evaluated at its mean: no extra kernel call when that is the lobe's own
// direction, one when it is a light's direction (a plane wave seen through D14). A thick film under
// a wide source takes tens to a few hundred nodes (LobeAverageCost counts them; docs/accuracy.md).
#pragma once

#include <array>
#include <optional>
#include <utility>

#include "core/render/genray.h"
#include "core/render/material.h"

namespace phasor {

/// The remainder bound of every average, relative to sup a_j (theory §0 D15); kernels' bandwidths
/// count the harmonics of their multiple reflections down to it.
inline constexpr double LobeAverageTolerance = 1e-4;

/// The factor that turns a bandwidth evaluated at the hero wavelength into a bound for every carried
/// wavelength: λ_hero/λ_min (phases scale as 1/λ) with 10 % for dispersion.
double HeroToShortest(const SampledWavelengths &wl);

/// The plane waves a lobe's efficiency is averaged over, per carried wavelength, in the local
/// shading frame of the hit. Directions are unit vectors pointing away from the surface towards the
/// light (a lobe's wo side).
struct LobeEnsemble {
    struct Wave {
        Vec3 source{0, 0, 1};     // the profile's centre: the light's central arrival direction
        AngularProfile profile;   // about `source` (Delta: the light's own direction only)
        Vec3 windowAxis{0, 0, 1};  // the measuring GR's mean direction along the lobe (towards the light)
        double windowVariance = Infinity;  // its σ_k²/k² [rad²]; Infinity: no window
        bool operator==(const Wave &o) const {
            return source == o.source && profile.kind == o.profile.kind && profile.radius == o.profile.radius &&
                   profile.variance == o.profile.variance && profile.windowed == o.profile.windowed &&
                   profile.localized == o.profile.localized &&
                   windowAxis == o.windowAxis && windowVariance == o.windowVariance;
        }
    };
    std::array<Wave, NumWavelengths> wave{};
};

/// A closed-form measurement of a light through listed lobe `lobe` (D14): the light's profile about
/// its arrival direction `toLight` (world, unit, towards the light; or about −profile.centre when
/// given) times the window of the GR leaving along the lobe (`g` as above; each wavelength's window
/// about lobe.wo[i]) unless the profile already includes it.
LobeEnsemble MeasurementEnsemble(const Frame &shading, const SpectralGenRay &g, const NearDeltaLobe &lobe,
                                 const Vec3 &toLight, const AngularProfile &profile);

/// A measurement that integrates the light's own profile only (a sensor plane's D4a through a
/// lobe, a shadow ray crossing a film towards a sensor): every wavelength's wave is the profile
/// about `toLight` (world, unit, towards the light), without a GR's window.
LobeEnsemble SourceEnsemble(const Frame &shading, const Vec3 &toLight, const AngularProfile &profile);

/// What is averaged.
enum class LobeTransfer {
    /// a_j: a radiance measurement through the lobe (D14) and a sampled lobe's weight.
    Radiance,
    /// a_j times the lobe's irradiance transfer |dω_o/dω_i|⁻¹ = (n_out/n_in)²·|cosθ_o|/|cosθ_i|
    /// (θ_o at the light's side), relative to its value at the ensemble's central direction: what a
    /// sensor plane integrating the light over its directions through the lobe collects (D4a through
    /// lobes), as a factor on the value at the centre — for a refraction, T·cosθ_i/cosθ_t per plane
    /// wave. For a localized profile (a beam) also the obliquity |cosθ_o|/|cosθ_o,centre| with which
    /// each plane wave's power crosses the surface (the sensor's pixels are mapped onto the surface
    /// along the central direction: summed over them, this is what they collect of each plane wave).
    Irradiance,
};

/// ⟨a_j⟩ of listed lobe `lobe` of `k` (kernel m prepared for the hit's query) over the ensemble, per
/// carried wavelength (only `wavelength` when ≥ 0; the others are 0). Equals lobe.Weight() where the
/// ensemble is a single direction along the lobe. Every node asks k.LobeWeightAt, or prepares m for
/// its own direction in a scratch buffer of this file's (k's buffer is not touched).
SampledSpectrum AverageLobeWeight(const Material &m, const PreparedKernel &k, const NearDeltaLobe &lobe,
                                  const LobeEnsemble &e, LobeTransfer transfer = LobeTransfer::Radiance,
                                  int wavelength = -1);

/// The Mueller matrix of listed lobe `lobeId` averaged over the ensemble (EvalLobe at every node,
/// towards the lobe's direction there), per carried wavelength: the partially coherent response a
/// `sample_solve` beam meets (per polarisation: the matrices are averaged, not their M00). Without
/// the coherence terms (the average is the response) and, when more than one node contributes,
/// without a Jones matrix (an average of Mueller matrices depolarises). nullopt if the lobe is not
/// listed by k. M00 equals AverageLobeWeight with the same transfer.
std::optional<LobeResponse> AverageLobeResponse(const Material &m, const PreparedKernel &k, int lobeId,
                                                const LobeEnsemble &e, LobeTransfer transfer = LobeTransfer::Radiance);

/// Cost counters of this thread (rules built, kernel evaluations), for benchmarks and tests.
struct LobeAverageCounters {
    long long averages = 0;     // AverageLobeWeight / AverageLobeResponse calls
    long long rules = 0;        // quadrature rules built (one per distinct wavelength ensemble)
    long long evaluations = 0;  // kernels prepared at nodes (for a lobe's weight or its EvalLobe)
    long long capped = 0;       // rules whose bound does not hold (EnsembleRuleInfo::capped)
};
LobeAverageCounters &LobeAverageCost();

/// A test hook: with `true`, every average returns the lobe's value at the ensemble's central
/// direction (the mean-direction evaluation this file replaces) — for showing that the tests of the
/// accuracy map fail without it. Per thread; off by default.
void SetLobeAverageDisabledForTesting(bool disabled);

/// A test hook: the rates (R_x, R_y) the rules of this file get for the ensemble coordinates about
/// `centre` (local, unit; the ensemble's frame) over the box [lo, hi], with nOut the index of the
/// light's medium: {sampled at 5×5 points, the cheap bound asked first (Infinity where it declines)}.
std::pair<Vec2, Vec2> LobeAverageRatesForTesting(const PreparedKernel &k, const Vec3 &centre, double nOut,
                                                 const Vec2 &lo, const Vec2 &hi);

}  // namespace phasor
