// SPDX-License-Identifier: Apache-2.0
#include "core/params/schema.h"

#include <sstream>

#include "core/spectrum/named_ior.h"

namespace phasor {

const char *ToString(ParamKind k) {
    switch (k) {
        case ParamKind::Number: return "number";
        case ParamKind::Integer: return "integer";
        case ParamKind::Bool: return "bool";
        case ParamKind::String: return "string";
        case ParamKind::File: return "file";
        case ParamKind::Complex: return "complex";
        case ParamKind::Vector3: return "vector";
        case ParamKind::NumberList: return "number list";
        case ParamKind::IntegerList: return "integer list";
        case ParamKind::StringList: return "string list";
        case ParamKind::Spectrum: return "spectrum";
        case ParamKind::Transform: return "transform";
        case ParamKind::Ref: return "reference";
        case ParamKind::RefList: return "reference list";
        case ParamKind::FloatTexture: return "number or texture";
        case ParamKind::SpectrumTexture: return "spectrum or texture";
        case ParamKind::ComplexSpectrum: return "complex spectrum";
        case ParamKind::RecordList: return "record list";
    }
    return "?";
}

const ParamSpec *Schema::Find(const std::string &n) const {
    for (const ParamSpec &p : params)
        if (p.name == n) return &p;
    return nullptr;
}

std::vector<std::string> Schema::Names() const {
    std::vector<std::string> v;
    for (const ParamSpec &p : params) v.push_back(p.name);
    return v;
}

namespace {
std::string KindText(const ParamSpec &p) {
    std::string k = ToString(p.kind);
    const bool dimensioned = p.kind == ParamKind::Number || p.kind == ParamKind::Vector3 ||
                             p.kind == ParamKind::NumberList || p.kind == ParamKind::FloatTexture;
    if (p.anyDim) k += p.kind == ParamKind::Spectrum ? " or number [any unit]" : " [any unit]";
    else if (dimensioned && !p.dim.IsNone()) k += " [" + p.dim.ToString() + "]";
    if (!p.refFamily.empty()) k += " (" + p.refFamily + ")";
    if (p.kind == ParamKind::RecordList && p.record) k = "list of " + p.record->name + "(…)";
    return k;
}
std::string DefaultText(const ParamSpec &p) {
    if (p.required) return "required";
    if (p.defaultValue) return p.defaultValue->ToString();
    return "-";
}
std::string RangeText(const ParamSpec &p) {
    std::string r;
    if (p.minValue) r += std::string(p.minExclusive ? "> " : "≥ ") + FormatDouble(*p.minValue);
    if (p.maxValue) r += (r.empty() ? "" : ", ") + std::string("≤ ") + FormatDouble(*p.maxValue);
    if (!p.choices.empty()) {
        r += p.kind == ParamKind::ComplexSpectrum ? "or a named material:" : "one of:";
        for (const auto &c : p.choices) r += " " + c;
    }
    return r;
}
}  // namespace

std::string Schema::Describe() const {
    std::ostringstream os;
    os << family << " \"" << name << "\" — " << doc << "\n";
    if (params.empty()) os << "  (no parameters)\n";
    for (const ParamSpec &p : params) {
        os << "  " << p.name << " : " << KindText(p) << " = " << DefaultText(p);
        std::string r = RangeText(p);
        if (!r.empty()) os << "  (" << r << ")";
        os << "\n      " << p.doc << "\n";
        if (p.kind == ParamKind::RecordList && p.record) {
            // The record's fields, indented one level further.
            std::istringstream fields(p.record->Describe());
            std::string line;
            std::getline(fields, line);  // the record's own header
            os << "      " << p.record->name << "(…) — " << p.record->doc << "\n";
            while (std::getline(fields, line)) os << "    " << line << "\n";
        }
    }
    return os.str();
}

std::string Schema::Markdown() const {
    std::ostringstream os;
    os << "### " << family << " `" << name << "`\n\n" << doc << "\n\n";
    if (params.empty()) return os.str() + "No parameters.\n\n";
    os << "| parameter | kind | default | range | description |\n|---|---|---|---|---|\n";
    for (const ParamSpec &p : params)
        os << "| `" << p.name << "` | " << KindText(p) << " | `" << DefaultText(p) << "` | " << RangeText(p)
           << " | " << p.doc << " |\n";
    for (const ParamSpec &p : params)
        if (p.kind == ParamKind::RecordList && p.record) {
            os << "\nFields of each `" << p.record->name << "(…)` record in `" << p.name << "` ("
               << p.record->doc << "):\n\n| field | kind | default | range | description |\n|---|---|---|---|---|\n";
            for (const ParamSpec &f : p.record->params)
                os << "| `" << f.name << "` | " << KindText(f) << " | `" << DefaultText(f) << "` | " << RangeText(f)
                   << " | " << f.doc << " |\n";
        }
    return os.str() + "\n";
}

namespace P {
namespace {
ParamSpec Make(std::string name, ParamKind k, std::string doc, Dim d = Dim::None()) {
    ParamSpec s;
    s.name = std::move(name);
    s.kind = k;
    s.doc = std::move(doc);
    s.dim = d;
    return s;
}
}  // namespace
ParamSpec Number(std::string n, std::string d, Dim dim) { return Make(std::move(n), ParamKind::Number, std::move(d), dim); }
ParamSpec Length(std::string n, std::string d) { return Make(std::move(n), ParamKind::Number, std::move(d), Dim::Length()); }
ParamSpec Angle(std::string n, std::string d) { return Make(std::move(n), ParamKind::Number, std::move(d), Dim::Angle()); }
ParamSpec Integer(std::string n, std::string d) { return Make(std::move(n), ParamKind::Integer, std::move(d)); }
ParamSpec Bool(std::string n, std::string d) { return Make(std::move(n), ParamKind::Bool, std::move(d)); }
ParamSpec String(std::string n, std::string d) { return Make(std::move(n), ParamKind::String, std::move(d)); }
ParamSpec File(std::string n, std::string d) { return Make(std::move(n), ParamKind::File, std::move(d)); }
ParamSpec Complex(std::string n, std::string d) { return Make(std::move(n), ParamKind::Complex, std::move(d)); }
ParamSpec Vector(std::string n, std::string d, Dim dim) { return Make(std::move(n), ParamKind::Vector3, std::move(d), dim); }
ParamSpec NumberList(std::string n, std::string d, Dim dim) { return Make(std::move(n), ParamKind::NumberList, std::move(d), dim); }
ParamSpec IntegerList(std::string n, std::string d) { return Make(std::move(n), ParamKind::IntegerList, std::move(d)); }
ParamSpec StringList(std::string n, std::string d) { return Make(std::move(n), ParamKind::StringList, std::move(d)); }
ParamSpec Spectrum(std::string n, std::string d) {
    ParamSpec s = Make(std::move(n), ParamKind::Spectrum, std::move(d));
    s.refFamily = "spectrum";
    return s;
}
ParamSpec Transform(std::string n, std::string d) { return Make(std::move(n), ParamKind::Transform, std::move(d)); }
ParamSpec Ref(std::string n, std::string family, std::string d) {
    ParamSpec s = Make(std::move(n), ParamKind::Ref, std::move(d));
    s.refFamily = std::move(family);
    return s;
}
ParamSpec RefList(std::string n, std::string family, std::string d) {
    ParamSpec s = Make(std::move(n), ParamKind::RefList, std::move(d));
    s.refFamily = std::move(family);
    return s;
}
ParamSpec FloatTexture(std::string n, std::string d, Dim dim) {
    return Make(std::move(n), ParamKind::FloatTexture, std::move(d), dim);
}
ParamSpec SpectrumTexture(std::string n, std::string d) { return Make(std::move(n), ParamKind::SpectrumTexture, std::move(d)); }
ParamSpec ComplexSpectrum(std::string n, std::string d) {
    ParamSpec s = Make(std::move(n), ParamKind::ComplexSpectrum, std::move(d));
    s.choices = NamedIndexNames();
    return s;
}
ParamSpec RecordList(std::string n, std::string d, std::string recordName, std::string recordDoc,
                     std::vector<ParamSpec> fields) {
    ParamSpec s = Make(std::move(n), ParamKind::RecordList, std::move(d));
    s.record = std::make_shared<const Schema>(Schema{"record", std::move(recordName), std::move(recordDoc), std::move(fields)});
    return s;
}
}  // namespace P

}  // namespace phasor
