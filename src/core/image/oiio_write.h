// SPDX-License-Identifier: Apache-2.0
// phasor — internal to phasor_image: the atomic OpenImageIO writer shared by image_io.cpp and
// plot.cpp. OIIO types are allowed here (this header is only included inside src/core/image/).
#pragma once

#include <string>

#include <OpenImageIO/imageio.h>

namespace phasor::detail {

/// Writes `pixels` (of type `type`, packed) described by `spec` to `path` with the OIIO plug-in
/// for `format` ("exr", "png"), through a temporary file in the same directory that is renamed
/// into place; on any failure the temporary file is removed and phasor::Error is thrown
/// ("cannot write '<path>': <reason>").
void WriteAtomically(const std::string &path, const char *format, const OIIO::ImageSpec &spec,
                     OIIO::TypeDesc type, const void *pixels);

}  // namespace phasor::detail
