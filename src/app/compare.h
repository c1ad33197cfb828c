// SPDX-License-Identifier: Apache-2.0
// phasor — `phasor compare`: renders one scene with several integrators (equal spp or equal time)
// and compares them against a reference: per-integrator EXR and PNG, a labelled grid, false-colour
// signed differences, a table (CSV, Markdown), optional profile and convergence plots, and an
// index.html that shows it all (docs/compare.md).
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "app/cli.h"
#include "app/compare_report.h"
#include "core/render/integrator.h"

namespace phasor {

class Scene;
struct SceneDesc;

/// What the runs of a comparison share: the reference when it is known before they render (an
/// image, or the reference run rendered first; then each snapshot is compared at once and its
/// pixels dropped), and the memory left for snapshots whose reference is not known yet.
struct SnapshotContext {
    const std::vector<double> *reference = nullptr;
    double bytesLeft = 0;
};

/// Every integrator a name may pick: the registry's plug-ins and the scene's named integrators.
std::vector<std::string> IntegratorChoices(const SceneDesc &desc);

/// How one run of a comparison renders (RenderCompareRun).
struct CompareRunSettings {
    /// spp, seed, threads, sampler; its progress and warn callbacks, if set, are called too.
    RenderOptions options;
    double budget = 0;     // equal time: seconds of rendering for a sampling integrator (0: options.spp)
    std::string scenePath;  // for the image's metadata
    const std::atomic<bool> *stop = nullptr;  // a stop request (Ctrl-C): the run is then Interrupted
    bool shared = false;  // every MPI rank renders the run's tiles (rank 0 alone fills `run`)
};

/// Renders one run of a comparison with the scene built for its integrator and fills `run`: its
/// status, time, spp, image (with the metadata of `render`), intensity, variance, and the snapshots
/// of the convergence plot, taken between the render loop's passes (compared at once when
/// snap.reference is known). A stopped `rs` has no image (status Interrupted). Returns the render's
/// statistics; an integrator's phasor::Error marks the run Failed (run.error) and is rethrown.
/// Shared by `phasor compare` and the Python module's phasor.compare.
RenderStats RenderCompareRun(CompareRun &run, const Scene &scene, const CompareRunSettings &s, SnapshotContext &snap);

/// Runs `phasor compare` (README "Using phasor", docs/compare.md). Exit status: 0 when every
/// integrator rendered and every output was written; 1 for bad input (nothing is written), when
/// an output cannot be written (nothing is written), or when some integrator failed (the outputs
/// of the others are written, the table says which failed and why); 128 + the signal after
/// Ctrl-C/SIGTERM (the finished runs are written, the page says the comparison was stopped).
int RunCompare(const CliOptions &o);

}  // namespace phasor
