// SPDX-License-Identifier: Apache-2.0
// phasor — `phasor compare`: renders one scene with several integrators (equal spp or equal time)
// and compares them against a reference: per-integrator EXR and PNG, a labelled grid, false-colour
// signed differences, a table (CSV, Markdown), optional profile and convergence plots, and an
// index.html that shows it all (docs/compare.md). Its steps are the methods of Comparison, which
// the Python module's phasor.compare runs too (with CompareHooks of its own).
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/cli.h"
#include "app/compare_report.h"
#include "core/diagnostics.h"
#include "core/render/detector.h"
#include "core/render/registry.h"

namespace phasor {

class Scene;

/// Runs `phasor compare` (README "Using phasor", docs/compare.md). Exit status: 0 when every
/// integrator rendered and every output was written; 1 for bad input (nothing is written), when
/// an output cannot be written (nothing is written), or when some integrator failed (the outputs
/// of the others are written, the table says which failed and why); 128 + the signal after
/// Ctrl-C/SIGTERM (the finished runs are written, the page says the comparison was stopped).
int RunCompare(const CliOptions &o);

/// How a comparison reaches its caller. Every member left unset is the command line's: stopped by
/// Ctrl-C/SIGTERM (StopFlag, handlers installed while it renders), a progress bar on a terminal,
/// warnings and errors on stderr, the scene parsed from o.scene and built for each integrator.
struct CompareHooks {
    /// A stop request polled instead of the signals (no handlers are installed), and what the
    /// page calls it ("KeyboardInterrupt").
    const std::atomic<bool> *stop = nullptr;
    std::string stopName;
    /// The progress callback of one run (ProgressBar's arguments; budget > 0: an equal-time run).
    std::function<std::function<void(int, int)>(const std::string &label, bool deterministic, long long pixels,
                                                double budget)>
        progress;
    /// A warning while a run renders, "NAME: …".
    std::function<void(const std::string &)> warn;
    /// The scene already parsed, and its build for an integrator (errors in `diag`, nothing printed).
    const SceneDesc *desc = nullptr;
    std::function<std::shared_ptr<const Scene>(const std::string &integrator, Diagnostics &diag)> build;
    /// The reference as an image in memory instead of --reference's file (o.compare.reference
    /// then only names it).
    std::optional<Image> referenceImage;
    /// Errors and messages on stderr; false: errors only in Comparison::Failure() and the runs.
    bool print = true;
};

/// One comparison. RunCompare calls its steps in order: Load, PrepareDirectory, RenderCompared,
/// RenderReference, Report, Write (a step returning false ends it; Failure() says why).
class Comparison {
  public:
    explicit Comparison(const CliOptions &o, CompareHooks hooks = {});
    ~Comparison();
    Comparison(const Comparison &) = delete;
    Comparison &operator=(const Comparison &) = delete;

    /// Parses the scene, checks every integrator name and reads a reference image; false when the
    /// comparison cannot start (nothing is written).
    bool Load();
    /// Creates the output directory (removed again if it stays empty) and checks that it can be
    /// written; false after an error.
    bool PrepareDirectory();
    /// Renders each compared integrator; false (after an error) when the comparison must stop
    /// before writing anything (the detector's memory, a reference of another size).
    bool RenderCompared();
    /// Chooses the reference (an image, a deterministic run, or a rendered one: independent seeds,
    /// more samples, the same physics as the runs it grades) and renders it.
    void RenderReference();
    /// The errors, the display exposure and what the page says; false when nothing was rendered.
    bool Report();
    /// Stages and commits every output; returns the exit status.
    int Write();

    /// Stages every output in `dir` and commits them all or nothing; returns the names written.
    /// Throws phasor::Error.
    std::vector<std::string> WriteTo(const std::string &dir);
    /// Why the last step returned false ("" when none did).
    const std::string &Failure() const { return failure_; }
    const std::vector<CompareRun> &Runs() const { return runs_; }
    const CompareReference &Reference() const { return ref_; }
    const CompareReport &Summary() const { return report_; }

  private:
    std::shared_ptr<const Scene> Build(CompareRun &run);
    void RenderRun(CompareRun &run, const Scene &scene, int index, double budget, bool shared);
    bool CheckFirstScene(const Scene &scene);
    std::string ReferenceIntegrator() const;
    int ReferenceSpp(const std::string &integrator, const Scene &scene) const;
    void DescribeReferenceImage();
    int Index(const CompareRun &run) const { return int(&run - runs_.data()) + 1; }
    /// `--reference none`: the runs side by side, no errors.
    bool NoReference() const { return c_.reference == "none"; }
    const SceneDesc &Desc() const;
    bool Stopped() const;
    void RemoveHandlers() const;
    bool Fail(const std::string &message);
    std::function<void(int, int)> Progress(const std::string &label, bool deterministic, long long pixels,
                                           double budget) const;
    std::function<void(const std::string &)> Warn(CompareRun &run, bool bar) const;

    const CliOptions o_;
    const CliOptions::CompareOptions &c_;
    CompareHooks hooks_;
    std::string dir_;
    bool dirCreated_ = false;
    std::string failure_;
    std::optional<SceneDesc> desc_;
    Diagnostics parseDiag_;
    std::vector<std::string> integrators_;
    std::optional<Image> refImage_;
    CompareReference ref_;
    std::vector<CompareRun> runs_;
    // The memory left for convergence snapshots of runs rendered before the reference.
    struct SnapshotBudget {
        const std::vector<double> *reference = nullptr;  // known while the runs render: compare at once
        double bytesLeft = 0;
    } snap_;
    // What the first scene built tells (every run renders the same detector).
    int width_ = 0, height_ = 0, sceneSpp_ = 0;
    unsigned long long seed_ = 0;
    std::string sampler_, detectorName_;
    bool radiometric_ = false;
    DetectorExposure exposure_;
    CompareReport report_;
};

}  // namespace phasor
