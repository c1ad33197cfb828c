// SPDX-License-Identifier: Apache-2.0
// phasor — reading .wscene scene descriptions (the format is specified in docs/wscene.md).
//
//   text ──lexer──▶ tokens ──syntax──▶ FileAst ──resolver──▶ SceneDesc
//
// The resolver follows Includes, substitutes $defines (with command-line -D overrides), evaluates
// arithmetic with dimensions, converts quantities to SI, evaluates pure math functions, drops
// entities whose `enabled` is false and checks names and @references. Plug-in schemas are not
// consulted here: BuildContext (core/params/build_context.h) validates each entity against its schema.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/diagnostics.h"
#include "core/params/dict.h"
#include "core/params/scene_desc.h"

namespace phasor {

/// Command-line overrides: (name, value text) pairs from `-D name=value`.
using DefineList = std::vector<std::pair<std::string, std::string>>;

struct ParseOptions {
    DefineList defines;
    /// Reads an included file; returns nullopt if it cannot be read. Default: the file system
    /// (regular files only). (Tests and the fuzzer supply in-memory files.)
    std::function<std::optional<std::string>(const std::string &path)> readFile;
    // Limits against runaway input (docs/wscene.md §7).
    int maxIncludeDepth = 32;
    std::size_t maxIncludes = 10000;           // Include expansions in one scene
    std::size_t maxSceneBytes = 32u << 20;     // text of the scene: every file, every expansion
    /// Return what was read cleanly even after errors (SceneDesc::incomplete is then set), so the
    /// caller can build it and report the scene's remaining errors in the same run.
    bool partial = false;
    /// Names among `defines` whose value is a bare number in SI units (the Python module's floats):
    /// overriding a Define of a dimensioned quantity it takes that dimension (1.5e-4 for a length is
    /// 150 um). Other bare numbers for a dimensioned Define are errors, as on the command line.
    std::vector<std::string> siDefines;
};

/// Parses and resolves a scene file. Returns nullopt if any error was reported to `diag` (the
/// diagnostics say why) unless `options.partial`, and if the file cannot be read; warnings alone
/// do not fail (unless `diag` is strict).
std::optional<SceneDesc> ParseSceneFile(const std::string &path, const DefineList &defines,
                                        Diagnostics &diag);
std::optional<SceneDesc> ParseSceneFile(const std::string &path, const ParseOptions &options,
                                        Diagnostics &diag);

/// As ParseSceneFile, for text held in memory. `virtualFileName` names it in diagnostics and is
/// the base for relative Include paths.
std::optional<SceneDesc> ParseSceneString(const std::string &text, const std::string &virtualFileName,
                                          const DefineList &defines, Diagnostics &diag);
std::optional<SceneDesc> ParseSceneString(const std::string &text, const std::string &virtualFileName,
                                          const ParseOptions &options, Diagnostics &diag);

/// Splits a command-line argument "name=value" (the text after -D). Returns nullopt (and
/// reports an error) if there is no '=' or the name is not an identifier.
std::optional<std::pair<std::string, std::string>> SplitDefineArgument(const std::string &arg,
                                                                       Diagnostics &diag);

/// Evaluates one standalone value expression (no $variables), e.g. "150 um" → 1.5e-4 (length).
/// Used by tests and tools; errors go to `diag` with positions in `virtualFileName`.
std::optional<Value> ParseValueString(const std::string &text, const std::string &virtualFileName,
                                      Diagnostics &diag);

/// The canonical text of a .wscene file (`phasor format`): the source structure is kept
/// (Includes, Defines, expressions, comments), layout and spacing are normalised. Only the one
/// file is read (Includes are not followed). Returns nullopt if the file has lexical or syntax
/// errors. Re-parsing the output gives a SceneDesc identical to the input's (Value::SameAs).
std::optional<std::string> FormatSceneString(const std::string &text, const std::string &virtualFileName,
                                             Diagnostics &diag);
std::optional<std::string> FormatSceneFile(const std::string &path, Diagnostics &diag);

/// True if two scene descriptions are identical entity by entity (keyword, type, name and every
/// parameter's name and value by Value::SameAs, in order); locations are ignored. If `why` is
/// given, it receives a description of the first difference.
bool SameScene(const SceneDesc &a, const SceneDesc &b, std::string *why = nullptr);

/// Names the math functions the parser evaluates itself (round, min, sqrt, …).
const std::vector<std::string> &MathFunctionNames();

}  // namespace phasor
