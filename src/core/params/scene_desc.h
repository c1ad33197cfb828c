// SPDX-License-Identifier: Apache-2.0
// phasor — a scene description: the entities the parser reads (or C++ code builds), each a plug-in
// type, an optional name and its parameter dictionary, in source order. BuildContext
// (build_context.h) turns it into plug-in objects (docs/architecture.md, "Data flow").
#pragma once

#include <string>
#include <unordered_set>
#include <vector>

#include "core/diagnostics.h"
#include "core/params/dict.h"

namespace phasor {

/// One entity of a scene description (the IR the parser produces; C++ code may build it too).
struct SceneEntity {
    std::string keyword;  // "Shape", "Light", … or "Render"
    std::string type;     // plug-in name ("sphere"); empty for Render
    std::string name;     // optional user name (defines @name)
    ParamDict params;
    FileLoc loc;          // location of the keyword
    FileLoc nameLoc;      // location of the name (for redefinition errors)

    /// How messages name the entity: its name, or `type@file:line` (file without directories)
    /// if it has none.
    std::string DisplayName() const;
};

/// A whole scene description, in source order.
struct SceneDesc {
    std::vector<SceneEntity> entities;
    std::string sourceFile;  // the top-level file ("" for C++-built scenes)

    /// Errors were reported while reading: `entities` holds only what was read cleanly, so that
    /// building it can report the remaining errors of the scene in the same run.
    bool incomplete = false;
    /// Names already reported (a block that failed to read, an undefined or disabled reference):
    /// a reference to one fails without a further error. With `namesLost` (text was skipped after a
    /// lexical error, or an Include after a limit), so does a reference to any unknown name.
    std::unordered_set<std::string> unavailable;
    bool namesLost = false;
};

/// How messages name something unnamed: `type@file:line` (file without directories), or `type`
/// where the location is unknown.
std::string AnonymousName(const std::string &type, const FileLoc &loc);

}  // namespace phasor
