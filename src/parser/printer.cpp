// SPDX-License-Identifier: Apache-2.0
// phasor — the canonical .wscene printer (`phasor format`, docs/wscene.md §8). Prints the syntax
// tree with normalised layout: one statement per line group, 4-space indented parameters, one
// space around binary operators, units separated from their number by one space, long lists
// wrapped. Comments and single empty lines are kept.
#include <fstream>
#include <sstream>

#include "parser/ast.h"
#include "parser/parser.h"

namespace phasor {

namespace wscene {

namespace {

constexpr int kWidth = 100;  // wrap lists whose one-line form would pass this column

std::string Quote(const std::string &s) {
    std::string out = "\"";
    for (char c : s) {
        switch (c) {
            case '"':
                out += "\\\"";
                break;
            case '\\':
                out += "\\\\";
                break;
            case '\n':
                out += "\\n";
                break;
            case '\t':
                out += "\\t";
                break;
            case '\r':
                out += "\\r";
                break;
            default:
                out += c;
        }
    }
    return out + "\"";
}

bool IsCompactComplex(const Expr &e) {
    return e.kind == Expr::Kind::Binary && (e.text == "+" || e.text == "-") &&
           e.kids[1].kind == Expr::Kind::Imag && e.kids[0].kind == Expr::Kind::Number &&
           e.kids[0].unit.empty();
}

void Print(const Expr &e, std::string &out, int indent, int column);

// Prints a list; wraps items over several lines when the one-line form is too long.
void PrintList(const Expr &e, std::string &out, int indent, int column) {
    std::string oneLine = "[";
    for (std::size_t i = 0; i < e.kids.size(); ++i) {
        if (i) oneLine += ' ';
        Print(e.kids[i], oneLine, indent + 4, 0);
    }
    oneLine += ']';
    std::string unit = e.unit.empty() ? "" : " " + e.unit;
    if (column + (int)oneLine.size() + (int)unit.size() <= kWidth || e.kids.size() < 2) {
        out += oneLine + unit;
        return;
    }
    std::string pad(indent + 4, ' ');
    out += "[\n" + pad;
    int col = indent + 4;
    for (std::size_t i = 0; i < e.kids.size(); ++i) {
        std::string item;
        Print(e.kids[i], item, indent + 4, col);
        if (i > 0) {
            if (col + 1 + (int)item.size() > kWidth) {
                out += "\n" + pad;
                col = indent + 4;
            } else {
                out += ' ';
                ++col;
            }
        }
        out += item;
        col += (int)item.size();
    }
    out += "\n" + std::string(indent, ' ') + "]" + unit;
}

void Print(const Expr &e, std::string &out, int indent, int column) {
    switch (e.kind) {
        case Expr::Kind::Number:
            out += e.text;
            if (!e.unit.empty()) out += " " + e.unit;
            return;
        case Expr::Kind::Imag:
            out += e.text + "i";
            return;
        case Expr::Kind::String:
            out += Quote(e.text);
            return;
        case Expr::Kind::Bool:
            out += e.boolean ? "true" : "false";
            return;
        case Expr::Kind::Ref:
            out += "@" + e.text;
            return;
        case Expr::Kind::Var:
            out += "$" + e.text;
            return;
        case Expr::Kind::List: {
            std::size_t lineStart = out.rfind('\n');
            int col = column + int(out.size() - (lineStart == std::string::npos ? 0 : lineStart + 1));
            if (lineStart == std::string::npos) col = column + (int)out.size();
            PrintList(e, out, indent, col);
            return;
        }
        case Expr::Kind::Call:
            out += e.text + "(";
            for (std::size_t i = 0; i < e.kids.size(); ++i) {
                if (i) out += ", ";
                if (i < e.argNames.size() && !e.argNames[i].empty()) out += e.argNames[i] + " = ";
                Print(e.kids[i], out, indent, column);
            }
            out += ")";
            return;
        case Expr::Kind::Unary:
            out += e.text == "not" ? "not " : e.text;
            Print(e.kids[0], out, indent, column);
            return;
        case Expr::Kind::Binary:
            Print(e.kids[0], out, indent, column);
            out += IsCompactComplex(e) ? e.text : " " + e.text + " ";
            Print(e.kids[1], out, indent, column);
            return;
        case Expr::Kind::Paren:
            out += "(";
            Print(e.kids[0], out, indent, column);
            out += ")";
            return;
    }
}

void PrintComments(const std::vector<std::string> &lines, std::string &out, int indent) {
    for (const std::string &l : lines) {
        if (l == "\n")
            out += "\n";
        else
            out += std::string(indent, ' ') + "#" + l + "\n";
    }
}

void PrintLeading(const Comments &c, std::string &out, int indent, bool first) {
    if (c.blankBefore && !first) out += "\n";
    PrintComments(c.leading, out, indent);
}

void EndLine(const Comments &c, std::string &out) {
    if (c.hasTrailing) out += "  #" + c.trailing;
    out += "\n";
}

std::string FormatAst(const FileAst &ast) {
    std::string out;
    bool first = true;
    for (const Stmt &st : ast.stmts) {
        PrintLeading(st.comments, out, 0, first);
        first = false;
        switch (st.kind) {
            case Stmt::Kind::Header:
                out += "wscene " + st.text;
                break;
            case Stmt::Kind::Include:
                out += "Include " + Quote(st.text);
                break;
            case Stmt::Kind::Define: {
                out += "Define " + st.name + " = ";
                Print(st.value, out, 0, 0);
                break;
            }
            case Stmt::Kind::Block: {
                out += st.keyword;
                if (st.hasType) out += " " + Quote(st.text);
                if (st.hasName) out += " " + Quote(st.name);
                if (st.params.empty() && st.closingComments.empty()) {
                    out += " {}";
                    break;
                }
                out += " {\n";
                bool firstParam = true;
                for (const ParamNode &p : st.params) {
                    PrintLeading(p.comments, out, 4, firstParam);
                    firstParam = false;
                    std::string line = "    " + p.name + " = ";
                    Print(p.value, line, 4, 0);
                    out += line;
                    EndLine(p.comments, out);
                }
                if (st.closingBlankBefore && !firstParam) out += "\n";
                PrintComments(st.closingComments, out, 4);
                out += "}";
                break;
            }
        }
        EndLine(st.comments, out);
    }
    if (ast.trailingBlankBefore && !first) out += "\n";
    PrintComments(ast.trailingComments, out, 0);
    return out;
}

}  // namespace

std::string PrintExpr(const Expr &e) {
    std::string out;
    Print(e, out, 0, 0);
    return out;
}

}  // namespace wscene

std::optional<std::string> FormatSceneString(const std::string &text, const std::string &virtualFileName,
                                             Diagnostics &diag) {
    diag.AddSource(virtualFileName, text);
    wscene::FileAst ast;
    if (!wscene::ParseFileAst(text, virtualFileName, diag, ast) || ast.lexError || ast.syntaxError)
        return std::nullopt;
    return wscene::FormatAst(ast);
}

std::optional<std::string> FormatSceneFile(const std::string &path, Diagnostics &diag) {
    wscene::FileText file = wscene::ReadSceneText(path, ParseOptions{}.maxSceneBytes);
    if (!file.text) {
        diag.Error(FileLoc{path, 0, 0, 1}, "cannot read scene file '" + path + "': " + file.problem);
        return std::nullopt;
    }
    return FormatSceneString(*file.text, path, diag);
}

}  // namespace phasor
