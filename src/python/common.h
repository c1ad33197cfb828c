// SPDX-License-Identifier: Apache-2.0
// phasor's Python module (docs/python.md): what its files share. The module is a thin layer over
// the library the program uses — the scene loading of app/render_common.h, Scene::Build (and with
// it every scene check), the render loop and the film — never a second implementation.
#pragma once

#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "app/render_common.h"
#include "core/diagnostics.h"
#include "core/image/film.h"
#include "core/render/scene.h"
#include "core/units.h"
#include "parser/parser.h"

namespace phasor::python {

namespace py = pybind11;

/// How a scene is read: a file or text, with defines and strictness (the command line's -D,
/// --strict, --permissive).
struct LoadSpec {
    std::string path;                 // the file, or the name text is known by in messages
    std::optional<std::string> text;  // load_string: the scene text
    DefineList defines;               // in the order given
    std::vector<std::string> siDefines;  // names among `defines` given as Python numbers (SI)
    bool strict = false, permissive = false;
};

/// A loaded scene: its description (parsed once) and the scene built for each integrator asked
/// for ("" = the scene's own choice, built at load). Shared by every object made from it (images,
/// probes), so that none outlives what it refers to.
class LoadedScene {
  public:
    /// Parses and builds `spec` for `integrator` ("" = the scene's own; a name picks as
    /// --integrator does), the GIL released. Raises phasor.SceneError with every error (as
    /// `phasor check` reports them); warnings go to Python's `warnings`.
    static std::shared_ptr<LoadedScene> Load(const LoadSpec &spec, const std::string &integrator = "");
    /// Load without Python (no GIL needed): nullptr with `diag` holding the errors, which
    /// holds the warnings otherwise.
    static std::shared_ptr<LoadedScene> LoadQuietly(const LoadSpec &spec, Diagnostics &diag,
                                                    const std::string &integrator = "");

    /// The scene built for `integrator`, built on first use. Raises phasor.SceneError (needs the GIL).
    std::shared_ptr<const Scene> For(const std::string &integrator);
    /// For without Python: nullptr with `diag` holding the errors.
    std::shared_ptr<const Scene> ForQuietly(const std::string &integrator, Diagnostics &diag);

    const LoadSpec &Spec() const { return spec_; }
    const SceneDesc &Desc() const { return desc_; }
    /// Warnings reported so far (each emitted once through Python's `warnings`).
    std::vector<std::string> &EmittedWarnings() { return emitted_; }

  private:
    LoadSpec spec_;
    SceneDesc desc_;
    std::mutex mutex_;
    std::map<std::string, std::shared_ptr<const Scene>> built_;
    std::vector<std::string> emitted_;
};

/// Adds a Python call's defines ({"d": "150um", "lambda": 5.5e-7, "on": True}) to `spec`: strings
/// are scene-language text as after -D, numbers are SI (LoadSpec::siDefines), booleans true/false;
/// a name given again replaces its earlier value. Raises TypeError.
void AddDefines(LoadSpec &spec, const py::object &defines);

/// Raises phasor.SceneError for the errors in `diag` (needs the GIL). `scene` names the file in the
/// summary line ("2 errors in 'x.wscene'").
[[noreturn]] void RaiseSceneError(const Diagnostics &diag, const std::string &scene);
/// Emits every warning in `diag` through Python's `warnings` as phasor.SceneWarning, except those
/// already in `emitted` (which receives the new ones); needs the GIL.
void EmitWarnings(const Diagnostics &diag, std::vector<std::string> *emitted = nullptr);
/// Emits one message through Python's `warnings` as phasor.RenderWarning.
void EmitRenderWarning(const std::string &message);
/// Raises the Python exception class `name` of phasor._errors with `args` (needs the GIL).
[[noreturn]] void RaiseError(const char *name, py::tuple args);
/// A phasor::Error as the Python exception phasor.<cls> (PhasorError, RenderError: with .file,
/// .line, .column when located).
[[noreturn]] void RaisePhasorError(const Error &e, const char *cls = "PhasorError");

/// A quantity given as a Python number (SI) or a string in the scene language ("550nm", "30 deg",
/// "0.25*pi rad"), of dimension `dim`; `what` names the argument in errors. Raises ValueError.
double Quantity(py::handle value, Dim dim, const std::string &what, const char *example);

/// Checks a `sampler` argument as --sampler: a sampler plug-in or one of the scene's Sampler blocks
/// (Scene::NewSampler); raises ValueError with a suggestion otherwise.
void CheckSampler(const Scene &scene, const std::string &sampler);

/// Runs C++ work (a render) on a thread of its own while the calling Python thread waits with the
/// GIL released, waking every 20 ms to run Python's signal handlers — Ctrl-C's KeyboardInterrupt
/// then asks the work to stop (Cancel()), as SIGINT does in the program — to show progress and to
/// pass on warnings. Python code the work calls (kernels written in Python) takes the GIL itself.
class Interruptible {
  public:
    /// `progress`: None or False (nothing), True (a bar on sys.stderr, as the program draws it),
    /// or a callable(done, total) (units as RenderOptions::progress counts them).
    explicit Interruptible(py::object progress);
    ~Interruptible();
    const std::atomic<bool> *Cancel() const { return &cancel_; }
    /// RenderOptions callbacks (called from the work's thread): progress under `label`, warnings.
    /// (Neither needs the GIL, to make or to call.)
    std::function<void(int, int)> Progress(const std::string &label, bool deterministic, long long pixels,
                                           double budgetSeconds = 0);
    std::function<void(const std::string &)> Warn();
    /// Stops the work (Cancel()) `seconds` from now (a time budget); ≤ 0: no deadline.
    void SetDeadline(double seconds);
    /// Runs `work` (on another thread) and returns when it has finished: the exception a Python
    /// signal handler (or a progress callback, or a warning filter that raises) raised meanwhile,
    /// if any. Rethrows what `work` threw. Needs the GIL.
    std::optional<py::error_already_set> Run(const std::function<void()> &work);

  private:
    void Flush();  // progress and warnings (GIL held)
    py::object progress_;
    bool bar_ = false, callable_ = false;  // progress_ is True / a callable
    std::atomic<bool> cancel_{false};
    std::mutex mutex_;
    std::condition_variable cv_;
    bool finished_ = false;
    std::vector<std::string> warnings_;
    std::string line_;      // the progress line to show (bar) …
    int done_ = -1, total_ = 0;  // … or the callable's arguments
    bool dirty_ = false, shown_ = false;
    std::chrono::steady_clock::time_point start_, deadline_;
    bool hasDeadline_ = false;
};

/// A rendered (or read) image with the scene it came from (null for an image read from a file).
struct PyImage {
    Image image;
    std::shared_ptr<LoadedScene> scene;
    std::string integrator;          // as asked for ("" = the scene's own)
    bool radiometric = false;        // the detector's response has no RGB meaning (false colour dB)
    std::vector<std::string> warnings;  // the render's warnings (also emitted)
};

// Each file binds its part of the API.
void BindScene(py::module_ &m);
void BindImage(py::module_ &m);
void BindRender(py::module_ &m);
void BindPlugins(py::module_ &m);
void BindProbe(py::module_ &m);
void BindCompare(py::module_ &m);
void BindKernels(py::module_ &m);
void BindTesting(py::module_ &m);

}  // namespace phasor::python
