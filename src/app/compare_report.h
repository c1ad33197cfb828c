// SPDX-License-Identifier: Apache-2.0
// phasor — the results of `phasor compare` (compare.h): the runs, the reference, the error
// metrics and the test against the reference's noise, and every output file (EXR, PNG, grid,
// differences, tables, results.json and the page rendered from it, plots).
#pragma once

#include <limits>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "core/image/film.h"

namespace phasor {

class OutputFiles;

/// Errors of an image I against a reference R over the pixels where both are finite (values of
/// the `intensity` channel; N pixels): RMSE = √(Σ(I−R)²/N); relative MSE = Σ(I−R)²/(R² + ε)/N with
/// ε = 0.01·mean(R)² (the usual relMSE of an image scaled to mean 1; NaN when mean(R) = 0);
/// max error = max|I−R| / max(R) (the double-slit validation's figure; NaN when max(R) ≤ 0);
/// RGB RMSE = √mean((I_c − R_c)²) over the pixels and the R, G, B channels (scene-linear Rec.709)
/// — the colour error of cameras (RgbRmse; NaN without colour channels).
struct CompareMetrics {
    double rmse = std::numeric_limits<double>::quiet_NaN();
    double relMse = std::numeric_limits<double>::quiet_NaN();
    double maxError = std::numeric_limits<double>::quiet_NaN();
    double rgbRmse = std::numeric_limits<double>::quiet_NaN();
    long long skipped = 0;  // pixels with a non-finite value in I or R
};
CompareMetrics ErrorMetrics(const std::vector<double> &image, const std::vector<double> &reference);
/// √mean((I_c − R_c)²) over the pixels where all six values are finite and c ∈ {R, G, B}; NaN when
/// either image lacks them or their sizes differ.
double RgbRmse(const Image &image, const Image &reference);

/// Whether I and R can have the same expectation, given the variance of each pixel's value
/// (`imageVariance`, `referenceVariance`: variance of the pixel mean, 0 for a deterministic image):
/// the pixels are pooled into at most 16 × 16 blocks of whole pixels, and
/// T = Σ_b (Σ_{i∈b} (I_i − R_i))² / Σ_{i∈b} (v_I,i + v_R,i) is χ² with one degree of freedom per
/// block with positive variance when both are unbiased and independent (pixels are independent
/// samples; block sums make each term close to normal); z = (T − dof)/√(2·dof). The verdict is
/// "differs" when z > 3.09 (one-sided p = 0.001) or a block without variance differs at all.
/// A variance that overstates the noise (the i.i.d. `variance` channel of Owen-scrambled Sobol'
/// samples) makes the test conservative — "differs" stays significant, "consistent" may hide a
/// bias — and a reference that shares the run's random numbers (the same seed) makes T far too
/// small, which is why compare's reference never does (docs/compare.md).
struct ConsistencyTest {
    bool tested = false;  // false: no variance to test with
    double chi2 = 0;
    int dof = 0;
    double z = std::numeric_limits<double>::quiet_NaN();
    bool consistent = true;
};
ConsistencyTest TestConsistency(const std::vector<double> &image, const std::vector<double> &imageVariance,
                                const std::vector<double> &reference, const std::vector<double> &referenceVariance,
                                int width, int height);
/// z beyond which TestConsistency says "differs" (one-sided p = 0.001).
inline constexpr double ConsistencyZ = 3.09;

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
    bool isReferenceRun = false;  // rendered as the reference (independent seeds, more samples)
    bool isReference = false;     // the reference of the comparison
    bool deterministic = false;   // no samples (rs)
    bool waveOptical = true;      // Integrator::WaveOptical
    Status status = Status::NotRun;
    std::string error;  // Failed: the integrator's message
    /// What the scene checks said about this integrator at load (e.g. a light it cannot reach):
    /// shown beside its status on the page and in results.md.
    std::vector<std::string> warnings;
    std::string work;   // a deterministic integrator's own account ("solved 48 pixels …")
    int sppRequested = 0, sppReached = 0;
    std::vector<unsigned long long> seeds;  // the seed of each render (the reference: one per replica)
    double seconds = 0;                     // render time
    std::optional<Image> image;
    std::vector<double> intensity, variance;  // variance of each pixel's mean (see CompareReference)
    std::vector<CompareSnapshot> snapshots;   // in order; all with metrics after ComputeErrors
    bool snapshotsCut = false;                // no more snapshots were kept (memory)
    std::optional<CompareMetrics> metrics;    // against the reference (not for the reference)
    std::optional<ConsistencyTest> test;      // against the reference's noise (same physics only)
    bool comparable = true;                   // same physics as the reference
    /// Notes about this integrator on this scene for the page (e.g. what it cannot see); empty
    /// unless someone fills it — the table shows them.
    std::vector<std::string> messages;
};

/// What the runs are compared against.
struct CompareReference {
    enum class Kind { None, Image, Run } kind = Kind::None;
    std::string name;          // short: "rs", "grt", "reference image"
    std::string description;   // for the table and the page: what it is
    std::string independence;  // why its noise is independent of every compared run's
    const Image *image = nullptr;
    std::vector<double> values;    // its intensity
    std::vector<double> variance;  // variance of each pixel's value; empty when unknown
    std::string noiseSource;       // where `variance` comes from
    double noiseFloor = std::numeric_limits<double>::quiet_NaN();  // √mean(variance)
    double peak = 0;                                               // its largest finite intensity
    std::optional<bool> waveOptical;    // its physics (unknown for an image phasor did not render)
    std::vector<std::string> warnings;  // e.g. an image that shares the compared runs' seed
};

/// Fills `ref` from the reference run (isReferenceRun, or the one marked isReference: a complete
/// deterministic run), or keeps the image it already holds; then the metrics, the consistency test
/// and the snapshots' errors of every other run. A run of other physics than the reference gets
/// its metrics (the difference of the two physics) but no test (comparable = false).
void ComputeErrors(std::vector<CompareRun> &runs, CompareReference &ref);
/// The noise floor and its source for the reference from `variance` (NaN when empty).
void SetNoiseFloor(CompareReference &ref, std::vector<double> variance, const std::string &source);

/// What the page and results.json say about the comparison besides the runs.
struct CompareReport {
    std::string scene, dir, command, detector, version, sampler;
    std::string modeKind;  // "spp" or "time"
    std::string modeText;  // "equal samples: 64 spp per integrator"
    int spp = 0;           // equal samples: per integrator
    double seconds = 0;    // equal time: per integrator
    unsigned long long seed = 0;
    std::vector<std::pair<std::string, std::string>> defines;  // -D name=value, in order
    std::vector<std::string> sceneWarnings;                    // the scene's own (parse) warnings
    int width = 0, height = 0;
    bool radiometric = false;
    double exposureStops = 0;   // cameras: the display exposure every run is shown with
    bool autoExposure = false;  // …chosen from the reference
    std::string stopped;        // "" or the signal's name ("Ctrl-C", "SIGTERM")
    int row = -1, column = -1;
};

/// Stages every output in `files`: <run>.exr and <run>.png, reference.png (a given reference
/// image), grid.png, diff_<run>.png, results.csv, results.md, results.json, profile.csv/.png,
/// convergence.csv/.png and index.html (results.json through python/templates/compare.html.j2).
/// Returns the names staged. Throws phasor::Error.
std::vector<std::string> StageCompareOutputs(OutputFiles &files, std::vector<CompareRun> &runs,
                                             const CompareReference &ref, const Image *refImage,
                                             const CompareReport &report);

/// results.csv: one row per run — integrator (the reference run's with " (reference)"), role,
/// status, spp, seconds, samples_per_second, rmse, rel_mse, max_error, rgb_rmse, noise_floor,
/// comparable, chi2, dof, z, verdict, error (empty where a run has no value).
std::string CompareCsv(const std::vector<CompareRun> &runs, const CompareReference &ref);
/// The table as text, for the terminal.
void PrintSummary(std::ostream &os, const std::vector<CompareRun> &runs, const CompareReference &ref);
/// "0.25 s", "12 s", "2m05s".
std::string FormatSeconds(double seconds);

}  // namespace phasor
