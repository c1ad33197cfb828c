// SPDX-License-Identifier: Apache-2.0
// phasor — `phasor probe`: one diffraction kernel of a scene, at one incidence and wavelength, for
// kernel authors (README "Using phasor", docs/kernels.md "Probing a kernel").
#pragma once

#include "app/cli.h"

namespace phasor {

/// Runs `phasor probe` with the parsed options (o.scene, o.probe, o.defines, o.seed, strictness):
/// builds only the named material (and what it references) from the scene, prints R, T and the
/// near-delta lobes, and writes the CSV and the plot all or nothing. Errors are printed to stderr;
/// returns the exit status (0, or 1 with no output file written).
int RunProbe(const CliOptions &o);

}  // namespace phasor
