// SPDX-License-Identifier: Apache-2.0
// phasor — cylinder functions: the Hankel functions H₀⁽¹⁾, H₁⁽¹⁾ of the 2-D Rayleigh–Sommerfeld
// kernel (theory §6.2, `rs`) and the scaled modified Bessel function I₀ of the GR disc
// measurement (core/render/genray.h).
#pragma once

#include "core/math.h"

namespace phasor {

/// From this argument on, Hankel01 uses the asymptotic series (error < 1e-16 there).
constexpr double HankelAsymptoticMin = 25;

/// The slowly varying factors P_ν(x) = Σ i^m a_m(ν)/x^m of H_ν⁽¹⁾(x) = √(2/(πx))·e^{i(x − νπ/2 −
/// π/4)}·P_ν(x) (DLMF 10.17.5), for ν = 0 (*p0) and ν = 1 (*p1); for x ≥ HankelAsymptoticMin,
/// summed until the terms drop below 1e-17 (the remainder is bounded by the first neglected
/// term, DLMF 10.17(iii)). Callers that factor out a common phase use these directly.
void HankelAsymptoticFactors(double x, Complex *p0, Complex *p1);

/// H₀⁽¹⁾(x) = J₀(x) + iY₀(x) and H₁⁽¹⁾(x) = J₁(x) + iY₁(x) for x > 0 (HankelAsymptoticFactors for
/// x ≥ HankelAsymptoticMin, std::cyl_bessel_j / cyl_neumann below); relative error ≲ 1e-14.
void Hankel01(double x, Complex *h0, Complex *h1);

/// The exponentially scaled modified Bessel function I₀(x)·e^{−x} for x ≥ 0 (std::cyl_bessel_i
/// below 600, the asymptotic expansion A&S 9.7.1 to four terms above, relative error < 1e-12).
double BesselI0Scaled(double x);

}  // namespace phasor
