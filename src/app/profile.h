// SPDX-License-Identifier: Apache-2.0
// phasor — `phasor profile`: one row or column of one channel of each input image as CSV and as a
// line plot (grt vs rs comparisons, supplement Fig. S6).
#pragma once

#include <string>
#include <vector>

#include "app/cli.h"

namespace phasor {

/// Runs `phasor profile` with the parsed options; prints errors as "error: …" to stderr and
/// returns the exit status (0, or 1 with no output file written).
class OutputFiles;
struct Image;

/// `phasor profile` (README "Using phasor"). `preloaded[i]`, when given and not null, is the image
/// of o.profile.inputs[i] already in memory (the name is still used in messages and labels);
/// with `into`, the CSV and plot are staged there instead of written (the caller commits them,
/// e.g. `render` writing a one-row image's plot together with its EXR) and a failed write throws
/// phasor::Error instead of being printed. When matplotlib is missing
/// the plot's data is written instead, with a warning — unless `plotData` is given: it then
/// receives that file's name and the caller tells the user. Returns the exit status.
int RunProfile(const CliOptions &o, const std::vector<const Image *> &preloaded = {}, OutputFiles *into = nullptr,
               std::string *plotData = nullptr);

}  // namespace phasor
