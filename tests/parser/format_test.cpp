// SPDX-License-Identifier: Apache-2.0
// The canonical printer (`phasor format`): its output re-parses to an identical SceneDesc
// (entity by entity, Value::SameAs), it is idempotent and it keeps comments. Inputs: every scene
// under scenes/, tests/parser/roundtrip/, the corpus files that parse cleanly, and the complete
// examples of docs/wscene.md (which must also build without warnings).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/render/registry.h"
#include "core/render/scene.h"
#include "parser/parser.h"

namespace phasor {
namespace {

namespace fs = std::filesystem;

fs::path Source() { return fs::path(PHASOR_SOURCE_DIR); }

std::string ReadText(const fs::path &p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::string Printed(const Diagnostics &d) {
    std::ostringstream os;
    d.Print(os);
    return os.str();
}

// Formats `text` (as file `name`), re-parses the output and compares with the original's IR.
void CheckRoundTrip(const std::string &text, const std::string &name, const DefineList &defines = {}) {
    SCOPED_TRACE(name);
    Diagnostics d1;
    std::optional<SceneDesc> original = ParseSceneString(text, name, defines, d1);
    ASSERT_TRUE(original) << Printed(d1);
    Diagnostics d2;
    std::optional<std::string> formatted = FormatSceneString(text, name, d2);
    ASSERT_TRUE(formatted) << Printed(d2);
    Diagnostics d3;
    // Same file name, so relative Includes resolve as in the original.
    std::optional<SceneDesc> again = ParseSceneString(*formatted, name, defines, d3);
    ASSERT_TRUE(again) << Printed(d3) << "\nformatted text:\n" << *formatted;
    std::string why;
    EXPECT_TRUE(SameScene(*original, *again, &why)) << why << "\nformatted text:\n" << *formatted;
    Diagnostics d4;
    std::optional<std::string> twice = FormatSceneString(*formatted, name, d4);
    ASSERT_TRUE(twice);
    EXPECT_EQ(*twice, *formatted) << "format is not idempotent";
}

std::vector<fs::path> Glob(const fs::path &dir, bool recursive) {
    std::vector<fs::path> out;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return out;
    if (recursive) {
        for (const auto &e : fs::recursive_directory_iterator(dir, ec))
            if (e.is_regular_file() && e.path().extension() == ".wscene") out.push_back(e.path());
    } else {
        for (const auto &e : fs::directory_iterator(dir, ec))
            if (e.is_regular_file() && e.path().extension() == ".wscene") out.push_back(e.path());
    }
    std::sort(out.begin(), out.end());
    return out;
}

TEST(Format, RoundTripsTheFeatureFile) {
    for (const fs::path &p : Glob(Source() / "tests/parser/roundtrip", false))
        CheckRoundTrip(ReadText(p), p.lexically_normal().generic_string());
    // With -D overrides as well.
    fs::path f = Source() / "tests/parser/roundtrip/features.wscene";
    CheckRoundTrip(ReadText(f), f.generic_string(), {{"mode", "slow"}, {"width", "\"300 um\""}});
}

TEST(Format, RoundTripsEverySceneUnderScenes) {
    for (const fs::path &p : Glob(Source() / "scenes", true)) CheckRoundTrip(ReadText(p), p.generic_string());
}

// Issue #3 item 6: every scene under scenes/ loads with --strict, without warnings. A file with a
// Render block is a complete scene (Scene::Build); other files are libraries meant for Include
// (their entities are built with BuildContext).
TEST(Scenes, EverySceneLoadsStrictlyWithoutWarnings) {
    for (const fs::path &p : Glob(Source() / "scenes", true)) {
        std::string name = p.lexically_normal().generic_string();
        SCOPED_TRACE(name);
        Diagnostics diag(/*strict=*/true);
        std::optional<SceneDesc> desc = ParseSceneFile(name, DefineList{}, diag);
        ASSERT_TRUE(desc) << Printed(diag);
        bool complete = false;
        for (const SceneEntity &e : desc->entities) complete = complete || e.keyword == "Render";
        if (complete) {
            EXPECT_TRUE(Scene::Build(*desc, diag)) << Printed(diag);
        } else {
            BuildContext ctx(*desc, diag);
            ctx.BuildAll();
        }
        EXPECT_FALSE(diag.HasErrors()) << Printed(diag);
        EXPECT_EQ(diag.WarningCount(), 0u) << Printed(diag);
    }
}

TEST(Format, RoundTripsCorpusFilesThatParse) {
    int n = 0;
    for (const fs::path &p : Glob(Source() / "tests/parser/diagnostics", false)) {
        std::string text = ReadText(p);
        if (text.find("# stage: build") == std::string::npos) continue;
        CheckRoundTrip(text, p.generic_string());
        ++n;
    }
    EXPECT_GT(n, 0);
}

TEST(Format, CanonicalLayout) {
    const std::string src =
        "# head\nwscene 1\nDefine w=150um\nShape \"sphere\" \"b\"{radius=$w/2 center=[0,0,-1]m # c\n"
        "material=@m}\nMaterial \"diffuse\" \"m\" {}\n\n\n# tail\n";
    Diagnostics d;
    std::optional<std::string> f = FormatSceneString(src, "x.wscene", d);
    ASSERT_TRUE(f) << Printed(d);
    EXPECT_EQ(*f,
              "# head\n"
              "wscene 1\n"
              "Define w = 150 um\n"
              "Shape \"sphere\" \"b\" {\n"
              "    radius = $w / 2\n"
              "    center = [0 0 -1] m  # c\n"
              "    material = @m\n"
              "}\n"
              "Material \"diffuse\" \"m\" {}\n"
              "\n"
              "# tail\n");
}

TEST(Format, WrapsLongListsAndKeepsThemValid) {
    std::string src = "wscene 1\nShape \"trianglemesh\" { positions = [";
    for (int i = 0; i < 300; ++i) src += std::to_string(i % 7) + (i % 3 == 2 ? "  " : " ");
    src += "] cm indices = [0 1 2] }\n";
    Diagnostics d;
    std::optional<std::string> f = FormatSceneString(src, "x.wscene", d);
    ASSERT_TRUE(f);
    std::istringstream lines(*f);
    std::string line;
    int count = 0;
    while (std::getline(lines, line)) {
        EXPECT_LE(line.size(), 100u) << line;
        ++count;
    }
    EXPECT_GT(count, 5);
    CheckRoundTrip(src, "x.wscene");
}

TEST(Format, RefusesFilesWithSyntaxErrors) {
    Diagnostics d;
    EXPECT_FALSE(FormatSceneString("wscene 1\nShape \"s\" { r = }\n", "x.wscene", d));
    EXPECT_TRUE(d.HasErrors());
    Diagnostics e;
    EXPECT_FALSE(FormatSceneString("wscene 1\nShape \"s\" { r = \"x }\n", "x.wscene", e));
    Diagnostics f;
    EXPECT_FALSE(FormatSceneFile("no/such/file.wscene", f));
}

// Fenced ```wscene blocks in docs/wscene.md must parse, build without warnings (strict; blocks with
// a Render block as whole scenes with Scene::Build) and round-trip.
TEST(Docs, WsceneExamplesParseBuildAndRoundTrip) {
    std::string doc = ReadText(Source() / "docs/wscene.md");
    ASSERT_FALSE(doc.empty()) << "docs/wscene.md is missing";
    std::istringstream in(doc);
    std::string line, block;
    bool inside = false;
    int n = 0, startLine = 0, lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        if (!inside && line == "```wscene") {
            inside = true;
            block.clear();
            startLine = lineNo;
            continue;
        }
        if (inside && line == "```") {
            inside = false;
            ++n;
            std::string name = "docs/wscene.md@" + std::to_string(startLine);
            SCOPED_TRACE(name);
            Diagnostics diag(/*strict=*/true);
            std::optional<SceneDesc> desc = ParseSceneString(block, name, DefineList{}, diag);
            ASSERT_TRUE(desc) << Printed(diag) << block;
            bool complete = false;
            for (const SceneEntity &e : desc->entities) complete = complete || e.keyword == "Render";
            if (complete) {
                EXPECT_TRUE(Scene::Build(*desc, diag)) << Printed(diag);
            } else {
                BuildContext ctx(*desc, diag);
                ctx.BuildAll();
            }
            EXPECT_FALSE(diag.HasErrors()) << Printed(diag) << block;
            EXPECT_EQ(diag.WarningCount(), 0u) << Printed(diag);
            CheckRoundTrip(block, name);
            continue;
        }
        if (inside) block += line + "\n";
    }
    EXPECT_GE(n, 3);
}

}  // namespace
}  // namespace phasor
