// SPDX-License-Identifier: Apache-2.0
// phasor — the .wscene lexer (docs/wscene.md §2). Turns source text into tokens with 1-based
// line/column positions. Comments are kept (separately) so the canonical printer can keep them.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace phasor::wscene {

enum class Tok {
    End,     // end of input
    Error,   // lexical error; `text` holds the message
    Ident,   // name or keyword
    Number,  // numeric literal; `text` is the literal as written
    Imag,    // imaginary literal such as 0.01i; `text` is the number without the 'i'
    Unit,    // unit after a number or ']' (e.g. um, W/m^2); `text` as written
    String,  // "..."; `text` is the decoded content
    Ref,     // @name; `text` is the name
    Var,     // $name; `text` is the name
    LBrace,
    RBrace,
    LBracket,
    RBracket,
    LParen,
    RParen,
    Comma,
    Assign,  // =
    Plus,
    Minus,
    Star,
    Slash,
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
};

/// Short human-readable token kind ("a number", "'{'") for syntax errors.
const char *Describe(Tok t);

struct Token {
    Tok kind = Tok::End;
    std::string text;
    int line = 1, col = 1;     // 1-based; columns count bytes
    int length = 0;            // bytes of source covered (on the token's line)
    uint32_t offset = 0;       // byte offset of the first character
    uint32_t endOffset = 0;    // byte offset just past the token
    bool spaceBefore = false;  // whitespace, a comment or the start of the input right before it
    bool spaceAfter = false;   // whitespace, a comment or the end of the input right after it
};

struct Comment {
    std::string text;  // without the leading '#', trailing whitespace removed
    int line = 1, col = 1;
    uint32_t offset = 0;
};

/// The tokens of one source text. When lexing failed the last token has kind Error (its `text`
/// is the message) and nothing after it was lexed.
struct TokenStream {
    std::vector<Token> tokens;  // always ends with End or Error
    std::vector<Comment> comments;
};

/// An incremental lexer over one text (which must outlive it). With `resync`, an Error token is
/// followed by the tokens from the next line that starts with a statement keyword (so a file's
/// later statements are still read); without, it is the last token.
class TokenSource {
  public:
    explicit TokenSource(std::string_view text, int firstLine = 1, int firstCol = 1, bool resync = false);
    ~TokenSource();
    /// Appends the next token(s) to `tokens` and any comments before them to `comments`. Returns
    /// false once the final token (End or Error) has been appended.
    bool More(std::deque<Token> &tokens, std::deque<Comment> &comments);

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Lexes a whole text. `firstLine`/`firstCol` place the text inside a larger file (used for
/// command-line values).
TokenStream Tokenize(std::string_view text, int firstLine = 1, int firstCol = 1);

/// Words with a fixed meaning that can never be a unit or a parameter value.
bool IsStatementKeyword(std::string_view word);
bool IsReservedWord(std::string_view word);  // statement keywords, true/false/and/or/not
bool IsIdentifier(std::string_view word);

}  // namespace phasor::wscene
