// SPDX-License-Identifier: Apache-2.0
// phasor — `phasor profile`: one row of one channel of each input image as CSV and as a line plot
// (grt vs rs comparisons, supplement Fig. S6).
#pragma once

#include "app/cli.h"

namespace phasor {

/// Runs `phasor profile` with the parsed options; prints errors as "error: …" to stderr and
/// returns the exit status (0, or 1 with no output file written).
int RunProfile(const CliOptions &o);

}  // namespace phasor
