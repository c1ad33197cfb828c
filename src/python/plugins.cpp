// SPDX-License-Identifier: Apache-2.0
// phasor's Python module: the plug-in registry (phasor.plugins, phasor.describe) — what `phasor
// list` and `phasor describe` print, from the same schemas, as Python data.
#include <pybind11/complex.h>
#include <pybind11/stl.h>

#include "core/render/registry.h"
#include "python/common.h"

namespace phasor::python {

namespace {

// The family a word names ("material", "Material", "materials", "kernel"), as the program's
// `list`/`describe` accept it; raises ValueError with a suggestion.
std::string FamilyOf(const std::string &word) {
    std::string w = word;
    std::vector<std::string> names;
    for (const FamilyInfo &f : AllFamilies()) names.push_back(f.family);
    auto known = [&](const std::string &x) {
        for (const FamilyInfo &f : AllFamilies())
            if (x == f.family || x == f.keyword) return f.family;
        return std::string();
    };
    if (std::string f = known(w); !f.empty()) return f;
    if (w.size() > 1 && (w.back() == 's' || w.back() == 'S')) w.pop_back();
    if (w == "kernel" || w == "Kernel") w = "material";
    if (std::string f = known(w); !f.empty()) return f;
    const std::string sug = Suggest(word, names);
    std::string all;
    for (const std::string &n : names) all += (all.empty() ? "" : ", ") + n;
    throw py::value_error("unknown family '" + word + "'" + (sug.empty() ? "" : "; did you mean '" + sug + "'?") +
                          " (families: " + all + ")");
}

py::object ValueToPython(const Value &v) {
    switch (v.kind) {
        case Value::Kind::Number:
            if (v.isInteger) return py::int_((long long)v.number);
            return py::float_(v.number);
        case Value::Kind::Bool: return py::bool_(v.boolean);
        case Value::Kind::String: return py::str(v.text);
        case Value::Kind::Complex: return py::cast(v.complex);
        default: return py::str(v.ToString());  // lists, references, calls: their scene-language text
    }
}

py::dict SchemaDict(const Schema &s);

py::dict ParamDict(const ParamSpec &p) {
    py::dict d;
    d["name"] = p.name;
    d["kind"] = ToString(p.kind);
    d["unit"] = p.anyDim ? "any" : p.dim.IsNone() ? "" : p.dim.ToString();
    d["required"] = p.required;
    d["default"] = p.defaultValue ? ValueToPython(*p.defaultValue) : py::object(py::none());
    d["default_text"] = p.defaultValue ? py::str(p.defaultValue->ToString()) : py::object(py::none());
    py::dict range;
    range["min"] = p.minValue ? py::float_(*p.minValue) : py::object(py::none());
    range["max"] = p.maxValue ? py::float_(*p.maxValue) : py::object(py::none());
    range["min_exclusive"] = p.minExclusive;
    d["range"] = range;
    d["choices"] = p.choices;
    d["references"] = p.refFamily;
    d["doc"] = p.doc;
    if (p.record) d["record"] = SchemaDict(*p.record);
    return d;
}

py::dict SchemaDict(const Schema &s) {
    py::dict d;
    d["family"] = s.family;
    d["name"] = s.name;
    d["doc"] = s.doc;
    py::list params;
    for (const ParamSpec &p : s.params) params.append(ParamDict(p));
    d["parameters"] = params;
    d["text"] = s.Describe();
    return d;
}

}  // namespace

void BindPlugins(py::module_ &m) {
    m.def(
        "plugins",
        [](const py::object &family) {
            const std::string only = family.is_none() ? "" : FamilyOf(family.cast<std::string>());
            py::list out;
            for (const FamilyInfo &f : AllFamilies()) {
                if (!only.empty() && f.family != only) continue;
                for (const Schema *s : f.schemas) {
                    py::dict d;
                    d["family"] = f.family;
                    d["name"] = s->name;
                    d["doc"] = s->doc;
                    out.append(d);
                }
            }
            return out;
        },
        py::arg("family") = py::none(), R"doc(
The registered plug-ins, as `phasor list` prints them: a list of dicts {family, name, doc}, of
every family or of one ("material", "Material", "materials" and "kernel" all name the materials).
Kernels registered from Python (phasor.register_material) are listed with the others.)doc");

    m.def(
        "families", [] {
            std::vector<std::string> v;
            for (const FamilyInfo &f : AllFamilies()) v.push_back(f.family);
            return v;
        },
        "The plug-in families: spectrum, texture, material, shape, light, detector, integrator.");

    m.def(
        "describe",
        [](const std::string &a, const py::object &b) {
            // describe(name) or describe(family, name), as `phasor describe [FAMILY] NAME`.
            if (b.is_none()) {
                if (a == "Render" || a == "render") return SchemaDict(RenderSchema());
                std::vector<const Schema *> found;
                std::vector<std::string> all;
                for (const FamilyInfo &f : AllFamilies())
                    for (const Schema *x : f.schemas) {
                        if (x->name == a) found.push_back(x);
                        all.push_back(x->name);
                    }
                if (found.size() == 1) return SchemaDict(*found[0]);
                if (found.empty()) {
                    const std::string sug = Suggest(a, all);
                    throw py::value_error("no plug-in named '" + a + "'" +
                                          (sug.empty() ? "" : "; did you mean '" + sug + "'?"));
                }
                std::string fams;
                for (const Schema *x : found) fams += (fams.empty() ? "'" : ", '") + x->family + "'";
                throw py::value_error("'" + a + "' names a plug-in in several families (" + fams +
                                      "); say which: describe(family, '" + a + "')");
            }
            const std::string family = FamilyOf(a), name = b.cast<std::string>();
            if (const Schema *s = FindSchema(family, name)) return SchemaDict(*s);
            std::vector<std::string> names;
            for (const FamilyInfo &f : AllFamilies())
                if (f.family == family)
                    for (const Schema *x : f.schemas) names.push_back(x->name);
            const std::string sug = Suggest(name, names);
            throw py::value_error("no " + family + " named '" + name + "'" +
                                  (sug.empty() ? "" : "; did you mean '" + sug + "'?"));
        },
        py::arg("family_or_name"), py::arg("name") = py::none(), R"doc(
A plug-in's schema, as `phasor describe [FAMILY] NAME` prints it, as a dict: family, name, doc,
text (the program's listing) and parameters — one dict each: name, kind ("number", "spectrum",
"reference", ...), unit (SI, "" for none, "any" when the value brings its own), required,
default (SI value; None when the plug-in decides), default_text (as a scene writes it),
range {min, max, min_exclusive} (SI), choices, references (the family a reference must name),
doc, and record (the schema of each record of a record list). describe("Render") is the Render
block's.)doc");
}

}  // namespace phasor::python
