// SPDX-License-Identifier: Apache-2.0
// libFuzzer target for the .wscene reader (build and run: docs/wscene.md §10). Each input is a
// scene text; leading lines "#D name=value" become -D overrides. Includes resolve to a small
// in-memory library (and the input itself, which makes cycles reachable). Beyond "no crash, no
// sanitizer report" it checks the printer's contract: a scene that parses formats, the output
// re-parses to the same SceneDesc, and formatting is idempotent.
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "parser/parser.h"

namespace {

void Check(bool ok, const char *what) {
    if (!ok) {
        std::fprintf(stderr, "fuzz_parser invariant violated: %s\n", what);
        std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, std::size_t size) {
    using namespace phasor;
    if (size > 64 * 1024) return 0;  // keep each run fast
    const std::string text(reinterpret_cast<const char *>(data), size);

    ParseOptions opt;
    std::istringstream lines(text);
    std::string line;
    Diagnostics defineDiag;
    while (std::getline(lines, line) && line.rfind("#D ", 0) == 0)
        if (auto kv = SplitDefineArgument(line.substr(3), defineDiag)) opt.defines.push_back(*kv);
    opt.readFile = [&text](const std::string &path) -> std::optional<std::string> {
        if (path == "lib/a.wscene")
            return std::string("wscene 1\nDefine lib_a = 2 mm\nMaterial \"diffuse\" \"lib_m\" {}\n");
        if (path == "lib/b.wscene") return std::string("wscene 1\nInclude \"a.wscene\"\n");
        if (path == "self.wscene" || path == "fuzz.wscene") return text;
        return std::nullopt;
    };
    opt.maxIncludeDepth = 8;

    Diagnostics diag;
    std::optional<SceneDesc> desc = ParseSceneString(text, "fuzz.wscene", opt, diag);
    std::ostringstream sink;
    diag.Print(sink);

    Diagnostics fdiag;
    std::optional<std::string> formatted = FormatSceneString(text, "fuzz.wscene", fdiag);
    if (!desc) return 0;
    Check(formatted.has_value(), "a scene that parses must format");
    Diagnostics rdiag;
    std::optional<SceneDesc> again = ParseSceneString(*formatted, "fuzz.wscene", opt, rdiag);
    Check(again.has_value(), "formatted text must parse");
    std::string why;
    Check(SameScene(*desc, *again, &why), "formatted text must give the same SceneDesc");
    Diagnostics gdiag;
    std::optional<std::string> twice = FormatSceneString(*formatted, "fuzz.wscene", gdiag);
    Check(twice.has_value() && *twice == *formatted, "format must be idempotent");
    return 0;
}
