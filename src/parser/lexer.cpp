// SPDX-License-Identifier: Apache-2.0
#include "parser/lexer.h"

#include <array>
#include <cstdio>
#include <iterator>
#include <memory>

#include "core/plugin_families.h"

namespace phasor::wscene {

namespace {

#define PHASOR_FAMILY_KEYWORD(Keyword, family, Interface, Example) #Keyword,
constexpr std::string_view kStatementKeywords[] = {"wscene", "Include", "Define", "Render",
                                                   PHASOR_PLUGIN_FAMILIES(PHASOR_FAMILY_KEYWORD)};
#undef PHASOR_FAMILY_KEYWORD
constexpr std::array<std::string_view, 5> kWordOperators = {"true", "false", "and", "or", "not"};

bool IsAsciiLetter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
bool IsDigit(char c) { return c >= '0' && c <= '9'; }
bool IsIdentStart(char c) { return IsAsciiLetter(c) || c == '_'; }
bool IsIdentChar(char c) { return IsIdentStart(c) || IsDigit(c); }

// Decodes one UTF-8 sequence at s[i]; returns its length (0 if invalid) and the code point.
int DecodeUtf8(std::string_view s, std::size_t i, uint32_t *cp) {
    unsigned char c = s[i];
    int n;
    uint32_t v;
    if (c < 0x80) {
        *cp = c;
        return 1;
    }
    if ((c & 0xE0) == 0xC0) {
        n = 2;
        v = c & 0x1F;
    } else if ((c & 0xF0) == 0xE0) {
        n = 3;
        v = c & 0x0F;
    } else if ((c & 0xF8) == 0xF0) {
        n = 4;
        v = c & 0x07;
    } else
        return 0;
    if (i + n > s.size()) return 0;
    for (int k = 1; k < n; ++k) {
        unsigned char d = s[i + k];
        if ((d & 0xC0) != 0x80) return 0;
        v = (v << 6) | (d & 0x3F);
    }
    // Reject overlong forms, surrogates and values beyond U+10FFFF.
    if ((n == 2 && v < 0x80) || (n == 3 && v < 0x800) || (n == 4 && v < 0x10000) || v > 0x10FFFF ||
        (v >= 0xD800 && v <= 0xDFFF))
        return 0;
    *cp = v;
    return n;
}

// Length of a micro sign (U+00B5 or U+03BC) at s[i], else 0.
int MicroSign(std::string_view s, std::size_t i) {
    if (i + 1 >= s.size()) return 0;
    unsigned char a = s[i], b = s[i + 1];
    if ((a == 0xC2 && b == 0xB5) || (a == 0xCE && b == 0xBC)) return 2;
    return 0;
}

class Lexer {
  public:
    Lexer(std::string_view text, int line, int col, bool resync)
        : s_(text), line_(line), col_(col), resync_(resync) {}

    // Appends the next token (a number with an attached unit gives two) to `tokens`; returns false
    // once End or Error was appended.
    bool Step(std::deque<Token> &tokens, std::deque<Comment> &comments) {
        if (done_) return false;
        if (first_) {
            first_ = false;
            // A UTF-8 byte-order mark is ignored.
            if (s_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;
        }
        space_ = SkipSpaceAndComments(comments) || space_;
        if (error_) return Finish(tokens, std::move(errorTok_));
        if (pos_ >= s_.size()) {
            Token end;
            end.kind = Tok::End;
            end.line = line_;
            end.col = col_;
            end.offset = end.endOffset = (uint32_t)pos_;
            end.spaceBefore = true;
            return Finish(tokens, std::move(end));
        }
        Token t;
        bool unitAllowed = (prev_ == Tok::Number || prev_ == Tok::RBracket);
        if (unitAllowed && space_ && ScanUnitAfterSpace(t, prevEnd_)) {
            // (t filled in)
        } else if (!LexToken(t)) {
            return Finish(tokens, std::move(errorTok_));
        }
        t.spaceBefore = space_;
        space_ = false;
        t.spaceAfter = t.endOffset >= s_.size() || IsSpaceOrComment(s_[t.endOffset]);
        prev_ = t.kind;
        prevEnd_ = t.endOffset;
        tokens.push_back(std::move(t));
        Token *from = &tokens.back();
        // A unit may be attached to a number or a ']' directly ("150um", "[0 0 1]m").
        if ((prev_ == Tok::Number || prev_ == Tok::RBracket) && pos_ < s_.size() &&
            (IsAsciiLetter(s_[pos_]) || MicroSign(s_, pos_))) {
            Token u;
            LexAttachedUnit(u);
            u.spaceBefore = false;
            u.spaceAfter = u.endOffset >= s_.size() || IsSpaceOrComment(s_[u.endOffset]);
            tokens.back().spaceAfter = false;
            bool afterNumber = prev_ == Tok::Number;
            prev_ = Tok::Unit;
            prevEnd_ = u.endOffset;
            tokens.push_back(std::move(u));
            // An attached unit is reported together with its number ("0x10").
            from = afterNumber ? &tokens[tokens.size() - 2] : &tokens.back();
        }
        if (prev_ == Tok::Number || prev_ == Tok::Imag || prev_ == Tok::Unit) {
            if (!CheckAfterNumber(*from)) return Finish(tokens, std::move(errorTok_));
        }
        return true;
    }

  private:
    bool Finish(std::deque<Token> &tokens, Token t) {
        const bool error = t.kind == Tok::Error;
        tokens.push_back(std::move(t));
        if (error && resync_) {
            Resync();
            return true;
        }
        done_ = true;
        return false;
    }

    // After a lexical error: goes on at the next line that starts with a statement keyword.
    void Resync() {
        error_ = false;
        prev_ = Tok::End;
        space_ = true;
        while (pos_ < s_.size()) {
            while (pos_ < s_.size() && s_[pos_] != '\n') Advance();
            Advance();  // the line break
            std::size_t i = pos_;
            while (i < s_.size() && (s_[i] == ' ' || s_[i] == '\t')) ++i;
            std::size_t j = i;
            while (j < s_.size() && IsIdentChar(s_[j])) ++j;
            std::string_view word = s_.substr(i, j - i);
            if (word != "wscene" && IsStatementKeyword(word)) return;
        }
    }

    static bool IsSpaceOrComment(char c) {
        return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '#';
    }

    void Advance(std::size_t n = 1) {
        for (std::size_t k = 0; k < n && pos_ < s_.size(); ++k) {
            if (s_[pos_] == '\n') {
                ++line_;
                col_ = 1;
            } else
                ++col_;
            ++pos_;
        }
    }

    bool Fail(int line, int col, int length, std::string msg) {
        error_ = true;
        errorTok_ = Token{};
        errorTok_.kind = Tok::Error;
        errorTok_.text = std::move(msg);
        errorTok_.line = line;
        errorTok_.col = col;
        errorTok_.length = length < 1 ? 1 : length;
        errorTok_.offset = (uint32_t)pos_;
        errorTok_.endOffset = (uint32_t)pos_;
        return false;
    }

    std::string CharName(std::size_t i) {
        uint32_t cp = 0;
        int n = DecodeUtf8(s_, i, &cp);
        char buf[64];
        if (n == 0) {
            std::snprintf(buf, sizeof buf, "invalid UTF-8 byte 0x%02X", (unsigned)(unsigned char)s_[i]);
            return buf;
        }
        if (cp < 0x20 || cp == 0x7F) {
            std::snprintf(buf, sizeof buf, "unexpected control character U+%04X", (unsigned)cp);
            return buf;
        }
        std::snprintf(buf, sizeof buf, " (U+%04X)", (unsigned)cp);
        return "unexpected character '" + std::string(s_.substr(i, n)) + "'" + (cp >= 0x80 ? buf : "");
    }

    // Skips whitespace and comments; returns true if anything was skipped.
    bool SkipSpaceAndComments(std::deque<Comment> &comments) {
        bool skipped = false;
        while (pos_ < s_.size()) {
            char c = s_[pos_];
            if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
                Advance();
                skipped = true;
            } else if (c == '#') {
                Comment cm;
                cm.line = line_;
                cm.col = col_;
                cm.offset = (uint32_t)pos_;
                std::size_t start = pos_ + 1;
                std::size_t i = start;
                while (i < s_.size() && s_[i] != '\n') {
                    uint32_t cp;
                    int n = DecodeUtf8(s_, i, &cp);
                    if (n == 0 || (cp < 0x20 && cp != '\t' && cp != '\r') || cp == 0x7F) {
                        int col = col_ + int(i - pos_);
                        std::string what = CharName(i);
                        Advance(i - pos_);
                        Fail(line_, col, 1, what + " in a comment");
                        return skipped;
                    }
                    i += n;
                }
                std::size_t end = i;
                while (end > start && (s_[end - 1] == ' ' || s_[end - 1] == '\t' || s_[end - 1] == '\r'))
                    --end;
                cm.text = std::string(s_.substr(start, end - start));
                comments.push_back(std::move(cm));
                Advance(i - pos_);
                skipped = true;
            } else {
                break;
            }
        }
        return skipped;
    }

    void Begin(Token &t, Tok kind) {
        t.kind = kind;
        t.line = line_;
        t.col = col_;
        t.offset = (uint32_t)pos_;
    }
    void Finish(Token &t) {
        t.endOffset = (uint32_t)pos_;
        t.length = int(t.endOffset - t.offset);
    }
    bool Single(Token &t, Tok kind, std::size_t n = 1) {
        Begin(t, kind);
        t.text = std::string(s_.substr(pos_, n));
        Advance(n);
        Finish(t);
        return true;
    }

    bool LexToken(Token &t) {
        char c = s_[pos_];
        char next = pos_ + 1 < s_.size() ? s_[pos_ + 1] : '\0';
        switch (c) {
            case '{':
                return Single(t, Tok::LBrace);
            case '}':
                return Single(t, Tok::RBrace);
            case '[':
                return Single(t, Tok::LBracket);
            case ']':
                return Single(t, Tok::RBracket);
            case '(':
                return Single(t, Tok::LParen);
            case ')':
                return Single(t, Tok::RParen);
            case ',':
                return Single(t, Tok::Comma);
            case '+':
                return Single(t, Tok::Plus);
            case '-':
                return Single(t, Tok::Minus);
            case '*':
                return Single(t, Tok::Star);
            case '/':
                return Single(t, Tok::Slash);
            case '=':
                return next == '=' ? Single(t, Tok::Eq, 2) : Single(t, Tok::Assign);
            case '<':
                return next == '=' ? Single(t, Tok::Le, 2) : Single(t, Tok::Lt);
            case '>':
                return next == '=' ? Single(t, Tok::Ge, 2) : Single(t, Tok::Gt);
            case '!':
                if (next == '=') return Single(t, Tok::Ne, 2);
                return Fail(line_, col_, 1, "unexpected '!'; write 'not' for logical negation");
            case '&':
                return Fail(line_, col_, next == '&' ? 2 : 1, "unexpected '&'; write 'and'");
            case '|':
                return Fail(line_, col_, next == '|' ? 2 : 1, "unexpected '|'; write 'or'");
            case '"':
                return LexString(t);
            case '@':
            case '$':
                return LexSigil(t, c == '@' ? Tok::Ref : Tok::Var);
            default:
                break;
        }
        if (IsDigit(c) || (c == '.' && IsDigit(next))) return LexNumber(t);
        if (IsIdentStart(c)) {
            Begin(t, Tok::Ident);
            std::size_t i = pos_;
            while (i < s_.size() && IsIdentChar(s_[i])) ++i;
            t.text = std::string(s_.substr(pos_, i - pos_));
            Advance(i - pos_);
            Finish(t);
            return true;
        }
        if (c == ';')
            return Fail(line_, col_, 1, "unexpected ';'; statements and parameters need no separator");
        if (MicroSign(s_, pos_))
            return Fail(line_, col_, 2, "unexpected 'µ'; a unit must follow a number or a ']'");
        uint32_t cp;
        int n = DecodeUtf8(s_, pos_, &cp);
        return Fail(line_, col_, n > 0 ? n : 1, CharName(pos_));
    }

    bool LexSigil(Token &t, Tok kind) {
        Begin(t, kind);
        std::size_t i = pos_ + 1;
        if (i >= s_.size() || !IsIdentStart(s_[i]))
            return Fail(
                line_, col_, 1,
                std::string("expected a name directly after '") + s_[pos_] + "' (e.g. " + s_[pos_] + "name)");
        while (i < s_.size() && IsIdentChar(s_[i])) ++i;
        t.text = std::string(s_.substr(pos_ + 1, i - pos_ - 1));
        Advance(i - pos_);
        Finish(t);
        return true;
    }

    bool LexString(Token &t) {
        Begin(t, Tok::String);
        int startLine = line_, startCol = col_;
        std::size_t i = pos_ + 1;
        std::string out;
        for (;;) {
            if (i >= s_.size() || s_[i] == '\n' || s_[i] == '\r')
                return Fail(startLine, startCol, 1,
                            "unterminated string (strings end on the same line with '\"')");
            char c = s_[i];
            if (c == '"') {
                ++i;
                break;
            }
            if (c == '\\') {
                char e = i + 1 < s_.size() ? s_[i + 1] : '\0';
                switch (e) {
                    case '"':
                        out += '"';
                        break;
                    case '\\':
                        out += '\\';
                        break;
                    case 'n':
                        out += '\n';
                        break;
                    case 't':
                        out += '\t';
                        break;
                    case 'r':
                        out += '\r';
                        break;
                    default: {
                        if (e == '\n' || e == '\0' || e == '\r')
                            return Fail(startLine, startCol, 1,
                                        "unterminated string (strings end on the same line with '\"')");
                        Advance(i - pos_);
                        uint32_t cp;
                        int n = DecodeUtf8(s_, i + 1, &cp);
                        return Fail(line_, col_, 1 + (n > 0 ? n : 1),
                                    "unknown escape sequence '\\" +
                                        std::string(s_.substr(i + 1, n > 0 ? n : 1)) +
                                        "' in string (use \\\" \\\\ \\n \\t or \\r)");
                    }
                }
                i += 2;
                continue;
            }
            uint32_t cp;
            int n = DecodeUtf8(s_, i, &cp);
            if (n == 0 || (cp < 0x20 && cp != '\t') || cp == 0x7F) {
                std::string what = CharName(i);
                Advance(i - pos_);
                return Fail(line_, col_, 1, what + " in a string");
            }
            out.append(s_.substr(i, n));
            i += n;
        }
        t.text = std::move(out);
        Advance(i - pos_);
        Finish(t);
        return true;
    }

    bool LexNumber(Token &t) {
        Begin(t, Tok::Number);
        std::size_t i = pos_;
        while (i < s_.size() && IsDigit(s_[i])) ++i;
        if (i < s_.size() && s_[i] == '.') {
            ++i;
            if (i >= s_.size() || !IsDigit(s_[i])) return MalformedNumber();
            while (i < s_.size() && IsDigit(s_[i])) ++i;
        }
        if (i < s_.size() && (s_[i] == 'e' || s_[i] == 'E')) {
            std::size_t j = i + 1;
            if (j < s_.size() && (s_[j] == '+' || s_[j] == '-')) ++j;
            if (j < s_.size() && IsDigit(s_[j])) {
                while (j < s_.size() && IsDigit(s_[j])) ++j;
                i = j;
            } else if (j > i + 1 || j >= s_.size() || !IsAsciiLetter(s_[j])) {
                // "1e", "1e+", "1e-x": an exponent without digits.
                return MalformedNumber();
            }
        }
        t.text = std::string(s_.substr(pos_, i - pos_));
        // An imaginary literal: the number directly followed by 'i' (and nothing name-like).
        if (i < s_.size() && s_[i] == 'i' && (i + 1 >= s_.size() || !IsIdentChar(s_[i + 1]))) {
            t.kind = Tok::Imag;
            ++i;
        }
        Advance(i - pos_);
        Finish(t);
        return true;
    }

    // The maximal run of name-like characters from the current position, for messages.
    std::string RunFrom(std::size_t start) {
        std::size_t i = start;
        while (i < s_.size() && (IsIdentChar(s_[i]) || s_[i] == '.' || s_[i] == '^' || MicroSign(s_, i))) {
            i += MicroSign(s_, i) ? 2 : 1;
        }
        return std::string(s_.substr(start, i - start));
    }

    bool MalformedNumber() {
        std::string run = RunFrom(pos_);
        std::size_t i = pos_ + run.size();
        // Include a sign of an exponent ("1e+") in the message.
        while (i < s_.size() && (s_[i] == '+' || s_[i] == '-')) {
            run += s_[i];
            ++i;
        }
        return Fail(line_, col_, (int)run.size(), "malformed number '" + run + "'");
    }

    // After a number / imaginary literal / unit: a name character, digit or '.' directly after it
    // means the literal is malformed (e.g. "1.5.3", "2um2", "0x10").
    bool CheckAfterNumber(const Token &last) {
        if (pos_ >= s_.size()) return true;
        char c = s_[pos_];
        if (!(IsIdentChar(c) || c == '.' || c == '^' || MicroSign(s_, pos_))) return true;
        // Find where the number started, for the message.
        std::string run = std::string(s_.substr(last.offset, pos_ - last.offset)) + RunFrom(pos_);
        if (last.kind == Tok::Unit)
            return Fail(last.line, last.col, (int)run.size(),
                        "malformed unit '" + run + "' (powers are written with '^', e.g. um^2)");
        return Fail(last.line, last.col, (int)run.size(), "malformed number '" + run + "'");
    }

    // unit := first { ('/' | '*') factor } ; first := factor | '1' (before '/') ;
    // factor := name [ '^' ['-'] digits ] ; name := { letter | µ }+.
    // Returns the length of the unit text at `i` (0 if none).
    std::size_t ScanUnit(std::size_t i, bool *simple) const {
        std::size_t start = i;
        *simple = true;
        auto name = [&](std::size_t k) {
            std::size_t j = k;
            while (j < s_.size()) {
                if (IsAsciiLetter(s_[j]))
                    ++j;
                else if (int m = MicroSign(s_, j))
                    j += m;
                else
                    break;
            }
            return j - k;
        };
        auto factor = [&](std::size_t k) -> std::size_t {
            std::size_t n = name(k);
            if (n == 0) return 0;
            std::size_t j = k + n;
            if (j < s_.size() && s_[j] == '^') {
                std::size_t e = j + 1;
                if (e < s_.size() && s_[e] == '-') ++e;
                std::size_t d = e;
                while (d < s_.size() && IsDigit(s_[d])) ++d;
                if (d > e) j = d;
            }
            return j - k;
        };
        std::size_t n = factor(i);
        if (n == 0) {
            if (s_[i] == '1' && i + 1 < s_.size() && s_[i + 1] == '/' && i + 2 < s_.size() &&
                (IsAsciiLetter(s_[i + 2]) || MicroSign(s_, i + 2)))
                n = 1;
            else
                return 0;
        }
        i += n;
        while (i + 1 < s_.size() && (s_[i] == '/' || s_[i] == '*')) {
            std::size_t f = factor(i + 1);
            if (f == 0) break;
            i += 1 + f;
        }
        std::string_view text = s_.substr(start, i - start);
        for (char c : text)
            if (c == '/' || c == '*' || c == '^') *simple = false;
        if (!text.empty() && text[0] == '1') *simple = false;
        return i - start;
    }

    bool LexAttachedUnit(Token &t) {
        bool simple;
        std::size_t n = ScanUnit(pos_, &simple);
        Begin(t, Tok::Unit);
        t.text = std::string(s_.substr(pos_, n));
        Advance(n);
        Finish(t);
        return true;
    }

    // A unit after whitespace (same line only): "150 um", "[0 0 1] m". A single name is not a
    // unit if it is a reserved word, is followed by '=' (the next parameter) or directly by '('
    // (a call).
    bool ScanUnitAfterSpace(Token &t, std::size_t prevEnd) {
        // Only spaces and tabs (no line break, no comment) may separate a unit from its number.
        for (std::size_t k = prevEnd; k < pos_; ++k)
            if (s_[k] != ' ' && s_[k] != '\t') return false;
        char c = s_[pos_];
        if (!(IsAsciiLetter(c) || MicroSign(s_, pos_) || c == '1')) return false;
        bool simple;
        std::size_t n = ScanUnit(pos_, &simple);
        if (n == 0) return false;
        if (simple) {
            std::string_view word = s_.substr(pos_, n);
            if (IsReservedWord(word)) return false;
            std::size_t j = pos_ + n;
            if (j < s_.size() && (s_[j] == '(' || s_[j] == '_' || IsDigit(s_[j]))) {
                if (s_[j] == '(') return false;
                // "um2" / "my_name": let the general lexer produce an identifier; a name is never
                // a valid value, so the parser reports it.
                std::size_t k = j;
                while (k < s_.size() && IsIdentChar(s_[k])) ++k;
                std::size_t m = k;
                while (m < s_.size() && (s_[m] == ' ' || s_[m] == '\t')) ++m;
                if (m < s_.size() && s_[m] == '=' && !(m + 1 < s_.size() && s_[m + 1] == '=')) return false;
                if (k < s_.size() && s_[k] == '(') return false;
                // Otherwise treat it as a (malformed) unit so the error says so.
            }
            while (j < s_.size() && (s_[j] == ' ' || s_[j] == '\t')) ++j;
            if (j < s_.size() && s_[j] == '=' && !(j + 1 < s_.size() && s_[j + 1] == '=')) return false;
        }
        Begin(t, Tok::Unit);
        t.text = std::string(s_.substr(pos_, n));
        Advance(n);
        Finish(t);
        return true;
    }

    std::string_view s_;
    std::size_t pos_ = 0;
    int line_, col_;
    bool resync_;  // go on after a lexical error (TokenSource)
    bool error_ = false, done_ = false, first_ = true, space_ = true;
    Tok prev_ = Tok::End;
    std::size_t prevEnd_ = 0;
    Token errorTok_;
};

}  // namespace

const char *Describe(Tok t) {
    switch (t) {
        case Tok::End:
            return "end of file";
        case Tok::Error:
            return "an invalid token";
        case Tok::Ident:
            return "a name";
        case Tok::Number:
            return "a number";
        case Tok::Imag:
            return "an imaginary number";
        case Tok::Unit:
            return "a unit";
        case Tok::String:
            return "a string";
        case Tok::Ref:
            return "a reference";
        case Tok::Var:
            return "a variable";
        case Tok::LBrace:
            return "'{'";
        case Tok::RBrace:
            return "'}'";
        case Tok::LBracket:
            return "'['";
        case Tok::RBracket:
            return "']'";
        case Tok::LParen:
            return "'('";
        case Tok::RParen:
            return "')'";
        case Tok::Comma:
            return "','";
        case Tok::Assign:
            return "'='";
        case Tok::Plus:
            return "'+'";
        case Tok::Minus:
            return "'-'";
        case Tok::Star:
            return "'*'";
        case Tok::Slash:
            return "'/'";
        case Tok::Eq:
            return "'=='";
        case Tok::Ne:
            return "'!='";
        case Tok::Lt:
            return "'<'";
        case Tok::Le:
            return "'<='";
        case Tok::Gt:
            return "'>'";
        case Tok::Ge:
            return "'>='";
    }
    return "a token";
}

struct TokenSource::Impl {
    Lexer lexer;
};

TokenSource::TokenSource(std::string_view text, int firstLine, int firstCol, bool resync)
    : impl_(std::make_unique<Impl>(Impl{Lexer(text, firstLine, firstCol, resync)})) {}
TokenSource::~TokenSource() = default;

bool TokenSource::More(std::deque<Token> &tokens, std::deque<Comment> &comments) {
    return impl_->lexer.Step(tokens, comments);
}

TokenStream Tokenize(std::string_view text, int firstLine, int firstCol) {
    TokenSource src(text, firstLine, firstCol);
    std::deque<Token> tokens;
    std::deque<Comment> comments;
    while (src.More(tokens, comments)) {}
    TokenStream out;
    out.tokens.assign(std::make_move_iterator(tokens.begin()), std::make_move_iterator(tokens.end()));
    out.comments.assign(std::make_move_iterator(comments.begin()), std::make_move_iterator(comments.end()));
    return out;
}

bool IsStatementKeyword(std::string_view w) {
    for (std::string_view k : kStatementKeywords)
        if (w == k) return true;
    return false;
}

bool IsReservedWord(std::string_view w) {
    if (IsStatementKeyword(w)) return true;
    for (std::string_view k : kWordOperators)
        if (w == k) return true;
    return false;
}

bool IsIdentifier(std::string_view w) {
    if (w.empty() || !IsIdentStart(w[0])) return false;
    for (char c : w)
        if (!IsIdentChar(c)) return false;
    return true;
}

}  // namespace phasor::wscene
