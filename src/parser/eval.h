// SPDX-License-Identifier: Apache-2.0
// phasor — evaluation of .wscene value expressions (docs/wscene.md §4): literals → SI Values,
// dimensioned arithmetic, comparisons and logic, math functions. Other calls stay symbolic.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "core/params/dict.h"
#include "parser/ast.h"

namespace phasor::wscene {

class Evaluator {
  public:
    explicit Evaluator(Diagnostics &diag) : diag_(diag) {}

    /// Resolves $name (e.text) used at `loc`; nullopt if it cannot (the callee reports why).
    std::function<std::optional<Value>(const Expr &, const FileLoc &)> lookupVar;
    /// Notes attached to every error in `file` (the include chain).
    std::function<std::vector<Diagnostic>(const std::string &file)> notesFor;

    /// Evaluates `e` (written in `file`). Returns nullopt after reporting an error, or silently
    /// when a part of it failed earlier (e.g. a $variable whose Define had an error).
    std::optional<Value> Eval(const Expr &e, const std::string &file);

  private:
    std::optional<Value> EvalNumber(const Expr &e, const FileLoc &loc);
    std::optional<Value> EvalCall(const Expr &e, const std::string &file, const FileLoc &loc);
    std::optional<Value> EvalMath(const Expr &e, std::vector<Value> &args, const std::string &file,
                                  const FileLoc &loc);
    std::optional<Value> Unary(const std::string &op, const Value &a, const FileLoc &opLoc,
                               const FileLoc &loc);
    std::optional<Value> Arith(const std::string &op, const Value &a, const Value &b, const FileLoc &opLoc,
                               const FileLoc &loc);
    std::optional<Value> Compare(const std::string &op, const Value &a, const Value &b, const FileLoc &opLoc,
                                 const FileLoc &loc);
    bool ApplyUnit(Value &v, double scale, Dim dim, const std::string &unit, const FileLoc &unitLoc);
    bool CheckDim(Dim d, const FileLoc &loc);
    bool Finite(double x, const FileLoc &loc, const char *what);
    void Error(const FileLoc &loc, const std::string &msg);

    Diagnostics &diag_;
    int depth_ = 0;
};

/// "a length (150 um)", "a string (\"x\")" — for messages.
std::string DescribeValue(const Value &v);

}  // namespace phasor::wscene
