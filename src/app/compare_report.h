// SPDX-License-Identifier: Apache-2.0
// phasor — the results of `phasor compare` (compare.h): the runs, the reference, the error
// metrics, and every output file (EXR, PNG, grid, differences, table, plots, index.html).
#pragma once

#include <limits>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "core/image/film.h"

namespace phasor {

class OutputFiles;

/// Errors of an image I against a reference R over the pixels where both are finite (values of
/// the `intensity` channel; N pixels): RMSE = √(Σ(I−R)²/N); relative MSE = Σ(I−R)²/(R² + ε)/N with
/// ε = 0.01·mean(R)² (the usual relMSE of an image scaled to mean 1; NaN when mean(R) = 0);
/// max error = max|I−R| / max(R) (the double-slit validation's figure; NaN when max(R) ≤ 0).
struct CompareMetrics {
    double rmse = std::numeric_limits<double>::quiet_NaN();
    double relMse = std::numeric_limits<double>::quiet_NaN();
    double maxError = std::numeric_limits<double>::quiet_NaN();
    long long skipped = 0;  // pixels with a non-finite value in I or R
};
CompareMetrics ErrorMetrics(const std::vector<double> &image, const std::vector<double> &reference);

/// A sampling run after `spp` samples per pixel, `seconds` into it: its errors against the
/// reference when that was known during the render, else its `intensity` (float, to be compared
/// when the reference is chosen).
struct CompareSnapshot {
    int spp = 0;
    double seconds = 0;
    std::optional<CompareMetrics> metrics;
    std::vector<float> intensity;
};

/// One integrator's run.
struct CompareRun {
    enum class Status { NotRun, Done, Interrupted, Failed };
    std::string name;             // the integrator, as named on the command line
    std::string file;             // its files' stem in the output directory
    bool isReferenceRun = false;  // rendered for --reference-integrator
    bool isReference = false;     // the reference of the comparison (chosen or given)
    bool deterministic = false;   // no samples (rs)
    Status status = Status::NotRun;
    std::string error;  // Failed: the integrator's message
    /// What the scene checks said about this integrator at load (e.g. a light it cannot reach):
    /// shown beside its status on the page and in results.md.
    std::vector<std::string> warnings;
    std::string work;   // a deterministic integrator's own account ("solved 48 pixels …")
    int sppRequested = 0, sppReached = 0;
    double seconds = 0;  // render time
    std::optional<Image> image;
    std::vector<double> intensity, variance;
    std::vector<CompareSnapshot> snapshots;  // in order; all with metrics after ComputeErrors
    bool snapshotsCut = false;               // no more snapshots were kept (memory)
    std::optional<CompareMetrics> metrics;   // against the reference (not for the reference)
};

/// What the runs are compared against.
struct CompareReference {
    std::string name;         // short: "rs", "reference image"
    std::string description;  // for the table and the page
    const Image *image = nullptr;
    std::vector<double> values;  // its intensity
    double peak = 0;             // its largest finite intensity
};

/// The best-converged run: a complete deterministic run, else the run with the least estimated
/// noise Σ variance / Σ intensity² (the `variance` channel: the i.i.d. estimate, which overstates
/// Sobol' noise but alike for every sampling run). Marks it, fills `ref`.
void ChooseReference(std::vector<CompareRun> &runs, CompareReference &ref);
/// Unless `ref` already holds an image (--reference): the reference run (--reference-integrator),
/// else (or when it failed) the best-converged run (ChooseReference). Then the metrics of every
/// other run and of its snapshots.
void ComputeErrors(std::vector<CompareRun> &runs, CompareReference &ref);

/// What the page says about the comparison.
struct CompareReport {
    std::string scene, dir, command, mode, detector;
    int width = 0, height = 0;
    bool radiometric = false;
    bool stopped = false;  // by Ctrl-C/SIGTERM
    int row = -1, column = -1;
};

/// Stages every output in `files`: <run>.exr and <run>.png, reference.png (a given reference
/// image), grid.png, diff_<run>.png, results.csv, results.md, profile.csv/.png, convergence.csv/.png,
/// index.html. Returns the names staged. Throws phasor::Error.
std::vector<std::string> StageCompareOutputs(OutputFiles &files, std::vector<CompareRun> &runs,
                                             const CompareReference &ref, const Image *refImage,
                                             const CompareReport &report);

/// The table as text, for the terminal.
void PrintSummary(std::ostream &os, const std::vector<CompareRun> &runs);
/// "0.25 s", "12 s", "2m05s".
std::string FormatSeconds(double seconds);

}  // namespace phasor
