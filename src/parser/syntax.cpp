// SPDX-License-Identifier: Apache-2.0
// phasor — .wscene syntax: tokens → FileAst (docs/wscene.md §3–§4). Recursive descent; a syntax
// error skips to the next statement keyword that starts a line; so does a lexical error (the
// lexer resynchronises there).
#include <algorithm>
#include <array>
#include <deque>
#include <functional>
#include <string_view>

#include "core/plugin_families.h"
#include "core/units.h"
#include "parser/ast.h"

namespace phasor::wscene {

namespace {

// The statement keyword of each plug-in family and a plug-in of it (for messages).
struct FamilyKeyword {
    const char *keyword, *example;
};
#define PHASOR_FAMILY_KEYWORD(Keyword, family, Interface, Example) FamilyKeyword{#Keyword, #Example},
constexpr FamilyKeyword kFamilyKeywords[] = {PHASOR_PLUGIN_FAMILIES(PHASOR_FAMILY_KEYWORD)};
#undef PHASOR_FAMILY_KEYWORD
constexpr int kMaxDepth = 256;  // nesting levels of an expression (docs/wscene.md §4)

bool IsFamilyKeyword(std::string_view w) {
    for (const FamilyKeyword &k : kFamilyKeywords)
        if (w == k.keyword) return true;
    return false;
}

std::vector<std::string> StatementKeywordList() {
    std::vector<std::string> v = {"Include", "Define", "Render"};
    for (const FamilyKeyword &k : kFamilyKeywords) v.push_back(k.keyword);
    return v;
}

// "Include, Define, Render, Spectrum, … or Integrator".
std::string StatementKeywordText() {
    const std::vector<std::string> v = StatementKeywordList();
    std::string s;
    for (std::size_t i = 0; i < v.size(); ++i) s += (i == 0 ? "" : i + 1 == v.size() ? " or " : ", ") + v[i];
    return s;
}

struct SyntaxError {};  // thrown after the error was reported
struct LexAbort {};     // thrown after a lexical error was reported

class SyntaxParser {
  public:
    // `resync`: a lexical error drops the statement it is in, like a syntax error (a file).
    SyntaxParser(std::string_view text, int line, int col, const std::string &file, Diagnostics &diag,
                 const std::vector<Diagnostic> &notes, bool resync)
        : text_(text), src_(text, line, col, resync), resync_(resync), file_(file), diag_(diag), notes_(notes) {}

    // Parses the file; each statement goes to `onStmt` if given, else into out.stmts.
    bool ParseFile(FileAst &out, const std::function<void(Stmt &)> &onStmt) {
        auto emit = [&](Stmt &st) {
            if (onStmt)
                onStmt(st);
            else
                out.stmts.push_back(std::move(st));
        };
        std::size_t errorsBefore = diag_.ErrorCount();
        lexError_ = &out.lexError;
        try {
            try {
                ParseHeader(out, emit);
            } catch (const SyntaxError &) {
                out.syntaxError = true;
                Recover(0);
            }
            for (;;) {
                Compact();
                std::size_t start = i_;
                Stmt st;
                try {
                    if (Peek().kind == Tok::End) break;
                    ParseStatement(st);
                    emit(st);
                } catch (const SyntaxError &) {
                    out.syntaxError = true;
                    if (st.broken) emit(st);
                    Recover(start);
                }
            }
        } catch (const LexAbort &) {
            out.lexError = true;
        }
        // Comments after the last statement.
        Comments tail;
        if (!out.lexError) Fill(~std::size_t(0));
        TakeLeading(out.lexError ? At(i_).offset : ~0u, tail);
        out.trailingComments = std::move(tail.leading);
        out.trailingBlankBefore = tail.blankBefore;
        return diag_.ErrorCount() == errorsBefore;
    }

    bool ParseSingleExpr(Expr &out) {
        try {
            out = ParseExpr(false);
            if (Peek().kind != Tok::End)
                Fail(Peek(), std::string("unexpected ") + Describe(Peek().kind) + " after the value");
            return true;
        } catch (const SyntaxError &) {
            return false;
        } catch (const LexAbort &) {
            return false;
        }
    }

  private:
    // ---- tokens ----------------------------------------------------------------------------
    // Lexes until token `g` (a global index) exists or the input ended.
    void Fill(std::size_t g) {
        while (!exhausted_ && base_ + toks_.size() <= g) exhausted_ = !src_.More(toks_, comments_);
    }
    // Token `g`; past the end, the final End/Error token.
    const Token &At(std::size_t g) {
        Fill(g);
        if (g >= base_ + toks_.size()) return toks_.back();
        return toks_[g - base_];
    }
    // Forgets tokens and comments before the previous token (called between statements).
    void Compact() {
        while (base_ + 1 < i_ && toks_.size() > 1) {
            toks_.pop_front();
            ++base_;
        }
        while (cbase_ < ci_ && !comments_.empty()) {
            comments_.pop_front();
            ++cbase_;
        }
    }
    bool HaveComment() { return ci_ - cbase_ < comments_.size(); }
    const Comment &CurComment() { return comments_[ci_ - cbase_]; }

    const Token &Peek(std::size_t k = 0) {
        std::size_t j = i_ + k;
        // Never look past an error token; report it when reached.
        for (std::size_t m = i_; m < j; ++m)
            if (At(m).kind == Tok::Error || At(m).kind == Tok::End) {
                j = m;
                break;
            }
        const Token &t = At(j);
        if (t.kind == Tok::Error && j == i_) LexFail(t, j);
        return t;
    }
    const Token &Next() {
        const Token &t = Peek();
        if (t.kind != Tok::End) ++i_;
        last_ = &t;
        return t;
    }
    bool IsIdent(const Token &t, std::string_view w) { return t.kind == Tok::Ident && t.text == w; }

    // Reports the Error token at global index `g` (once); then the file (or, with resync_, the
    // statement) is abandoned.
    [[noreturn]] void LexFail(const Token &t, std::size_t g) {
        ReportLexError(t, g);
        if (resync_) throw SyntaxError{};
        throw LexAbort{};
    }
    void ReportLexError(const Token &t, std::size_t g) {
        if (lexReported_ != ~std::size_t(0) && g <= lexReported_) return;
        lexReported_ = g;
        if (lexError_) *lexError_ = true;
        diag_.Error(Loc(t.line, t.col, t.length), t.text, notes_);
    }

    FileLoc Loc(int line, int col, int length) const {
        return FileLoc{file_, line, col, std::max(1, length)};
    }
    FileLoc Loc(const Token &t) const { return Loc(t.line, t.col, t.kind == Tok::End ? 1 : t.length); }
    FileLoc Loc(const Pos &p) const { return Loc(p.line, p.col, p.length); }
    static std::string Where(const Token &t) { return std::to_string(t.line) + ":" + std::to_string(t.col); }
    static Pos PosOf(const Token &t) { return Pos{t.line, t.col, std::max(1, t.length)}; }

    [[noreturn]] void Fail(const Token &t, const std::string &msg, std::vector<Diagnostic> extra = {}) {
        std::string m = msg;
        if (t.kind == Tok::End && m.rfind("unexpected end of file", 0) != 0)
            m = "unexpected end of file: " + m;
        for (const Diagnostic &n : notes_) extra.push_back(n);
        diag_.Error(Loc(t), m, std::move(extra));
        throw SyntaxError{};
    }
    std::string Got(const Token &t) {
        switch (t.kind) {
            case Tok::Ident:
                return "'" + t.text + "'";
            case Tok::Number:
                return "number " + t.text;
            case Tok::String:
                return "string \"" + t.text + "\"";
            case Tok::Ref:
                return "'@" + t.text + "'";
            case Tok::Var:
                return "'$" + t.text + "'";
            case Tok::Unit:
                return "unit '" + t.text + "'";
            default:
                return Describe(t.kind);
        }
    }
    const Token &Expect(Tok kind, const std::string &what) {
        const Token &t = Peek();
        if (t.kind != kind) Fail(t, "expected " + what + "; got " + Got(t));
        return Next();
    }

    // Skips to the next statement keyword that starts a line (or the end).
    void Recover(std::size_t start) {
        if (i_ == start && At(i_).kind != Tok::End && At(i_).kind != Tok::Error) ++i_;
        for (;;) {
            const Token &t = At(i_);
            if (t.kind == Tok::End) return;
            if (t.kind == Tok::Error) {
                if (!resync_) {
                    Peek();  // reports and throws LexAbort
                    return;
                }
                ReportLexError(t, i_);  // the lexer goes on at a statement keyword
                ++i_;
                continue;
            }
            // A statement keyword starting a line, or a name starting a line followed by a string
            // (a misspelled block keyword, reported as such).
            if (t.kind == Tok::Ident && StartsLine(i_) &&
                ((IsStatementKeyword(t.text) && t.text != "wscene") ||
                 (!IsReservedWord(t.text) && At(i_ + 1).kind == Tok::String)))
                return;
            ++i_;
        }
    }
    bool StartsLine(std::size_t k) { return k == 0 || At(k - 1).line < At(k).line; }

    // ---- comments --------------------------------------------------------------------------
    // Moves comments before `offset` into c.leading, recording empty lines.
    void TakeLeading(uint32_t offset, Comments &c) {
        while (HaveComment() && CurComment().offset < offset) {
            const Comment &cm = CurComment();
            if (cm.line > prevLine_ + 1 && prevLine_ > 0) {
                if (c.leading.empty())
                    c.blankBefore = true;
                else
                    c.leading.push_back("\n");
            }
            c.leading.push_back(cm.text);
            prevLine_ = cm.line;
            ++ci_;
        }
    }
    void StartItem(const Token &t, Comments &c) {
        TakeLeading(t.offset, c);
        if (t.line > prevLine_ + 1 && prevLine_ > 0) {
            if (c.leading.empty())
                c.blankBefore = true;
            else
                c.leading.push_back("\n");
        }
    }
    // After an item's last token: comments inside it move before it; a comment on its last line
    // becomes the trailing comment.
    void EndItem(Comments &c) {
        if (!last_) return;
        while (HaveComment() && CurComment().offset < last_->offset) {
            c.leading.push_back(CurComment().text);
            ++ci_;
        }
        prevLine_ = last_->line;
        // (Only if no other token follows on that line before the comment.)
        uint32_t nextOffset = At(i_).offset;  // lexes the comments before the next token
        if (HaveComment() && CurComment().line == last_->line && CurComment().offset < nextOffset) {
            c.trailing = CurComment().text;
            c.hasTrailing = true;
            ++ci_;
        }
    }

    // ---- statements ------------------------------------------------------------------------
    void ParseHeader(FileAst &out, const std::function<void(Stmt &)> &emit) {
        const Token &t = Peek();
        if (!IsIdent(t, "wscene")) {
            if (t.kind == Tok::End) {
                diag_.Error(Loc(t), "empty scene: a .wscene file must start with the header 'wscene 1'",
                            notes_);
                return;
            }
            diag_.Error(Loc(t),
                        "missing header: a .wscene file must start with 'wscene 1' (got " + Got(t) + ")",
                        notes_);
            out.syntaxError = true;
            return;
        }
        Stmt st;
        st.kind = Stmt::Kind::Header;
        st.keyword = "wscene";
        StartItem(t, st.comments);
        st.pos = PosOf(Next());
        const Token &v = Peek();
        if (v.kind != Tok::Number) {
            diag_.Error(Loc(v), "expected the format version after 'wscene' (e.g. wscene 1); got " + Got(v),
                        notes_);
            out.syntaxError = true;
            emit(st);
            return;
        }
        Next();
        st.text = v.text;
        st.textPos = PosOf(v);
        if (Peek().kind == Tok::Unit) {
            diag_.Error(Loc(Peek()), "unexpected unit after the format version", notes_);
            out.syntaxError = true;
            Next();
        }
        EndItem(st.comments);
        emit(st);
    }

    void ParseStatement(Stmt &st) {
        const Token &t = Peek();
        if (t.kind != Tok::Ident) {
            std::string hint;
            if (t.kind == Tok::RBrace) hint = " ('}' without a matching '{')";
            Fail(t,
                 "expected a statement (Include, Define, Render or a block such as Shape \"sphere\" { … }); "
                 "got " +
                     Got(t) + hint);
        }
        StartItem(t, st.comments);
        if (t.text == "Include") {
            st.kind = Stmt::Kind::Include;
            st.keyword = t.text;
            st.pos = PosOf(Next());
            const Token &p = Expect(Tok::String, "the file name in quotes after 'Include'");
            st.text = p.text;
            st.textPos = PosOf(p);
        } else if (t.text == "Define") {
            st.kind = Stmt::Kind::Define;
            st.keyword = t.text;
            st.pos = PosOf(Next());
            const Token &n = Peek();
            if (n.kind == Tok::Var)
                Fail(n, "write the variable's name without '$' after Define (Define " + n.text + " = …)");
            if (n.kind != Tok::Ident) Fail(n, "expected a variable name after 'Define'; got " + Got(n));
            if (IsReservedWord(n.text))
                Fail(n, "'" + n.text + "' is a reserved word and cannot name a variable");
            Next();
            st.name = n.text;
            st.namePos = PosOf(n);
            st.hasName = true;
            st.broken = true;  // until the value parsed
            Expect(Tok::Assign, "'=' after 'Define " + st.name + "'");
            st.value = ParseExpr(false);
            st.broken = false;
        } else if (t.text == "Render") {
            st.kind = Stmt::Kind::Block;
            st.keyword = t.text;
            st.pos = PosOf(Next());
            if (Peek().kind == Tok::String)
                Fail(Peek(), "'Render' takes no type or name: write Render { … }");
            st.broken = true;
            ParseBody(st);
            st.broken = false;
        } else if (IsFamilyKeyword(t.text)) {
            st.kind = Stmt::Kind::Block;
            st.keyword = t.text;
            st.pos = PosOf(Next());
            const Token &ty = Peek();
            if (ty.kind != Tok::String)
                Fail(ty, "expected the plug-in type in quotes after '" + st.keyword + "' (e.g. " +
                             st.keyword + " \"" + ExampleType(st.keyword) + "\" { … }); got " + Got(ty));
            Next();
            st.text = ty.text;
            st.textPos = PosOf(ty);
            st.hasType = true;
            if (Peek().kind == Tok::String) {
                const Token &nm = Next();
                st.name = nm.text;
                st.namePos = PosOf(nm);
                st.hasName = true;
            }
            st.broken = true;
            ParseBody(st);
            st.broken = false;
        } else if (t.text == "wscene") {
            Fail(t, "the header 'wscene " + std::string("1") +
                        "' may appear only once, at the start of the file");
        } else {
            std::string sug = Suggest(t.text, StatementKeywordList());
            if (sug.empty()) {
                // Case-insensitive match ("shape" → "Shape").
                for (const std::string &k : StatementKeywordList()) {
                    std::string a = k, b = t.text;
                    std::transform(a.begin(), a.end(), a.begin(), ::tolower);
                    std::transform(b.begin(), b.end(), b.begin(), ::tolower);
                    if (a == b) sug = k;
                }
            }
            if (Peek(1).kind == Tok::Assign)
                Fail(t, "parameter '" + t.text +
                            "' outside a block; parameters go inside { } after a block header");
            Fail(t,
                 "unknown statement '" + t.text + "'" +
                     (sug.empty() ? " (expected " + StatementKeywordText() + ")"
                                  : "; did you mean '" + sug + "'?"));
        }
        EndItem(st.comments);
    }

    static std::string ExampleType(const std::string &kw) {
        for (const FamilyKeyword &k : kFamilyKeywords)
            if (kw == k.keyword) return k.example;
        return "";
    }

    void ParseBody(Stmt &st) {
        const Token &open = Peek();
        if (open.kind != Tok::LBrace)
            Fail(open, "expected '{' to open the parameters of " + st.keyword +
                           (st.hasType ? " \"" + st.text + "\"" : std::string()) + "; got " + Got(open));
        Next();
        const Token &openTok = *last_;
        prevLine_ = openTok.line;
        std::vector<Diagnostic> openNote = {
            Diagnostic{Severity::Note, Loc(openTok), "the block was opened here", {}}};
        for (;;) {
            const Token &t = Peek();
            if (t.kind == Tok::RBrace) {
                Comments closing;
                TakeLeading(t.offset, closing);
                st.closingComments = std::move(closing.leading);
                st.closingBlankBefore = closing.blankBefore;
                Next();
                return;
            }
            if (t.kind == Tok::End)
                Fail(t, "unexpected end of file: missing '}' to close " + st.keyword + " block", openNote);
            if (t.kind != Tok::Ident) {
                std::string hint;
                if (t.kind == Tok::Comma)
                    hint = " (parameters are separated by spaces or line breaks, not ',')";
                Fail(t, "expected a parameter name or '}'; got " + Got(t) + hint);
            }
            if (IsStatementKeyword(t.text) && Peek(1).kind != Tok::Assign)
                Fail(t, "missing '}' before '" + t.text + "' (the " + st.keyword + " block is not closed)",
                     openNote);
            if (Peek(1).kind != Tok::Assign) {
                const Token &a = Peek(1);
                Next();
                Fail(a, "expected '=' after parameter name '" + t.text + "'; got " + Got(a));
            }
            ParamNode p;
            StartItem(t, p.comments);
            p.name = t.text;
            p.namePos = PosOf(t);
            Next();
            Next();  // '='
            if (Peek().kind == Tok::RBrace || Peek().kind == Tok::End)
                Fail(Peek(), "expected a value after '" + p.name + " ='; got " + Got(Peek()));
            p.value = ParseExpr(false);
            EndItem(p.comments);
            st.params.push_back(std::move(p));
        }
    }

    // ---- expressions -----------------------------------------------------------------------
    struct DepthGuard {
        SyntaxParser &p;
        explicit DepthGuard(SyntaxParser &pp) : p(pp) {
            if (++p.depth_ > kMaxDepth) p.Fail(p.Peek(), "expression nested too deeply");
        }
        ~DepthGuard() { --p.depth_; }
    };

    // Each operator of a chain ("a + b + c") adds a level to the tree; count it like nesting.
    struct ChainGuard {
        SyntaxParser &p;
        int n = 0;
        explicit ChainGuard(SyntaxParser &pp) : p(pp) {}
        void Step() {
            ++n;
            if (++p.depth_ > kMaxDepth) p.Fail(p.Peek(), "expression nested too deeply");
        }
        ~ChainGuard() { p.depth_ -= n; }
    };

    // Span from token `first` to the last consumed token, clipped to the first line.
    Pos Span(const Token &first) {
        Pos p = PosOf(first);
        if (!last_) return p;
        uint32_t end = last_->endOffset;
        if (last_->line != first.line) {
            std::size_t nl = text_.find('\n', first.offset);
            end = nl == std::string_view::npos ? (uint32_t)text_.size() : (uint32_t)nl;
            if (end > first.offset && text_[end - 1] == '\r') --end;
        }
        p.length = std::max(1, int(end) - int(first.offset));
        return p;
    }

    Expr MakeBinary(const Token &first, const Token &op, Expr l, Expr r) {
        Expr e;
        e.kind = Expr::Kind::Binary;
        e.text = op.text;
        e.opPos = PosOf(op);
        e.kids.reserve(2);
        e.kids.push_back(std::move(l));
        e.kids.push_back(std::move(r));
        e.pos = Span(first);
        return e;
    }

    Expr ParseExpr(bool listElem) {
        DepthGuard g(*this);
        return ParseOr(listElem);
    }
    Expr ParseOr(bool listElem) {
        const Token &first = Peek();
        Expr l = ParseAnd(listElem);
        ChainGuard chain(*this);
        while (IsIdent(Peek(), "or")) {
            chain.Step();
            const Token &op = Next();
            Expr r = ParseAnd(listElem);
            l = MakeBinary(first, op, std::move(l), std::move(r));
        }
        return l;
    }
    Expr ParseAnd(bool listElem) {
        const Token &first = Peek();
        Expr l = ParseNot(listElem);
        ChainGuard chain(*this);
        while (IsIdent(Peek(), "and")) {
            chain.Step();
            const Token &op = Next();
            Expr r = ParseNot(listElem);
            l = MakeBinary(first, op, std::move(l), std::move(r));
        }
        return l;
    }
    Expr ParseNot(bool listElem) {
        if (IsIdent(Peek(), "not")) {
            DepthGuard g(*this);
            const Token &op = Next();
            Expr e;
            e.kind = Expr::Kind::Unary;
            e.text = "not";
            e.opPos = PosOf(op);
            e.kids.push_back(ParseNot(listElem));
            e.pos = Span(op);
            return e;
        }
        return ParseCmp(listElem);
    }
    static bool IsCmp(Tok k) {
        return k == Tok::Eq || k == Tok::Ne || k == Tok::Lt || k == Tok::Le || k == Tok::Gt || k == Tok::Ge;
    }
    Expr ParseCmp(bool listElem) {
        const Token &first = Peek();
        Expr l = ParseSum(listElem);
        if (IsCmp(Peek().kind)) {
            const Token &op = Next();
            Expr r = ParseSum(listElem);
            l = MakeBinary(first, op, std::move(l), std::move(r));
            if (IsCmp(Peek().kind)) Fail(Peek(), "comparisons cannot be chained; combine them with 'and'");
        }
        return l;
    }
    Expr ParseSum(bool listElem) {
        const Token &first = Peek();
        Expr l = ParseProd(listElem);
        ChainGuard chain(*this);
        for (;;) {
            const Token &op = Peek();
            if (op.kind != Tok::Plus && op.kind != Tok::Minus) break;
            // In a list, "[0 -1 0]": a sign after a space and glued to its operand starts a new item.
            if (listElem && op.spaceBefore && !op.spaceAfter) break;
            chain.Step();
            Next();
            Expr r = ParseProd(listElem);
            l = MakeBinary(first, op, std::move(l), std::move(r));
        }
        return l;
    }
    Expr ParseProd(bool listElem) {
        const Token &first = Peek();
        Expr l = ParseUnary(listElem);
        ChainGuard chain(*this);
        for (;;) {
            const Token &op = Peek();
            if (op.kind != Tok::Star && op.kind != Tok::Slash) break;
            chain.Step();
            Next();
            Expr r = ParseUnary(listElem);
            l = MakeBinary(first, op, std::move(l), std::move(r));
        }
        return l;
    }
    Expr ParseUnary(bool listElem) {
        const Token &t = Peek();
        if (t.kind == Tok::Minus || t.kind == Tok::Plus) {
            DepthGuard g(*this);
            Next();
            Expr e;
            e.kind = Expr::Kind::Unary;
            e.text = t.text;
            e.opPos = PosOf(t);
            e.kids.push_back(ParseUnary(listElem));
            e.pos = Span(t);
            return e;
        }
        return ParsePrimary();
    }

    Expr ParsePrimary() {
        const Token &t = Peek();
        Expr e;
        e.pos = PosOf(t);
        switch (t.kind) {
            case Tok::Number:
                Next();
                e.kind = Expr::Kind::Number;
                e.text = t.text;
                if (Peek().kind == Tok::Unit) {
                    const Token &u = Next();
                    e.unit = u.text;
                    e.unitPos = PosOf(u);
                }
                e.pos = Span(t);
                return e;
            case Tok::Imag:
                Next();
                e.kind = Expr::Kind::Imag;
                e.text = t.text;
                return e;
            case Tok::String:
                Next();
                e.kind = Expr::Kind::String;
                e.text = t.text;
                return e;
            case Tok::Ref:
            case Tok::Var:
                Next();
                e.kind = t.kind == Tok::Ref ? Expr::Kind::Ref : Expr::Kind::Var;
                e.text = t.text;
                return e;
            case Tok::LBracket:
                return ParseList();
            case Tok::LParen: {
                DepthGuard g(*this);
                Next();
                e.kind = Expr::Kind::Paren;
                e.kids.push_back(ParseExpr(false));
                if (Peek().kind != Tok::RParen)
                    Fail(Peek(), "expected ')' to close the '(' at " + Where(t) + "; got " + Got(Peek()));
                Next();
                e.pos = Span(t);
                return e;
            }
            case Tok::Ident: {
                if (t.text == "true" || t.text == "false") {
                    Next();
                    e.kind = Expr::Kind::Bool;
                    e.boolean = t.text == "true";
                    return e;
                }
                if (Peek(1).kind == Tok::LParen && !IsReservedWord(t.text)) return ParseCall();
                std::string hint;
                if (ParseUnit(t.text))
                    hint = "; a unit must follow its number on the same line (e.g. 2 " + t.text + ")";
                else if (IsStatementKeyword(t.text))
                    hint = "; a value is missing before it";
                else if (!IsReservedWord(t.text))
                    hint = "; write strings in quotes (\"" + t.text + "\"), references as @" + t.text +
                           " and variables as $" + t.text;
                Fail(t, "expected a value; got '" + t.text + "'" + hint);
            }
            case Tok::Unit:
                Fail(t, "unexpected unit '" + t.text + "'");
            default:
                break;
        }
        Fail(t, "expected a value; got " + Got(t));
    }

    Expr ParseList() {
        DepthGuard g(*this);
        const Token &open = Next();
        Expr e;
        e.kind = Expr::Kind::List;
        for (;;) {
            const Token &t = Peek();
            if (t.kind == Tok::RBracket) break;
            if (t.kind == Tok::End)
                Fail(t, "unexpected end of file: missing ']' to close the list opened at " + Where(open));
            if (t.kind == Tok::Comma) Fail(t, "expected a list item; got ','");
            if (t.kind == Tok::RBrace || (t.kind == Tok::Ident && IsStatementKeyword(t.text)))
                Fail(t, "missing ']' to close the list opened at " + Where(open));
            e.kids.push_back(ParseExpr(true));
            if (Peek().kind == Tok::Comma) Next();
        }
        Next();  // ']'
        if (Peek().kind == Tok::Unit) {
            const Token &u = Next();
            e.unit = u.text;
            e.unitPos = PosOf(u);
        }
        e.pos = Span(open);
        return e;
    }

    Expr ParseCall() {
        DepthGuard g(*this);
        const Token &name = Next();
        const Token &open = Next();  // '('
        Expr e;
        e.kind = Expr::Kind::Call;
        e.text = name.text;
        for (;;) {
            const Token &t = Peek();
            if (t.kind == Tok::RParen) break;
            if (t.kind == Tok::End)
                Fail(t, "unexpected end of file: missing ')' to close the call to '" + name.text +
                            "' opened at " + Where(open));
            std::string argName;
            Pos argPos;
            if (t.kind == Tok::Ident && Peek(1).kind == Tok::Assign) {
                argName = t.text;
                argPos = PosOf(t);
                Next();
                Next();
            }
            e.kids.push_back(ParseExpr(false));
            e.argNames.push_back(argName);
            e.argNamePos.push_back(argPos);
            if (Peek().kind == Tok::Comma) {
                Next();
                continue;
            }
            if (Peek().kind != Tok::RParen)
                Fail(Peek(),
                     "expected ',' or ')' in the arguments of '" + name.text + "'; got " + Got(Peek()));
        }
        Next();  // ')'
        e.pos = Span(name);
        return e;
    }

    std::string_view text_;
    TokenSource src_;
    bool resync_;
    bool *lexError_ = nullptr;                  // FileAst::lexError of the file being parsed
    std::size_t lexReported_ = ~std::size_t(0);  // the last Error token reported
    std::deque<Token> toks_;        // tokens base_ … base_ + size - 1 (global indices)
    std::deque<Comment> comments_;  // comments cbase_ …
    std::size_t base_ = 0, cbase_ = 0;
    bool exhausted_ = false;
    const std::string &file_;
    Diagnostics &diag_;
    const std::vector<Diagnostic> &notes_;
    std::size_t i_ = 0;
    std::size_t ci_ = 0;
    int prevLine_ = 0;
    int depth_ = 0;
    const Token *last_ = nullptr;
};

}  // namespace

bool ParseFileAst(const std::string &text, const std::string &fileName, Diagnostics &diag, FileAst &out,
                  const std::vector<Diagnostic> &notes, const std::function<void(Stmt &)> &onStmt) {
    SyntaxParser p(text, 1, 1, fileName, diag, notes, /*resync=*/true);
    return p.ParseFile(out, onStmt);
}

bool ParseExprAst(const std::string &text, const std::string &fileName, int line, int col, Diagnostics &diag,
                  Expr &out) {
    std::vector<Diagnostic> noNotes;
    SyntaxParser p(text, line, col, fileName, diag, noNotes, /*resync=*/false);
    if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
        diag.Error(FileLoc{fileName, line, col, 1}, "empty value");
        return false;
    }
    std::size_t before = diag.ErrorCount();
    bool ok = p.ParseSingleExpr(out);
    return ok && diag.ErrorCount() == before;
}

}  // namespace phasor::wscene
