// SPDX-License-Identifier: Apache-2.0
// The diagnostics corpus: every tests/parser/diagnostics/*.wscene is a malformed scene annotated
// with the diagnostics it must produce (format: tests/parser/diagnostics/README.md). Each file is
// parsed in-process and what was read cleanly is built with BuildContext (or, for `# stage:
// scene`, with Scene::Build), as `phasor check` does in one run; the reported errors and warnings
// must be exactly the expected ones, at the expected line:col, with the expected text.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "core/render/registry.h"
#include "core/render/scene.h"
#include "parser/parser.h"

namespace phasor {
namespace {

namespace fs = std::filesystem;

fs::path CorpusDir() { return fs::path(PHASOR_SOURCE_DIR) / "tests" / "parser" / "diagnostics"; }

struct Expectation {
    Severity severity = Severity::Error;
    std::string file;  // normalised path
    int line = 0, col = 0;
    std::string fragment;
    std::string text;  // the annotation, for messages
    bool matched = false;
};

struct CorpusCase {
    std::vector<Expectation> expect;
    DefineList defines;
    bool strict = false, permissive = false;
    enum class Stage { Any, Build, Scene } stage = Stage::Any;  // Build, Scene: it parses cleanly
};

std::string Normal(const fs::path &p) { return p.lexically_normal().generic_string(); }

CorpusCase ReadCase(const fs::path &file, std::string *error) {
    CorpusCase c;
    std::ifstream in(file);
    std::string line;
    static const std::regex expectRe(
        R"(^#\s*expect:\s*(error|warning|note)\s+(?:(.+?):)?(\d+):(\d+)\s+(.*?)\s*$)");
    static const std::regex defineRe(R"(^#\s*define:\s*(.*?)\s*$)");
    while (std::getline(in, line)) {
        if (line.rfind("#", 0) != 0) continue;
        std::smatch m;
        if (std::regex_match(line, m, expectRe)) {
            Expectation e;
            e.severity = m[1] == "error"     ? Severity::Error
                         : m[1] == "warning" ? Severity::Warning
                                             : Severity::Note;
            std::string f = m[2].matched ? m[2].str() : std::string();
            if (f.empty())
                e.file = Normal(file);
            else if (f[0] == '<')
                e.file = f;  // <command line>
            else
                e.file = Normal(file.parent_path() / f);
            e.line = std::stoi(m[3]);
            e.col = std::stoi(m[4]);
            e.fragment = m[5];
            e.text = line;
            c.expect.push_back(e);
        } else if (std::regex_match(line, m, defineRe)) {
            Diagnostics d;
            auto kv = SplitDefineArgument(m[1], d);
            if (!kv)
                *error = "bad '# define:' line: " + line;
            else
                c.defines.push_back(*kv);
        } else if (line == "# strict") {
            c.strict = true;
        } else if (line == "# permissive") {
            c.permissive = true;
        } else if (line == "# stage: build") {
            c.stage = CorpusCase::Stage::Build;
        } else if (line == "# stage: scene") {
            c.stage = CorpusCase::Stage::Scene;
        } else if (line.find("expect") != std::string::npos || line.find("define:") != std::string::npos) {
            *error = "malformed annotation: " + line;
        }
    }
    return c;
}

std::vector<std::string> CorpusFiles() {
    std::vector<std::string> files;
    std::error_code ec;
    for (const auto &entry : fs::directory_iterator(CorpusDir(), ec))
        if (entry.is_regular_file() && entry.path().extension() == ".wscene")
            files.push_back(entry.path().filename().string());
    std::sort(files.begin(), files.end());
    return files;
}

bool Matches(const Expectation &e, Severity sev, const FileLoc &loc, const std::string &msg) {
    return e.severity == sev && e.line == loc.line && e.col == loc.col &&
           (e.file == loc.file || e.file == Normal(loc.file)) && msg.find(e.fragment) != std::string::npos;
}

class DiagnosticsCorpus : public ::testing::TestWithParam<std::string> {};

TEST_P(DiagnosticsCorpus, ReportsExactlyTheExpectedDiagnostics) {
    fs::path file = CorpusDir() / GetParam();
    std::string annotationError;
    CorpusCase c = ReadCase(file, &annotationError);
    ASSERT_TRUE(annotationError.empty()) << annotationError;
    bool anyError = false;
    for (const Expectation &e : c.expect) anyError = anyError || e.severity == Severity::Error;
    ASSERT_TRUE(anyError) << "a corpus file must expect at least one error";

    Diagnostics diag(c.strict);
    diag.SetPermissive(c.permissive);
    ParseOptions options;
    options.defines = c.defines;
    options.partial = true;
    std::optional<SceneDesc> desc = ParseSceneFile(Normal(file), options, diag);
    if (c.stage != CorpusCase::Stage::Any) {
        ASSERT_TRUE(desc && !desc->incomplete) << "a '# stage:' case must parse cleanly";
    }
    if (c.stage == CorpusCase::Stage::Scene) {
        EXPECT_FALSE(Scene::Build(*desc, diag));
    } else if (desc) {
        BuildContext ctx(*desc, diag);
        ctx.BuildAll();
    }
    std::ostringstream printed;
    diag.Print(printed);
    SCOPED_TRACE("diagnostics:\n" + printed.str());

    for (const Diagnostic &d : diag.All()) {
        if (d.severity == Severity::Note) continue;
        bool found = false;
        for (Expectation &e : c.expect)
            if (!e.matched && Matches(e, d.severity, d.loc, d.message)) {
                e.matched = found = true;
                break;
            }
        EXPECT_TRUE(found) << "unexpected diagnostic: " << d.loc.ToString() << ": " << d.message;
        for (const Diagnostic &n : d.notes)
            for (Expectation &e : c.expect)
                if (!e.matched && Matches(e, Severity::Note, n.loc, n.message)) e.matched = true;
    }
    for (const Expectation &e : c.expect) EXPECT_TRUE(e.matched) << "not reported: " << e.text;
    EXPECT_TRUE(diag.HasErrors());
}

std::string CaseName(const ::testing::TestParamInfo<std::string> &info) {
    std::string n = fs::path(info.param).stem().string();
    for (char &ch : n)
        if (!std::isalnum((unsigned char)ch)) ch = '_';
    return n;
}

INSTANTIATE_TEST_SUITE_P(Corpus, DiagnosticsCorpus, ::testing::ValuesIn(CorpusFiles()), CaseName);

TEST(DiagnosticsCorpusSize, AtLeastFortyMalformedFiles) { EXPECT_GE(CorpusFiles().size(), 40u); }

}  // namespace
}  // namespace phasor
