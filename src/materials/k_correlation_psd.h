// SPDX-License-Identifier: Apache-2.0
// phasor — the K-correlation ("ABC") surface-height power spectral density of the `harvey_shack`
// rough-surface kernel (theory §4.3, §0 D7), in the dimensionless form a kernel needs, and the
// Holzschuch–Pacanowski sampling quantities built on it.
//
// Units: with k = 2π·n/λ the wavenumber of the medium the light arrives in, the surface spatial
// frequency ζ [rad/m] is written ξ = ζ/k (a 2-vector of direction-cosine units), and the PSD's
// correlation parameter T [m²] enters only as the dimensionless t = k²T. The PSD normalised to unit
// integral over the plane of ξ is
//     p(ξ) = ((γ−1)·t/2π)·(1 + t|ξ|²)^{−(γ+1)/2},   γ > 1,
// (theory §4.3's p_PSD(ζ)·k²), whose radial CDF is P(|ξ| < r) = 1 − (1 + t r²)^{−(γ−1)/2}.
// A scattered direction ω_o exists (propagates) for ξ inside the *visible disc* |ξ − s·ê_i| ≤ 1,
// s = sinθ_i (ê_i the azimuth of wi's tangential part), so the lobe holds only the mass V(s, t)
// inside it — V = 0.96 / 0.88 / 0.49 at θ_i = 0 / 45 / 80° for α_r = 0.1 (D7).
// References: Church, Jenkinson & Zavada, Opt. Eng. 18 (1979) (K-correlation PSD); Holzschuch &
// Pacanowski, ACM TOG 36(4) 2017 (the sampling); theory §4.3.
#pragma once

#include <memory>
#include <vector>

namespace phasor {

/// The PSD and its sampling quantities for one exponent γ > 1.
class KCorrelationPsd {
  public:
    explicit KCorrelationPsd(double gamma) : gamma_(gamma) {}
    double Gamma() const { return gamma_; }

    /// p(ξ) for |ξ|² = r2: the PSD per unit ξ-area (unit integral over the plane).
    double Density(double t, double r2) const;
    /// P(|ξ| < r) = 1 − (1 + t r²)^{−(γ−1)/2} (accurate for small t·r², via log1p/expm1).
    double RadialCdf(double t, double r) const;
    /// The radius r with RadialCdf(t, r) = c, c ∈ [0, 1) (theory §4.3 sampling step 2).
    double InverseRadialCdf(double t, double c) const;

    /// Half-angle φ_max ∈ [0, π] of the arc of radius r about the origin that lies inside the
    /// visible disc |ξ − s·ê| ≤ 1 (centred at distance s ∈ [0, 1] from the origin), measured from
    /// ê: cosφ_max = (r² + s² − 1)/(2rs) (theory §4.3 sampling step 3); π where the whole circle is
    /// inside, 0 where none of it is.
    static double ArcHalfAngle(double r, double s);

    /// V(s, t): the PSD mass inside the visible disc, by direct quadrature. Written as
    ///     V = ∫₀^{M} φ_max(P⁻¹(c), s)/π dc,   M = RadialCdf(t, 1 + s)
    /// (the probability that the Holzschuch–Pacanowski radius falls on the visible arc), with the
    /// integrand = 1 below c₀ = RadialCdf(t, 1 − s) and a 64-point Gauss–Legendre rule over
    /// [c₀, M] after c = c₀ + (M − c₀)(1 − cos τ)/2, which removes the square-root endpoint
    /// behaviour of φ_max. The integrand is bounded by 1, so a feature narrower than the rule's
    /// node spacing (large t) costs at most its own width; measured against a 2-D brute-force
    /// quadrature in tests/materials/harvey_shack_test.cpp.
    double VisibleMass(double s, double t) const;

  private:
    double gamma_;
};

/// V(s, t) tabulated over x = √cosθ_i ∈ [0, 1] (nodes dense towards grazing, where V changes
/// over cosθ_i ~ t^{−1/4}) and ln t ∈ [ln TableTMin, ln TableTMax], interpolated bicubically
/// (Catmull–Rom); outside that t range it falls back to the direct quadrature. Interpolation
/// error (absolute; V ≤ 1) ≤ 2e-4 everywhere and ≤ 2e-5 for cosθ_i ≥ 0.05 (γ ≤ 8), measured against
/// VisibleMass at random points in tests/materials/harvey_shack_test.cpp (the worst case is near
/// grazing at t ~ 1e8). Built once per γ (~0.2 s) and shared (For).
class VisibleMassTable {
  public:
    static constexpr double TableTMin = 1e-4, TableTMax = 1e8;
    static constexpr int CosNodes = 193, LogTNodes = 169;

    explicit VisibleMassTable(double gamma);
    /// The table of exponent γ, built on first use and kept for the program's life (thread-safe).
    static std::shared_ptr<const VisibleMassTable> For(double gamma);

    const KCorrelationPsd &Psd() const { return psd_; }
    /// V at cosθ_i = cosTheta ∈ [0, 1] and t = k²T > 0.
    double Eval(double cosTheta, double t) const;

  private:
    double Node(int i, int j) const { return v_[std::size_t(j) * CosNodes + std::size_t(i)]; }
    KCorrelationPsd psd_;
    double logMin_, logStep_;
    std::vector<double> v_;  // [ln t][√cosθ]
};

}  // namespace phasor
