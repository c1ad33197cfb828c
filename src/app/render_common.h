// SPDX-License-Identifier: Apache-2.0
// phasor — what `render` and `compare` share: stopping on Ctrl-C/SIGTERM, loading a scene, the
// memory check, the progress bar, the metadata of a rendered image and its display PNG.
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/cli.h"
#include "core/image/film.h"
#include "core/render/integrator.h"
#include "core/render/scene.h"

namespace phasor {

class OutputFiles;

// ---- stopping (README "Stopping a render") ------------------------------------------------------
/// Installs the handlers: the first SIGINT (Ctrl-C) or SIGTERM sets StopFlag() (and prints
/// "stopping: …" when `announce`); a second one ends the program at once (the default action).
void InstallStopHandlers(bool announce);
/// Restores the default actions.
void RemoveStopHandlers();
/// Set by the first signal; renders poll it (RenderOptions::cancel).
const std::atomic<bool> &StopFlag();
/// The first signal received, 0 if none.
int StopSignal();
/// The exit status of a command stopped by StopSignal(): 128 + the signal (130 for SIGINT, 143 for
/// SIGTERM), as a shell reports a process killed by it.
int StoppedStatus();

// ---- loading ------------------------------------------------------------------------------------
/// Whether messages on stderr may use colour.
bool Colour();
/// Parses the scene file with the command line's defines; prints the diagnostics. nullopt after
/// errors (what was read cleanly is still returned to Build when `partial`, so one run reports
/// parse and build errors together: see Load).
std::optional<SceneDesc> ParseScene(const CliOptions &o, Diagnostics &diag);
/// Builds `desc` with `integrator` ("" = the scene's own); prints `diag` and "N errors in 'SCENE'".
std::unique_ptr<Scene> BuildScene(const CliOptions &o, const SceneDesc &desc, Diagnostics &diag,
                                  const std::string &integrator);
/// Scene::Build, with running out of memory reported as an error at `scenePath` instead of thrown;
/// nothing printed (BuildScene prints; the Python module raises `diag`'s errors).
std::unique_ptr<Scene> BuildSceneQuietly(const std::string &scenePath, const SceneDesc &desc, Diagnostics &diag,
                                         const std::string &integrator);
/// ParseScene + BuildScene with o.integrator: nullptr after errors (all of them printed). The
/// description read goes to `desc` when given.
std::unique_ptr<Scene> Load(const CliOptions &o, Diagnostics &diag, SceneDesc *desc = nullptr);
/// Prints an error: `file:line:col: error: …` with the source line when it has a location in a
/// file, else `error: …` (a file-level error names its file in its message, once).
void PrintError(const Error &e);

// ---- rendering ----------------------------------------------------------------------------------
std::string FormatDuration(double seconds);
/// Verifies before rendering that `path` can be created (so a long render never ends in an
/// unwritable path), creating missing parent directories. Throws phasor::Error.
void CheckWritable(const std::string &path);
/// Throws a located phasor::Error when the detector's film and images would not fit in the
/// available memory (film.h Film::MemoryNeeded, AvailableMemory).
void CheckMemory(const Scene &scene);
/// RenderOptions from the scene's Render block and the command line (--spp, --seed, --threads,
/// --sampler), cancelled by StopFlag(). Without --threads, an MPI rank takes its share of its
/// node's cores (dist::DefaultThreads).
RenderOptions OptionsFor(const Scene &scene, const CliOptions &o);

/// A RenderOptions::progress callback drawing a bar on stderr: "[label] [====   ]  40% 8/16 spp
/// 1.2s elapsed  ETA 1.8s  3.41 Msamples/s". With `budgetSeconds` > 0 (a render stopped after a
/// time budget) the fraction is the time used of the budget. Deterministic integrators (rs) count
/// their own steps and have no sample rate.
std::function<void(int, int)> ProgressBar(const std::string &label, bool deterministic, long long pixels,
                                          double budgetSeconds = 0);
/// The text ProgressBar draws (without the leading carriage return) after `seconds` of a render
/// that has done `done` of `total` units.
std::string ProgressText(const std::string &label, bool deterministic, long long pixels, double budgetSeconds,
                         int done, int total, double seconds);

/// The image of a finished or stopped render: the film resolved, with StampMetadata's metadata
/// (what `render` writes).
Image ResolvedImage(const Film &film, const Scene &scene, const std::string &scenePath, const RenderOptions &opt,
                    const RenderStats &st);
/// One render in this process, as `render` does it without MPI or checkpoints (the Python
/// module's render): a film of the detector's size, the integrator's render loop, ResolvedImage,
/// and the display exposure stamped (StampDisplayExposure).
/// `image` is empty when the render stopped before it had anything honest to show
/// (RenderStats::hasImage false). Throws phasor::Error (an integrator's refusal at render time).
struct RenderResult {
    RenderStats stats;
    std::optional<Image> image;
};
RenderResult RenderToImage(const Scene &scene, const std::string &scenePath, const RenderOptions &opt);

/// Stamps a render's metadata on its image: scene, integrator, spp (requested, reached, max),
/// seed, sampler, the integrator's own keys, time, cancellation, a sensor plane's pixel positions.
void StampMetadata(Image &img, const Scene &scene, const std::string &scenePath, const RenderOptions &opt,
                   const RenderStats &st);

/// The exposure [stops] a camera's image is shown with (Detector::Exposure): `exposure` plus, with
/// `auto_exposure`, AutoExposureStops of `basis` (the image itself; in `compare`, the reference, so
/// that every run is shown alike). 0 for radiometric detectors (shown in dB).
double DisplayStops(const Detector &det, const Image &basis);
/// Records the display's exposure in the image's metadata (phasor:display_exposure, stops).
void StampDisplayExposure(Image &img, const Detector &det, double stops);

/// The PNG shown for a rendered image, staged in `files`: a one-row image as `phasor profile`'s
/// line plot of its intensity (matplotlib), a radiometric detector's (`radiometric`) as the dB false colour with its
/// colour bar (0 dB = `zeroDb`, ≤ 0: the image's maximum), a camera's through the OCIO display
/// transform of 2^`stops` × the image (DisplayStops). Returns the file staged: `png`, or the plot's data (a .csv beside it) when matplotlib
/// is missing, which the caller tells the user (MatplotlibMissing()). Throws phasor::Error.
std::string StageDisplayPng(OutputFiles &files, const std::string &png, const Image &img, bool radiometric,
                            const std::string &label, const std::string &title, double zeroDb = 0,
                            double stops = 0);

/// The warnings after a render: render-time events, a black image (with its likely cause),
/// discarded samples (without "warning: ").
std::vector<std::string> RenderWarnings(const Scene &scene, const RenderStats &st, const Image &img);
/// Prints RenderWarnings, each as "warning: …"; returns them.
std::vector<std::string> PrintRenderWarnings(const Scene &scene, const RenderStats &st, const Image &img);
/// The warnings of `diag`, each as "file:line:col: message".
std::vector<std::string> WarningsOf(const Diagnostics &diag);

}  // namespace phasor
