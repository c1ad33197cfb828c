// SPDX-License-Identifier: Apache-2.0
// Test helper: a generalized ray with one wavelength, built from its physical quantities.
#pragma once

#include <cmath>

#include "core/math.h"
#include "core/render/genray.h"

namespace phasor::test {

/// A GR at `o` [m] travelling along `d` (normalised here) with one wavelength `lambda` [m]
/// (k = 2π/λ, vacuum) and footprint β² [m²], ρ [1/m] there.
inline SpectralGenRay OneWavelengthGr(const Vec3 &o, const Vec3 &d, double lambda, double beta2, double rho) {
    SpectralGenRay g;
    g.o = o;
    g.d = Normalize(d);
    g.count = 1;
    g.k[0] = 2 * Pi / lambda;
    g.beta2[0] = beta2;
    g.rho[0] = rho;
    return g;
}

}  // namespace phasor::test
