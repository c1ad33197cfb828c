// SPDX-License-Identifier: Apache-2.0
// phasor — the Faddeeva (scaled complex complementary error) function w(z) = e^{−z²}·erfc(−iz)
// (DLMF 7.2.3), used by the `aperture` footprint integral and by `rs`'s slit-end error model.
#pragma once

#include "core/math.h"

namespace phasor {

/// w(z) for any complex z (libcerf; the reference, relative error ~1e-14).
Complex FaddeevaW(Complex z);

/// w(z) for Im z ≥ 0 by Weideman's rational approximation (SIAM J. Numer. Anal. 31, 1994) with
/// N = 28 terms: |error| ≤ 2·10⁻¹² over the closed upper half-plane (|w| ≤ 1 there). About 3×
/// faster than libcerf one at a time; outside the upper half-plane it is not w.
Complex FaddeevaWUpper(Complex z);

/// FaddeevaWUpper at n points given as structure of arrays (z = zr[i] + i·zi[i], Im z ≥ 0),
/// written to (wr[i], wi[i]); vectorisable, the same values as n single calls.
void FaddeevaWUpperBatch(int n, const double *zr, const double *zi, double *wr, double *wi);

}  // namespace phasor
