// SPDX-License-Identifier: Apache-2.0
// phasor's Python module: phasor.compare — `phasor compare` from Python. It runs the program's own
// Comparison (app/compare.h) step by step — Load, RenderCompared, RenderReference, Report, and
// WriteTo on request — with CompareHooks that put its progress, warnings and Ctrl-C through
// Python and build the scene from the Scene already loaded. Nothing of the comparison is here.
#include <pybind11/stl.h>

#include <filesystem>
#include <sstream>

#include "app/compare.h"
#include "core/image/image_io.h"
#include "python/common.h"

namespace phasor::python {

namespace {

namespace fs = std::filesystem;

// The result: the program's comparison, the scene it came from and the runs' images for Python.
struct PyComparison {
    std::shared_ptr<LoadedScene> scene;
    std::unique_ptr<Comparison> c;
    py::list images;  // per run, in the order of Runs() (None without an image)
};

std::string Path(const py::handle &p) { return py::str(py::module_::import("os").attr("fspath")(p)); }

std::vector<std::string> WriteReport(PyComparison &p, const std::string &dir) {
    std::vector<std::string> written;
    try {
        py::gil_scoped_release release;
        CheckWritable((fs::path(dir) / "index.html").string());
        written = p.c->WriteTo(dir);
    } catch (const Error &e) {
        RaisePhasorError(e);
    }
    for (std::string &w : written) w = (fs::path(dir) / w).string();
    return written;
}

// The Python image of a run (its own copy of the pixels: the runs keep theirs for the report).
py::object ImageOfRun(const CompareRun &r, const PyComparison &p) {
    if (!r.image) return py::none();
    auto img = std::make_shared<PyImage>();
    img->image = *r.image;
    img->scene = p.scene;
    img->integrator = r.name;
    img->radiometric = p.c->Summary().radiometric;
    img->warnings = r.warnings;
    return py::cast(img);
}

}  // namespace

void BindCompare(py::module_ &m) {
    py::class_<PyComparison, std::shared_ptr<PyComparison>> cls(m, "Comparison", R"doc(
The result of phasor.compare: the images, the reference and the error table of `phasor compare`.)doc");
    cls.def_property_readonly(
           "_images", [](const PyComparison &p) { return p.images; },
           "The runs' images (None for a run without one), in the order of the table's rows.")
        .def_property_readonly(
            "_csv", [](const PyComparison &p) { return CompareCsv(p.c->Runs(), p.c->Reference()); },
            "results.csv as text (Comparison.table reads it).")
        .def_property_readonly(
            "reference",
            [](const PyComparison &p) {
                const CompareReference &ref = p.c->Reference();
                py::dict d;
                d["name"] = ref.name;
                d["description"] = ref.description;
                d["independence"] = ref.independence;
                d["noise_floor"] = std::isfinite(ref.noiseFloor) ? py::object(py::float_(ref.noiseFloor)) : py::none();
                d["noise_source"] = ref.noiseSource;
                d["warnings"] = ref.warnings;
                return d;
            },
            R"doc(What the runs are compared against: {name, description, independence (why its noise is
independent of the runs'), noise_floor (the RMS of its own noise; None when unknown), noise_source,
warnings}; name is "" without a reference (reference="none").)doc")
        .def_property_readonly("mode", [](const PyComparison &p) { return p.c->Summary().modeText; },
                               "\"equal samples: …\" or \"equal time: …\".")
        .def_property_readonly("scene", [](const PyComparison &p) { return p.scene; }, "The Scene compared.")
        .def_property_readonly(
            "convergence",
            [](const PyComparison &p) {
                py::list rows;
                for (const CompareRun &r : p.c->Runs())
                    for (const CompareSnapshot &s : r.snapshots) {
                        if (!s.metrics) continue;
                        py::dict d;
                        d["integrator"] = r.name;
                        d["spp"] = s.spp;
                        d["seconds"] = s.seconds;
                        d["rmse"] = s.metrics->rmse;
                        d["rel_mse"] = s.metrics->relMse;
                        d["max_error"] = s.metrics->maxError;
                        rows.append(d);
                    }
                return rows;
            },
            "The convergence curves (convergence.csv): one dict per snapshot of a sampling run: integrator, spp, "
            "seconds, rmse, rel_mse, max_error.")
        .def(
            "write_report", [](PyComparison &p, const py::object &dir) { return WriteReport(p, Path(dir)); },
            py::arg("directory"), R"doc(
Writes what `phasor compare -o DIRECTORY` writes: each run's EXR and PNG, grid.png, the
differences, results.csv, results.md and results.json, the profile and convergence plots and
index.html (all or nothing). Returns the paths written.)doc")
        .def("__repr__", [](const PyComparison &p) {
            std::ostringstream os;
            os << "<phasor.Comparison of";
            for (const CompareRun &r : p.c->Runs()) os << " " << r.name;
            os << "; reference: " << (p.c->Reference().name.empty() ? "none" : p.c->Reference().name) << ">";
            return os.str();
        });

    m.def(
        "compare",
        [](const py::object &sceneArg, const py::object &integratorsArg, std::optional<int> spp,
           const py::object &time, const py::object &reference, std::optional<std::string> referenceIntegrator,
           std::optional<int> referenceSpp, std::optional<long long> seed, std::optional<int> threads,
           std::optional<std::string> sampler, const py::object &output, std::optional<int> row,
           std::optional<int> column, py::object progress) {
            auto p = std::make_shared<PyComparison>();
            if (py::isinstance<LoadedScene>(sceneArg)) {
                p->scene = sceneArg.cast<std::shared_ptr<LoadedScene>>();
            } else {
                LoadSpec spec;
                spec.path = Path(sceneArg);
                p->scene = LoadedScene::Load(spec);
            }
            if (sampler) CheckSampler(*p->scene->For(""), *sampler);
            const LoadSpec &spec = p->scene->Spec();
            // The command line this comparison is (its report prints it, to rerun it).
            CliOptions o;
            o.scene = spec.path;
            o.defines = spec.defines;
            o.strict = spec.strict;
            o.permissive = spec.permissive;
            o.quiet = true;
            o.spp = spp.value_or(-1);
            o.seed = seed.value_or(-1);
            o.threads = threads.value_or(0);
            o.sampler = sampler.value_or("");
            if (!output.is_none()) o.output = Path(output);
            CliOptions::CompareOptions &c = o.compare;
            c.integrators = py::isinstance<py::str>(integratorsArg)
                                ? std::vector<std::string>{integratorsArg.cast<std::string>()}
                                : integratorsArg.cast<std::vector<std::string>>();
            if (c.integrators.empty()) throw py::value_error("'integrators' names no integrator");
            if (!time.is_none()) {
                c.seconds = Quantity(time, Dim::Time(), "time", "10s");
                if (!(c.seconds > 0)) throw py::value_error("'time' must be positive");
                if (spp) throw py::value_error("give 'spp' (equal samples) or 'time' (equal time), not both");
            }
            c.referenceIntegrator = referenceIntegrator.value_or("");
            c.referenceSpp = referenceSpp.value_or(0);
            c.row = row.value_or(-1);
            c.column = column.value_or(-1);

            Interruptible run(progress);
            CompareHooks hooks;
            hooks.stop = run.Cancel();
            hooks.stopName = "KeyboardInterrupt";
            hooks.progress = [&run](const std::string &label, bool deterministic, long long pixels, double budget) {
                return run.Progress(label, deterministic, pixels, budget);
            };
            hooks.warn = run.Warn();
            hooks.desc = &p->scene->Desc();
            hooks.build = [scene = p->scene](const std::string &integrator, Diagnostics &diag) {
                return scene->ForQuietly(integrator, diag);
            };
            hooks.print = false;
            if (!reference.is_none()) {
                if (py::isinstance<PyImage>(reference)) {
                    hooks.referenceImage = reference.cast<const PyImage &>().image;
                    c.reference = "(an Image)";
                } else if (py::isinstance<py::str>(reference) && reference.cast<std::string>() == "none") {
                    c.reference = "none";
                } else {
                    c.reference = Path(reference);
                }
            }
            p->c = std::make_unique<Comparison>(o, std::move(hooks));
            Comparison &cmp = *p->c;
            bool loaded = false, rendered = false, reported = false;
            std::optional<py::error_already_set> interrupt = run.Run([&] {
                loaded = cmp.Load();
                if (!loaded) return;
                rendered = cmp.RenderCompared();
                if (!rendered) return;
                cmp.RenderReference();
                reported = cmp.Report();
            });
            for (const CompareRun &r : cmp.Runs()) p->images.append(ImageOfRun(r, *p));
            if (interrupt) {
                if (!interrupt->matches(PyExc_KeyboardInterrupt)) throw *interrupt;
                py::object e = py::module_::import("phasor._errors")
                                   .attr("RenderCancelled")("comparison stopped by KeyboardInterrupt; what finished is "
                                                            "in .comparison",
                                                            py::none(), p->images);
                e.attr("comparison") = p;
                PyErr_SetObject(e.get_type().ptr(), e.ptr());
                throw py::error_already_set();
            }
            if (!loaded) throw py::value_error(cmp.Failure());
            if (!rendered) RaiseError("RenderError", py::make_tuple(cmp.Failure()));
            if (!reported) {
                std::string why = cmp.Failure();
                for (const CompareRun &r : cmp.Runs())
                    if (!r.error.empty()) why += "\n  " + r.name + ": " + r.error;
                RaiseError("RenderError", py::make_tuple(why));
            }
            if (!o.output.empty()) WriteReport(*p, o.output);
            return p;
        },
        py::arg("scene"), py::arg("integrators"), py::kw_only(), py::arg("spp") = py::none(),
        py::arg("time") = py::none(), py::arg("reference") = py::none(), py::arg("reference_integrator") = py::none(),
        py::arg("reference_spp") = py::none(), py::arg("seed") = py::none(), py::arg("threads") = py::none(),
        py::arg("sampler") = py::none(), py::arg("output") = py::none(), py::arg("row") = py::none(),
        py::arg("column") = py::none(), py::arg("progress") = true, R"doc(
Renders a scene with several integrators and compares them: `phasor compare` itself (the same
steps, reference and errors; docs/compare.md) -> Comparison (images, table, convergence,
write_report).

scene: a Scene or a path. integrators: a list of names (plug-ins or the scene's @names), or "all".
spp: equal samples per integrator (None: the scene's); time: equal time each instead, seconds or
"10s". The reference: an image (`reference`: a path or an Image), "none" (the runs side by side,
no errors), else a complete deterministic run (rs), else independent renders of
`reference_integrator` (default: the first wave-optical sampling integrator compared) at
`reference_spp` samples in all (default: 4x the runs'). output: a directory to write the report
into (Comparison.write_report). An integrator that cannot render the scene is a failed row (its
error in the table) while the others run; an unknown name is a ValueError before anything is
rendered. Ctrl-C raises phasor.RenderCancelled whose .comparison holds what finished. Other
arguments as Scene.render.)doc");
}

}  // namespace phasor::python
