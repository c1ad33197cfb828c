// SPDX-License-Identifier: Apache-2.0
// phasor — complex spectra (complex_spectrum.h): scene-file text of each kind.
#include "core/spectrum/complex_spectrum.h"

#include <cstdio>

namespace phasor {

std::string ConstantComplexSpectrum::ToString() const {
    char buf[96];
    if (c_.imag() == 0)
        std::snprintf(buf, sizeof buf, "%.17g", c_.real());
    else
        std::snprintf(buf, sizeof buf, "%.17g%+.17gi", c_.real(), c_.imag());
    return buf;
}

std::string NkSpectrum::ToString() const {
    return "nk(n = " + n_->ToString() + (k_ ? ", k = " + k_->ToString() : std::string()) + ")";
}

}  // namespace phasor
