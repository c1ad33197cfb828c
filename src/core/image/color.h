// SPDX-License-Identifier: Apache-2.0
// phasor — internal to phasor_image: the OpenColorIO display transform on a packed RGB buffer
// (color.cpp), used by WritePng. No OCIO types here.
#pragma once

#include <cstddef>

#include "core/image/image_io.h"

namespace phasor::detail {

/// Multiplies by 2^opt.exposure and applies the (display, view) transform from the scene_linear
/// role to `numPixels` packed RGB float triples in place. Thread-safe. Throws phasor::Error for
/// an unusable $OCIO config or an unknown display/view.
void ApplyDisplayTransformInPlace(float *rgb, std::size_t numPixels, const DisplayOptions &opt);

}  // namespace phasor::detail
