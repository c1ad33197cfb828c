// SPDX-License-Identifier: Apache-2.0
// phasor — the parameter dictionary of one scene entity: its values by name with their locations,
// validated against the plug-in's schema, read by the plug-in's Create (docs/architecture.md,
// "From a scene value to a plug-in").
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/diagnostics.h"
#include "core/math.h"
#include "core/params/schema.h"
#include "core/params/value.h"

namespace phasor {

struct Param {
    std::string name;
    Value value;
    FileLoc loc;  // location of the parameter name
    mutable bool used = false;
};

/// The `.wscene` format version this phasor writes (docs/wscene.md §2): 2 since light strengths are
/// totals over their spectrum; version 1 files are still read (a light whose strength meant a
/// scale is a located error with the equivalent total).
inline constexpr int CurrentFormatVersion = 2;

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
    /// The format version (`wscene N` header) of the file the entity was written in; C++-built
    /// scenes have the current one. Plug-ins whose parameters changed meaning between versions
    /// read it to turn an old file into a located error (never a silent reinterpretation).
    int FormatVersion() const { return formatVersion_; }
    void SetFormatVersion(int version) { formatVersion_ = version; }

    /// The dictionary of one record: `call`'s arguments bound to the fields of `record`
    /// (positional ones in field order). Binding errors (too many arguments, a field given twice)
    /// go to `diag` when given, else throw phasor::Error.
    static ParamDict FromRecord(const Value &call, const Schema &record, Diagnostics *diag);

  private:
    std::vector<Param> params_;
    FileLoc entityLoc_;
    mutable const Schema *schema_ = nullptr;
    int formatVersion_ = CurrentFormatVersion;
};

}  // namespace phasor
