// SPDX-License-Identifier: Apache-2.0
// phasor — warnings for kernel parameters far outside their model's validity (docs/kernels.md,
// each kernel's "Validity"), given in Create: the kernel is built and the render runs, and the
// user is told the range.
#pragma once

#include <string>

#include "core/diagnostics.h"
#include "core/render/registry.h"

namespace phasor {

/// The longest visible wavelength [m]: a surface length above it is larger than every visible
/// wavelength.
inline constexpr double LongestVisibleWavelength = 830e-9;

/// Warns at `param` of `d` when the length `value` [m] exceeds LongestVisibleWavelength: the
/// kernel's model (`model`: what it needs, e.g. "the thin-phase model holds for h/λ ≲ 0.2
/// (docs/kernels.md, grating)") holds only for light longer than `factor` × value; `remedy`
/// says what to use instead.
inline void WarnIfBeyondVisible(const ParamDict &d, BuildContext &ctx, const std::string &param, double value,
                                const std::string &model, double factor, const std::string &remedy) {
    if (!(value > LongestVisibleWavelength)) return;
    ctx.Diag().Warning(d.Loc(param), "'" + param + "' = " + Value::Number(value, Dim::Length()).ToString() + " is " +
                                         FormatRatio(value / LongestVisibleWavelength) +
                                         " times the longest visible wavelength (830 nm): " + model +
                                         ", so it holds only for light longer than " +
                                         Value::Number(factor * value, Dim::Length()).ToString() + "; " + remedy);
}

}  // namespace phasor
