// SPDX-License-Identifier: Apache-2.0
// phasor — the generalized ray (GR): a mean ray plus an isotropic Gaussian phase-space footprint
// (β², ρ) per transverse axis (theory §1, §0 D1), its ABCD evolution (§1.6, D3), its wave function
// on a plane (§1.3, §6.3 oblique cut) and the closed-form phase-space overlaps with source WDFs
// (Eq. 24, theory §2.4). Everything is double precision; lengths in metres, k in rad/m.
//
// Conventions (docs/generalized_rays.md):
//   * (r, k) transverse coordinates in the GR's own frame (⊥ to its mean direction d); per axis the
//     covariance is Σ = ½[[β², ρ], [ρ, (1+ρ²)/β²]] (det Σ = ¼, a pure state).
//   * ρ > 0 means diverging along d. A backward tracer propagates along its tracing direction
//     (ρ grows); the *physical* field is the time reverse (d → −d, ρ → −ρ, ψ → ψ*), D3.
//   * Measurements (Eq. 24) take the physical GR: d is the direction in which light flows.
#pragma once

#include <array>

#include "core/math.h"
#include "core/geometry/shape.h"
#include "core/spectrum/spectrum.h"

namespace phasor {

/// A ray-transfer matrix acting on one transverse axis in (r, k) coordinates (theory §1.6):
/// (r, k) ← (A r + B k, C r + D k). det = 1 for every lossless element.
struct Abcd {
    double a = 1, b = 0, c = 0, d = 1;
    /// Free space over a distance z [m] in a medium of wavenumber k: B = z̄ = z/k (S6.3).
    static Abcd FreeSpace(double z, double k) { return {1, z / k, 0, 1}; }
    /// Thin lens of focal length f [m] (f > 0 converging): C = −k/f.
    static Abcd ThinLens(double f, double k) { return {1, 0, -k / f, 1}; }
    /// Spherical mirror of radius R [m] (R > 0 concave, focusing): a thin lens with f = R/2.
    static Abcd CurvedMirror(double radius, double k) { return ThinLens(0.5 * radius, k); }
    /// Spherical refracting interface of radius R [m] (R > 0: centre of curvature on the far side)
    /// from wavenumber k1 to k2. In (r, θ) it is [[1, 0], [(n₁−n₂)/(R n₂), n₁/n₂]]; with k⊥ = kθ
    /// this is [[1, 0], [(k₁−k₂)/R, 1]] (transverse wavevector conserved plus a lens term).
    static Abcd CurvedInterface(double radius, double k1, double k2) { return {1, 0, (k1 - k2) / radius, 1}; }
    /// Matrix product: (this * o) applies o first.
    Abcd operator*(const Abcd &o) const {
        return {a * o.a + b * o.c, a * o.b + b * o.d, c * o.a + d * o.c, c * o.b + d * o.d};
    }
    double Det() const { return a * d - b * c; }
};

/// Per-axis covariance of a GR in (r, k): rr = Var r, rk = Cov(r, k), kk = Var k (theory §1.2).
struct GrCovariance {
    double rr = 0, rk = 0, kk = 0;
    /// Σ = ½[[β², ρ], [ρ, (1+ρ²)/β²]].
    static GrCovariance FromBetaRho(double beta2, double rho) {
        return {0.5 * beta2, 0.5 * rho, 0.5 * (1 + rho * rho) / beta2};
    }
    double Beta2() const { return 2 * rr; }
    double Rho() const { return 2 * rk; }
    double Det() const { return rr * kk - rk * rk; }
    /// Σ ← T Σ Tᵀ.
    GrCovariance Transformed(const Abcd &t) const;
    GrCovariance operator+(const GrCovariance &o) const { return {rr + o.rr, rk + o.rk, kk + o.kk}; }
};

/// One generalized ray at one wavelength (theory §1.7).
struct GenRay {
    Vec3 o;            // mean position r0 [m]
    Vec3 d{0, 0, 1};   // unit mean direction; k0 = k·d
    double k = 0;      // wavenumber in the current medium, 2πη/λ [rad/m]
    double beta2 = 0;  // β² [m²]
    double rho = 0;    // correlation (curvature) parameter, dimensionless

    /// σ_r² = β²/2 per transverse axis [m²] (theory §1.2).
    double SigmaR2() const { return 0.5 * beta2; }
    /// σ_k² = (1+ρ²)/(2β²) per transverse axis [rad²/m²]; invariant in free space.
    double SigmaK2() const { return 0.5 * (1 + rho * rho) / beta2; }
    /// Angular variance of the propagation direction per axis, σ_k²/k² [rad²].
    double AngularVariance() const { return SigmaK2() / (k * k); }
    GrCovariance Covariance() const { return GrCovariance::FromBetaRho(beta2, rho); }
    Ray MeanRay() const { return Ray{o, d}; }
    /// The GR's own transverse frame: (s, t) span the plane ⊥ d, n = d.
    Frame TransverseFrame() const { return Frame::FromNormal(d); }

    /// Free-space propagation by z [m] along d (supplement S6.3, theory §1.6):
    /// β² ← β² + z̄(2ρ + z̄(1+ρ²)/β²), ρ ← ρ + z̄(1+ρ²)/β², z̄ = z/k; r0 ← r0 + z d.
    void Propagate(double z);
    /// Applies a transfer matrix to the footprint (Σ ← TΣTᵀ); the mean ray is unchanged.
    void Apply(const Abcd &t);
    /// Reflection/refraction at a smooth flat interface (S6.4): new mean direction and wavenumber,
    /// β and ρ kept.
    void Redirect(const Vec3 &newDirection, double newK) {
        d = newDirection;
        k = newK;
    }
    /// Time reversal (D3): d → −d, ρ → −ρ (the complex-conjugate wave function). An involution.
    GenRay TimeReversed() const { return GenRay{o, -d, k, beta2, -rho}; }

    /// Wave function ψ (theory §1.3) at a point x near the transverse plane through o:
    /// (πβ²)^{-1/2}·e^{ik d·Δ}·e^{−(1−iρ)|Δ⊥|²/(2β²)}, Δ = x − o (paraxial: no evolution along d).
    /// Unit norm over the transverse plane.
    Complex WaveFunction(const Vec3 &x) const;
    /// ψ on the plane through o with unit normal n (the oblique cut, theory §6.3 step 3): the
    /// transverse profile at the projected offset, the carrier e^{ik d·Δ}, and √|d·n| so that
    /// ∫_plane |ψ|² dA = 1. Zero if d ∥ plane.
    Complex OnPlane(const Vec3 &x, const Vec3 &n) const;
    /// The physical field on the plane: the time reverse of the traced GR, i.e. conj(OnPlane).
    Complex PhysicalOnPlane(const Vec3 &x, const Vec3 &n) const { return std::conj(OnPlane(x, n)); }

    /// The phase-space density g(r, k) (theory §1.2) at transverse offsets (Δr, Δk) in the own
    /// frame: π⁻²·exp(−|Δr|²/β² − |βΔk − (ρ/β)Δr|²). Integrates to 1 over d²r d²k.
    double PhaseSpaceDensity(const Vec2 &dr, const Vec2 &dk) const;
};

/// The detection state of a sensor-plane pixel that a GR stands for while it travels straight
/// from the sensor (docs/narrow_pixels.md, theory §0 D2, D16): the Gabor state
/// ψ(δ) = (πβ²)^{−1/2}·e^{−|δ|²/(2β²)}·e^{−ik u·δ} on the sensor plane (δ = offset from `centre`
/// in the plane), whose label u — the traced direction's sensor-plane direction cosines for a
/// state inside the propagating disc — may lie outside the unit disc: such a state has no mean
/// ray, yet the propagating part of its angular spectrum still detects light. Summed over all
/// labels u ∈ ℝ² with weight d²κ/(2π)² = d²u/λ², these states measure exactly the flux weighted
/// by the pixel's Gaussian N(0, β²/2) — what `rs` computes — whatever the pixel's size. Footprint-
/// aware kernels evaluate such a state's field non-paraxially (materials/aperture_integral.h,
/// PixelWavelet); a GR loses it at its first interaction (Redirect).
struct PixelState {
    bool valid = false;
    Vec3 centre;       // the pixel state's centre on the sensor plane (world) [m]
    Frame frame;       // s, t span the sensor plane; n = its front normal (towards the scene)
    double beta2 = 0;  // β_D² = 2σ_pix² [m²], the same for every wavelength
    Vec2 label;        // u (dimensionless); the transverse wavevector of the light it detects is −k·u
    /// The GR's mean ray is not along the label (a label outside the propagating disc, or one
    /// whose own ray misses the aperture plate the sensor aims at): it only aims the state at the
    /// plate, and only a footprint-aware kernel may measure it.
    bool labelOnly = false;
    bool LabelOnly() const { return valid && labelOnly; }
};

/// The wavelengths a path carries share one mean ray; each has its own footprint (for a camera
/// β ∝ λ, for a sensor plane σ_k/k ∝ λ). Used by the `grt` integrator.
struct SpectralGenRay {
    Vec3 o, d;
    int count = 1;  // wavelengths in use (SampledWavelengths::Count())
    std::array<double, NumWavelengths> k{}, beta2{}, rho{};
    PixelState pixel;  // set by a sensor plane; cleared by Redirect (see PixelState)
    /// The wavelength slots (bit i: slot i) whose closed-form measurement a caller uses: a GR along
    /// one wavelength's direction of a dispersive lobe needs only that one (set in grt's
    /// ThroughListedLobes on a GR made for that measurement). Measurements leave the others 0
    /// (MeasurePerWavelength; DistantDiscOutOfReach ignores them). Copies, Redirect, Propagate and
    /// TimeReversed keep it.
    unsigned measured = ~0u;
    bool Measures(int i) const { return (measured >> i) & 1u; }

    GenRay At(int i) const { return GenRay{o, d, k[i], beta2[i], rho[i]}; }
    Ray MeanRay() const { return Ray{o, d}; }
    void Propagate(double z);
    /// New mean direction; every wavenumber scaled by etaRatio (= η_new/η_old; 1 on reflection).
    /// The GR no longer stands for a sensor pixel's state (pixel.valid = false).
    void Redirect(const Vec3 &newDirection, double etaRatio);
    SpectralGenRay TimeReversed() const;
};

// ---- Coherent TEM₀₀ Gaussian beams (the `gaussian_beam` light, theory §2.2) ---------------------

/// A Gaussian beam by its geometry: waist centre, unit axis (direction of travel) and β_s² of the
/// waist [m²] (w₀ = √2·β_s, the 1/e² intensity radius). For wavenumber k, with z = axis·(p − waist),
/// r = the distance of p from the axis, z_R = kβ_s² and q = z − i·z_R, the field of a beam of unit
/// power is (paraxial; Siegman, "Lasers", §17.1, in the GR convention of theory §1.3)
///     ψ(p) = (πβ_s²)^{−1/2}·(q(0)/q(z))·exp(ik z + ik r²/(2q(z))),
/// so |ψ|² = exp(−r²/β²(z))/(πβ²(z)), β²(z) = β_s²(1 + (z/z_R)²), and the wavefront diverges for
/// z > 0 (e^{ikr} convention of a spherical wave).
struct GaussianBeamGeometry {
    Vec3 waist;
    Vec3 axis{0, 0, 1};
    double beta2 = 0;  // β_s² [m²]

    /// z = axis·(p − waist) [m].
    double Axial(const Vec3 &p) const { return Dot(p - waist, axis); }
    /// q(z) = z − i·kβ_s² [m].
    Complex Q(double z, double k) const { return Complex(z, -k * beta2); }
    /// β²(z) = β_s²(1 + (z/z_R)²) [m²].
    double Beta2At(double z, double k) const;
    /// ψ(p) of a unit-power beam [1/m] (above), with the phase k·zRef removed (only relative phases
    /// matter; keeps the argument small far from the waist).
    Complex Field(const Vec3 &p, double k, double zRef = 0) const;
};

/// The angular profile of the plane waves a closed-form measurement integrates, about its central
/// direction (theory §0 D14, D15), in direction cosines transverse to that direction: what a lobe's
/// efficiency is averaged over (core/render/lobe_average.h).
///   * Delta: one direction (a plane wave, a point or spot light; a Gaussian beam whose local
///     spread the measurement's own window already holds);
///   * Disc: uniform over a disc of radius `radius` = sin α (a `distant` disc);
///   * Gaussian: N(0, variance·I) (a `distant` Gaussian; a Gaussian beam's local spectrum).
/// `windowed`: the profile already includes the measuring GR's angular window (a beam's overlap
/// with the GR, a product of Gaussians), which must not be applied again.
struct AngularProfile {
    enum class Kind { Delta, Disc, Gaussian };
    Kind kind = Kind::Delta;
    double radius = 0;    // Disc [direction cosine]
    double variance = 0;  // Gaussian, per axis [rad²]
    bool windowed = false;
    /// The profile's centre as a unit direction of travel (world), if it is not the measurement's
    /// own central direction (a beam's overlap with a GR peaks between their axes); zero: that one.
    Vec3 centre;
    /// A light of finite cross-section (a beam): each plane wave's whole power crosses a surface
    /// wider than it, with the obliquity of its own direction (lobe_average.h, LobeTransfer). False
    /// for lights that fill the surface (plane waves, distant sources).
    bool localized = false;
    static AngularProfile Disc(double r) { return {Kind::Disc, r, 0, false, Vec3(), false}; }
    static AngularProfile Gaussian(double v, bool windowed = false) {
        return {Kind::Gaussian, 0, v, windowed, Vec3(), false};
    }
};

// ---- Closed-form measurements (Eq. 24, theory §2.4) ------------------------------------------
// `g` is always the *physical* GR (d = direction of light flow, ρ > 0 diverging along it). The
// returned M is the phase-space overlap ∫∫ 𝒲_s g in the source's units times m² (M = L/k² for a
// thermal emitter); multiply by k² for the camera's radiance units (theory §0 D4).

/// Density of the isotropic bivariate normal N₂(x; 0, var·I) at |x|² = r2.
inline double Normal2(double r2, double var) { return std::exp(-0.5 * r2 / var) / (2 * Pi * var); }
/// Transverse part of k·s in g's own frame (|·| = k sin∠(s, d)); zero vector if s·d ≤ 0.
Vec2 TransverseWavevector(const GenRay &g, const Vec3 &s);
/// Item 2: a coherent plane wave of irradiance E (normal to its direction s):
/// M = E·β²/(π(1+ρ²))·exp(−β²|k_s⊥|²/(1+ρ²)). 0 if s points against g.
double MeasurePlaneWave(const GenRay &g, const Vec3 &s, double irradiance);
/// Item 3: a distant source with a Gaussian angular profile of covariance omega·I [rad²]:
/// M = E·N₂(k_s⊥; 0, σ_k²I + k²Ω).
double MeasureDistantGaussian(const GenRay &g, const Vec3 &s, double irradiance, double omega);
/// A distant source of uniform radiance over a cone of half-angle alpha (a disc, e.g. the sun):
/// 𝒲_s = E/(πk²sin²α) on the disc |k⊥ − k_s⊥| < k sinα, so M = E/(πk²sin²α)·P(disc) with P the
/// mass of N₂(0, σ_k²I) in that disc (Rice distribution). Takes sinα (callers measuring one light
/// at many GRs compute it once); sinα = 0 gives the plane wave.
double MeasureDistantDisc(const GenRay &g, const Vec3 &s, double irradiance, double sinAlpha);
/// True only if MeasureDistantDisc(g.At(i), s, ·, sinAlpha) is exactly 0 at every wavelength g
/// measures (conservative: false may still mean 0): a disc (sinAlpha > 0) whose edge lies more than
/// RiceReach angular standard deviations of each window beyond g.d. One test instead of a
/// transverse frame and an overlap per wavelength (most GRs see none of a small disc).
bool DistantDiscOutOfReach(const SpectralGenRay &g, const Vec3 &s, double sinAlpha);
/// Item 5: an isotropic point source of intensity I [W/sr] at p (coherent spherical wave):
/// M = (I/R²)·exp(−β²|κ|²/(1+a²β²))/(π(β⁻²+a²)), κ = k(r0−p)⊥/R, a = βk/R − ρ/β.
double MeasurePointSource(const GenRay &g, const Vec3 &p, double intensity);
/// A Gaussian (Schell-model) beam source: power P, its own GR-like state `beam` (mean ray along
/// the light flow, footprint at beam.o). Item 1 per axis in g's frame:
/// M = P·Π_axes N₂(Δu; 0, Σ_g + Σ_s), evaluated in the plane ⊥ g.d through g.o (the beam is
/// propagated to that plane along its axis; paraxial, axes nearly parallel).
double MeasureGaussianBeam(const GenRay &g, const GenRay &beam, double power);
/// The plane waves the overlap of MeasureGaussianBeam integrates (theory §0 D15): the wave-vector
/// marginal of the product of the two phase-space Gaussians, per axis Σ = (Σ_g⁻¹ + Σ_s⁻¹)⁻¹ with its
/// mean, as a windowed Gaussian profile (variance Σ_kk/k², centre the mean's direction of travel).
AngularProfile GaussianBeamOverlapProfile(const GenRay &g, const GenRay &beam);
/// The plane waves a sensor-plane GR g integrating a beam over all its directions (D4a) sees at g.o:
/// the beam's wave vectors there weighted by the GR's spatial footprint — per axis a Gaussian of
/// variance [1/(2β²) + ρ²β_g²/(2β²(β² + β_g²))]/k² (β, ρ the beam's at g's axial position) about the
/// direction `local` (the beam's local wavefront normal). Not windowed (the detector integrates the
/// GR's own spread out).
AngularProfile GaussianBeamIncidenceProfile(const GenRay &g, const GenRay &beamAtG);

// ---- What closed-form sources deliver to a GR (used by lights, detectors and `grt`) ------------

/// Eq. 24 for one physical GR (per carried wavelength) in radiance units, k²·M (theory §0 D4), and
/// where the source is seen from the GR's origin (for the visibility test).
struct GrMeasurement {
    SampledSpectrum value;   // k²·M [W/m²/sr per spectral unit of the light's spectrum]
    Vec3 wi;                 // unit direction from the GR's origin towards the source
    double dist = Infinity;  // distance to the source (Infinity for sources at infinity)
    /// The plane waves M integrates, about −wi's direction of travel (the hero's; see AngularProfile).
    AngularProfile profile;
};

/// D4a: a closed-form source integrated over every direction of a GR at its waist,
/// ∫d²k⊥ M[g(k⊥)] in the GR's own transverse frame (≈ the irradiance normal to wi, smoothed by the
/// GR's spatial footprint where the source varies in space). A sensor multiplies by cosθ and by
/// the fraction of the directions that its acceptance cone keeps.
struct GrIncidence {
    SampledSpectrum irradiance;  // [W/m² per spectral unit]
    Vec3 wi;                     // unit mean direction towards the source
    double dist = Infinity;
    double angularVariance = 0;  // per-axis variance of the arrival direction about wi [rad²]
    /// The source's own angular profile about wi (without the GR's spread, which the detector
    /// integrates out): what a lobe's efficiency is averaged over (D15).
    AngularProfile profile;
};

/// P(|X| ≤ radius) for X ~ N₂(μ, σ²I) with |μ| = offset (the Rice CDF, i.e. 1 − Marcum Q₁):
/// RiceCdf(offset/σ, radius/σ) (core/numerics/rice.h: Marcum's Bessel series or a Poisson-mixture
/// series, relative error ≤ 2e-12 by a proven bound; 0 or 1 where offset and radius differ by ≥ 11σ;
/// a quadrature accurate to ~1e-12 absolute beyond offset·radius ≈ 39 000σ²). sigma = 0 gives the
/// indicator.
double DiscGaussianProbability(double offset, double radius, double sigma);
/// P(X ∈ [lo.x, hi.x] × [lo.y, hi.y]) for X ~ N₂(μ, σ²I).
double RectGaussianProbability(const Vec2 &mu, double sigma, const Vec2 &lo, const Vec2 &hi);

}  // namespace phasor
