// SPDX-License-Identifier: Apache-2.0
// phasor — scene values, plug-in schemas and the parameter dictionary (docs/architecture.md, "Plug-ins").
//
// A Value is what a scene file (or C++ code building a scene) says for one parameter, already
// resolved: $defines substituted, arithmetic evaluated, numbers converted to SI with their
// dimension kept. References (@name) and calls (blackbody(5800 K), translate(...)) stay symbolic;
// the builder resolves them with the registry (see registry.h, BuildContext).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
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

struct Param {
    std::string name;
    Value value;
    FileLoc loc;  // location of the parameter name
    mutable bool used = false;
};

/// The parameters of one scene entity. Created by the parser (or C++ code), validated against the
/// plug-in's schema, then read by the plug-in's Create(). Every accessor marks the parameter used
/// and falls back to the schema default; reading a parameter that is absent, not required and has
/// no default is an internal error (use Has() first).
class ParamDict {
  public:
    ParamDict() = default;
    explicit ParamDict(FileLoc entityLoc) : entityLoc_(std::move(entityLoc)) {}

    /// Adds a parameter; returns false (and keeps the first) if the name is already present.
    bool Add(std::string name, Value v, FileLoc loc = {});
    /// Convenience for C++ scene building.
    ParamDict &Set(std::string name, Value v) { Add(std::move(name), std::move(v)); return *this; }

    bool Has(const std::string &name) const { return Find(name) != nullptr; }
    const Param *Find(const std::string &name) const;
    const std::vector<Param> &All() const { return params_; }
    std::vector<Param> &All() { return params_; }

    /// Checks every parameter against `schema` (unknown names → warning with suggestion; wrong
    /// kind / dimension, missing required, out of range → error). Remembers the schema for
    /// defaults. Returns false if an error was reported.
    bool Validate(const Schema &schema, Diagnostics &diag) const;
    /// Warns about parameters that were provided but never read.
    void ReportUnused(Diagnostics &diag, const std::string &what) const;

    double GetNumber(const std::string &name) const;  // SI value
    int GetInt(const std::string &name) const;
    bool GetBool(const std::string &name) const;
    std::string GetString(const std::string &name) const;
    Complex GetComplex(const std::string &name) const;
    Vec3 GetVector(const std::string &name) const;
    std::vector<double> GetNumbers(const std::string &name) const;
    std::vector<int> GetInts(const std::string &name) const;
    std::vector<std::string> GetStrings(const std::string &name) const;
    /// A RecordList parameter: one dictionary per record, in written order, each with the
    /// record's schema (defaults apply) and a location per field (Loc(field)); an absent
    /// parameter without default is an empty list.
    std::vector<ParamDict> GetRecords(const std::string &name) const;
    /// The raw value (parameter or schema default); marks it used.
    const Value &GetValue(const std::string &name) const;
    /// Location of a parameter (or of the entity, if absent) for follow-up errors.
    FileLoc Loc(const std::string &name) const;
    const FileLoc &EntityLoc() const { return entityLoc_; }
    const Schema *GetSchema() const { return schema_; }

    /// The dictionary of one record: `call`'s arguments bound to the fields of `record`
    /// (positional ones in field order). Binding errors (too many arguments, a field given twice)
    /// go to `diag` when given, else throw phasor::Error.
    static ParamDict FromRecord(const Value &call, const Schema &record, Diagnostics *diag);

  private:
    std::vector<Param> params_;
    FileLoc entityLoc_;
    mutable const Schema *schema_ = nullptr;
};

}  // namespace phasor
