// SPDX-License-Identifier: Apache-2.0
// phasor — cylinder functions: the Hankel functions H₀⁽¹⁾, H₁⁽¹⁾ of the 2-D Rayleigh–Sommerfeld
// kernel (theory §6.2, `rs`), the scaled modified Bessel function I₀ of the GR disc
// measurement (core/render/genray.h) and the sequence J₀ … J_N of the grating orders
// (materials/grating.cpp).
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

/// The exponentially scaled modified Bessel function I₀(x)·e^{−x} for x ≥ 0: the power series
/// below 22, the asymptotic expansion A&S 9.7.1 summed to convergence above (relative error
/// < 1e-14 against std::cyl_bessel_i; ~6× faster; RiceCdfQuadrature calls it 192 times).
double BesselI0Scaled(double x);

/// J_0(x), J_1(x), …, J_nMax(x) for x ≥ 0 into out[0 … nMax], by Miller's backward recurrence
/// J_{n−1} = (2n/x)·J_n − J_{n+1} started well above max(nMax, x) and normalised with
/// J_0 + 2·Σ_k J_2k = 1 (DLMF 10.74(iv), 10.12.4); a power series for x < 1e-8; for x ≤ 2 and
/// nMax ≤ 24 the series of the top two orders and the same recurrence from there. One pass costs
/// O(max(nMax, x)) flops, ~50× less than nMax + 1 calls of std::cyl_bessel_j; agrees with it to
/// ~1e-15 absolute (~3.5e-15 on the series path at 24 orders; tests/core/numerics/bessel_test.cpp).
void BesselJSequence(double x, int nMax, double *out);

}  // namespace phasor
