// SPDX-License-Identifier: Apache-2.0
// Per-kernel throughput (Google Benchmark) for every registered kernel × each of its TestPresets(),
// registered at start-up from the registry, so a new kernel is measured without new code:
//   * Sample: Material::Prepare for the query, then one PreparedKernel::Sample (what a path vertex
//     costs: one sample per prepared kernel);
//   * Eval: Prepare, then one Eval (a kernel asked once per query);
//   * Eval prepared: Eval on a kernel prepared once per query (what light sampling and MIS pay per
//     further direction). Each call carries the hero wavelength 550 nm and three companions (as
// in a render; tests/materials/material_test_util.h TestWavelengths) and cycles through a fixed set
// of incident directions (normal, 37°, 66°, 85°, and from below) and, for Eval, of outgoing ones.
// Footprint-aware kernels are queried in the wave regime with the contract suite's incident
// generalized ray on its test plate (material_test_util.h); the others as `grt` queries them
// (rayOptics = false). After Google Benchmark's own table, prints a Markdown table of ns per call
// (CPU time, one thread) for docs/kernels.md ("Kernel throughput"). Kernels are prepared in a
// ScratchBuffer reset after each call, as the render loop does after each sample.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "materials/material_test_util.h"
#include "support/stats.h"

namespace phasor::test {
namespace {

constexpr int Batch = 256;  // calls per benchmark iteration
constexpr double Lambda = 550e-9;
// (cosθ, φ) of the incident directions.
constexpr double Incidents[][2] = {{1.0, 0.0}, {0.8, 0.7}, {0.4, 2.1}, {0.08, 3.9}, {-0.6, 5.0}};
constexpr int NumIncidents = int(std::size(Incidents));

// One kernel preset with its queries (one per incident direction) and fixed random inputs.
struct Fixture {
    std::string name;  // "kernel/pN"
    std::shared_ptr<Material> material;
    SampledWavelengths wl = TestWavelengths(Lambda);
    ContractPlate plate;
    SurfaceInteraction si[NumIncidents];
    SpectralGenRay gr[NumIncidents];
    ScatterQuery q[NumIncidents];
    std::vector<double> u;  // 3 per call: u0, u1, u2
    std::vector<Vec3> wo;   // one per call: uniform on the sphere

    Fixture(std::string n, std::shared_ptr<Material> m) : name(std::move(n)), material(std::move(m)) {
        const bool footprint = material->IsFootprintAware();
        for (int d = 0; d < NumIncidents; ++d) {
            q[d].wi = DirectionFromCosTheta(Incidents[d][0], Incidents[d][1]);
            q[d].wl = &wl;
            q[d].etaOutside = 1;
            q[d].rayOptics = false;
            q[d].tex.uv = Vec2(0.13 + 0.19 * d, 0.61 - 0.07 * d);
            if (footprint) {
                si[d].p = ContractHit;
                AttachFootprint(q[d], gr[d], si[d], plate);
            }
        }
        TestRng rng(7);
        for (int i = 0; i < 3 * Batch; ++i) u.push_back(rng.Uniform());
        for (int i = 0; i < Batch; ++i) {
            const double a = rng.Uniform(), b = rng.Uniform();
            wo.push_back(UniformSphere(a, b));
        }
    }
};

void BenchSample(benchmark::State &state, const Fixture *f) {
    double sink = 0;
    ScratchBuffer scratch;
    for (auto _ : state)
        for (int i = 0; i < Batch; ++i) {
            const PreparedKernel &k = f->material->Prepare(f->q[i % NumIncidents], scratch);
            const auto s = k.Sample(f->u[3 * i], Vec2(f->u[3 * i + 1], f->u[3 * i + 2]));
            if (s) sink += s->weight[0];
            scratch.Reset();
        }
    benchmark::DoNotOptimize(sink);
    state.SetItemsProcessed(state.iterations() * Batch);
}

void BenchEval(benchmark::State &state, const Fixture *f) {
    double sink = 0;
    ScratchBuffer scratch;
    for (auto _ : state)
        for (int i = 0; i < Batch; ++i) {
            sink += f->material->Prepare(f->q[i % NumIncidents], scratch).Eval(f->wo[i])[0];
            scratch.Reset();
        }
    benchmark::DoNotOptimize(sink);
    state.SetItemsProcessed(state.iterations() * Batch);
}

void BenchEvalPrepared(benchmark::State &state, const Fixture *f) {
    double sink = 0;
    ScratchBuffer scratch;
    const PreparedKernel *k[NumIncidents];
    for (int d = 0; d < NumIncidents; ++d) k[d] = &f->material->Prepare(f->q[d], scratch);
    for (auto _ : state)
        for (int i = 0; i < Batch; ++i) sink += k[i % NumIncidents]->Eval(f->wo[i])[0];
    benchmark::DoNotOptimize(sink);
    state.SetItemsProcessed(state.iterations() * Batch);
}

// Google Benchmark's console table, then a Markdown table: ns per call of Sample and Eval per preset.
class TableReporter : public benchmark::ConsoleReporter {
  public:
    TableReporter() : ConsoleReporter(isatty(1) ? OO_ColorTabular : OO_Tabular) {}
    void ReportRuns(const std::vector<Run> &runs) override {
        ConsoleReporter::ReportRuns(runs);
        for (const Run &r : runs) {
            if (r.error_occurred || r.run_type != Run::RT_Iteration) continue;
            const std::string name = r.benchmark_name();  // "Sample/kernel/pN"
            const std::size_t slash = name.find('/');
            const double nsPerCall = r.GetAdjustedCPUTime() / Batch;  // the time unit is ns
            const std::string what = name.substr(0, slash);
            (what == "Sample" ? sample_ : what == "Eval" ? eval_ : prepared_)[name.substr(slash + 1)] = nsPerCall;
            if (std::find(order_.begin(), order_.end(), name.substr(slash + 1)) == order_.end())
                order_.push_back(name.substr(slash + 1));
        }
    }
    void Finalize() override {
        ConsoleReporter::Finalize();
        std::printf("\n| kernel / preset | Sample [ns] | Eval [ns] | Eval prepared [ns] |\n|---|---:|---:|---:|\n");
        for (const std::string &k : order_)
            std::printf("| %s | %.0f | %.0f | %.0f |\n", k.c_str(), sample_[k], eval_[k], prepared_[k]);
    }

  private:
    std::vector<std::string> order_;
    std::map<std::string, double> sample_, eval_, prepared_;
};

}  // namespace
}  // namespace phasor::test

int main(int argc, char **argv) {
    using namespace phasor;
    using namespace phasor::test;
    benchmark::Initialize(&argc, argv);
    std::vector<std::unique_ptr<Fixture>> fixtures;
    for (const auto &e : Registry<Material>::Entries()) {
        const std::vector<ParamDict> presets = e.presets();
        for (std::size_t p = 0; p < presets.size(); ++p) {
            Diagnostics diag;
            auto m = BuildMaterial(e.name, presets[p], diag);
            const std::string name = std::string(e.name) + "/p" + std::to_string(p);
            if (!m) {
                std::fprintf(stderr, "kernel_bench: preset %s does not build\n", name.c_str());
                return 1;
            }
            fixtures.push_back(std::make_unique<Fixture>(name, m));
            const Fixture *f = fixtures.back().get();
            benchmark::RegisterBenchmark(("Sample/" + name).c_str(), BenchSample, f)->Unit(benchmark::kNanosecond);
            benchmark::RegisterBenchmark(("Eval/" + name).c_str(), BenchEval, f)->Unit(benchmark::kNanosecond);
            benchmark::RegisterBenchmark(("EvalPrepared/" + name).c_str(), BenchEvalPrepared, f)
                ->Unit(benchmark::kNanosecond);
        }
    }
    TableReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::Shutdown();
    return 0;
}
