// SPDX-License-Identifier: Apache-2.0
// phasor's Python module: phasor.compare — `phasor compare` from Python. Each run renders through
// the program's RenderCompareRun (app/compare.h: equal spp or equal time, convergence snapshots),
// the reference and the errors come from its ComputeErrors and the report from its
// StageCompareOutputs (app/compare_report.h); this file only calls them in the program's order.
#include <pybind11/stl.h>

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "app/compare.h"
#include "app/compare_report.h"
#include "core/image/image_io.h"
#include "core/image/output_file.h"
#include "python/common.h"

namespace phasor::python {

namespace {

namespace fs = std::filesystem;

// The result: the runs as `phasor compare` has them, the reference, and the scene they came from.
struct Comparison {
    std::shared_ptr<LoadedScene> scene;
    std::vector<CompareRun> runs;
    CompareReference ref;
    std::optional<Image> refImage;
    CompareReport report;
    std::map<std::string, std::shared_ptr<PyImage>> images;  // by run name (sharing nothing with runs)
};

const char *StatusName(CompareRun::Status s) {
    switch (s) {
        case CompareRun::Status::Done: return "ok";
        case CompareRun::Status::Interrupted: return "interrupted";
        case CompareRun::Status::Failed: return "failed";
        case CompareRun::Status::NotRun: return "not_run";
    }
    return "not_run";
}

py::object Maybe(bool known, double v) { return known ? py::object(py::float_(v)) : py::object(py::none()); }

// One row of the error table: the columns of results.csv, as numbers (None where it has none).
py::dict Row(const CompareRun &r) {
    py::dict d;
    d["integrator"] = r.name;
    d["role"] = r.isReference ? "reference" : "compared";
    d["status"] = StatusName(r.status);
    const bool rendered = r.status == CompareRun::Status::Done || r.status == CompareRun::Status::Interrupted;
    const bool sampled = rendered && !r.deterministic && r.image;
    d["spp"] = sampled ? py::object(py::int_(r.sppReached)) : py::object(py::none());
    d["seconds"] = Maybe(rendered, r.seconds);
    const double pixels = r.image ? double(r.image->width) * r.image->height : 0;
    d["samples_per_second"] = Maybe(sampled && r.seconds > 0, double(r.sppReached) * pixels / r.seconds);
    d["rmse"] = Maybe(bool(r.metrics), r.metrics ? r.metrics->rmse : 0);
    d["rel_mse"] = Maybe(bool(r.metrics), r.metrics ? r.metrics->relMse : 0);
    d["max_error"] = Maybe(bool(r.metrics), r.metrics ? r.metrics->maxError : 0);
    d["error"] = r.error;
    return d;
}

std::vector<std::string> WriteReport(Comparison &c, const std::string &dir) {
    std::vector<std::string> written;
    try {
        py::gil_scoped_release release;
        CheckWritable((fs::path(dir) / "index.html").string());
        CompareReport report = c.report;
        report.dir = dir;
        OutputFiles files;
        written = StageCompareOutputs(files, c.runs, c.ref, c.refImage ? &*c.refImage : nullptr, report);
        files.Commit();
    } catch (const Error &e) {
        RaisePhasorError(e);
    }
    for (std::string &w : written) w = (fs::path(dir) / w).string();
    return written;
}

// The Python image of a run (its own copy of the pixels: the runs keep theirs for the report).
std::shared_ptr<PyImage> ImageOfRun(const CompareRun &r, const std::shared_ptr<LoadedScene> &scene) {
    auto p = std::make_shared<PyImage>();
    p->image = *r.image;
    p->scene = scene;
    p->integrator = r.name;
    return p;
}

}  // namespace

void BindCompare(py::module_ &m) {
    py::class_<Comparison, std::shared_ptr<Comparison>> cls(m, "Comparison", R"doc(
The result of phasor.compare: the images, the reference and the error table of `phasor compare`.)doc");
    cls.def_property_readonly(
           "images",
           [](const Comparison &c) {
               py::dict d;
               for (const CompareRun &r : c.runs)
                   if (auto it = c.images.find(r.name); it != c.images.end()) d[py::str(r.name)] = it->second;
               return d;
           },
           "{integrator: Image} for every run that produced an image (the reference run's too).")
        .def_property_readonly(
            "table", [](const Comparison &c) {
                py::list rows;
                for (const CompareRun &r : c.runs) rows.append(Row(r));
                return rows;
            },
            R"doc(The error table as a list of dicts, one per run, with the columns of results.csv: integrator,
role ("reference" | "compared"), status ("ok", "interrupted", "failed", "not_run"), spp, seconds,
samples_per_second, rmse, rel_mse, max_error (errors of `intensity` against the reference:
docs/compare.md), error (a failed integrator's message); None where a run has no value.)doc")
        .def_property_readonly(
            "reference",
            [](const Comparison &c) {
                py::dict d;
                d["name"] = c.ref.name;
                d["description"] = c.ref.description;
                return d;
            },
            "What the runs are compared against: {name, description}.")
        .def_property_readonly("mode", [](const Comparison &c) { return c.report.mode; },
                               "\"equal samples: …\" or \"equal time: …\".")
        .def_property_readonly("scene", [](const Comparison &c) { return c.scene; }, "The Scene compared.")
        .def_property_readonly(
            "convergence",
            [](const Comparison &c) {
                py::list rows;
                for (const CompareRun &r : c.runs)
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
            "write_report", [](Comparison &c, const py::object &dir) {
                return WriteReport(c, py::str(py::module_::import("os").attr("fspath")(dir)));
            },
            py::arg("directory"), R"doc(
Writes what `phasor compare -o DIRECTORY` writes: each run's EXR and PNG, grid.png, the
differences, results.csv and results.md, the profile and convergence plots and index.html (all or
nothing). Returns the paths written.)doc")
        .def("__repr__", [](const Comparison &c) {
            std::ostringstream os;
            os << "<phasor.Comparison of";
            for (const CompareRun &r : c.runs) os << " " << r.name;
            os << "; reference: " << c.ref.name << ">";
            return os.str();
        });

    m.def(
        "compare",
        [](const py::object &sceneArg, const py::object &integratorsArg, std::optional<int> spp,
           const py::object &time, const py::object &reference, const py::object &referenceIntegrator,
           std::optional<int> referenceSpp, std::optional<long long> seed, std::optional<int> threads,
           std::optional<std::string> sampler, const py::object &output, std::optional<int> row,
           std::optional<int> column, py::object progress) {
            std::shared_ptr<LoadedScene> scene;
            if (py::isinstance<LoadedScene>(sceneArg)) {
                scene = sceneArg.cast<std::shared_ptr<LoadedScene>>();
            } else {
                LoadSpec spec;
                spec.path = py::str(py::module_::import("os").attr("fspath")(sceneArg));
                scene = LoadedScene::Load(spec);
            }
            // The integrators, each a name a run can pick (before anything is rendered).
            std::vector<std::string> integrators;
            if (py::isinstance<py::str>(integratorsArg)) {
                const std::string s = integratorsArg.cast<std::string>();
                if (s == "all") integrators = Registry<Integrator>::Names();
                else integrators = {s};
            } else {
                integrators = integratorsArg.cast<std::vector<std::string>>();
            }
            if (integrators.empty()) throw py::value_error("'integrators' names no integrator");
            const std::string refName = referenceIntegrator.is_none() ? "" : referenceIntegrator.cast<std::string>();
            const std::vector<std::string> choices = IntegratorChoices(scene->Desc());
            std::vector<std::string> names = integrators;
            if (!refName.empty()) names.push_back(refName);
            for (const std::string &n : names)
                if (std::find(choices.begin(), choices.end(), n) == choices.end()) {
                    const std::string sug = Suggest(n, choices);
                    std::string all;
                    for (const std::string &k : choices) all += " " + k;
                    throw py::value_error("unknown integrator '" + n + "'" +
                                          (sug.empty() ? "" : "; did you mean '" + sug + "'?") +
                                          " (integrators:" + all + ")");
                }
            double seconds = 0;
            if (!time.is_none()) {
                seconds = Quantity(time, Dim::Time(), "time", "10s");
                if (!(seconds > 0)) throw py::value_error("'time' must be positive");
                if (spp) throw py::value_error("give 'spp' (equal samples) or 'time' (equal time), not both");
            }

            auto c = std::make_shared<Comparison>();
            c->scene = scene;
            if (!reference.is_none()) {
                try {
                    c->refImage = py::isinstance<PyImage>(reference)
                                      ? reference.cast<const PyImage &>().image
                                      : ReadImage(py::str(py::module_::import("os").attr("fspath")(reference)));
                    c->ref.values = ChannelValues(*c->refImage, "intensity");
                } catch (const Error &e) {
                    RaisePhasorError(e);
                }
                const std::string given = py::isinstance<PyImage>(reference) ? std::string("the image given")
                                                                              : "the image '" + py::str(reference).cast<std::string>() + "'";
                c->ref.description = given;
                c->ref.name = "reference image";
            }
            if (!refName.empty()) {
                CompareRun r;
                r.name = refName;
                r.file = "reference_" + refName;
                r.isReferenceRun = true;
                c->runs.push_back(std::move(r));
            }
            for (const std::string &n : integrators) {
                CompareRun r;
                r.name = n;
                r.file = n;
                c->runs.push_back(std::move(r));
            }
            for (CompareRun &r : c->runs)
                for (char &ch : r.file)
                    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_' && ch != '-') ch = '_';

            // As `phasor compare`: snapshots compared at once with a known reference, else kept within
            // a quarter of the available memory (at most 1 GB).
            SnapshotContext snap;
            snap.reference = c->refImage ? &c->ref.values : nullptr;
            snap.bytesLeft = std::min(1e9, AvailableMemory() / 4);
            Interruptible run(progress);
            int sceneSpp = 0;
            std::optional<py::error_already_set> interrupt;
            for (std::size_t i = 0; i < c->runs.size() && !interrupt; ++i) {
                CompareRun &r = c->runs[i];
                Diagnostics diag(scene->Spec().strict);
                std::shared_ptr<const Scene> built;
                {
                    py::gil_scoped_release release;
                    built = scene->ForQuietly(r.name, diag);
                }
                if (!built) {  // this integrator cannot render the scene: the others still run
                    r.status = CompareRun::Status::Failed;
                    for (const Diagnostic &d : diag.All())
                        if (d.severity == Severity::Error) {
                            r.error = d.message;
                            break;
                        }
                    continue;
                }
                EmitWarnings(diag, &scene->EmittedWarnings());
                const Detector &det = built->GetDetector();
                if (c->report.width == 0) {
                    c->report.width = det.Width();
                    c->report.height = det.Height();
                    c->report.radiometric = det.Response().GetKind() == SensorResponse::Kind::Radiometric;
                    c->report.detector = det.name;
                    sceneSpp = built->Settings().spp;
                    if (c->refImage && (c->refImage->width != det.Width() || c->refImage->height != det.Height()))
                        throw py::value_error("the reference image is " + std::to_string(c->refImage->width) + "x" +
                                              std::to_string(c->refImage->height) + " pixels but detector '" +
                                              det.name + "' renders " + std::to_string(det.Width()) + "x" +
                                              std::to_string(det.Height()));
                    try {
                        CheckMemory(*built);
                    } catch (const Error &e) {
                        RaisePhasorError(e, "RenderError");
                    }
                }
                CliOptions o;
                o.spp = r.isReferenceRun ? referenceSpp.value_or(-1) : spp.value_or(-1);
                o.seed = seed.value_or(-1);
                o.threads = threads.value_or(0);
                o.sampler = sampler.value_or("");
                CompareRunSettings s;
                s.options = OptionsFor(*built, o);
                s.budget = r.isReferenceRun ? 0 : seconds;
                s.scenePath = scene->Spec().path;
                s.stop = run.Cancel();
                const bool timed = s.budget > 0 && !built->GetIntegrator().Deterministic();
                const std::string label = "[" + std::to_string(i + 1) + "/" + std::to_string(c->runs.size()) + "] " + r.name;
                s.options.progress = run.Progress(label, built->GetIntegrator().Deterministic(),
                                                  (long long)det.Width() * det.Height(), timed ? s.budget : 0);
                if (!timed) s.options.warn = run.Warn();
                RenderStats st;
                try {
                    interrupt = run.Run([&] { st = RenderCompareRun(r, *built, s, snap); });
                } catch (const Error &) {
                    continue;  // the run is Failed with the integrator's message (RenderCompareRun)
                }
                if (r.image) {
                    auto img = ImageOfRun(r, scene);
                    img->warnings = RenderWarnings(*built, st, *r.image);
                    for (const std::string &w : img->warnings) EmitRenderWarning(r.name + ": " + w);
                    c->images[r.name] = img;
                }
                if (r.isReferenceRun && r.image && r.status == CompareRun::Status::Done) snap.reference = &r.intensity;
            }
            const bool any = std::any_of(c->runs.begin(), c->runs.end(), [](const CompareRun &r) { return r.image.has_value(); });
            if (any) ComputeErrors(c->runs, c->ref);
            c->report.scene = scene->Spec().path;
            c->report.mode = seconds > 0 ? "equal time: " + FormatSeconds(seconds) + " per integrator"
                             : spp       ? "equal samples: " + std::to_string(*spp) + " spp per integrator"
                                         : "equal samples: the scene's " + std::to_string(sceneSpp) + " spp per integrator";
            c->report.stopped = interrupt.has_value();
            c->report.row = row.value_or(-1);
            c->report.column = column.value_or(-1);
            std::ostringstream cmd;  // the equivalent command line, for the page
            cmd << "phasor compare " << scene->Spec().path << " --integrators ";
            for (std::size_t k = 0; k < integrators.size(); ++k) cmd << (k ? "," : "") << integrators[k];
            if (seconds > 0) cmd << " --time " << seconds;
            if (spp) cmd << " --spp " << *spp;
            if (!refName.empty()) {
                cmd << " --reference-integrator " << refName;
                if (referenceSpp) cmd << " --reference-spp " << *referenceSpp;
            }
            for (const auto &[k, v] : scene->Spec().defines) cmd << " -D " << k << "=" << v;
            if (seed) cmd << " --seed " << *seed;
            if (sampler) cmd << " --sampler " << *sampler;
            if (row) cmd << " --row " << *row;
            if (column) cmd << " --column " << *column;
            c->report.command = cmd.str();

            if (interrupt) {
                if (!interrupt->matches(PyExc_KeyboardInterrupt)) throw *interrupt;
                py::list all;
                for (const CompareRun &r : c->runs)
                    all.append(c->images.count(r.name) ? py::cast(c->images.at(r.name)) : py::object(py::none()));
                py::object e = py::module_::import("phasor._errors")
                                   .attr("RenderCancelled")("comparison stopped by KeyboardInterrupt; what finished is "
                                                            "in .comparison",
                                                            py::none(), all);
                e.attr("comparison") = c;
                PyErr_SetObject(e.get_type().ptr(), e.ptr());
                throw py::error_already_set();
            }
            if (!any) {
                std::string why;
                for (const CompareRun &r : c->runs) why += "\n  " + r.name + ": " + r.error;
                RaiseError("RenderError", py::make_tuple("no integrator could render '" + scene->Spec().path + "':" + why));
            }
            if (!output.is_none()) {
                const std::string dir = py::str(py::module_::import("os").attr("fspath")(output));
                WriteReport(*c, dir);
            }
            return c;
        },
        py::arg("scene"), py::arg("integrators"), py::kw_only(), py::arg("spp") = py::none(),
        py::arg("time") = py::none(), py::arg("reference") = py::none(), py::arg("reference_integrator") = py::none(),
        py::arg("reference_spp") = py::none(), py::arg("seed") = py::none(), py::arg("threads") = py::none(),
        py::arg("sampler") = py::none(), py::arg("output") = py::none(), py::arg("row") = py::none(),
        py::arg("column") = py::none(), py::arg("progress") = true, R"doc(
Renders a scene with several integrators and compares them, as `phasor compare` does -> Comparison
(images, error table, convergence, write_report).

scene: a Scene or a path. integrators: a list of names (plug-ins or the scene's @names), or "all".
spp: equal samples per integrator (None: the scene's); time: equal time each instead, seconds or
"10s". The reference: an image (`reference`: a path or an Image), else a run of
`reference_integrator` at `reference_spp`, else the best-converged run. output: a directory to
write the report into (Comparison.write_report). An integrator that cannot render the scene is a
failed row (its error in the table) while the others run; an unknown name is a ValueError before
anything is rendered. Ctrl-C raises phasor.RenderCancelled whose .comparison holds what finished.
Other arguments as Scene.render.)doc");
}

}  // namespace phasor::python
