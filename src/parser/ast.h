// SPDX-License-Identifier: Apache-2.0
// phasor — the syntax tree of one .wscene file, as written (docs/wscene.md). The resolver turns
// it into a SceneDesc; the canonical printer prints it back (keeping Defines, expressions and
// comments).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "parser/lexer.h"

namespace phasor::wscene {

/// A position inside one file (the file name is kept by the owner of the tree).
struct Pos {
    int line = 0, col = 0, length = 1;
};

struct Expr {
    enum class Kind {
        Number,  // text: literal; unit: unit text or ""
        Imag,    // text: literal without 'i'
        String,  // text: content
        Bool,    // boolean
        Ref,     // text: name
        Var,     // text: name
        List,    // kids: items; unit: unit text or ""
        Call,    // text: function name; kids: arguments; argNames: one per argument ("" = positional)
        Unary,   // text: "-", "+" or "not"; kids[0]: operand
        Binary,  // text: operator ("+", "*", "==", "and", …); kids[0], kids[1]
        Paren,   // kids[0]: the parenthesised expression
    };
    Kind kind = Kind::Number;
    std::string text;
    std::string unit;
    Pos unitPos;
    bool boolean = false;
    std::vector<Expr> kids;
    std::vector<std::string> argNames;
    std::vector<Pos> argNamePos;
    Pos pos;    // span of the whole expression (clipped to its first line)
    Pos opPos;  // Unary/Binary: the operator
};

/// Comments attached to an item: the lines before it and the comment ending its line.
struct Comments {
    std::vector<std::string> leading;  // comment texts (without '#'); "\n" marks an empty line
    std::string trailing;
    bool hasTrailing = false;
    bool blankBefore = false;  // the source had an empty line before the item (or its comments)
};

struct ParamNode {
    std::string name;
    Pos namePos;
    Expr value;
    Comments comments;
};

struct Stmt {
    enum class Kind { Header, Include, Define, Block };
    Kind kind = Kind::Block;
    std::string keyword;  // "wscene", "Include", "Define", "Shape", "Render", …
    Pos pos;              // the keyword
    // Header: version literal. Include: path. Block: plug-in type (hasType).
    std::string text;
    Pos textPos;
    bool hasType = false;
    // Define: variable name. Block: entity name (hasName).
    std::string name;
    Pos namePos;
    bool hasName = false;
    Expr value;                                // Define
    std::vector<ParamNode> params;             // Block
    std::vector<std::string> closingComments;  // Block: comments before '}'
    bool closingBlankBefore = false;
    Comments comments;
    bool broken = false;  // a syntax error inside; only the header (keyword, type, name) is valid
};

struct FileAst {
    std::vector<Stmt> stmts;
    std::vector<std::string> trailingComments;  // after the last statement
    bool trailingBlankBefore = false;
    bool lexError = false;     // at least one lexical error (text after it was skipped)
    bool syntaxError = false;  // at least one syntax error (recovered from)
};

/// Parses one file into `out`, reporting lexical and syntax errors to `diag` (positions in
/// `fileName`). Returns false if any error was reported. `notes` are attached to every error
/// (the include chain). With `onStmt`, each statement is handed over as soon as it is parsed
/// (and not stored in out.stmts), so a large file never exists as a whole tree.
bool ParseFileAst(const std::string &text, const std::string &fileName, Diagnostics &diag, FileAst &out,
                  const std::vector<Diagnostic> &notes = {}, const std::function<void(Stmt &)> &onStmt = {});

/// Parses a single value expression (a command-line `-D` value) placed at (line, col) of the
/// pseudo-file `fileName`. Returns false after reporting an error.
bool ParseExprAst(const std::string &text, const std::string &fileName, int line, int col, Diagnostics &diag,
                  Expr &out);

/// Canonical text of an expression (single line).
std::string PrintExpr(const Expr &e);

/// The text of a scene file, or why there is none.
struct FileText {
    std::optional<std::string> text;
    std::string problem;    // without text: "no such file", "it is a directory", …
    bool tooLarge = false;  // the problem is the size limit
    static FileText TooLarge(std::size_t limit);  // "it is larger than the limit of … for a scene"
};

/// Reads a regular file of at most `limit` bytes. Other files (directories, devices such as
/// /dev/zero, pipes) are refused before they are opened: reading them may never end.
FileText ReadSceneText(const std::string &path, std::size_t limit);

}  // namespace phasor::wscene
