// SPDX-License-Identifier: Apache-2.0
// phasor — small helpers shared by the spectrum plug-ins (formatting for ToString()).
#pragma once

#include <cstdio>
#include <string>

namespace phasor::spectra {

/// A number with up to 9 significant digits ("0.5", "5800").
inline std::string Num(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}
/// A wavelength [m] written in nanometres, as a scene file would ("632.8 nm").
inline std::string Nm(double lambda) { return Num(lambda * 1e9) + " nm"; }

}  // namespace phasor::spectra
