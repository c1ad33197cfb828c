// SPDX-License-Identifier: Apache-2.0
#include "parser/eval.h"

#include <charconv>
#include <cmath>
#include <set>

#include "core/math.h"
#include "core/units.h"
#include "parser/parser.h"

namespace phasor {

const std::vector<std::string> &MathFunctionNames() {
    static const std::vector<std::string> names = {
        "abs", "acos",  "asin", "atan", "atan2", "ceil",  "clamp", "cos",  "exp", "floor", "hypot",
        "log", "log10", "max",  "min",  "pow",   "round", "select", "sin", "sqrt", "tan", "trunc"};
    return names;
}

namespace wscene {

namespace {

constexpr double kMaxExactInteger = 9007199254740992.0;  // 2^53
constexpr int kMaxDimExponent = 16;

bool IsMath(const std::string &name) {
    for (const std::string &n : MathFunctionNames())
        if (n == name) return true;
    return false;
}

bool IsPlain(const Value &v) { return v.kind == Value::Kind::Number && v.dim.IsNone(); }

Value MakeNumber(double x, Dim d, bool integer, const FileLoc &loc) {
    Value v = Value::Number(x, d, loc);
    v.isInteger = integer && d.IsNone() && std::abs(x) <= kMaxExactInteger && x == std::floor(x);
    return v;
}

std::string OpWord(const std::string &op) {
    if (op == "+") return "add";
    if (op == "-") return "subtract";
    if (op == "*") return "multiply";
    if (op == "/") return "divide";
    return "apply '" + op + "' to";
}

}  // namespace

std::string DescribeValue(const Value &v) {
    switch (v.kind) {
        case Value::Kind::Number:
        case Value::Kind::Complex:
        case Value::Kind::String:
        case Value::Kind::Bool:
            return v.DescribeKind() + " (" + v.ToString() + ")";
        default:
            return v.DescribeKind();
    }
}

void Evaluator::Error(const FileLoc &loc, const std::string &msg) {
    std::vector<Diagnostic> notes;
    if (notesFor) notes = notesFor(loc.file);
    diag_.Error(loc, msg, std::move(notes));
}

bool Evaluator::CheckDim(Dim d, const FileLoc &loc) {
    for (int e : {d.length, d.angle, d.solidAngle, d.power, d.temperature, d.time})
        if (std::abs(e) > kMaxDimExponent) {
            Error(loc, "unit exponent out of range (more than " + std::to_string(kMaxDimExponent) + ")");
            return false;
        }
    return true;
}

bool Evaluator::Finite(double x, const FileLoc &loc, const char *what) {
    if (std::isfinite(x)) return true;
    Error(loc, std::string(what) + " is out of range (not a finite number)");
    return false;
}

std::optional<Value> Evaluator::Eval(const Expr &e, const std::string &file) {
    struct Depth {
        int &d;
        explicit Depth(int &dd) : d(dd) { ++d; }
        ~Depth() { --d; }
    } depthGuard(depth_);
    FileLoc loc{file, e.pos.line, e.pos.col, std::max(1, e.pos.length)};
    if (depth_ > 2000) {  // the syntax pass bounds nesting; this is a safety net
        Error(loc, "expression nested too deeply");
        return std::nullopt;
    }
    switch (e.kind) {
        case Expr::Kind::Number:
            return EvalNumber(e, loc);
        case Expr::Kind::Imag: {
            double x = 0;
            auto r = std::from_chars(e.text.data(), e.text.data() + e.text.size(), x);
            if (r.ec != std::errc() || !std::isfinite(x)) {
                Error(loc, "number '" + e.text + "i' is out of range");
                return std::nullopt;
            }
            return Value::ComplexNumber(Complex(0, x), loc);
        }
        case Expr::Kind::String:
            return Value::String(e.text, loc);
        case Expr::Kind::Bool:
            return Value::Bool(e.boolean, loc);
        case Expr::Kind::Ref:
            return Value::Ref(e.text, loc);
        case Expr::Kind::Var: {
            if (!lookupVar) {
                Error(loc, "'$" + e.text + "' is not defined");
                return std::nullopt;
            }
            return lookupVar(e, loc);
        }
        case Expr::Kind::List: {
            std::vector<Value> items;
            bool ok = true;
            for (const Expr &k : e.kids) {
                std::optional<Value> v = Eval(k, file);
                if (!v)
                    ok = false;
                else if (ok)
                    items.push_back(std::move(*v));
            }
            if (!ok) return std::nullopt;
            Value list = Value::List(std::move(items), loc);
            if (!e.unit.empty()) {
                FileLoc uLoc{file, e.unitPos.line, e.unitPos.col, std::max(1, e.unitPos.length)};
                std::optional<Unit> u = ParseUnit(e.unit);
                if (!u) {
                    std::string sug = Suggest(e.unit, KnownUnitNames());
                    Error(uLoc, "unknown unit '" + e.unit + "'" +
                                    (sug.empty() ? "" : "; did you mean '" + sug + "'?"));
                    return std::nullopt;
                }
                if (!ApplyUnit(list, u->scale, u->dim, e.unit, uLoc)) return std::nullopt;
            }
            return list;
        }
        case Expr::Kind::Call:
            return EvalCall(e, file, loc);
        case Expr::Kind::Paren: {
            std::optional<Value> v = Eval(e.kids[0], file);
            if (v) v->loc = loc;
            return v;
        }
        case Expr::Kind::Unary: {
            std::optional<Value> a = Eval(e.kids[0], file);
            if (!a) return std::nullopt;
            FileLoc opLoc{file, e.opPos.line, e.opPos.col, std::max(1, e.opPos.length)};
            return Unary(e.text, *a, opLoc, loc);
        }
        case Expr::Kind::Binary: {
            std::optional<Value> a = Eval(e.kids[0], file);
            std::optional<Value> b = Eval(e.kids[1], file);
            if (!a || !b) return std::nullopt;
            FileLoc opLoc{file, e.opPos.line, e.opPos.col, std::max(1, e.opPos.length)};
            const std::string &op = e.text;
            if (op == "and" || op == "or") {
                for (const Value *v : {&*a, &*b})
                    if (v->kind != Value::Kind::Bool) {
                        Error(v->loc, "'" + op + "' needs booleans on both sides; got " + DescribeValue(*v));
                        return std::nullopt;
                    }
                return Value::Bool(op == "and" ? (a->boolean && b->boolean) : (a->boolean || b->boolean),
                                   loc);
            }
            if (op == "==" || op == "!=" || op == "<" || op == "<=" || op == ">" || op == ">=")
                return Compare(op, *a, *b, opLoc, loc);
            return Arith(op, *a, *b, opLoc, loc);
        }
    }
    return std::nullopt;
}

std::optional<Value> Evaluator::EvalNumber(const Expr &e, const FileLoc &loc) {
    double x = 0;
    auto r = std::from_chars(e.text.data(), e.text.data() + e.text.size(), x);
    if (r.ec != std::errc() || r.ptr != e.text.data() + e.text.size() || !std::isfinite(x)) {
        Error(FileLoc{loc.file, e.pos.line, e.pos.col, (int)e.text.size()},
              "number '" + e.text + "' is out of range");
        return std::nullopt;
    }
    bool integer = e.text.find_first_of(".eE") == std::string::npos;
    if (e.unit.empty()) return MakeNumber(x, Dim::None(), integer, loc);
    FileLoc uLoc{loc.file, e.unitPos.line, e.unitPos.col, std::max(1, e.unitPos.length)};
    std::optional<Unit> u = ParseUnit(e.unit);
    if (!u) {
        std::string sug = Suggest(e.unit, KnownUnitNames());
        Error(uLoc, "unknown unit '" + e.unit + "'" + (sug.empty() ? "" : "; did you mean '" + sug + "'?"));
        return std::nullopt;
    }
    if (!CheckDim(u->dim, uLoc)) return std::nullopt;
    double si = x * u->scale;
    if (!Finite(si, loc, ("'" + e.text + " " + e.unit + "'").c_str())) return std::nullopt;
    return Value::Number(si, u->dim, loc);
}

bool Evaluator::ApplyUnit(Value &v, double scale, Dim dim, const std::string &unit, const FileLoc &unitLoc) {
    if (v.kind == Value::Kind::List) {
        bool ok = true;
        for (Value &it : v.items) ok = ApplyUnit(it, scale, dim, unit, unitLoc) && ok;
        return ok;
    }
    if (!IsPlain(v)) {
        Error(v.loc, "the list's unit '" + unit + "' applies to every item, but this item is " +
                         DescribeValue(v) + " (give either the list a unit or its items, not both)");
        return false;
    }
    if (!CheckDim(dim, unitLoc)) return false;
    v.number *= scale;
    v.dim = dim;
    v.isInteger = false;
    return Finite(v.number, v.loc, "the value");
}

std::optional<Value> Evaluator::EvalCall(const Expr &e, const std::string &file, const FileLoc &loc) {
    std::vector<Value> args;
    std::vector<std::string> names;
    std::vector<FileLoc> nameLocs;
    bool ok = true;
    std::set<std::string> seen;
    for (std::size_t i = 0; i < e.kids.size(); ++i) {
        const std::string &n = i < e.argNames.size() ? e.argNames[i] : std::string();
        if (!n.empty() && !seen.insert(n).second) {
            const Pos &p = e.argNamePos[i];
            Error(FileLoc{file, p.line, p.col, std::max(1, p.length)},
                  "argument '" + n + "' is given twice in the call to '" + e.text + "'");
            ok = false;
        }
        std::optional<Value> v = Eval(e.kids[i], file);
        if (!v) {
            ok = false;
            continue;
        }
        args.push_back(std::move(*v));
        names.push_back(n);
        const Pos &p = i < e.argNamePos.size() ? e.argNamePos[i] : Pos{};
        nameLocs.push_back(n.empty() ? FileLoc{} : FileLoc{file, p.line, p.col, std::max(1, p.length)});
    }
    if (!ok) return std::nullopt;
    if (IsMath(e.text)) return EvalMath(e, args, file, loc);
    Value call = Value::Call(e.text, std::move(args), std::move(names), loc);
    call.argLocs = std::move(nameLocs);  // where each named argument's name is (records report there)
    return call;
}

std::optional<Value> Evaluator::EvalMath(const Expr &e, std::vector<Value> &args, const std::string &file,
                                         const FileLoc &loc) {
    const std::string &f = e.text;
    for (std::size_t i = 0; i < e.argNames.size(); ++i)
        if (!e.argNames[i].empty()) {
            const Pos &p = e.argNamePos[i];
            Error(FileLoc{file, p.line, p.col, std::max(1, p.length)},
                  "'" + f + "' takes no named arguments");
            return std::nullopt;
        }
    // min/max also accept a single list.
    if ((f == "min" || f == "max") && args.size() == 1 && args[0].kind == Value::Kind::List) {
        std::vector<Value> items = args[0].items;
        if (items.empty()) {
            Error(args[0].loc, "'" + f + "' of an empty list");
            return std::nullopt;
        }
        args = std::move(items);
    }
    auto arity = [&](std::size_t lo, std::size_t hi) {
        if (args.size() >= lo && args.size() <= hi) return true;
        std::string want = lo == hi   ? std::to_string(lo)
                           : hi > 100 ? "at least " + std::to_string(lo)
                                      : std::to_string(lo) + " to " + std::to_string(hi);
        Error(loc, "'" + f + "' takes " + want + " argument" + (lo == 1 && hi == 1 ? "" : "s") + "; got " +
                       std::to_string(args.size()));
        return false;
    };
    if (f == "select") {  // select(condition, a, b): a if the boolean condition holds, else b
        if (!arity(3, 3)) return std::nullopt;
        if (args[0].kind != Value::Kind::Bool) {
            Error(args[0].loc, "'select' needs a boolean condition first; got " + DescribeValue(args[0]));
            return std::nullopt;
        }
        return args[0].boolean ? args[1] : args[2];
    }
    // Every argument must be a real number (abs also takes a complex number).
    for (const Value &a : args)
        if (a.kind != Value::Kind::Number && !(f == "abs" && a.kind == Value::Kind::Complex)) {
            Error(a.loc, "'" + f + "' needs numbers; got " + DescribeValue(a));
            return std::nullopt;
        }
    auto needPlain = [&](const Value &a, const std::string &hint) {
        if (IsPlain(a)) return true;
        Error(a.loc, "'" + f + "' needs a plain number; got " + DescribeValue(a) + hint);
        return false;
    };
    auto sameDims = [&]() {
        for (std::size_t i = 1; i < args.size(); ++i)
            if (args[i].dim != args[0].dim) {
                Error(args[i].loc, "'" + f + "' needs arguments of one dimension; got " +
                                       DescribeValue(args[0]) + " and " + DescribeValue(args[i]));
                return false;
            }
        return true;
    };
    auto result = [&](double x, Dim d, bool integer) -> std::optional<Value> {
        if (!Finite(x, loc, ("the result of '" + f + "'").c_str())) return std::nullopt;
        return MakeNumber(x, d, integer, loc);
    };
    const Value *a = args.empty() ? nullptr : &args[0];
    if (f == "round" || f == "floor" || f == "ceil" || f == "trunc") {
        if (!arity(1, 1) || !needPlain(*a, " (divide by a unit first, e.g. round($width / 1 um))"))
            return std::nullopt;
        double x = f == "round"   ? std::round(a->number)
                   : f == "floor" ? std::floor(a->number)
                   : f == "ceil"  ? std::ceil(a->number)
                                  : std::trunc(a->number);
        return result(x, Dim::None(), true);
    }
    if (f == "abs") {
        if (!arity(1, 1)) return std::nullopt;
        if (a->kind == Value::Kind::Complex) return result(std::abs(a->complex), Dim::None(), false);
        return result(std::abs(a->number), a->dim, a->isInteger);
    }
    if (f == "min" || f == "max") {
        if (!arity(1, 1000000) || !sameDims()) return std::nullopt;
        const Value *best = a;
        bool integer = true;
        for (const Value &v : args) {
            if (f == "min" ? v.number < best->number : v.number > best->number) best = &v;
            integer = integer && v.isInteger;
        }
        return result(best->number, best->dim, integer);
    }
    if (f == "clamp") {
        if (!arity(3, 3) || !sameDims()) return std::nullopt;
        if (args[1].number > args[2].number) {
            Error(loc, "'clamp' needs lo <= hi");
            return std::nullopt;
        }
        double x = std::min(std::max(a->number, args[1].number), args[2].number);
        return result(x, a->dim, a->isInteger && args[1].isInteger && args[2].isInteger);
    }
    if (f == "sqrt") {
        if (!arity(1, 1)) return std::nullopt;
        Dim d = a->dim;
        for (int x : {d.length, d.angle, d.solidAngle, d.power, d.temperature, d.time})
            if (x % 2 != 0) {
                Error(a->loc, "'sqrt' of " + DescribeValue(*a) + " has no unit (its exponents must be even)");
                return std::nullopt;
            }
        if (a->number < 0) {
            Error(a->loc, "'sqrt' of a negative number");
            return std::nullopt;
        }
        Dim h{int8_t(d.length / 2), int8_t(d.angle / 2),       int8_t(d.solidAngle / 2),
              int8_t(d.power / 2),  int8_t(d.temperature / 2), int8_t(d.time / 2)};
        return result(std::sqrt(a->number), h, false);
    }
    if (f == "pow") {
        if (!arity(2, 2) || !needPlain(args[1], "")) return std::nullopt;
        double n = args[1].number;
        if (!a->dim.IsNone()) {
            if (n != std::floor(n) || std::abs(n) > kMaxDimExponent) {
                Error(args[1].loc, "'pow' of " + DescribeValue(*a) + " needs a whole exponent (at most " +
                                       std::to_string(kMaxDimExponent) + ")");
                return std::nullopt;
            }
            Dim d = a->dim.Pow(int(n));
            if (!CheckDim(d, loc)) return std::nullopt;
            return result(std::pow(a->number, n), d, false);
        }
        return result(std::pow(a->number, n), Dim::None(), a->isInteger && args[1].isInteger && n >= 0);
    }
    if (f == "exp" || f == "log" || f == "log10") {
        if (!arity(1, 1) || !needPlain(*a, "")) return std::nullopt;
        if (f != "exp" && a->number <= 0) {
            Error(a->loc, "'" + f + "' of a number that is not positive");
            return std::nullopt;
        }
        double x = f == "exp"   ? std::exp(a->number)
                   : f == "log" ? std::log(a->number)
                                : std::log10(a->number);
        return result(x, Dim::None(), false);
    }
    if (f == "sin" || f == "cos" || f == "tan") {
        if (!arity(1, 1)) return std::nullopt;
        if (!a->dim.IsNone() && a->dim != Dim::Angle()) {
            Error(a->loc, "'" + f + "' needs an angle; got " + DescribeValue(*a));
            return std::nullopt;
        }
        double x = f == "sin" ? std::sin(a->number) : f == "cos" ? std::cos(a->number) : std::tan(a->number);
        return result(x, Dim::None(), false);
    }
    if (f == "asin" || f == "acos" || f == "atan") {
        if (!arity(1, 1) || !needPlain(*a, "")) return std::nullopt;
        if (f != "atan" && std::abs(a->number) > 1) {
            Error(a->loc, "'" + f + "' needs a number in [-1, 1]");
            return std::nullopt;
        }
        double x = f == "asin"   ? std::asin(a->number)
                   : f == "acos" ? std::acos(a->number)
                                 : std::atan(a->number);
        return result(x, Dim::Angle(), false);
    }
    if (f == "atan2") {
        if (!arity(2, 2) || !sameDims()) return std::nullopt;
        return result(std::atan2(a->number, args[1].number), Dim::Angle(), false);
    }
    if (f == "hypot") {
        if (!arity(2, 2) || !sameDims()) return std::nullopt;
        return result(std::hypot(a->number, args[1].number), a->dim, false);
    }
    Error(loc, "internal: unhandled math function '" + f + "'");
    return std::nullopt;
}

std::optional<Value> Evaluator::Unary(const std::string &op, const Value &a, const FileLoc &opLoc,
                                      const FileLoc &loc) {
    if (op == "not") {
        if (a.kind != Value::Kind::Bool) {
            Error(opLoc, "'not' needs a boolean; got " + DescribeValue(a));
            return std::nullopt;
        }
        return Value::Bool(!a.boolean, loc);
    }
    switch (a.kind) {
        case Value::Kind::Number: {
            Value v = a;
            if (op == "-") v.number = -v.number;
            v.loc = loc;
            return v;
        }
        case Value::Kind::Complex: {
            Value v = a;
            if (op == "-") v.complex = -v.complex;
            v.loc = loc;
            return v;
        }
        case Value::Kind::List: {
            Value v = a;
            for (Value &it : v.items) {
                std::optional<Value> r = Unary(op, it, opLoc, it.loc);
                if (!r) return std::nullopt;
                it = std::move(*r);
            }
            v.loc = loc;
            return v;
        }
        default:
            break;
    }
    Error(opLoc, "cannot apply unary '" + op + "' to " + DescribeValue(a));
    return std::nullopt;
}

std::optional<Value> Evaluator::Arith(const std::string &op, const Value &a, const Value &b,
                                      const FileLoc &opLoc, const FileLoc &loc) {
    using K = Value::Kind;
    // Lists: elementwise (list ± list of the same length; list * or / a scalar; scalar * list).
    if (a.kind == K::List || b.kind == K::List) {
        Value out = Value::List({}, loc);
        if (a.kind == K::List && b.kind == K::List && (op == "+" || op == "-")) {
            if (a.items.size() != b.items.size()) {
                Error(opLoc, "cannot " + OpWord(op) + " lists of different lengths (" +
                                 std::to_string(a.items.size()) + " and " + std::to_string(b.items.size()) +
                                 ")");
                return std::nullopt;
            }
            for (std::size_t i = 0; i < a.items.size(); ++i) {
                std::optional<Value> r = Arith(op, a.items[i], b.items[i], opLoc, loc);
                if (!r) return std::nullopt;
                out.items.push_back(std::move(*r));
            }
            return out;
        }
        bool scalarB = b.kind == K::Number || b.kind == K::Complex;
        bool scalarA = a.kind == K::Number || a.kind == K::Complex;
        if (a.kind == K::List && scalarB && (op == "*" || op == "/")) {
            for (const Value &it : a.items) {
                std::optional<Value> r = Arith(op, it, b, opLoc, loc);
                if (!r) return std::nullopt;
                out.items.push_back(std::move(*r));
            }
            return out;
        }
        if (b.kind == K::List && scalarA && op == "*") {
            for (const Value &it : b.items) {
                std::optional<Value> r = Arith(op, a, it, opLoc, loc);
                if (!r) return std::nullopt;
                out.items.push_back(std::move(*r));
            }
            return out;
        }
        Error(opLoc, "cannot " + OpWord(op) + " " + DescribeValue(a) + " and " + DescribeValue(b));
        return std::nullopt;
    }
    if (a.kind == K::String && b.kind == K::String && op == "+") return Value::String(a.text + b.text, loc);
    bool numA = a.kind == K::Number || a.kind == K::Complex;
    bool numB = b.kind == K::Number || b.kind == K::Complex;
    if (!numA || !numB) {
        Error(opLoc, "cannot " + OpWord(op) + " " + DescribeValue(a) + " and " + DescribeValue(b));
        return std::nullopt;
    }
    if (a.kind == K::Complex || b.kind == K::Complex) {
        for (const Value *v : {&a, &b})
            if (v->kind == K::Number && !v->dim.IsNone()) {
                Error(opLoc, "cannot " + OpWord(op) + " a complex number and " + DescribeValue(*v) +
                                 " (complex numbers have no unit)");
                return std::nullopt;
            }
        Complex x = a.kind == K::Complex ? a.complex : Complex(a.number, 0);
        Complex y = b.kind == K::Complex ? b.complex : Complex(b.number, 0);
        if (op == "/" && y == Complex(0, 0)) {
            Error(opLoc, "division by zero");
            return std::nullopt;
        }
        Complex r = op == "+" ? x + y : op == "-" ? x - y : op == "*" ? x * y : x / y;
        if (!Finite(r.real(), loc, "the result") || !Finite(r.imag(), loc, "the result")) return std::nullopt;
        return Value::ComplexNumber(r, loc);
    }
    double x = a.number, y = b.number;
    if (op == "+" || op == "-") {
        if (a.dim != b.dim) {
            Error(opLoc, "cannot " + OpWord(op) + " " + DescribeValue(a) + " and " + DescribeValue(b) +
                             " (different dimensions)");
            return std::nullopt;
        }
        double r = op == "+" ? x + y : x - y;
        if (!Finite(r, loc, "the result")) return std::nullopt;
        return MakeNumber(r, a.dim, a.isInteger && b.isInteger, loc);
    }
    Dim d = op == "*" ? a.dim * b.dim : a.dim / b.dim;
    if (!CheckDim(d, opLoc)) return std::nullopt;
    if (op == "/" && y == 0) {
        Error(opLoc, "division by zero");
        return std::nullopt;
    }
    double r = op == "*" ? x * y : x / y;
    if (!Finite(r, loc, "the result")) return std::nullopt;
    return MakeNumber(r, d, op == "*" && a.isInteger && b.isInteger, loc);
}

std::optional<Value> Evaluator::Compare(const std::string &op, const Value &a, const Value &b,
                                        const FileLoc &opLoc, const FileLoc &loc) {
    using K = Value::Kind;
    bool ordering = op != "==" && op != "!=";
    if (a.kind == K::Number && b.kind == K::Number) {
        if (a.dim != b.dim) {
            Error(opLoc, "cannot compare " + DescribeValue(a) + " and " + DescribeValue(b) +
                             " (different dimensions)");
            return std::nullopt;
        }
        double x = a.number, y = b.number;
        bool r = op == "=="   ? x == y
                 : op == "!=" ? x != y
                 : op == "<"  ? x < y
                 : op == "<=" ? x <= y
                 : op == ">"  ? x > y
                              : x >= y;
        return Value::Bool(r, loc);
    }
    if (ordering) {
        Error(opLoc, "'" + op + "' compares numbers; got " + DescribeValue(a) + " and " + DescribeValue(b));
        return std::nullopt;
    }
    bool numA = a.kind == K::Number || a.kind == K::Complex,
         numB = b.kind == K::Number || b.kind == K::Complex;
    if (a.kind != b.kind && !(numA && numB)) {
        Error(opLoc, "cannot compare " + DescribeValue(a) + " and " + DescribeValue(b));
        return std::nullopt;
    }
    bool same;
    if (numA && numB && a.kind != b.kind) {
        Complex x = a.kind == K::Complex ? a.complex : Complex(a.number, 0);
        Complex y = b.kind == K::Complex ? b.complex : Complex(b.number, 0);
        same = x == y && a.dim.IsNone() && b.dim.IsNone();
    } else {
        same = a.SameAs(b);
    }
    return Value::Bool(op == "==" ? same : !same, loc);
}

}  // namespace wscene
}  // namespace phasor
