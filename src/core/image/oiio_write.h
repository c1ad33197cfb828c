// SPDX-License-Identifier: Apache-2.0
// phasor — internal to phasor_image: encoding through OpenImageIO into memory, then writing through
// the all-or-nothing OutputFiles (core/image/output_file.h); shared by image_io.cpp and plot.cpp. OIIO
// types are allowed here (this header is only included inside src/core/image/).
#pragma once

#include <string>

#include <OpenImageIO/imageio.h>

#include "core/image/output_file.h"

namespace phasor::detail {

/// Encodes `pixels` (of type `type`, packed) described by `spec` in memory with the OIIO plug-in
/// for `format` ("exr", "png") and stages the bytes for `path` in `files` (checked writes to a
/// temporary file; renamed by files.Commit()). Throws phasor::Error ("cannot write '<path>':
/// <reason>"), leaving nothing behind.
void StageImage(OutputFiles &files, const std::string &path, const char *format, const OIIO::ImageSpec &spec,
                OIIO::TypeDesc type, const void *pixels);

}  // namespace phasor::detail
