// SPDX-License-Identifier: Apache-2.0
// Parsing (and building) a generated 100k-entity .wscene scene (issue #3: < 1 s).
// Links phasor_parser and phasor.
#include <benchmark/benchmark.h>

#include <string>

#include "core/render/registry.h"
#include "parser/parser.h"

namespace phasor {
namespace {

// `n` entities: one material per 100 shapes, spheres with Defines, arithmetic, lists, units,
// references and comments.
std::string GenerateScene(int n) {
    std::string s = "wscene 1\n# generated benchmark scene\nDefine r = 2 mm\nDefine pitch = 1 cm\n";
    s.reserve(std::size_t(n) * 110);
    int materials = n / 100 + 1;
    for (int m = 0; m < materials; ++m)
        s += "Material \"diffuse\" \"m" + std::to_string(m) + "\" { reflectance = 0." +
             std::to_string(1 + m % 8) + " }\n";
    for (int i = materials; i < n; ++i) {
        s += "Shape \"sphere\" \"s" + std::to_string(i) + "\" {\n    center = [" + std::to_string(i % 100) +
             " " + std::to_string((i / 100) % 100) + " " + std::to_string(i / 10000) +
             "] * $pitch\n    radius = $r / 2 + " + std::to_string(i % 7) + " um\n    material = @m" +
             std::to_string(i % materials) + "  # comment\n}\n";
    }
    return s;
}

void BM_Parse100k(benchmark::State &state) {
    const std::string text = GenerateScene(int(state.range(0)));
    for (auto _ : state) {
        Diagnostics diag;
        std::optional<SceneDesc> desc = ParseSceneString(text, "bench.wscene", DefineList{}, diag);
        if (!desc || desc->entities.size() != std::size_t(state.range(0)))
            state.SkipWithError("parse failed");
        benchmark::DoNotOptimize(desc);
    }
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(text.size()));
    state.counters["entities"] = double(state.range(0));
}
BENCHMARK(BM_Parse100k)->Arg(100000)->Unit(benchmark::kMillisecond);

void BM_ParseAndBuild100k(benchmark::State &state) {
    const std::string text = GenerateScene(int(state.range(0)));
    for (auto _ : state) {
        Diagnostics diag;
        std::optional<SceneDesc> desc = ParseSceneString(text, "bench.wscene", DefineList{}, diag);
        if (!desc) {
            state.SkipWithError("parse failed");
            break;
        }
        BuildContext ctx(*desc, diag);
        ctx.BuildAll();
        if (diag.HasErrors()) state.SkipWithError("build failed");
        benchmark::DoNotOptimize(ctx);
    }
    state.counters["entities"] = double(state.range(0));
}
BENCHMARK(BM_ParseAndBuild100k)->Arg(100000)->Unit(benchmark::kMillisecond);

void BM_Format100k(benchmark::State &state) {
    const std::string text = GenerateScene(int(state.range(0)));
    for (auto _ : state) {
        Diagnostics diag;
        std::optional<std::string> out = FormatSceneString(text, "bench.wscene", diag);
        if (!out) state.SkipWithError("format failed");
        benchmark::DoNotOptimize(out);
    }
}
BENCHMARK(BM_Format100k)->Arg(100000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace phasor

BENCHMARK_MAIN();
