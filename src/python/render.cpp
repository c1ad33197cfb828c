// SPDX-License-Identifier: Apache-2.0
// phasor's Python module: rendering (Scene.render, Scene.render_many, phasor.sweep) through the
// program's own render path (app/render_common.h RenderToImage: film, render loop, metadata), on a
// thread of its own so that the Python thread can turn Ctrl-C into a stop request.
#include <pybind11/stl.h>

#include <thread>

#include "core/geometry/geometry_cache.h"
#include "python/common.h"

namespace phasor::python {

// ---- Interruptible ------------------------------------------------------------------------------

Interruptible::Interruptible(py::object progress) : progress_(std::move(progress)) {
    start_ = std::chrono::steady_clock::now();
    const bool flag = py::isinstance<py::bool_>(progress_);
    bar_ = flag && progress_.cast<bool>();
    callable_ = !flag && !progress_.is_none();
}

Interruptible::~Interruptible() = default;

std::function<void(int, int)> Interruptible::Progress(const std::string &label, bool deterministic, long long pixels,
                                                      double budgetSeconds) {
    if (!bar_ && !callable_) return {};
    const bool bar = bar_;
    const auto start = std::chrono::steady_clock::now();
    return [=, this](int done, int total) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (bar) {
            const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            line_ = ProgressText(label, deterministic, pixels, budgetSeconds, done, total, t);
        }
        done_ = done;
        total_ = total;
        dirty_ = true;
    };
}

std::function<void(const std::string &)> Interruptible::Warn() {
    return [this](const std::string &w) {
        std::lock_guard<std::mutex> lock(mutex_);
        warnings_.push_back(w);
    };
}

void Interruptible::SetDeadline(double seconds) {
    hasDeadline_ = seconds > 0;
    deadline_ = std::chrono::steady_clock::now() +
                std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
}

void Interruptible::Flush() {
    std::vector<std::string> warnings;
    std::string line;
    int done = -1, total = 0;
    bool dirty;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        warnings.swap(warnings_);
        dirty = dirty_;
        dirty_ = false;
        line = line_;
        done = done_;
        total = total_;
    }
    if (dirty && !progress_.is_none()) {
        if (py::isinstance<py::bool_>(progress_)) {
            py::object err = py::module_::import("sys").attr("stderr");
            err.attr("write")("\r" + line);
            err.attr("flush")();
            shown_ = true;
        } else {
            progress_(done, total);
        }
    }
    for (const std::string &w : warnings) {
        if (shown_) py::module_::import("sys").attr("stderr").attr("write")("\n");
        EmitRenderWarning(w);
    }
}

std::optional<py::error_already_set> Interruptible::Run(const std::function<void()> &work) {
    std::exception_ptr failure;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        finished_ = false;
    }
    std::thread worker([&] {
        try {
            work();
        } catch (...) {
            failure = std::current_exception();
        }
        std::lock_guard<std::mutex> lock(mutex_);
        finished_ = true;
        cv_.notify_all();
    });
    std::optional<py::error_already_set> interrupt;
    // Everything below until the join catches what Python raises: the worker must be joined.
    auto stop = [&] {
        if (!interrupt) interrupt.emplace();  // fetches the raised exception
        else PyErr_Clear();
        cancel_.store(true);
    };
    for (;;) {
        bool finished;
        {
            py::gil_scoped_release release;
            std::unique_lock<std::mutex> lock(mutex_);
            cv_.wait_for(lock, std::chrono::milliseconds(20), [&] { return finished_; });
            finished = finished_;
        }
        try {
            Flush();
        } catch (py::error_already_set &e) {
            e.restore();
            stop();
        }
        if (finished) break;
        if (PyErr_CheckSignals() != 0) stop();  // Ctrl-C: KeyboardInterrupt from Python's handler
        if (hasDeadline_ && std::chrono::steady_clock::now() >= deadline_) cancel_.store(true);
    }
    worker.join();
    if (shown_) {
        py::module_::import("sys").attr("stderr").attr("write")("\n");
        shown_ = false;
    }
    if (failure) std::rethrow_exception(failure);
    return interrupt;
}

// ---- render -------------------------------------------------------------------------------------

namespace {

// What render(), render_many() and sweep() take besides the scene.
struct RenderArgs {
    std::string integrator;  // "" = the scene's own
    std::optional<int> spp, threads;
    std::optional<long long> seed;
    std::optional<std::string> sampler;
    py::object progress;
};

RenderOptions OptionsOf(const Scene &scene, const RenderArgs &a) {
    // The program's defaulting: the Render block unless given (app/render_common.h OptionsFor).
    CliOptions o;
    if (a.spp) {
        if (*a.spp < 1) throw py::value_error("'spp' must be at least 1; got " + std::to_string(*a.spp));
        o.spp = *a.spp;
    }
    if (a.seed) {
        if (*a.seed < 0) throw py::value_error("'seed' must not be negative; got " + std::to_string(*a.seed));
        o.seed = *a.seed;
    }
    if (a.threads) {
        if (*a.threads < 1) throw py::value_error("'threads' must be at least 1 (None: every core)");
        o.threads = *a.threads;
    }
    if (a.sampler) {
        CheckSampler(scene, *a.sampler);
        o.sampler = *a.sampler;
    }
    RenderOptions opt = OptionsFor(scene, o);
    opt.cancel = nullptr;
    return opt;
}

// One render to do: the scene (kept alive by `loaded`), its options, and afterwards its result.
struct Job {
    std::shared_ptr<LoadedScene> loaded;
    std::shared_ptr<const Scene> scene;
    RenderOptions opt;
    std::string label;
    RenderResult result;
    bool started = false, finished = false;
};

void RunJob(Job &job, Interruptible &run) {
    job.opt.cancel = run.Cancel();
    if (run.Cancel()->load()) return;  // stopped before this one began
    job.started = true;
    job.result = RenderToImage(*job.scene, job.loaded->Spec().path, job.opt);
    job.finished = true;
}

// The image of a finished (or stopped) job, its warnings emitted.
std::shared_ptr<PyImage> ImageOf(Job &job, const std::string &integrator) {
    if (!job.result.image) return nullptr;
    auto p = std::make_shared<PyImage>();
    p->image = std::move(*job.result.image);
    p->scene = job.loaded;
    p->integrator = integrator;
    p->warnings = RenderWarnings(*job.scene, job.result.stats, p->image);
    for (const std::string &w : p->warnings) EmitRenderWarning(w);
    return p;
}

// Runs the jobs one after the other (each on every thread, the GIL released) and returns their
// images; raises RenderCancelled after Ctrl-C (with what was rendered), RenderError when an
// integrator fails at render time, and whatever a Python kernel raised.
std::vector<std::shared_ptr<PyImage>> RunJobs(std::vector<Job> &jobs, const RenderArgs &args) {
    for (Job &job : jobs) {
        try {
            CheckMemory(*job.scene);
        } catch (const Error &e) {
            RaisePhasorError(e, "RenderError");
        }
    }
    Interruptible run(args.progress);
    for (Job &job : jobs) {
        const Detector &det = job.scene->GetDetector();
        job.opt.progress = run.Progress(job.label, job.scene->GetIntegrator().Deterministic(),
                                        (long long)det.Width() * det.Height());
        job.opt.warn = run.Warn();
    }
    std::optional<py::error_already_set> interrupt;
    try {
        interrupt = run.Run([&] {
            for (Job &job : jobs) RunJob(job, run);
        });
    } catch (const Error &e) {
        RaisePhasorError(e, "RenderError");
    }
    std::vector<std::shared_ptr<PyImage>> images;
    for (Job &job : jobs) images.push_back(job.started ? ImageOf(job, args.integrator) : nullptr);
    if (interrupt) {
        if (!interrupt->matches(PyExc_KeyboardInterrupt)) throw *interrupt;
        std::shared_ptr<PyImage> partial;
        for (std::size_t i = 0; i < jobs.size(); ++i)
            if (jobs[i].started) partial = images[i];
        py::list all;
        for (auto &img : images) all.append(img ? py::cast(img) : py::object(py::none()));
        const std::string what = partial ? "the partial image is in .image" : "no image (the render had nothing honest to show yet)";
        RaiseError("RenderCancelled", py::make_tuple("render stopped by KeyboardInterrupt; " + what,
                                                     partial ? py::cast(partial) : py::object(py::none()), all));
    }
    return images;
}

RenderArgs ArgsOf(const py::object &integrator, std::optional<int> spp, std::optional<long long> seed,
                  std::optional<int> threads, std::optional<std::string> sampler, py::object progress) {
    RenderArgs a;
    if (!integrator.is_none()) a.integrator = integrator.cast<std::string>();
    a.spp = spp;
    a.seed = seed;
    a.threads = threads;
    a.sampler = std::move(sampler);
    a.progress = std::move(progress);
    return a;
}

// Loads each variant of `base` (one load per defines dict, merged over base's) for the integrator,
// the GIL released; raises SceneError for the first that fails, before anything is rendered.
std::vector<Job> LoadJobs(const LoadSpec &base, const py::list &defineSets, const RenderArgs &args) {
    std::vector<LoadSpec> specs;
    for (py::handle d : defineSets) {
        LoadSpec s = base;
        AddDefines(s, py::reinterpret_borrow<py::object>(d));
        specs.push_back(std::move(s));
    }
    std::vector<Job> jobs(specs.size());
    std::vector<Diagnostics> diags;
    for (const LoadSpec &s : specs) diags.emplace_back(s.strict);
    std::size_t failed = specs.size();
    {
        py::gil_scoped_release release;
        for (std::size_t i = 0; i < specs.size() && failed == specs.size(); ++i) {
            jobs[i].loaded = LoadedScene::LoadQuietly(specs[i], diags[i], args.integrator);
            if (!jobs[i].loaded) failed = i;
        }
    }
    if (failed < specs.size()) RaiseSceneError(diags[failed], specs[failed].path);
    for (std::size_t i = 0; i < jobs.size(); ++i) {
        EmitWarnings(diags[i], &jobs[i].loaded->EmittedWarnings());
        jobs[i].scene = jobs[i].loaded->For(args.integrator);
        jobs[i].opt = OptionsOf(*jobs[i].scene, args);
        jobs[i].label = "[" + std::to_string(i + 1) + "/" + std::to_string(jobs.size()) + "]";
    }
    return jobs;
}

constexpr const char *RenderDoc = R"doc(
Renders the scene -> Image, as `phasor render` does (the same film, render loop and metadata: an
image equal bit for bit to the program's EXR at the same integrator, spp, seed and sampler).

integrator: a plug-in name or the @name of one of the scene's integrators (None: the scene's own),
as --integrator. spp, seed, sampler (a sampler plug-in such as 'sobol' or 'independent', or one of
the scene's Sampler blocks, as --sampler): None takes the scene's Render block.
threads: None for every core. progress: True draws the program's progress bar on sys.stderr, a
callable(done, total) receives the samples per pixel done (rs: its steps), False shows nothing.

The GIL is released while rendering. Ctrl-C (KeyboardInterrupt) stops the render within about a
second and raises phasor.RenderCancelled, a KeyboardInterrupt whose .image is the partial image
(metadata["phasor:cancelled"] == "true"). An integrator that refuses the scene at render time
raises phasor.RenderError; an exception raised by a kernel written in Python stops the render and
is raised as it is. Warnings (a black image and its likely cause, discarded samples) go through
Python's warnings module as phasor.RenderWarning.)doc";

}  // namespace

void BindRender(py::module_ &m) {
    py::class_<LoadedScene, std::shared_ptr<LoadedScene>> scene =
        py::reinterpret_borrow<py::class_<LoadedScene, std::shared_ptr<LoadedScene>>>(m.attr("Scene"));
    scene.def(
        "render",
        [](const std::shared_ptr<LoadedScene> &s, const py::object &integrator, std::optional<int> spp,
           std::optional<long long> seed, std::optional<int> threads, std::optional<std::string> sampler,
           py::object progress) {
            const RenderArgs args = ArgsOf(integrator, spp, seed, threads, std::move(sampler), std::move(progress));
            std::vector<Job> jobs(1);
            jobs[0].loaded = s;
            jobs[0].scene = s->For(args.integrator);
            jobs[0].opt = OptionsOf(*jobs[0].scene, args);
            return RunJobs(jobs, args)[0];
        },
        py::arg("integrator") = py::none(), py::kw_only(), py::arg("spp") = py::none(), py::arg("seed") = py::none(),
        py::arg("threads") = py::none(), py::arg("sampler") = py::none(), py::arg("progress") = true, RenderDoc);

    scene.def(
        "render_many",
        [](const std::shared_ptr<LoadedScene> &s, const py::list &defines, const py::object &integrator,
           std::optional<int> spp, std::optional<long long> seed, std::optional<int> threads,
           std::optional<std::string> sampler, py::object progress) {
            const RenderArgs args = ArgsOf(integrator, spp, seed, threads, std::move(sampler), std::move(progress));
            std::vector<Job> jobs = LoadJobs(s->Spec(), defines, args);
            return RunJobs(jobs, args);
        },
        py::arg("defines"), py::arg("integrator") = py::none(), py::kw_only(), py::arg("spp") = py::none(),
        py::arg("seed") = py::none(), py::arg("threads") = py::none(), py::arg("sampler") = py::none(),
        py::arg("progress") = true, R"doc(
Renders one variant of the scene per dict of `defines` (each merged over the scene's own defines;
one load per variant) -> list of Images, in order. Every variant is loaded first (a SceneError
names the first that fails, before anything is rendered); then they render one after the other,
each on every thread, the GIL released. Ctrl-C raises phasor.RenderCancelled with .images: the
finished images, the partial one, None for those not started. Other arguments as render().)doc");

    m.def(
        "sweep",
        [](const py::object &path, const std::string &name, const py::iterable &values, const py::object &defines,
           const py::object &integrator, std::optional<int> spp, std::optional<long long> seed,
           std::optional<int> threads, std::optional<std::string> sampler, py::object progress, bool strict,
           bool permissive) {
            LoadSpec base;
            base.path = py::str(py::module_::import("os").attr("fspath")(path));
            base.strict = strict;
            base.permissive = permissive;
            AddDefines(base, defines);
            py::list sets;
            for (py::handle v : values) {
                py::dict d;
                d[py::str(name)] = v;
                sets.append(d);
            }
            const RenderArgs args = ArgsOf(integrator, spp, seed, threads, std::move(sampler), std::move(progress));
            std::vector<Job> jobs = LoadJobs(base, sets, args);
            return RunJobs(jobs, args);
        },
        py::arg("path"), py::arg("name"), py::arg("values"), py::arg("defines") = py::none(),
        py::arg("integrator") = py::none(), py::kw_only(), py::arg("spp") = py::none(), py::arg("seed") = py::none(),
        py::arg("threads") = py::none(), py::arg("sampler") = py::none(), py::arg("progress") = true,
        py::arg("strict") = false, py::arg("permissive") = false, R"doc(
Renders the scene file at `path` once per value of the Define `name` -> list of Images:
sweep("double_slit.wscene", "d", ["100um", "200um"]) or sweep(..., "d", [1e-4, 2e-4]) (numbers in
SI units). `defines` holds further fixed defines. As Scene.render_many (one load per value, the
GIL released, Ctrl-C -> phasor.RenderCancelled with .images); other arguments as render().)doc");

    m.def(
        "geometry_cache",
        [](bool clear) {
            const GeometryCacheStats s = GetGeometryCacheStats();
            py::dict d;
            d["mesh_builds"] = s.meshBuilds;
            d["mesh_reuses"] = s.meshReuses;
            d["bvh_builds"] = s.bvhBuilds;
            d["bvh_reuses"] = s.bvhReuses;
            if (clear) ClearGeometryCache();
            return d;
        },
        py::arg("clear") = false, R"doc(
How often this process built and reused geometry -> {"mesh_builds", "mesh_reuses", "bvh_builds",
"bvh_reuses"}. Meshes (subdivision surfaces, OBJ files, ...) and the BVH are built once per process
and shared by every scene whose geometry is the same (a sweep over a material Define builds them
once); a Define that changes the geometry, or a mesh file rewritten on disk, builds them again.
clear=True then drops the cache's own references to recently used geometry (up to about 1 GiB of
meshes and 1 GiB of BVHs; scenes alive keep theirs) and zeroes the counts.)doc");
}

}  // namespace phasor::python
