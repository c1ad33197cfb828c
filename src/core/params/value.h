// SPDX-License-Identifier: Apache-2.0
// phasor — a scene value: what a scene file (or C++ code building a scene) says for one parameter.
//
// The first step of a parameter's way from the text to a kernel (docs/architecture.md, "From a
// scene value to a plug-in"): value (here) → schema (schema.h) → dictionary, validated against the
// schema (dict.h) → the plug-in's Create, which reads numbers from the dictionary and resolves
// spectra, textures, transforms and references through the BuildContext (build_context.h).
//
// A Value is already resolved: $defines substituted, arithmetic evaluated, numbers converted to SI
// with their dimension kept. References (@name) and calls (blackbody(5800 K), translate(...)) stay
// symbolic; the BuildContext resolves them.
#pragma once

#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "core/math.h"
#include "core/units.h"

namespace phasor {

struct Value {
    enum class Kind { Number, Bool, String, Complex, List, Ref, Call };
    Kind kind = Kind::Number;
    double number = 0;  // Number: SI value
    Dim dim;            // Number (and Complex, which is dimensionless): dimension
    bool isInteger = false;  // Number written without fraction/exponent/unit (e.g. `8`)
    bool boolean = false;
    Complex complex;
    std::string text;  // String: content; Ref: name without '@'; Call: function name
    std::vector<Value> items;  // List: elements; Call: arguments (see argNames)
    std::vector<std::string> argNames;  // Call: one per argument ("" = positional)
    std::vector<FileLoc> argLocs;  // Call: location of each argument's name (unknown if positional or absent)
    FileLoc loc;

    static Value Number(double si, Dim d = Dim::None(), FileLoc loc = {});
    static Value Integer(long long v, FileLoc loc = {});
    static Value Bool(bool b, FileLoc loc = {});
    static Value String(std::string s, FileLoc loc = {});
    static Value ComplexNumber(Complex c, FileLoc loc = {});
    static Value List(std::vector<Value> items, FileLoc loc = {});
    static Value Ref(std::string name, FileLoc loc = {});
    static Value Call(std::string name, std::vector<Value> args, std::vector<std::string> argNames,
                      FileLoc loc = {});
    static Value Vector(const Vec3 &v, Dim d = Dim::None(), FileLoc loc = {});

    /// "a number", "a length", "a string", "a list", "a reference", "a call to 'blackbody'"…
    std::string DescribeKind() const;
    /// Canonical .wscene text of the value (used by docs and `phasor format`).
    std::string ToString() const;
    /// Structural equality (ignores locations).
    bool SameAs(const Value &o) const;
};

/// A number as scene text writes it: 15 significant digits, no unit (Value::ToString, schemas'
/// ranges, messages).
std::string FormatDouble(double v);

}  // namespace phasor
