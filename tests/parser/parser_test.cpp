// SPDX-License-Identifier: Apache-2.0
// Parser + resolver tests: statements, value forms, units, arithmetic, Define/-D, Include,
// references and `enabled` (docs/wscene.md).
#include <gtest/gtest.h>

#include <map>

#include "core/math.h"
#include "core/plugin_families.h"
#include "parser/parser.h"

namespace phasor {
namespace {

struct Parsed {
    std::optional<SceneDesc> desc;
    std::unique_ptr<Diagnostics> diag;
    std::string Errors() const {
        std::string s;
        for (const Diagnostic &d : diag->All())
            s += d.loc.ToString() + ": " + (d.severity == Severity::Warning ? "warning: " : "") + d.message +
                 "\n";
        return s;
    }
};

Parsed Parse(const std::string &src, const DefineList &defines = {},
             const std::map<std::string, std::string> &files = {}, bool strict = false) {
    Parsed r;
    r.diag = std::make_unique<Diagnostics>(strict);
    ParseOptions o;
    o.defines = defines;
    o.readFile = [files](const std::string &path) -> std::optional<std::string> {
        auto it = files.find(path);
        if (it == files.end()) return std::nullopt;
        return it->second;
    };
    r.desc = ParseSceneString(src, "main.wscene", o, *r.diag);
    return r;
}

// The value of parameter `name` of the entity called `entity` (or the only entity).
const Value &Param(const Parsed &p, const std::string &name, std::size_t entity = 0) {
    static const Value none = Value::String("<missing>");
    if (!p.desc || entity >= p.desc->entities.size()) return none;
    const phasor::Param *q = p.desc->entities[entity].params.Find(name);
    return q ? q->value : none;
}

Parsed One(const std::string &params, const DefineList &defines = {}) {
    return Parse("wscene 1\nShape \"sphere\" \"s\" { " + params + " }\n", defines);
}

void ExpectNumber(const Value &v, double si, Dim d, double relTol = 1e-15) {
    ASSERT_EQ(v.kind, Value::Kind::Number) << v.ToString();
    EXPECT_NEAR(v.number, si, std::abs(si) * relTol) << v.ToString();
    EXPECT_EQ(v.dim, d) << v.ToString();
}

TEST(Parser, MinimalScene) {
    Parsed p = Parse("wscene 1\nShape \"sphere\" \"ball\" { radius = 2 cm }\nRender { spp = 4 }\n");
    ASSERT_TRUE(p.desc) << p.Errors();
    ASSERT_EQ(p.desc->entities.size(), 2u);
    const SceneEntity &e = p.desc->entities[0];
    EXPECT_EQ(e.keyword, "Shape");
    EXPECT_EQ(e.type, "sphere");
    EXPECT_EQ(e.name, "ball");
    EXPECT_EQ(e.loc.ToString(), "main.wscene:2:1");
    EXPECT_EQ(e.nameLoc.ToString(), "main.wscene:2:16");
    EXPECT_EQ(e.params.EntityLoc().ToString(), "main.wscene:2:1");
    ExpectNumber(Param(p, "radius"), 0.02, Dim::Length());
    const phasor::Param *r = e.params.Find("radius");
    EXPECT_EQ(r->loc.ToString(), "main.wscene:2:25");
    EXPECT_EQ(r->loc.length, 6);
    EXPECT_EQ(r->value.loc.ToString(), "main.wscene:2:34");
    EXPECT_EQ(r->value.loc.length, 4);
    EXPECT_EQ(p.desc->entities[1].keyword, "Render");
    EXPECT_EQ(p.desc->entities[1].type, "");
    EXPECT_EQ(p.desc->sourceFile, "main.wscene");
}

TEST(Parser, EveryFamilyKeyword) {
    Parsed p = Parse(
        "wscene 1\nSpectrum \"a\" {}\nTexture \"b\" {}\nMaterial \"c\" {}\nShape \"d\" {}\n"
        "Light \"e\" {}\nDetector \"f\" {}\nIntegrator \"g\" {}\nRender {}\n");
    ASSERT_TRUE(p.desc) << p.Errors();
    std::string kw;
    for (const SceneEntity &e : p.desc->entities) kw += e.keyword + e.type + " ";
    EXPECT_EQ(kw, "Spectruma Textureb Materialc Shaped Lighte Detectorf Integratorg Render ");
}

TEST(Parser, NumbersAndIntegers) {
    Parsed p = One("a = 8  b = 1.5e-3  c = -3  d = 2.0  e = 0.5 m  f = 99999999999999999999");
    ASSERT_TRUE(p.desc) << p.Errors();
    EXPECT_TRUE(Param(p, "a").isInteger);
    EXPECT_EQ(Param(p, "a").number, 8);
    EXPECT_FALSE(Param(p, "b").isInteger);
    EXPECT_EQ(Param(p, "b").number, 1.5e-3);
    EXPECT_TRUE(Param(p, "c").isInteger);
    EXPECT_EQ(Param(p, "c").number, -3);
    EXPECT_FALSE(Param(p, "d").isInteger);
    EXPECT_FALSE(Param(p, "e").isInteger);
    EXPECT_FALSE(Param(p, "f").isInteger);  // beyond 2^53 a double is not an exact integer
}

TEST(Parser, UnitsConvertToSI) {
    Parsed p =
        One("a = 532 nm  b = 150um  c = 3 \xC2\xB5m  d = 3 \xCE\xBCm  e = 1.5 mm  f = 2 cm  g = 1 m"
            "  h = 90 deg  i = 2 mrad  j = 300 K  k = 5 mW  l = 1000 W/m^2  m = 3 W/m^2/sr"
            "  n = 2500 um^2  o = 1 mm^2  p = 0.5 sr  q = 20 1/m  r = 1 rad");
    ASSERT_TRUE(p.desc) << p.Errors();
    ExpectNumber(Param(p, "a"), 532e-9, Dim::Length());
    ExpectNumber(Param(p, "b"), 150e-6, Dim::Length());
    ExpectNumber(Param(p, "c"), 3e-6, Dim::Length());
    ExpectNumber(Param(p, "d"), 3e-6, Dim::Length());
    ExpectNumber(Param(p, "e"), 1.5e-3, Dim::Length());
    ExpectNumber(Param(p, "f"), 0.02, Dim::Length());
    ExpectNumber(Param(p, "g"), 1, Dim::Length());
    ExpectNumber(Param(p, "h"), Pi / 2, Dim::Angle());
    ExpectNumber(Param(p, "i"), 2e-3, Dim::Angle());
    ExpectNumber(Param(p, "j"), 300, Dim::Temperature());
    ExpectNumber(Param(p, "k"), 5e-3, Dim::Power());
    ExpectNumber(Param(p, "l"), 1000, Dim::Irradiance());
    ExpectNumber(Param(p, "m"), 3, Dim::Radiance());
    ExpectNumber(Param(p, "n"), 2500e-12, Dim::Area());
    ExpectNumber(Param(p, "o"), 1e-6, Dim::Area());
    ExpectNumber(Param(p, "p"), 0.5, Dim::SolidAngle());
    ExpectNumber(Param(p, "q"), 20, Dim::None() / Dim::Length());
    ExpectNumber(Param(p, "r"), 1, Dim::Angle());
}

TEST(Parser, ComplexStringsBooleansRefsCalls) {
    Parsed p = Parse(
        "wscene 1\nMaterial \"m\" \"gold\" {}\nShape \"sphere\" { a = 1.5+0.01i  b = 0.2-3.4i"
        "  c = \"x\\\"y\"  d = true  e = false  f = @gold"
        "  g = blackbody(5800 K)  h = lookat(eye = [0 0 -1] m, target = [0 0 0] m) }\n");
    ASSERT_TRUE(p.desc) << p.Errors();
    const Value &a = Param(p, "a", 1);
    ASSERT_EQ(a.kind, Value::Kind::Complex);
    EXPECT_EQ(a.complex, Complex(1.5, 0.01));
    EXPECT_EQ(Param(p, "b", 1).complex, Complex(0.2, -3.4));
    EXPECT_EQ(Param(p, "c", 1).text, "x\"y");
    EXPECT_TRUE(Param(p, "d", 1).boolean);
    EXPECT_EQ(Param(p, "e", 1).kind, Value::Kind::Bool);
    EXPECT_EQ(Param(p, "f", 1).kind, Value::Kind::Ref);
    EXPECT_EQ(Param(p, "f", 1).text, "gold");
    const Value &g = Param(p, "g", 1);
    ASSERT_EQ(g.kind, Value::Kind::Call);
    EXPECT_EQ(g.text, "blackbody");
    ASSERT_EQ(g.items.size(), 1u);
    ExpectNumber(g.items[0], 5800, Dim::Temperature());
    const Value &h = Param(p, "h", 1);
    ASSERT_EQ(h.kind, Value::Kind::Call);
    EXPECT_EQ(h.argNames, (std::vector<std::string>{"eye", "target"}));
    ExpectNumber(h.items[0].items[2], -1, Dim::Length());
}

TEST(Parser, ListsWithTrailingUnitAndSigns) {
    Parsed p =
        One("a = [0 0 1] m  b = [1, 2, 3,]  c = [0 -1 0]  d = [1 - 1]  e = [1 -1]  f = [1-1]"
            "  g = [1 m 2 mm]  h = []  i = [[1 2] [3 4]] um  j = [1 +2i]");
    ASSERT_TRUE(p.desc) << p.Errors();
    const Value &a = Param(p, "a");
    ASSERT_EQ(a.items.size(), 3u);
    ExpectNumber(a.items[2], 1, Dim::Length());
    EXPECT_EQ(Param(p, "b").items.size(), 3u);
    ASSERT_EQ(Param(p, "c").items.size(), 3u);
    EXPECT_EQ(Param(p, "c").items[1].number, -1);
    ASSERT_EQ(Param(p, "d").items.size(), 1u);  // "1 - 1": subtraction
    EXPECT_EQ(Param(p, "d").items[0].number, 0);
    EXPECT_EQ(Param(p, "e").items.size(), 2u);  // "1 -1": two items
    EXPECT_EQ(Param(p, "f").items.size(), 1u);  // "1-1": subtraction
    ExpectNumber(Param(p, "g").items[1], 2e-3, Dim::Length());
    EXPECT_TRUE(Param(p, "h").items.empty());
    ExpectNumber(Param(p, "i").items[1].items[0], 3e-6, Dim::Length());
    ASSERT_EQ(Param(p, "j").items.size(), 2u);
    EXPECT_EQ(Param(p, "j").items[1].kind, Value::Kind::Complex);
}

TEST(Parser, DimensionedArithmetic) {
    Parsed p = Parse(
        "wscene 1\nDefine d = 2 mm\nDefine width = 150 um\nDefine pitch = 1.5 um\n"
        "Shape \"s\" { a = -$d/2  b = round($width/$pitch)  c = $d * $d  d = $width / $pitch"
        "  e = (1 + 2) * 3  f = 2 * 3 mm  g = 1 mm + 1 um  h = 10 W / (2 m^2)"
        "  i = [1 2 3] m * 2  j = [1 2] mm + [3 4] mm  k = \"a\" + \"b\" }\n");
    ASSERT_TRUE(p.desc) << p.Errors();
    ExpectNumber(Param(p, "a"), -1e-3, Dim::Length());
    ExpectNumber(Param(p, "b"), 100, Dim::None());
    EXPECT_TRUE(Param(p, "b").isInteger);
    ExpectNumber(Param(p, "c"), 4e-6, Dim::Area());
    ExpectNumber(Param(p, "d"), 100, Dim::None(), 1e-14);
    EXPECT_FALSE(Param(p, "d").isInteger);
    ExpectNumber(Param(p, "e"), 9, Dim::None());
    EXPECT_TRUE(Param(p, "e").isInteger);
    ExpectNumber(Param(p, "f"), 6e-3, Dim::Length());
    ExpectNumber(Param(p, "g"), 1.001e-3, Dim::Length(), 1e-14);
    ExpectNumber(Param(p, "h"), 5, Dim::Irradiance());
    ExpectNumber(Param(p, "i").items[2], 6, Dim::Length());
    ExpectNumber(Param(p, "j").items[1], 6e-3, Dim::Length());
    EXPECT_EQ(Param(p, "k").text, "ab");
}

TEST(Parser, MathFunctions) {
    Parsed p =
        One("a = sqrt(4 m^2)  b = min(3 mm, 1 cm, 2 mm)  c = max([1 5 2])  d = sin(30 deg)"
            "  e = cos(0)  f = abs(-2 K)  g = pow(2 m, 3)  h = floor(2.7)  i = ceil(2.1)"
            "  j = asin(1)  k = atan2(1 m, 1 m)  l = exp(0)  m = log(1)  n = clamp(5, 0, 3)"
            "  o = hypot(3 m, 4 m)  p = abs(3+4i)  q = pow(2, 10)  r = log10(1000)  s = tan(45 deg)"
            "  t = trunc(-2.5)  u = select(2 > 1, 4 um, 5 m)  v = select(false, 1, [2 3])");
    ASSERT_TRUE(p.desc) << p.Errors();
    ExpectNumber(Param(p, "a"), 2, Dim::Length());
    ExpectNumber(Param(p, "b"), 2e-3, Dim::Length());
    ExpectNumber(Param(p, "c"), 5, Dim::None());
    EXPECT_TRUE(Param(p, "c").isInteger);
    ExpectNumber(Param(p, "d"), 0.5, Dim::None(), 1e-14);
    ExpectNumber(Param(p, "e"), 1, Dim::None());
    ExpectNumber(Param(p, "f"), 2, Dim::Temperature());
    ExpectNumber(Param(p, "g"), 8, Dim::Length().Pow(3));
    ExpectNumber(Param(p, "h"), 2, Dim::None());
    ExpectNumber(Param(p, "i"), 3, Dim::None());
    ExpectNumber(Param(p, "j"), Pi / 2, Dim::Angle());
    ExpectNumber(Param(p, "k"), Pi / 4, Dim::Angle());
    ExpectNumber(Param(p, "l"), 1, Dim::None());
    ExpectNumber(Param(p, "m"), 0, Dim::None());
    ExpectNumber(Param(p, "n"), 3, Dim::None());
    ExpectNumber(Param(p, "o"), 5, Dim::Length());
    ExpectNumber(Param(p, "p"), 5, Dim::None());
    ExpectNumber(Param(p, "q"), 1024, Dim::None());
    EXPECT_TRUE(Param(p, "q").isInteger);
    ExpectNumber(Param(p, "r"), 3, Dim::None(), 1e-15);
    ExpectNumber(Param(p, "s"), 1, Dim::None(), 1e-14);
    ExpectNumber(Param(p, "t"), -2, Dim::None());
    ExpectNumber(Param(p, "u"), 4e-6, Dim::Length());
    EXPECT_EQ(Param(p, "v").items.size(), 2u);
}

TEST(Parser, BooleanExpressions) {
    Parsed p = Parse(
        "wscene 1\nDefine n = 3\nDefine mode = \"fast\"\nShape \"s\" { a = $n > 2 and $mode == \"fast\""
        "  b = not ($n >= 3)  c = $n != 3 or true  d = 1 mm < 2 mm  e = \"x\" != \"y\"  f = 2 <= 1"
        "  g = @x == @x }\nShape \"t\" \"x\" {}\n");
    ASSERT_TRUE(p.desc) << p.Errors();
    EXPECT_TRUE(Param(p, "a").boolean);
    EXPECT_FALSE(Param(p, "b").boolean);
    EXPECT_TRUE(Param(p, "c").boolean);
    EXPECT_TRUE(Param(p, "d").boolean);
    EXPECT_TRUE(Param(p, "e").boolean);
    EXPECT_FALSE(Param(p, "f").boolean);
    EXPECT_TRUE(Param(p, "g").boolean);
}

TEST(Parser, EnabledDropsEntitiesAndIsNotAParameter) {
    Parsed p = Parse(
        "wscene 1\nDefine exp = \"a\"\nShape \"s\" \"one\" { enabled = $exp == \"a\"  r = 1 m }\n"
        "Shape \"s\" \"two\" { enabled = $exp == \"b\" }\nShape \"s\" \"three\" { enabled = false }\n");
    ASSERT_TRUE(p.desc) << p.Errors();
    ASSERT_EQ(p.desc->entities.size(), 1u);
    EXPECT_EQ(p.desc->entities[0].name, "one");
    EXPECT_FALSE(p.desc->entities[0].params.Has("enabled"));
    Parsed q = Parse(
        "wscene 1\nDefine exp = \"a\"\nShape \"s\" \"one\" { enabled = $exp == \"a\" }\n"
        "Shape \"s\" \"two\" { enabled = $exp == \"b\" }\n",
        {{"exp", "b"}});
    ASSERT_TRUE(q.desc) << q.Errors();
    ASSERT_EQ(q.desc->entities.size(), 1u);
    EXPECT_EQ(q.desc->entities[0].name, "two");
}

TEST(Parser, DefinesAndOverrides) {
    const std::string src =
        "wscene 1\nDefine w = 150 um\nDefine half = $w / 2\nDefine on = true\n"
        "Define name = \"out.exr\"\nDefine v = [0 0 1] m\n"
        "Shape \"s\" { a = $w  b = $half  c = $on  d = $name  e = $v }\n";
    Parsed p = Parse(src);
    ASSERT_TRUE(p.desc) << p.Errors();
    ExpectNumber(Param(p, "a"), 150e-6, Dim::Length());
    ExpectNumber(Param(p, "b"), 75e-6, Dim::Length());
    // The value's location is where $w is used.
    EXPECT_EQ(Param(p, "a").loc.line, 7);

    for (const char *w : {"100um", "\"100 um\"", "1e-4 m", "100 \xCE\xBCm", "0.1 mm", "50 um * 2"}) {
        Parsed q = Parse(src, {{"w", w}, {"on", "false"}, {"name", "x.exr"}, {"v", "[1 0 0] m"}});
        ASSERT_TRUE(q.desc) << w << "\n" << q.Errors();
        ExpectNumber(Param(q, "a"), 100e-6, Dim::Length(), 1e-14);
        ExpectNumber(Param(q, "b"), 50e-6, Dim::Length(), 1e-14);  // later Defines see the override
        EXPECT_FALSE(Param(q, "c").boolean);
        EXPECT_EQ(Param(q, "d").text, "x.exr");
        ExpectNumber(Param(q, "e").items[0], 1, Dim::Length());
        EXPECT_EQ(q.diag->WarningCount(), 0u);
    }
    Parsed quoted = Parse(src, {{"name", "\"y.exr\""}});
    EXPECT_EQ(Param(quoted, "d").text, "y.exr");
}

TEST(Parser, OverrideWithWrongDimensionCitesTheDefine) {
    Parsed p = Parse("wscene 1\nDefine w = 150 um\nShape \"s\" { a = $w }\n", {{"w", "5 deg"}});
    EXPECT_FALSE(p.desc);
    ASSERT_EQ(p.diag->ErrorCount(), 1u) << p.Errors();
    const Diagnostic &d = p.diag->All()[0];
    EXPECT_EQ(d.loc.ToString(), "<command line>:1:6");
    EXPECT_NE(d.message.find("must be a length"), std::string::npos) << d.message;
    ASSERT_EQ(d.notes.size(), 1u);
    EXPECT_EQ(d.notes[0].loc.ToString(), "main.wscene:2:8");
    Parsed bare = Parse("wscene 1\nDefine w = 150 um\nShape \"s\" { a = $w }\n", {{"w", "150"}});
    EXPECT_FALSE(bare.desc);
}

// ParseOptions::siDefines (the Python module's numbers): a bare number takes the dimension of the
// Define it overrides; other overrides are read as before, and a wrong kind stays an error.
TEST(Parser, SiDefinesTakeTheDimensionOfTheirDefine) {
    const std::string src = "wscene 1\nDefine w = 150 um\nDefine n = 3\nDefine t = 10 deg\nShape \"s\" { a = $w  b = $n  c = $t }\n";
    auto parse = [&](const DefineList &defines, const std::vector<std::string> &si) {
        Parsed r;
        r.diag = std::make_unique<Diagnostics>();
        ParseOptions o;
        o.defines = defines;
        o.siDefines = si;
        r.desc = ParseSceneString(src, "main.wscene", o, *r.diag);
        return r;
    };
    Parsed p = parse({{"w", "0.0002"}, {"n", "4"}, {"t", "0.5"}}, {"w", "n", "t"});
    ASSERT_TRUE(p.desc) << p.Errors();
    ExpectNumber(Param(p, "a"), 2e-4, Dim::Length());
    ExpectNumber(Param(p, "b"), 4, Dim::None());
    ExpectNumber(Param(p, "c"), 0.5, Dim::Angle());  // radians
    Parsed text = parse({{"w", "100um"}}, {});  // a quantity with its unit, as -D
    ASSERT_TRUE(text.desc) << text.Errors();
    ExpectNumber(Param(text, "a"), 1e-4, Dim::Length(), 1e-14);
    EXPECT_FALSE(parse({{"w", "0.0002"}}, {}).desc);  // not declared SI: a bare number is an error
    EXPECT_FALSE(parse({{"w", "\"x\""}}, {"w"}).desc);  // a string is not a length either way
}

TEST(Parser, UnusedOverrideIsAnErrorOrAPermissiveWarning) {
    const std::string src = "wscene 1\nDefine width = 1 m\nShape \"s\" {}\n";
    Parsed p = Parse(src, {{"widt", "2 m"}});
    EXPECT_FALSE(p.desc);
    EXPECT_EQ(p.diag->ErrorCount(), 1u);
    EXPECT_NE(p.Errors().find("did you mean 'width'?"), std::string::npos) << p.Errors();
    Diagnostics permissive;
    permissive.SetPermissive(true);
    ParseOptions o;
    o.defines = {{"widt", "2 m"}};
    EXPECT_TRUE(ParseSceneString(src, "main.wscene", o, permissive));
    EXPECT_EQ(permissive.WarningCount(), 1u);
    EXPECT_EQ(permissive.ErrorCount(), 0u);
}

// Runaway input: the number of Include expansions and the scene's total text are capped; one
// error at the Include that crossed the limit names the chain, and the rest is skipped.
TEST(Parser, IncludeLimits) {
    std::map<std::string, std::string> bomb;
    for (int i = 0; i < 20; ++i)
        bomb["f" + std::to_string(i) + ".wscene"] = "wscene 1\nInclude \"f" + std::to_string(i + 1) +
                                                     ".wscene\"\nInclude \"f" + std::to_string(i + 1) + ".wscene\"\n";
    bomb["f20.wscene"] = "wscene 1\n";
    auto parse = [&](const std::string &src, std::size_t maxIncludes, std::size_t maxBytes) {
        Parsed r;
        r.diag = std::make_unique<Diagnostics>();
        ParseOptions o;
        o.readFile = [&](const std::string &path) -> std::optional<std::string> {
            auto it = bomb.find(path);
            return it == bomb.end() ? std::nullopt : std::optional<std::string>(it->second);
        };
        o.maxIncludes = maxIncludes;
        o.maxSceneBytes = maxBytes;
        r.desc = ParseSceneString(src, "main.wscene", o, *r.diag);
        return r;
    };
    const std::string top = "wscene 1\nInclude \"f0.wscene\"\n";
    Parsed n = parse(top, 1000, 1u << 30);
    EXPECT_FALSE(n.desc);
    ASSERT_EQ(n.diag->ErrorCount(), 1u) << n.Errors();
    EXPECT_NE(n.Errors().find("too many Include expansions (more than 1000"), std::string::npos) << n.Errors();
    EXPECT_NE(n.Errors().find("main.wscene → f0.wscene → f1.wscene → f2.wscene"), std::string::npos) << n.Errors();

    Parsed t = parse(top, 1u << 30, 2000);
    ASSERT_EQ(t.diag->ErrorCount(), 1u) << t.Errors();
    EXPECT_NE(t.Errors().find("would exceed the limit of 2000 bytes"), std::string::npos) << t.Errors();
    Parsed big = parse(std::string(3000, '#'), 1u << 30, 2000);
    EXPECT_NE(big.Errors().find("main.wscene: cannot read scene file 'main.wscene': it is larger than the limit"),
              std::string::npos)
        << big.Errors();
}

TEST(Parser, SplitDefineArgument) {
    Diagnostics diag;
    auto a = SplitDefineArgument("w=150um", diag);
    ASSERT_TRUE(a);
    EXPECT_EQ(a->first, "w");
    EXPECT_EQ(a->second, "150um");
    auto b = SplitDefineArgument("x=a=b", diag);
    ASSERT_TRUE(b);
    EXPECT_EQ(b->second, "a=b");
    EXPECT_FALSE(SplitDefineArgument("novalue", diag));
    EXPECT_FALSE(SplitDefineArgument("1x=2", diag));
    EXPECT_EQ(diag.ErrorCount(), 2u);
}

TEST(Parser, ParseValueString) {
    Diagnostics diag;
    auto v = ParseValueString("150 um", "<value>", diag);
    ASSERT_TRUE(v);
    ExpectNumber(*v, 150e-6, Dim::Length());
    EXPECT_FALSE(ParseValueString("150 umm", "<value>", diag));
    EXPECT_FALSE(ParseValueString("1 m + 1 deg", "<value>", diag));
    EXPECT_EQ(diag.ErrorCount(), 2u);
}

TEST(Parser, IncludesAreRelativeToTheIncludingFile) {
    std::map<std::string, std::string> files = {
        {"lib/materials.wscene", "wscene 1\nDefine n = 1.5\nInclude \"more/glass.wscene\"\n"},
        {"lib/more/glass.wscene", "wscene 1\nMaterial \"dielectric\" \"glass\" { ior = $n }\n"},
    };
    Parsed p =
        Parse("wscene 1\nInclude \"lib/materials.wscene\"\nShape \"s\" { material = @glass }\n", {}, files);
    ASSERT_TRUE(p.desc) << p.Errors();
    ASSERT_EQ(p.desc->entities.size(), 2u);
    EXPECT_EQ(p.desc->entities[0].name, "glass");
    EXPECT_EQ(p.desc->entities[0].loc.file, "lib/more/glass.wscene");
    EXPECT_EQ(Param(p, "ior").number, 1.5);
}

TEST(Parser, ErrorsInIncludedFilesCarryTheIncludeChain) {
    std::map<std::string, std::string> files = {
        {"a.wscene", "wscene 1\nInclude \"b.wscene\"\n"},
        {"b.wscene", "wscene 1\nShape \"s\" { r = 1 qm }\n"},
    };
    Parsed p = Parse("wscene 1\nInclude \"a.wscene\"\n", {}, files);
    EXPECT_FALSE(p.desc);
    ASSERT_EQ(p.diag->All().size(), 1u) << p.Errors();
    const Diagnostic &d = p.diag->All()[0];
    EXPECT_EQ(d.loc.ToString(), "b.wscene:2:19");
    ASSERT_EQ(d.notes.size(), 2u);
    EXPECT_EQ(d.notes[0].loc.ToString(), "a.wscene:2:1");
    EXPECT_EQ(d.notes[1].loc.ToString(), "main.wscene:2:1");
    EXPECT_NE(d.notes[0].message.find("included from"), std::string::npos);
}

TEST(Parser, IncludeCycleAndMissingInclude) {
    std::map<std::string, std::string> files = {
        {"a.wscene", "wscene 1\nInclude \"b.wscene\"\n"},
        {"b.wscene", "wscene 1\nInclude \"a.wscene\"\n"},
    };
    Parsed p = Parse("wscene 1\nInclude \"a.wscene\"\n", {}, files);
    EXPECT_FALSE(p.desc);
    EXPECT_NE(p.Errors().find("b.wscene:2:9: include cycle"), std::string::npos) << p.Errors();
    Parsed self = Parse("wscene 1\nInclude \"./main.wscene\"\n", {}, {});
    EXPECT_NE(self.Errors().find("include cycle"), std::string::npos) << self.Errors();
    Parsed missing = Parse("wscene 1\nInclude \"nope.wscene\"\n");
    EXPECT_NE(missing.Errors().find("main.wscene:2:9: cannot read included file 'nope.wscene'"),
              std::string::npos)
        << missing.Errors();
}

TEST(Parser, ForwardReferencesAreAllowed) {
    Parsed p = Parse(
        "wscene 1\nShape \"s\" { material = @m  list = [@a @m] }\nMaterial \"x\" \"m\" {}\n"
        "Material \"x\" \"a\" {}\n");
    ASSERT_TRUE(p.desc) << p.Errors();
}

TEST(Parser, UndefinedReferenceSuggests) {
    Parsed p = Parse("wscene 1\nMaterial \"conductor\" \"gold\" {}\nShape \"s\" { material = @gld }\n");
    EXPECT_FALSE(p.desc);
    EXPECT_NE(p.Errors().find("main.wscene:3:24: '@gld' is not defined; did you mean '@gold'"),
              std::string::npos)
        << p.Errors();
}

TEST(Parser, DuplicateNamesAndParametersCiteBothSites) {
    Parsed p = Parse("wscene 1\nShape \"s\" \"a\" {}\nLight \"l\" \"a\" {}\n");
    EXPECT_FALSE(p.desc);
    ASSERT_EQ(p.diag->All().size(), 1u);
    EXPECT_EQ(p.diag->All()[0].loc.ToString(), "main.wscene:3:11");
    ASSERT_EQ(p.diag->All()[0].notes.size(), 1u);
    EXPECT_EQ(p.diag->All()[0].notes[0].loc.ToString(), "main.wscene:2:11");
    Parsed q = Parse("wscene 1\nShape \"s\" { r = 1 m\n r = 2 m }\n");
    EXPECT_FALSE(q.desc);
    ASSERT_EQ(q.diag->All().size(), 1u);
    EXPECT_EQ(q.diag->All()[0].loc.ToString(), "main.wscene:3:2");
    EXPECT_EQ(q.diag->All()[0].notes[0].loc.ToString(), "main.wscene:2:13");
    Parsed d = Parse("wscene 1\nDefine x = 1\nDefine x = 2\n");
    EXPECT_FALSE(d.desc);
    EXPECT_EQ(d.diag->All()[0].notes[0].loc.ToString(), "main.wscene:2:8");
}

TEST(Parser, ManyErrorsAreCollectedUpToTheLimit) {
    std::string src = "wscene 1\n";
    for (int i = 0; i < 30; ++i) src += "Shape \"s\" { r = 1 qm }\n";
    Parsed p = Parse(src);
    EXPECT_FALSE(p.desc);
    EXPECT_EQ(p.diag->All().size(), 20u);
}

TEST(Parser, SyntaxErrorRecoversAtTheNextStatement) {
    Parsed p = Parse("wscene 1\nShape \"s\" { r = = 2 }\nShape \"t\" { r = 1 qm }\n");
    EXPECT_FALSE(p.desc);
    EXPECT_EQ(p.diag->ErrorCount(), 2u) << p.Errors();
    // A named block with a syntax error still defines its name: no cascade of undefined references.
    Parsed q = Parse("wscene 1\nMaterial \"x\" \"m\" { a = [1 2 }\nShape \"s\" { material = @m }\n");
    EXPECT_EQ(q.diag->ErrorCount(), 1u) << q.Errors();
}

TEST(Parser, LexicalErrorStopsThatFileOnly) {
    std::map<std::string, std::string> files = {{"inc.wscene", "wscene 1\nShape \"s\" \"x\" { a = \"open\n"}};
    Parsed p = Parse("wscene 1\nInclude \"inc.wscene\"\nShape \"t\" { r = 1 qm }\n", {}, files);
    EXPECT_FALSE(p.desc);
    EXPECT_EQ(p.diag->ErrorCount(), 2u) << p.Errors();
}

TEST(Parser, MissingHeader) {
    Parsed p = Parse("Shape \"s\" {}\n");
    EXPECT_FALSE(p.desc);
    EXPECT_NE(p.Errors().find("main.wscene:1:1: missing header"), std::string::npos) << p.Errors();
    Parsed v = Parse("wscene 3\n");
    EXPECT_NE(v.Errors().find("main.wscene:1:8: unsupported format version"), std::string::npos)
        << v.Errors();
    Parsed comments = Parse("# a comment first is fine\n\nwscene 1\n");
    EXPECT_TRUE(comments.desc) << comments.Errors();
    // Versions 1 and 2 are read; each entity knows its file's version (plug-ins whose parameters
    // changed meaning refuse version 1 where it matters).
    Parsed two = Parse("wscene 2\nShape \"sphere\" {}\n");
    ASSERT_TRUE(two.desc) << two.Errors();
    EXPECT_EQ(two.desc->entities.at(0).params.FormatVersion(), 2);
    Parsed one = Parse("wscene 1\nShape \"sphere\" {}\n");
    ASSERT_TRUE(one.desc) << one.Errors();
    EXPECT_EQ(one.desc->entities.at(0).params.FormatVersion(), 1);
}

TEST(Parser, MessagesNameEveryFamilyFromTheOneList) {
    // The keywords and example plug-ins come from core/plugin_families.h: an unknown statement
    // lists them all, and a block without its type shows the family's example.
    Parsed p = Parse("wscene 1\nQwertyuiop {}\n");
    EXPECT_NE(p.Errors().find("2:1: unknown statement 'Qwertyuiop' (expected Include, Define, Render, Spectrum, "
                              "Texture, Material, Shape, Light, Detector, Integrator or Sampler)"),
              std::string::npos)
        << p.Errors();
#define PHASOR_CHECK_FAMILY(Keyword, family, Interface, Example)                                        \
    {                                                                                                 \
        Parsed b = Parse("wscene 1\n" #Keyword " {}\n");                                            \
        EXPECT_NE(b.Errors().find("(e.g. " #Keyword " \"" #Example "\" { … })"), std::string::npos) \
            << b.Errors();                                                                            \
    }
    PHASOR_PLUGIN_FAMILIES(PHASOR_CHECK_FAMILY)
#undef PHASOR_CHECK_FAMILY
}

TEST(Parser, MisspelledKeywordSuggests) {
    Parsed p = Parse("wscene 1\nShap \"s\" {}\nmaterial \"m\" {}\n");
    EXPECT_NE(p.Errors().find("2:1: unknown statement 'Shap'; did you mean 'Shape'?"), std::string::npos)
        << p.Errors();
    EXPECT_NE(p.Errors().find("3:1: unknown statement 'material'; did you mean 'Material'?"),
              std::string::npos)
        << p.Errors();
}

TEST(Parser, UndefinedVariableSuggestsAndUseBeforeDefine) {
    Parsed p = Parse("wscene 1\nDefine width = 1 m\nShape \"s\" { a = $wdth }\n");
    EXPECT_NE(p.Errors().find("3:17: '$wdth' is not defined; did you mean '$width'?"), std::string::npos)
        << p.Errors();
    Parsed q = Parse("wscene 1\nShape \"s\" { a = $w }\nDefine w = 1 m\n");
    EXPECT_NE(q.Errors().find("2:17: '$w' is used before its Define"), std::string::npos) << q.Errors();
}

TEST(Parser, DimensionErrors) {
    Parsed p = One("a = 1 m + 2 deg");
    EXPECT_NE(p.Errors().find("2:30: cannot add a length (1 m) and an angle (2 deg)"), std::string::npos)
        << p.Errors();
    EXPECT_FALSE(One("a = 1 m < 1 K").desc);
    EXPECT_FALSE(One("a = sqrt(1 m)").desc);
    EXPECT_FALSE(One("a = round(1.5 mm)").desc);
    EXPECT_FALSE(One("a = sin(1 m)").desc);
    EXPECT_FALSE(One("a = 1 / 0").desc);
    EXPECT_FALSE(One("a = [1 m 2] m").desc);
    EXPECT_FALSE(One("a = (1+2i) * 1 m").desc);
    EXPECT_FALSE(One("a = 1e999").desc);
    EXPECT_FALSE(One("a = 1e300 km * 1e300").desc);
    EXPECT_FALSE(One("a = \"x\" + 1").desc);
    EXPECT_FALSE(One("a = not 1").desc);
    EXPECT_FALSE(One("a = 1 and true").desc);
    EXPECT_FALSE(One("enabled = 1").desc);
    EXPECT_FALSE(One("a = f(x = 1, x = 2)").desc);
    EXPECT_FALSE(One("a = min()").desc);
    EXPECT_FALSE(One("a = 1 < 2 < 3").desc);
}

TEST(Parser, UnknownUnitSuggests) {
    Parsed p = One("a = 2 umm");
    EXPECT_NE(p.Errors().find("2:28: unknown unit 'umm'; did you mean 'um'?"), std::string::npos)
        << p.Errors();
}

TEST(Parser, RenderRules) {
    EXPECT_FALSE(Parse("wscene 1\nRender {}\nRender {}\n").desc);
    EXPECT_FALSE(Parse("wscene 1\nRender \"x\" {}\n").desc);
}

TEST(Parser, DeepNestingIsAnErrorNotACrash) {
    std::string deep(5000, '(');
    EXPECT_FALSE(One("a = " + deep).desc);
    std::string chain = "a = 1";
    for (int i = 0; i < 5000; ++i) chain += " + 1";
    EXPECT_FALSE(One(chain).desc);
    std::string lists(5000, '[');
    EXPECT_FALSE(One("a = " + lists).desc);
}

TEST(Parser, ReadsFilesFromDisk) {
    Diagnostics diag;
    EXPECT_FALSE(ParseSceneFile("does/not/exist.wscene", DefineList{}, diag));
    EXPECT_EQ(diag.ErrorCount(), 1u);
}

TEST(Parser, RecordListFieldsKeepTheirLocations) {
    // A list of calls with named arguments parses to Calls whose arguments know where their names
    // are, so a record field's errors point at the field (ParamKind::RecordList, core/params/schema.h).
    Parsed p = One("layers = [layer(ior = 1.55, thickness = 85 nm),\n    layer(ior = \"BK7\", thicknes = 0.1 um)]");
    ASSERT_TRUE(p.desc) << p.Errors();
    const Schema s{"shape", "sphere", "", {P::RecordList("layers", "layers", "layer", "a layer",
                                                         {P::ComplexSpectrum("ior", "index").Required(),
                                                          P::Length("thickness", "thickness").Required()})}};
    Diagnostics d;
    const ParamDict &dict = p.desc->entities[0].params;
    EXPECT_FALSE(dict.Validate(s, d));
    ASSERT_EQ(d.ErrorCount(), 2u);
    EXPECT_EQ(d.All()[0].loc.ToString(), "main.wscene:3:24");  // the misspelt field's name
    EXPECT_NE(d.All()[0].message.find("did you mean 'thickness'?"), std::string::npos) << d.All()[0].message;
    EXPECT_EQ(d.All()[1].loc.ToString(), "main.wscene:3:5");  // the record missing 'thickness'
    const Value &first = Param(p, "layers").items[0];
    ASSERT_EQ(first.argLocs.size(), 2u);
    EXPECT_EQ(first.argLocs[1].col, 50);  // 'thickness' in line 2
    EXPECT_EQ(first.items[1].loc.col, 62);  // its value
}

}  // namespace
}  // namespace phasor
