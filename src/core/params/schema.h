// SPDX-License-Identifier: Apache-2.0
// phasor — plug-in schemas: each parameter's name, kind, unit, default, range and documentation,
// stated once (docs and `phasor describe` are generated from them; ParamDict::Validate checks a
// scene against them). docs/architecture.md, "From a scene value to a plug-in".
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/params/value.h"

namespace phasor {

/// The kinds a plug-in parameter can have; the schema states one per parameter.
enum class ParamKind {
    Number,      // a scalar with a dimension (Dim::None() = plain number)
    Integer,     // a whole number
    Bool,
    String,      // free text or one of `choices`
    File,        // a path, resolved relative to the file that names it
    Complex,     // n+ik (a real number is accepted)
    Vector3,     // a list of 3 numbers with the spec's dimension
    NumberList,  // a list of numbers with the spec's dimension
    IntegerList,
    StringList,
    Spectrum,    // number (constant), call (blackbody(…), table(…) …) or @ref to a Spectrum
    Transform,   // a call (translate/rotate/scale/lookat/matrix) or a list of calls
    Ref,         // @name of an object of family `refFamily`
    RefList,     // list of @names
    /// Constant-or-texture, scalar: a number with the spec's dimension or @ref to a scalar
    /// texture of that dimension (read with BuildContext::GetFloatTexture).
    FloatTexture,
    /// Constant-or-texture, spectral: what Spectrum accepts, or @ref to a spectral or a
    /// dimensionless scalar texture (read with BuildContext::GetSpectrumTexture).
    SpectrumTexture,
    ComplexSpectrum,  // n + iκ(λ): number, n+ik, named material ("Au"), spectrum call/@ref, nk(n=…, k=…)
                      // (core/spectrum/complex_spectrum.h; read with BuildContext::GetComplexSpectrum)
    RecordList,  // list of calls to the record `record->name`, e.g. [layer(ior = 1.5, thickness = 80nm), …],
                 // each validated against the sub-schema `record` (read with ParamDict::GetRecords)
};
const char *ToString(ParamKind k);

struct Schema;

/// One parameter in a plug-in's schema: the single source of its name, kind, unit, default,
/// range and documentation (docs and `phasor describe` are generated from it).
struct ParamSpec {
    std::string name;
    ParamKind kind = ParamKind::Number;
    Dim dim;
    std::string doc;
    std::optional<Value> defaultValue;  // absent and !required: the plug-in decides (see doc)
    bool required = false;
    std::optional<double> minValue, maxValue;  // inclusive bounds on SI numbers (and list items)
    bool minExclusive = false;
    std::string refFamily;  // Ref / RefList / Spectrum: family the reference must belong to
    std::vector<std::string> choices;  // String: allowed values; ComplexSpectrum: the named materials
    int listSize = -1;  // NumberList / IntegerList: required length (-1 = any)
    /// Number / NumberList / FloatTexture: any dimension is accepted, the value brings its own
    /// (e.g. a texture's `offset = 300 nm`); Spectrum: also a number with a unit.
    bool anyDim = false;
    /// RecordList: the record's schema (its `name` is the call name, e.g. "layer"; its params are
    /// the record's fields with kinds, dimensions, defaults, required flags and ranges).
    std::shared_ptr<const Schema> record;

    // Fluent helpers so schemas read as one line per parameter.
    ParamSpec &Default(Value v) { defaultValue = std::move(v); return *this; }
    ParamSpec &Required() { required = true; return *this; }
    ParamSpec &Min(double v, bool exclusive = false) { minValue = v; minExclusive = exclusive; return *this; }
    ParamSpec &Max(double v) { maxValue = v; return *this; }
    ParamSpec &Choices(std::vector<std::string> c) { choices = std::move(c); return *this; }
    ParamSpec &Size(int n) { listSize = n; return *this; }
    ParamSpec &AnyDim() { anyDim = true; return *this; }
};

/// A plug-in's schema: family ("shape"), scene name ("sphere"), one-line doc, parameters.
struct Schema {
    std::string family, name, doc;
    std::vector<ParamSpec> params;

    const ParamSpec *Find(const std::string &n) const;
    std::vector<std::string> Names() const;
    /// Human-readable listing (what `phasor describe` prints).
    std::string Describe() const;
    /// Markdown table for docs/plugins.
    std::string Markdown() const;
};

// Schema-building shorthands: P::Length("radius", "sphere radius").Default(...).
namespace P {
ParamSpec Number(std::string name, std::string doc, Dim dim = Dim::None());
ParamSpec Length(std::string name, std::string doc);
ParamSpec Angle(std::string name, std::string doc);
ParamSpec Integer(std::string name, std::string doc);
ParamSpec Bool(std::string name, std::string doc);
ParamSpec String(std::string name, std::string doc);
ParamSpec File(std::string name, std::string doc);
ParamSpec Complex(std::string name, std::string doc);
ParamSpec Vector(std::string name, std::string doc, Dim dim = Dim::None());
ParamSpec NumberList(std::string name, std::string doc, Dim dim = Dim::None());
ParamSpec IntegerList(std::string name, std::string doc);
ParamSpec StringList(std::string name, std::string doc);
ParamSpec Spectrum(std::string name, std::string doc);
ParamSpec Transform(std::string name, std::string doc);
ParamSpec Ref(std::string name, std::string family, std::string doc);
ParamSpec RefList(std::string name, std::string family, std::string doc);
ParamSpec FloatTexture(std::string name, std::string doc, Dim dim = Dim::None());
ParamSpec SpectrumTexture(std::string name, std::string doc);
/// A complex index n + iκ(λ); the named materials of core/spectrum/named_ior.h are its choices.
ParamSpec ComplexSpectrum(std::string name, std::string doc);
/// A list of `recordName(field = …, …)` records with the given fields (positional arguments bind to
/// the fields in order). A single record is accepted as a list of one.
ParamSpec RecordList(std::string name, std::string doc, std::string recordName, std::string recordDoc,
                     std::vector<ParamSpec> fields);
}  // namespace P

}  // namespace phasor
