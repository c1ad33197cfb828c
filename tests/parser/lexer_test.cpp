// SPDX-License-Identifier: Apache-2.0
// Token tests for the .wscene lexer (docs/wscene.md §2).
#include <gtest/gtest.h>

#include "core/plugin_families.h"
#include "parser/lexer.h"

namespace phasor::wscene {
namespace {

// "Kind:text" for every token but End, e.g. "Number:150 Unit:um".
std::string Kinds(const std::string &src) {
    TokenStream ts = Tokenize(src);
    std::string out;
    for (const Token &t : ts.tokens) {
        if (t.kind == Tok::End) break;
        if (!out.empty()) out += ' ';
        switch (t.kind) {
            case Tok::Error:
                out += "Error";
                break;
            case Tok::Ident:
                out += "Ident:" + t.text;
                break;
            case Tok::Number:
                out += "Number:" + t.text;
                break;
            case Tok::Imag:
                out += "Imag:" + t.text;
                break;
            case Tok::Unit:
                out += "Unit:" + t.text;
                break;
            case Tok::String:
                out += "String:" + t.text;
                break;
            case Tok::Ref:
                out += "Ref:" + t.text;
                break;
            case Tok::Var:
                out += "Var:" + t.text;
                break;
            default:
                out += t.text;
                break;
        }
    }
    return out;
}

const Token &Last(const TokenStream &ts) { return ts.tokens.back(); }

TEST(Lexer, BlockStatement) {
    EXPECT_EQ(Kinds("Shape \"sphere\" \"ball\" { radius = 2 cm }"),
              "Ident:Shape String:sphere String:ball { Ident:radius = Number:2 Unit:cm }");
}

TEST(Lexer, PositionsAreOneBasedLineAndColumn) {
    TokenStream ts = Tokenize("wscene 1\n  Shape \"s\" {\n\tr = 150um }");
    ASSERT_GE(ts.tokens.size(), 9u);
    EXPECT_EQ(ts.tokens[0].line, 1);
    EXPECT_EQ(ts.tokens[0].col, 1);
    EXPECT_EQ(ts.tokens[0].length, 6);
    EXPECT_EQ(ts.tokens[2].text, "Shape");
    EXPECT_EQ(ts.tokens[2].line, 2);
    EXPECT_EQ(ts.tokens[2].col, 3);
    EXPECT_EQ(ts.tokens[3].length, 3);  // "s" with its quotes
    EXPECT_EQ(ts.tokens[5].text, "r");
    EXPECT_EQ(ts.tokens[5].line, 3);
    EXPECT_EQ(ts.tokens[5].col, 2);  // columns count bytes; a tab is one
    EXPECT_EQ(ts.tokens[7].kind, Tok::Number);
    EXPECT_EQ(ts.tokens[7].col, 6);
    EXPECT_EQ(ts.tokens[8].kind, Tok::Unit);
    EXPECT_EQ(ts.tokens[8].col, 9);
    EXPECT_FALSE(ts.tokens[8].spaceBefore);
}

TEST(Lexer, QuantitiesWithAndWithoutSpace) {
    EXPECT_EQ(Kinds("150um"), "Number:150 Unit:um");
    EXPECT_EQ(Kinds("150 um"), "Number:150 Unit:um");
    EXPECT_EQ(Kinds("1.5e-4 m"), "Number:1.5e-4 Unit:m");
    EXPECT_EQ(Kinds("10 W/m^2/sr"), "Number:10 Unit:W/m^2/sr");
    EXPECT_EQ(Kinds("2 um^2"), "Number:2 Unit:um^2");
    EXPECT_EQ(Kinds("5 1/m"), "Number:5 Unit:1/m");
    EXPECT_EQ(Kinds("5 m^-1"), "Number:5 Unit:m^-1");
    EXPECT_EQ(Kinds("[0 0 1] m"), "[ Number:0 Number:0 Number:1 ] Unit:m");
    EXPECT_EQ(Kinds("[0 0 1]mm"), "[ Number:0 Number:0 Number:1 ] Unit:mm");
}

TEST(Lexer, BothMicroSigns) {
    EXPECT_EQ(Kinds("3 \xC2\xB5m"), "Number:3 Unit:\xC2\xB5m");  // U+00B5 MICRO SIGN
    EXPECT_EQ(Kinds("3\xCE\xBCm"), "Number:3 Unit:\xCE\xBCm");   // U+03BC GREEK SMALL LETTER MU
}

TEST(Lexer, UnitEndsAtOperatorsAndDigits) {
    // "m/2" is the unit m divided by 2; "m*m" is a unit.
    EXPECT_EQ(Kinds("5 m/2"), "Number:5 Unit:m / Number:2");
    EXPECT_EQ(Kinds("5 m*m"), "Number:5 Unit:m*m");
    EXPECT_EQ(Kinds("5 m / $x"), "Number:5 Unit:m / Var:x");
    EXPECT_EQ(Kinds("2 * 3 mm"), "Number:2 * Number:3 Unit:mm");
}

TEST(Lexer, NameAfterNumberIsNotAUnitWhenItStartsAParameterOrCall) {
    EXPECT_EQ(Kinds("a = 5 b = 3"), "Ident:a = Number:5 Ident:b = Number:3");
    EXPECT_EQ(Kinds("a = 5 m = 3"), "Ident:a = Number:5 Ident:m = Number:3");
    EXPECT_EQ(Kinds("a = 5 pixel_pitch = 3"), "Ident:a = Number:5 Ident:pixel_pitch = Number:3");
    EXPECT_EQ(Kinds("[1 translate(x)]"), "[ Number:1 Ident:translate ( Ident:x ) ]");
    EXPECT_EQ(Kinds("$a > 5 and $b"), "Var:a > Number:5 Ident:and Var:b");
    EXPECT_EQ(Kinds("[1 true]"), "[ Number:1 Ident:true ]");
    EXPECT_EQ(Kinds("Define x = 5 Define"), "Ident:Define Ident:x = Number:5 Ident:Define");
    EXPECT_EQ(Kinds("5 m == 5 m"), "Number:5 Unit:m == Number:5 Unit:m");
}

TEST(Lexer, UnitMustBeOnTheNumbersLine) {
    EXPECT_EQ(Kinds("5\nm"), "Number:5 Ident:m");
    EXPECT_EQ(Kinds("5 # c\nm"), "Number:5 Ident:m");
}

TEST(Lexer, ComplexAndImaginary) {
    EXPECT_EQ(Kinds("1.5+0.01i"), "Number:1.5 + Imag:0.01");
    EXPECT_EQ(Kinds("0.2-3.4i"), "Number:0.2 - Imag:3.4");
    EXPECT_EQ(Kinds("2i"), "Imag:2");
}

TEST(Lexer, NumbersForms) {
    EXPECT_EQ(Kinds("1 1.5 .5 1e3 1.5E-3 007"),
              "Number:1 Number:1.5 Number:.5 Number:1e3 Number:1.5E-3 Number:007");
    EXPECT_EQ(Kinds("-1"), "- Number:1");
}

TEST(Lexer, MalformedNumbers) {
    for (const char *bad : {"1.2.3", "1e", "1e+", "1.", "0x10", "2um2", "3 um2"}) {
        TokenStream ts = Tokenize(bad);
        EXPECT_EQ(Last(ts).kind, Tok::Error) << bad;
        EXPECT_NE(Last(ts).text.find("malformed"), std::string::npos) << bad << ": " << Last(ts).text;
    }
    TokenStream ts = Tokenize("x = 1.2.3");
    EXPECT_EQ(Last(ts).col, 5);
    EXPECT_EQ(Last(ts).text, "malformed number '1.2.3'");
}

TEST(Lexer, StringsAndEscapes) {
    TokenStream ts = Tokenize(R"("a\"b\\c\n\t")");
    ASSERT_EQ(ts.tokens[0].kind, Tok::String);
    EXPECT_EQ(ts.tokens[0].text, "a\"b\\c\n\t");
    EXPECT_EQ(Kinds("\"caf\xC3\xA9\""), "String:caf\xC3\xA9");
}

TEST(Lexer, UnterminatedString) {
    TokenStream ts = Tokenize("x = \"abc\ny = 2");
    EXPECT_EQ(Last(ts).kind, Tok::Error);
    EXPECT_EQ(Last(ts).line, 1);
    EXPECT_EQ(Last(ts).col, 5);
    EXPECT_NE(Last(ts).text.find("unterminated string"), std::string::npos);
    EXPECT_EQ(Last(Tokenize("\"abc")).kind, Tok::Error);
}

TEST(Lexer, UnknownEscape) {
    TokenStream ts = Tokenize(R"(x = "a\qb")");
    EXPECT_EQ(Last(ts).kind, Tok::Error);
    EXPECT_EQ(Last(ts).col, 7);
    EXPECT_NE(Last(ts).text.find("unknown escape sequence '\\q'"), std::string::npos);
}

TEST(Lexer, RefsVarsAndOperators) {
    EXPECT_EQ(Kinds("@gold $width_2"), "Ref:gold Var:width_2");
    EXPECT_EQ(Kinds("== != < <= > >= = + - * / ( ) [ ] { } ,"), "== != < <= > >= = + - * / ( ) [ ] { } ,");
    EXPECT_EQ(Last(Tokenize("@ x")).kind, Tok::Error);
    EXPECT_EQ(Last(Tokenize("$1")).kind, Tok::Error);
}

TEST(Lexer, OperatorHints) {
    EXPECT_NE(Last(Tokenize("!a")).text.find("'not'"), std::string::npos);
    EXPECT_NE(Last(Tokenize("a && b")).text.find("'and'"), std::string::npos);
    EXPECT_NE(Last(Tokenize("a || b")).text.find("'or'"), std::string::npos);
    EXPECT_NE(Last(Tokenize("a = 1;")).text.find("';'"), std::string::npos);
}

TEST(Lexer, CommentsAreKeptSeparately) {
    TokenStream ts = Tokenize("# one\nwscene 1  # two \n#three");
    ASSERT_EQ(ts.comments.size(), 3u);
    EXPECT_EQ(ts.comments[0].text, " one");
    EXPECT_EQ(ts.comments[1].text, " two");
    EXPECT_EQ(ts.comments[1].line, 2);
    EXPECT_EQ(ts.comments[1].col, 11);
    EXPECT_EQ(ts.comments[2].text, "three");
    EXPECT_EQ(Kinds("# one\nwscene 1  # two \n#three"), "Ident:wscene Number:1");
}

TEST(Lexer, ByteOrderMarkIsSkipped) {
    TokenStream ts = Tokenize("\xEF\xBB\xBFwscene 1");
    EXPECT_EQ(ts.tokens[0].text, "wscene");
    EXPECT_EQ(ts.tokens[0].col, 1);
}

TEST(Lexer, InvalidCharacters) {
    TokenStream bad = Tokenize("x = \xFF");
    EXPECT_EQ(Last(bad).kind, Tok::Error);
    EXPECT_NE(Last(bad).text.find("invalid UTF-8"), std::string::npos);
    TokenStream arrow = Tokenize("x = \xE2\x86\x92");
    EXPECT_NE(Last(arrow).text.find("U+2192"), std::string::npos);
    EXPECT_EQ(Last(Tokenize(std::string("x = \0", 5))).kind, Tok::Error);
    EXPECT_EQ(Last(Tokenize("# ok \xC3\xA9\n# bad \xC3")).kind, Tok::Error);
}

TEST(Lexer, SpacingFlags) {
    TokenStream ts = Tokenize("[0 -1 0 - 2]");
    ASSERT_GE(ts.tokens.size(), 7u);
    EXPECT_TRUE(ts.tokens[2].spaceBefore);  // '-' of "-1"
    EXPECT_FALSE(ts.tokens[2].spaceAfter);
    EXPECT_TRUE(ts.tokens[5].spaceBefore);  // '-' of "0 - 2"
    EXPECT_TRUE(ts.tokens[5].spaceAfter);
}

TEST(Lexer, EveryPluginFamilyKeywordIsAStatementKeyword) {
#define PHASOR_CHECK_KEYWORD(Keyword, family, Interface, Example) EXPECT_TRUE(IsStatementKeyword(#Keyword));
    PHASOR_PLUGIN_FAMILIES(PHASOR_CHECK_KEYWORD)
#undef PHASOR_CHECK_KEYWORD
}

TEST(Lexer, WordClasses) {
    EXPECT_TRUE(IsStatementKeyword("Integrator"));
    EXPECT_FALSE(IsStatementKeyword("shape"));
    EXPECT_TRUE(IsReservedWord("not"));
    EXPECT_TRUE(IsIdentifier("_a1"));
    EXPECT_FALSE(IsIdentifier("1a"));
    EXPECT_FALSE(IsIdentifier("a-b"));
}

}  // namespace
}  // namespace phasor::wscene
