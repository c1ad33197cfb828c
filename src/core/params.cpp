// SPDX-License-Identifier: Apache-2.0
#include "core/params.h"

#include "core/spectrum/named_ior.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace phasor {

// ---- Value --------------------------------------------------------------------------------

Value Value::Number(double si, Dim d, FileLoc loc) {
    Value v;
    v.kind = Kind::Number;
    v.number = si;
    v.dim = d;
    v.loc = std::move(loc);
    return v;
}
Value Value::Integer(long long i, FileLoc loc) {
    Value v = Number(double(i), Dim::None(), std::move(loc));
    v.isInteger = true;
    return v;
}
Value Value::Bool(bool b, FileLoc loc) {
    Value v;
    v.kind = Kind::Bool;
    v.boolean = b;
    v.loc = std::move(loc);
    return v;
}
Value Value::String(std::string s, FileLoc loc) {
    Value v;
    v.kind = Kind::String;
    v.text = std::move(s);
    v.loc = std::move(loc);
    return v;
}
Value Value::ComplexNumber(phasor::Complex c, FileLoc loc) {
    Value v;
    v.kind = Kind::Complex;
    v.complex = c;
    v.loc = std::move(loc);
    return v;
}
Value Value::List(std::vector<Value> items, FileLoc loc) {
    Value v;
    v.kind = Kind::List;
    v.items = std::move(items);
    v.loc = std::move(loc);
    return v;
}
Value Value::Ref(std::string name, FileLoc loc) {
    Value v;
    v.kind = Kind::Ref;
    v.text = std::move(name);
    v.loc = std::move(loc);
    return v;
}
Value Value::Call(std::string name, std::vector<Value> args, std::vector<std::string> argNames, FileLoc loc) {
    Value v;
    v.kind = Kind::Call;
    v.text = std::move(name);
    v.items = std::move(args);
    v.argNames = std::move(argNames);
    v.argNames.resize(v.items.size());
    v.argLocs.resize(v.items.size());
    v.loc = std::move(loc);
    return v;
}
Value Value::Vector(const Vec3 &p, Dim d, FileLoc loc) {
    return List({Number(p.x, d, loc), Number(p.y, d, loc), Number(p.z, d, loc)}, loc);
}

std::string Value::DescribeKind() const {
    switch (kind) {
        case Kind::Number:
            if (dim.IsNone()) return isInteger ? "a whole number" : "a plain number";
            return dim.Describe();
        case Kind::Bool: return "a boolean";
        case Kind::String: return "a string";
        case Kind::Complex: return "a complex number";
        case Kind::List: return "a list";
        case Kind::Ref: return "a reference";
        case Kind::Call: return "a call to '" + text + "'";
    }
    return "a value";
}

namespace {
std::string FormatDouble(double v) {
    std::ostringstream os;
    os.precision(15);
    os << v;
    return os.str();
}
std::string FormatNumber(const Value &v) {
    if (v.isInteger) return FormatDouble(v.number);
    if (v.dim.IsNone()) return FormatDouble(v.number);
    double scale = 1;
    std::string unit = PreferredUnit(v.dim, v.number, &scale);
    return FormatDouble(v.number / scale) + " " + unit;
}
std::string QuoteString(const std::string &s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        if (c == '\n') { out += "\\n"; continue; }
        out += c;
    }
    return out + "\"";
}
}  // namespace

std::string Value::ToString() const {
    switch (kind) {
        case Kind::Number: return FormatNumber(*this);
        case Kind::Bool: return boolean ? "true" : "false";
        case Kind::String: return QuoteString(text);
        case Kind::Complex: {
            std::string im = FormatDouble(std::abs(complex.imag()));
            return FormatDouble(complex.real()) + (complex.imag() < 0 ? "-" : "+") + im + "i";
        }
        case Kind::List: {
            std::string s = "[";
            for (std::size_t i = 0; i < items.size(); ++i) s += (i ? " " : "") + items[i].ToString();
            return s + "]";
        }
        case Kind::Ref: return "@" + text;
        case Kind::Call: {
            std::string s = text + "(";
            for (std::size_t i = 0; i < items.size(); ++i) {
                if (i) s += ", ";
                if (i < argNames.size() && !argNames[i].empty()) s += argNames[i] + " = ";
                s += items[i].ToString();
            }
            return s + ")";
        }
    }
    return "?";
}

bool Value::SameAs(const Value &o) const {
    if (kind != o.kind) return false;
    switch (kind) {
        case Kind::Number: return number == o.number && dim == o.dim;
        case Kind::Bool: return boolean == o.boolean;
        case Kind::String:
        case Kind::Ref: return text == o.text;
        case Kind::Complex: return complex == o.complex;
        case Kind::List:
        case Kind::Call:
            if (text != o.text || items.size() != o.items.size() || argNames != o.argNames) return false;
            for (std::size_t i = 0; i < items.size(); ++i)
                if (!items[i].SameAs(o.items[i])) return false;
            return true;
    }
    return false;
}

// ---- Schema -------------------------------------------------------------------------------

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

// ---- ParamDict ----------------------------------------------------------------------------

bool ParamDict::Add(std::string name, Value v, FileLoc loc) {
    if (Has(name)) return false;
    if (!loc.Known()) loc = v.loc.Known() ? v.loc : entityLoc_;
    params_.push_back(Param{std::move(name), std::move(v), std::move(loc), false});
    return true;
}

const Param *ParamDict::Find(const std::string &name) const {
    for (const Param &p : params_)
        if (p.name == name) return &p;
    return nullptr;
}

namespace {

// Where to point for a value: the value itself if it has a location, else the parameter.
FileLoc WhereOf(const Value &v, const Param &p) { return v.loc.Known() ? v.loc : p.loc; }

std::string BareNumberHint(const Value &v, Dim expected) {
    std::string unit = expected == Dim::Length()       ? "um"
                       : expected == Dim::Angle()      ? "deg"
                       : expected == Dim::Temperature() ? "K"
                       : expected == Dim::Power()      ? "W"
                                                       : expected.ToString();
    std::ostringstream os;
    os.precision(15);
    os << v.number;
    return " (write e.g. " + os.str() + " " + unit + ")";
}

bool CheckNumber(const Value &v, const ParamSpec &s, const Param &p, Diagnostics &diag) {
    if (v.kind != Value::Kind::Number) {
        diag.Error(WhereOf(v, p), "'" + s.name + "' expects " + s.dim.Describe() + "; got " + v.DescribeKind());
        return false;
    }
    if (v.dim != s.dim && !s.anyDim) {
        if (v.dim.IsNone())
            diag.Error(WhereOf(v, p), "'" + s.name + "' expects " + s.dim.Describe() + "; got bare number " +
                                          v.ToString() + BareNumberHint(v, s.dim));
        else
            diag.Error(WhereOf(v, p), "'" + s.name + "' expects " + s.dim.Describe() + "; got " +
                                          v.DescribeKind() + " (" + v.ToString() + ")");
        return false;
    }
    if (!std::isfinite(v.number)) {
        diag.Error(WhereOf(v, p), "'" + s.name + "' must be finite; got " + v.ToString());
        return false;
    }
    bool tooLow = s.minValue && (s.minExclusive ? v.number <= *s.minValue : v.number < *s.minValue);
    bool tooHigh = s.maxValue && v.number > *s.maxValue;
    if (tooLow || tooHigh) {
        std::string range;
        if (s.minValue) range += std::string(s.minExclusive ? "> " : "≥ ") + Value::Number(*s.minValue, s.dim).ToString();
        if (s.maxValue) range += (range.empty() ? "" : " and ") + std::string("≤ ") + Value::Number(*s.maxValue, s.dim).ToString();
        diag.Error(WhereOf(v, p), "'" + s.name + "' is out of range: " + v.ToString() + " (must be " + range + ")");
        return false;
    }
    return true;
}

bool CheckInteger(const Value &v, const ParamSpec &s, const Param &p, Diagnostics &diag) {
    if (v.kind != Value::Kind::Number || !v.dim.IsNone() || v.number != std::floor(v.number)) {
        diag.Error(WhereOf(v, p), "'" + s.name + "' expects a whole number; got " + v.DescribeKind() +
                                      (v.kind == Value::Kind::Number ? " " + v.ToString() : ""));
        return false;
    }
    // Whole numbers are read as int: the schema's range, clipped to int's, is what works.
    ParamSpec copy = s;
    copy.dim = Dim::None();
    constexpr double IntMin = std::numeric_limits<int>::min(), IntMax = std::numeric_limits<int>::max();
    if (!copy.minValue || *copy.minValue < IntMin) copy.minValue = IntMin, copy.minExclusive = false;
    if (!copy.maxValue || *copy.maxValue > IntMax) copy.maxValue = IntMax;
    return CheckNumber(v, copy, p, diag);
}

bool CheckList(const Value &v, const ParamSpec &s, const Param &p, Diagnostics &diag, int size) {
    if (v.kind != Value::Kind::List) {
        diag.Error(WhereOf(v, p), "'" + s.name + "' expects a list; got " + v.DescribeKind());
        return false;
    }
    if (size >= 0 && (int)v.items.size() != size) {
        diag.Error(WhereOf(v, p), "'" + s.name + "' expects a list of " + std::to_string(size) + " values; got " +
                                      std::to_string(v.items.size()));
        return false;
    }
    return true;
}

// A string against the spec's choices (none: anything goes). For a ComplexSpectrum the choices
// are the named materials, and a string outside them is an unknown material.
bool CheckChoice(const Value &v, const ParamSpec &s, const Param &p, Diagnostics &diag) {
    if (s.choices.empty()) return true;
    for (const auto &c : s.choices)
        if (c == v.text) return true;
    std::string list;
    for (const auto &c : s.choices) list += (list.empty() ? "" : ", ") + ("\"" + c + "\"");
    std::string sug = Suggest(v.text, s.choices);
    std::string msg = s.kind == ParamKind::ComplexSpectrum
                          ? "'" + s.name + "': unknown material \"" + v.text + "\" (known: " + list + ")"
                          : "'" + s.name + "' must be one of " + list + "; got \"" + v.text + "\"";
    diag.Error(WhereOf(v, p), msg + (sug.empty() ? "" : "; did you mean \"" + sug + "\"?"));
    return false;
}

bool CheckRecords(const Value &v, const ParamSpec &s, const Param &p, Diagnostics &diag);

bool CheckValue(const Value &v, const ParamSpec &s, const Param &p, Diagnostics &diag) {
    using K = Value::Kind;
    auto kindError = [&](const std::string &expected) {
        diag.Error(WhereOf(v, p), "'" + s.name + "' expects " + expected + "; got " + v.DescribeKind());
        return false;
    };
    switch (s.kind) {
        case ParamKind::Number: return CheckNumber(v, s, p, diag);
        case ParamKind::Integer: return CheckInteger(v, s, p, diag);
        case ParamKind::Bool: return v.kind == K::Bool ? true : kindError("a boolean (true or false)");
        case ParamKind::String:
            if (v.kind != K::String) return kindError("a string");
            return CheckChoice(v, s, p, diag);
        case ParamKind::File: return v.kind == K::String ? true : kindError("a file name (a string)");
        case ParamKind::Complex:
            if (v.kind == K::Complex || (v.kind == K::Number && v.dim.IsNone())) return true;
            return kindError("a complex number such as 1.5+0.01i");
        case ParamKind::Vector3:
        case ParamKind::NumberList: {
            if (!CheckList(v, s, p, diag, s.kind == ParamKind::Vector3 ? 3 : s.listSize)) return false;
            bool ok = true;
            for (const Value &it : v.items) ok = CheckNumber(it, s, p, diag) && ok;
            return ok;
        }
        case ParamKind::IntegerList: {
            if (!CheckList(v, s, p, diag, s.listSize)) return false;
            bool ok = true;
            for (const Value &it : v.items) ok = CheckInteger(it, s, p, diag) && ok;
            return ok;
        }
        case ParamKind::StringList: {
            if (!CheckList(v, s, p, diag, s.listSize)) return false;
            for (const Value &it : v.items)
                if (it.kind != K::String) {
                    diag.Error(WhereOf(it, p), "'" + s.name + "' expects a list of strings; got " + it.DescribeKind());
                    return false;
                }
            return true;
        }
        case ParamKind::Spectrum:
            if (v.kind == K::Number && (v.dim.IsNone() || s.anyDim)) return true;
            if (v.kind == K::Call || v.kind == K::Ref) return true;
            return kindError("a spectrum (a number, a call such as blackbody(5800 K), or @name)");
        case ParamKind::SpectrumTexture:
            if (v.kind == K::Number && v.dim.IsNone()) return true;
            if (v.kind == K::Call || v.kind == K::Ref) return true;
            return kindError("a spectrum (a number, a call such as blackbody(5800 K), or @name) or @texture");
        case ParamKind::FloatTexture:
            // A reference's dimension is checked when the texture is built (GetFloatTexture).
            if (v.kind == K::Ref) return true;
            if (v.kind == K::Number) return CheckNumber(v, s, p, diag);
            return kindError((s.anyDim ? std::string("a number") : s.dim.Describe()) + " or @texture");
        case ParamKind::Transform:
            if (v.kind == K::Call) return true;
            if (v.kind == K::List) {
                for (const Value &it : v.items)
                    if (it.kind != K::Call) {
                        diag.Error(WhereOf(it, p), "'" + s.name + "' expects a list of transforms; got " + it.DescribeKind());
                        return false;
                    }
                return true;
            }
            return kindError("a transform such as translate([0 0 1] m)");
        case ParamKind::Ref: return v.kind == K::Ref ? true : kindError("a reference (@name) to a " + s.refFamily);
        case ParamKind::RefList:
            if (v.kind == K::Ref) return true;  // a single reference is a list of one
            if (!CheckList(v, s, p, diag, -1)) return false;
            for (const Value &it : v.items)
                if (it.kind != K::Ref) {
                    diag.Error(WhereOf(it, p), "'" + s.name + "' expects a list of references; got " + it.DescribeKind());
                    return false;
                }
            return true;
        case ParamKind::ComplexSpectrum:
            if (v.kind == K::String) return CheckChoice(v, s, p, diag);
            if ((v.kind == K::Number && v.dim.IsNone()) || v.kind == K::Complex || v.kind == K::Call ||
                v.kind == K::Ref)
                return true;
            return kindError("a complex index (a number such as 1.5, n+ik such as 0.2+3.4i, a material such as "
                             "\"Au\", a spectrum such as table(…), or nk(n = …, k = …))");
        case ParamKind::RecordList: return CheckRecords(v, s, p, diag);
    }
    return true;
}

bool CheckRecords(const Value &v, const ParamSpec &s, const Param &p, Diagnostics &diag) {
    const Schema &rec = *s.record;
    const std::string expected = "a list of " + rec.name + "(…) records";
    if (v.kind != Value::Kind::Call && v.kind != Value::Kind::List) {
        diag.Error(WhereOf(v, p), "'" + s.name + "' expects " + expected + "; got " + v.DescribeKind());
        return false;
    }
    const std::vector<Value> one = {v};
    bool ok = true;
    for (const Value &it : v.kind == Value::Kind::Call ? one : v.items) {
        if (it.kind != Value::Kind::Call || it.text != rec.name) {
            std::string sug = it.kind == Value::Kind::Call ? Suggest(it.text, {rec.name}) : "";
            diag.Error(WhereOf(it, p), "'" + s.name + "' expects " + expected + "; got " + it.DescribeKind() +
                                           (sug.empty() ? "" : "; did you mean '" + sug + "'?"));
            ok = false;
            continue;
        }
        // Each record is validated like an entity: unknown fields, missing ones, kinds, ranges.
        const std::size_t before = diag.ErrorCount();
        ParamDict fields = ParamDict::FromRecord(it, rec, &diag);
        ok = diag.ErrorCount() == before && fields.Validate(rec, diag) && ok;
    }
    return ok;
}

}  // namespace

bool ParamDict::Validate(const Schema &schema, Diagnostics &diag) const {
    schema_ = &schema;
    std::size_t errorsBefore = diag.ErrorCount();
    std::string what = schema.family + " \"" + schema.name + "\"";
    for (const Param &p : params_) {
        const ParamSpec *s = schema.Find(p.name);
        if (!s) {
            std::string sug = Suggest(p.name, schema.Names());
            FileLoc loc = p.loc;
            loc.length = (int)p.name.size();
            diag.UnknownName(loc, "unknown parameter '" + p.name + "' for " + what +
                                      (sug.empty() ? "" : "; did you mean '" + sug + "'?"));
            p.used = true;  // reported once, here
            continue;
        }
        // A texture given to a number whose textured form is a separate parameter (thin_film's
        // thickness / thickness_texture): say where it goes.
        if (p.value.kind == Value::Kind::Ref && s->kind == ParamKind::Number && schema.Find(p.name + "_texture")) {
            diag.Error(WhereOf(p.value, p), "'" + p.name + "' expects " + s->dim.Describe() + "; got " +
                                                p.value.DescribeKind() + " — a texture goes in '" + p.name +
                                                "_texture' (" + p.name + "_texture = " + p.value.ToString() + ")");
            continue;
        }
        CheckValue(p.value, *s, p, diag);
    }
    for (const ParamSpec &s : schema.params)
        if (s.required && !Has(s.name))
            diag.Error(entityLoc_, "missing required parameter '" + s.name + "' for " + what + " (" + s.doc + ")");
    return diag.ErrorCount() == errorsBefore;
}

void ParamDict::ReportUnused(Diagnostics &diag, const std::string &what) const {
    for (const Param &p : params_)
        if (!p.used) {
            FileLoc loc = p.loc;
            loc.length = (int)p.name.size();
            diag.Warning(loc, "parameter '" + p.name + "' of " + what + " was given but not used");
        }
}

const Value &ParamDict::GetValue(const std::string &name) const {
    if (const Param *p = Find(name)) {
        p->used = true;
        return p->value;
    }
    if (schema_)
        if (const ParamSpec *s = schema_->Find(name); s && s->defaultValue) return *s->defaultValue;
    throw std::logic_error("internal: parameter '" + name + "' read but absent, without a schema default");
}

double ParamDict::GetNumber(const std::string &name) const {
    const Value &v = GetValue(name);
    if (v.kind == Value::Kind::Complex) return v.complex.real();
    return v.number;
}
int ParamDict::GetInt(const std::string &name) const { return (int)std::llround(GetNumber(name)); }
bool ParamDict::GetBool(const std::string &name) const { return GetValue(name).boolean; }
std::string ParamDict::GetString(const std::string &name) const { return GetValue(name).text; }
Complex ParamDict::GetComplex(const std::string &name) const {
    const Value &v = GetValue(name);
    return v.kind == Value::Kind::Complex ? v.complex : Complex(v.number, 0);
}
Vec3 ParamDict::GetVector(const std::string &name) const {
    const Value &v = GetValue(name);
    if (v.items.size() != 3) throw std::logic_error("internal: '" + name + "' is not a 3-vector");
    return {v.items[0].number, v.items[1].number, v.items[2].number};
}
std::vector<double> ParamDict::GetNumbers(const std::string &name) const {
    std::vector<double> out;
    for (const Value &it : GetValue(name).items) out.push_back(it.number);
    return out;
}
std::vector<int> ParamDict::GetInts(const std::string &name) const {
    std::vector<int> out;
    for (const Value &it : GetValue(name).items) out.push_back((int)std::llround(it.number));
    return out;
}
ParamDict ParamDict::FromRecord(const Value &call, const Schema &record, Diagnostics *diag) {
    ParamDict d(call.loc);
    const std::vector<std::string> order = record.Names();
    std::size_t next = 0;
    for (std::size_t i = 0; i < call.items.size(); ++i) {
        const Value &arg = call.items[i];
        const FileLoc argLoc = arg.loc.Known() ? arg.loc : call.loc;
        std::string name = i < call.argNames.size() ? call.argNames[i] : "";
        FileLoc nameLoc = i < call.argLocs.size() && call.argLocs[i].Known() ? call.argLocs[i] : argLoc;
        std::string problem;
        if (name.empty()) {
            if (next >= order.size()) problem = "too many arguments to '" + call.text + "'";
            else name = order[next++];
        }
        if (problem.empty() && !d.Add(name, arg, nameLoc)) problem = "field '" + name + "' of '" + call.text + "' given twice";
        if (problem.empty()) continue;
        if (!diag) throw Error(argLoc, problem);
        diag->Error(argLoc, problem);
    }
    d.schema_ = &record;
    return d;
}

std::vector<ParamDict> ParamDict::GetRecords(const std::string &name) const {
    const Param *p = Find(name);
    const ParamSpec *spec = schema_ ? schema_->Find(name) : nullptr;
    if (!spec || !spec->record) throw std::logic_error("internal: '" + name + "' is not a record list of the schema");
    if (!p && !spec->defaultValue) return {};
    const Value &v = GetValue(name);
    std::vector<ParamDict> out;
    if (v.kind == Value::Kind::Call) out.push_back(FromRecord(v, *spec->record, nullptr));
    else
        for (const Value &it : v.items) out.push_back(FromRecord(it, *spec->record, nullptr));
    return out;
}

std::vector<std::string> ParamDict::GetStrings(const std::string &name) const {
    std::vector<std::string> out;
    for (const Value &it : GetValue(name).items) out.push_back(it.text);
    return out;
}
FileLoc ParamDict::Loc(const std::string &name) const {
    if (const Param *p = Find(name)) return p->value.loc.Known() ? p->value.loc : p->loc;
    return entityLoc_;
}

}  // namespace phasor
