// SPDX-License-Identifier: Apache-2.0
// phasor — `phasor render`: one render, or one per value of a Define (--sweep), on one process or
// spread over MPI ranks (app/distributed.h), with checkpoints and resume (app/checkpoint.h).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "app/cli.h"

namespace phasor {

/// Runs `phasor render` (README "Using phasor", docs/distributed.md). Exit status: 0; 1 for bad
/// input (nothing written) or a failed render or write; 128 + the signal after Ctrl-C/SIGTERM (the
/// partial image is written). Under MPI every rank returns rank 0's status.
int RunRender(const CliOptions &o);

/// The renders of a sweep (--sweep NAME=v1,v2,…, repeated: every combination, the first name
/// varying slowest): for each, the -D pairs it adds and the suffix of its file names,
/// "-NAME=value[-NAME2=value2…]" (the value as written, double quotes dropped, every character but
/// letters, digits and . _ + - replaced by '_').
std::vector<std::pair<std::vector<std::pair<std::string, std::string>>, std::string>>
SweepRenders(const std::vector<std::pair<std::string, std::vector<std::string>>> &sweeps);

}  // namespace phasor
