// SPDX-License-Identifier: Apache-2.0
#include "core/params/dict.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace phasor {

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
    return " (write e.g. " + FormatDouble(v.number) + " " + unit + ")";
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
