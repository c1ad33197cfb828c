// SPDX-License-Identifier: Apache-2.0
#include "core/params/value.h"

#include <cmath>
#include <sstream>

namespace phasor {

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

std::string FormatDouble(double v) {
    std::ostringstream os;
    os.precision(15);
    os << v;
    return os.str();
}

namespace {
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

}  // namespace phasor
