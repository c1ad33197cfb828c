// SPDX-License-Identifier: Apache-2.0
// phasor — `phasor compare`: renders one scene with several integrators (equal spp or equal time)
// and compares them against a reference: per-integrator EXR and PNG, a labelled grid, false-colour
// signed differences, a table (CSV, Markdown), optional profile and convergence plots, and an
// index.html that shows it all (docs/compare.md).
#pragma once

#include "app/cli.h"

namespace phasor {

/// Runs `phasor compare` (README "Using phasor", docs/compare.md). Exit status: 0 when every
/// integrator rendered and every output was written; 1 for bad input (nothing is written), when
/// an output cannot be written (nothing is written), or when some integrator failed (the outputs
/// of the others are written, the table says which failed and why); 128 + the signal after
/// Ctrl-C/SIGTERM (the finished runs are written, the page says the comparison was stopped).
int RunCompare(const CliOptions &o);

}  // namespace phasor
