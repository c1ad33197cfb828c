// SPDX-License-Identifier: Apache-2.0
// phasor's Python module: loading scenes (phasor.load, phasor.load_string), their diagnostics as
// exceptions and warnings, quantities with units, and the Scene class.
#include <pybind11/stl.h>

#include <cmath>
#include <sstream>

#include "python/common.h"

namespace phasor::python {

namespace {

py::object ErrorsModule() { return py::module_::import("phasor._errors"); }

const char *SeverityName(Severity s) {
    switch (s) {
        case Severity::Note: return "note";
        case Severity::Warning: return "warning";
        case Severity::Error: return "error";
    }
    return "error";
}

py::object ToPython(const Diagnostics &diag, const Diagnostic &d) {
    py::list notes;
    for (const Diagnostic &n : d.notes) notes.append(ToPython(diag, n));
    return ErrorsModule().attr("Diagnostic")(SeverityName(d.severity), d.loc.file, d.loc.line, d.loc.col, d.message,
                                             diag.Format(d), notes);
}

}  // namespace

[[noreturn]] void RaiseError(const char *name, py::tuple args) {
    py::object cls = ErrorsModule().attr(name);
    py::object e = cls(*args);
    PyErr_SetObject(cls.ptr(), e.ptr());
    throw py::error_already_set();
}

[[noreturn]] void RaisePhasorError(const Error &e, const char *cls) {
    const FileLoc &l = e.Loc();
    std::string text = e.Message();
    if (l.Known()) {  // "file:line:col: error: …" with the source line, as the program prints it
        Diagnostics located;
        located.Report(e);
        std::ostringstream os;
        located.Print(os);
        text = os.str();
        while (!text.empty() && text.back() == '\n') text.pop_back();
    }
    RaiseError(cls, py::make_tuple(text, l.file, l.line, l.col, e.Message()));
}

[[noreturn]] void RaiseSceneError(const Diagnostics &diag, const std::string &scene) {
    std::ostringstream os;
    diag.Print(os);
    const std::size_t n = diag.ErrorCount();
    os << n << " error" << (n == 1 ? "" : "s") << " in '" << scene << "'";
    py::list errors;
    for (const Diagnostic &d : diag.All())
        if (d.severity == Severity::Error) errors.append(ToPython(diag, d));
    RaiseError("SceneError", py::make_tuple(os.str(), errors, n));
}

void EmitWarnings(const Diagnostics &diag, std::vector<std::string> *emitted) {
    py::object warn = py::module_::import("warnings").attr("warn");
    py::object cls = ErrorsModule().attr("SceneWarning");
    for (const Diagnostic &d : diag.All()) {
        if (d.severity != Severity::Warning) continue;
        std::string text = diag.Format(d);
        while (!text.empty() && text.back() == '\n') text.pop_back();
        if (emitted) {
            if (std::find(emitted->begin(), emitted->end(), text) != emitted->end()) continue;
            emitted->push_back(text);
        }
        warn(cls(text, ToPython(diag, d)), py::arg("stacklevel") = 1);
    }
}

void EmitRenderWarning(const std::string &message) {
    py::module_::import("warnings").attr("warn")(ErrorsModule().attr("RenderWarning")(message),
                                                 py::arg("stacklevel") = 1);
}

void CheckSampler(const Scene &scene, const std::string &sampler) {
    if (scene.NewSampler(sampler, 0)) return;
    const std::string s = Suggest(sampler, scene.SamplerNames());
    throw py::value_error("unknown sampler '" + sampler + "'" + (s.empty() ? "" : "; did you mean '" + s + "'?"));
}

double Quantity(py::handle value, Dim dim, const std::string &what, const char *example) {
    const std::string expects = "'" + what + "' expects " + dim.Describe() + " (a string such as '" + example +
                                "', or a number in SI units)";
    if (py::isinstance<py::bool_>(value)) throw py::value_error(expects + "; got a boolean");
    if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)) {
        const double v = value.cast<double>();
        if (!std::isfinite(v)) throw py::value_error("'" + what + "' must be finite; got " + std::to_string(v));
        return v;
    }
    if (!py::isinstance<py::str>(value))
        throw py::value_error(expects + "; got " + std::string(py::str(py::type::of(value).attr("__name__"))));
    const std::string text = value.cast<std::string>();
    Diagnostics diag;
    std::optional<Value> v = ParseValueString(text, what, diag);
    std::string why;
    for (const Diagnostic &d : diag.All())
        if (d.severity == Severity::Error && why.empty()) why = d.message;
    const std::string got = "; got '" + text + "'";
    if (!v || !why.empty()) throw py::value_error(expects + got + (why.empty() ? "" : " (" + why + ")"));
    if (v->kind != Value::Kind::Number) throw py::value_error(expects + got + ", " + v->DescribeKind());
    if (!(v->dim == dim))
        throw py::value_error(expects + got + ", " +
                              (v->dim.IsNone() ? std::string("a number without a unit") : v->dim.Describe()));
    if (!std::isfinite(v->number)) throw py::value_error(expects + got + ", which is not finite");
    return v->number;
}

// ---- loading ------------------------------------------------------------------------------------

std::shared_ptr<LoadedScene> LoadedScene::LoadQuietly(const LoadSpec &spec, Diagnostics &diag,
                                                     const std::string &integrator) {
    // As the program's Load (app/render_common.h): parse with the defines, keeping what was read
    // cleanly after errors so that one run reports parse and build errors together, then build.
    diag.SetPermissive(spec.permissive);
    ParseOptions parse;
    parse.defines = spec.defines;
    parse.siDefines = spec.siDefines;
    parse.partial = true;
    std::optional<SceneDesc> desc;
    try {
        desc = spec.text ? ParseSceneString(*spec.text, spec.path, parse, diag) : ParseSceneFile(spec.path, parse, diag);
    } catch (const std::bad_alloc &) {
        diag.Error(FileLoc{spec.path, 0, 0, 1}, "out of memory while loading the scene");
    }
    if (!desc) return nullptr;
    std::unique_ptr<Scene> scene = BuildSceneQuietly(spec.path, *desc, diag, integrator);
    if (!scene || diag.HasErrors()) return nullptr;
    auto loaded = std::make_shared<LoadedScene>();
    loaded->spec_ = spec;
    loaded->desc_ = std::move(*desc);
    loaded->built_[integrator] = std::move(scene);
    return loaded;
}

std::shared_ptr<LoadedScene> LoadedScene::Load(const LoadSpec &spec, const std::string &integrator) {
    Diagnostics diag(spec.strict);
    std::shared_ptr<LoadedScene> loaded;
    {
        py::gil_scoped_release release;
        loaded = LoadQuietly(spec, diag, integrator);
    }
    if (!loaded) RaiseSceneError(diag, spec.path);
    EmitWarnings(diag, &loaded->emitted_);
    return loaded;
}

std::shared_ptr<const Scene> LoadedScene::ForQuietly(const std::string &integrator, Diagnostics &diag) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (auto it = built_.find(integrator); it != built_.end()) return it->second;
    diag.SetPermissive(spec_.permissive);
    std::unique_ptr<Scene> scene = BuildSceneQuietly(spec_.path, desc_, diag, integrator);
    if (!scene || diag.HasErrors()) return nullptr;
    return built_.emplace(integrator, std::move(scene)).first->second;
}

std::shared_ptr<const Scene> LoadedScene::For(const std::string &integrator) {
    Diagnostics diag(spec_.strict);
    std::shared_ptr<const Scene> scene;
    {
        py::gil_scoped_release release;
        scene = ForQuietly(integrator, diag);
    }
    if (!scene) RaiseSceneError(diag, spec_.path);
    EmitWarnings(diag, &emitted_);
    return scene;
}

// The defines of a Python call: {"d": "150um", "n": 3, "lambda": 5.5e-7, "film": "Cu2O"}. Strings
// are scene-language text (as after -D); numbers are SI (ParseOptions::siDefines); booleans
// true/false.
void AddDefines(LoadSpec &spec, const py::object &defines) {
    if (defines.is_none()) return;
    if (!py::isinstance<py::dict>(defines)) throw py::type_error("'defines' must be a dict {name: value}");
    for (auto [k, v] : defines.cast<py::dict>()) {
        if (!py::isinstance<py::str>(k)) throw py::type_error("a define's name must be a string");
        const std::string name = k.cast<std::string>();
        std::string text;
        bool si = false;
        if (py::isinstance<py::bool_>(v)) {
            text = v.cast<bool>() ? "true" : "false";
        } else if (py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v)) {
            // repr of an int, or of a float (which round-trips exactly)
            text = py::repr(v).cast<std::string>();
            si = true;
        } else if (py::isinstance<py::str>(v)) {
            text = v.cast<std::string>();
        } else {
            throw py::type_error("define '" + name + "': expected a string (scene-language text such as '150um'), "
                                 "a number (SI units) or a boolean; got " +
                                 std::string(py::str(py::type::of(v).attr("__name__"))));
        }
        // A later value for the same name replaces the earlier one (dict merging).
        for (auto it = spec.defines.begin(); it != spec.defines.end();)
            it = it->first == name ? spec.defines.erase(it) : it + 1;
        std::erase(spec.siDefines, name);
        spec.defines.emplace_back(name, text);
        if (si) spec.siDefines.push_back(name);
    }
}

namespace {

py::dict DefinesDict(const LoadSpec &spec) {
    py::dict d;
    for (const auto &[k, v] : spec.defines) {
        const bool si = std::find(spec.siDefines.begin(), spec.siDefines.end(), k) != spec.siDefines.end();
        if (si) d[py::str(k)] = py::module_::import("ast").attr("literal_eval")(v);  // the number given
        else d[py::str(k)] = v;
    }
    return d;
}

std::string PathString(const py::object &path) {
    return py::str(py::module_::import("os").attr("fspath")(path)).cast<std::string>();
}

}  // namespace

/// A Scene holder with the LoadedScene it wraps (pybind11's holder: shared_ptr).
void BindScene(py::module_ &m) {
    py::class_<LoadedScene, std::shared_ptr<LoadedScene>> scene(m, "Scene", R"doc(
A loaded .wscene scene (phasor.load, phasor.load_string): parsed once, built for its own
integrator at load and for every other integrator the first time one is asked for. Images and
probes made from it keep it alive.)doc");
    scene.def_property_readonly("path", [](const LoadedScene &s) { return s.Spec().path; },
                                "The scene file (or the name given to load_string).")
        .def_property_readonly("defines", [](const LoadedScene &s) { return DefinesDict(s.Spec()); },
                               "The defines the scene was loaded with, as given.")
        .def_property_readonly("strict", [](const LoadedScene &s) { return s.Spec().strict; },
                               "Whether every warning was an error.")
        .def_property_readonly(
            "settings",
            [](LoadedScene &s) {
                const RenderSettings &r = s.For("")->Settings();
                py::dict d;
                d["spp"] = r.options.spp;
                d["seed"] = r.options.seed;
                d["sampler"] = r.options.sampler;
                d["output"] = r.output;
                return d;
            },
            "The scene's Render block: spp, seed, sampler, output (what render() uses by default).")
        .def_property_readonly(
            "integrator", [](LoadedScene &s) { return s.For("")->GetIntegrator().name; },
            "The name of the integrator the scene chooses (Render.integrator, its only one, else `ray`).")
        .def_property_readonly(
            "detector",
            [](LoadedScene &s) {
                const Detector &det = s.For("")->GetDetector();
                py::dict d;
                d["name"] = det.name;
                d["width"] = det.Width();
                d["height"] = det.Height();
                d["response"] = det.Response().Name();
                d["radiometric"] = det.Response().GetKind() == SensorResponse::Kind::Radiometric;
                return d;
            },
            "The detector rendered: name, width, height, response, radiometric (False for a camera's RGB).")
        .def_property_readonly(
            "entities",
            [](const LoadedScene &s) {
                py::list out;
                for (const SceneEntity &e : s.Desc().entities) {
                    py::dict d;
                    d["keyword"] = e.keyword;
                    d["type"] = e.type;
                    d["name"] = e.name;
                    d["file"] = e.loc.file;
                    d["line"] = e.loc.line;
                    out.append(d);
                }
                return out;
            },
            "Every entity of the scene description, in source order: keyword, type, name, file, line.")
        .def("__repr__", [](LoadedScene &s) {
            const Detector &det = s.For("")->GetDetector();
            return "<phasor.Scene '" + s.Spec().path + "': " + std::to_string(det.Width()) + "x" +
                   std::to_string(det.Height()) + " " + det.name + ", integrator " + s.For("")->GetIntegrator().name +
                   ">";
        });

    m.def(
        "load",
        [](const py::object &path, const py::object &defines, bool strict, bool permissive) {
            if (strict && permissive) throw py::value_error("'strict' and 'permissive' contradict each other");
            LoadSpec spec;
            spec.path = PathString(path);
            spec.strict = strict;
            spec.permissive = permissive;
            AddDefines(spec, defines);
            return LoadedScene::Load(spec);
        },
        py::arg("path"), py::arg("defines") = py::none(), py::kw_only(), py::arg("strict") = false,
        py::arg("permissive") = false, R"doc(
Loads a .wscene file -> Scene, as `phasor check` does.

defines: {name: value} overriding the file's Defines, as -D does: a string is scene-language text
('150um', '"Cu2O"'), a number is in SI units (1.5e-4 for a length Define is 150 um), a boolean
true/false. A name that matches no Define is an error (permissive=True: a warning).
strict: every warning is an error (--strict). permissive: unknown parameters and unused defines
are warnings (--permissive).

Raises phasor.SceneError with every error of the file (file, line, column, message; .errors lists
them all). Warnings go through Python's warnings module as phasor.SceneWarning.)doc");

    m.def(
        "load_string",
        [](const std::string &text, const py::object &defines, const std::string &name, bool strict,
           bool permissive) {
            if (strict && permissive) throw py::value_error("'strict' and 'permissive' contradict each other");
            LoadSpec spec;
            spec.path = name;
            spec.text = text;
            spec.strict = strict;
            spec.permissive = permissive;
            AddDefines(spec, defines);
            return LoadedScene::Load(spec);
        },
        py::arg("text"), py::arg("defines") = py::none(), py::kw_only(), py::arg("name") = "<string>",
        py::arg("strict") = false, py::arg("permissive") = false, R"doc(
Loads a scene from .wscene text -> Scene, as load() does for a file. `name` is the file name
messages give (and the base of relative Include and File paths: the working directory unless it
names a path).)doc");

    m.def(
        "quantity",
        [](const py::object &value, const std::string &kind) {
            static const std::map<std::string, Dim> kinds = {
                {"", Dim::None()},         {"length", Dim::Length()},           {"angle", Dim::Angle()},
                {"area", Dim::Area()},     {"solid_angle", Dim::SolidAngle()}, {"power", Dim::Power()},
                {"time", Dim::Time()},     {"temperature", Dim::Temperature()}, {"irradiance", Dim::Irradiance()},
                {"radiance", Dim::Radiance()}, {"intensity", Dim::Intensity()}};
            auto it = kinds.find(kind);
            if (it == kinds.end()) {
                std::string names;
                for (const auto &[k, d] : kinds)
                    if (!k.empty()) names += (names.empty() ? "" : ", ") + k;
                throw py::value_error("unknown kind '" + kind + "' (one of " + names + ")");
            }
            if (!kind.empty()) return Quantity(value, it->second, "value", "550nm");
            // Any dimension: the SI number.
            if (!py::isinstance<py::str>(value)) return value.cast<double>();
            Diagnostics diag;
            std::optional<Value> v = ParseValueString(value.cast<std::string>(), "value", diag);
            if (!v || diag.HasErrors() || v->kind != Value::Kind::Number)
                throw py::value_error("not a quantity: '" + value.cast<std::string>() + "'");
            return v->number;
        },
        py::arg("value"), py::arg("kind") = "", R"doc(
A quantity in SI units: quantity("550nm") -> 5.5e-07, quantity("30deg") -> 0.5235987755982988
(radians). `kind` ("length", "angle", "power", ...) requires that dimension (ValueError
otherwise); numbers are returned as they are (already SI).)doc");
}

}  // namespace phasor::python
