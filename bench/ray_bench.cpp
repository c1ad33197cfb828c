// SPDX-License-Identifier: Apache-2.0
// Whole-render benchmark of the classical `ray` integrator on a ≥ 1M-triangle scene, with — in
// the same run — Embree's raw rtcIntersect1 rate on the very rays the integrator traced, and
// 1- vs 2-thread scaling. The raw replay and the 1-thread render alternate --repeat times (so a
// change in the machine's load falls on both); the ratio is that of the two medians. Prints a
// Markdown table (copied into the README). bench/ray_cost.sh gives the same comparison in
// instructions (callgrind), independent of the load.
//
//   bench_ray [--levels L] [--res N] [--spp S] [--repeat R]
//   bench_ray --instructions [--levels L] [--res N]   (for bench/ray_cost.sh: one replay, one render)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>
#include <iostream>
#include <string>
#include <thread>

#include "support/scene_builder.h"

using namespace phasor;
using namespace phasor::test;

namespace {

double Seconds(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

SceneDesc BenchScene(int levels, int res) {
    SceneBuilder b;
    b.Add("Material", "diffuse", "white").Set("reflectance", Num(0.7));
    b.Add("Material", "conductor", "metal").Set("ior", Value::ComplexNumber({0.2, 3.5}));
    b.Add("Shape", "rectangle", "floor").Set("material", Ref("white"))
        .Set("to_world", Value::List({Call("scale", {Num(4)}), Call("rotate", {Value::Number(-Pi / 2, Dim::Angle()), Vec(1, 0, 0)})}));
    b.Add("Shape", "subdivision", "jack").Set("file", Str(std::string(PHASOR_SOURCE_DIR) + "/scenes/assets/jack_cage.obj"))
        .Set("levels", Int(levels)).Set("material", Ref("white"))
        .Set("to_world", Value::List({Call("scale", {Num(0.5)}), Call("translate", {LenVec(0, 0.9, 0)})}));
    b.Add("Shape", "sphere", "ball").Set("radius", Len(0.4)).Set("center", LenVec(1.4, 0.4, 0.3)).Set("material", Ref("metal"));
    b.Add("Shape", "rectangle", "panel").Set("to_world", Value::List({Call("rotate", {Value::Number(Pi / 2, Dim::Angle()), Vec(1, 0, 0)}), Call("translate", {LenVec(0, 4, 0)})}));
    b.Add("Light", "area").Set("shape", Ref("panel")).Set("radiance", Value::Number(5, Dim::Radiance()));
    b.Add("Detector", "perspective", "cam").Set("resolution", Value::List({Int(res), Int(res)}))
        .Set("to_world", Call("lookat", {LenVec(0, 1.5, 4.5), LenVec(0, 0.8, 0), Vec(0, 1, 0)}));
    b.Add("Integrator", "ray").Set("max_depth", Int(5));
    return b.Desc();
}

// The two measured parts, as functions of their own that callgrind can toggle its counting on
// (bench/ray_cost.sh): the raw replay, and a 1-thread render of the same pass's samples.
__attribute__((noinline)) std::size_t CountedReplay(const Scene &scene, const std::vector<Ray> &rays) {
    return scene.GetAccel().RawIntersectCount(rays);
}
__attribute__((noinline)) RenderStats CountedRender(const std::function<RenderStats()> &render) { return render(); }

}  // namespace

int main(int argc, char **argv) {
    int levels = 8, res = 256, spp = 16, repeat = 5;
    bool instructions = false;
    for (int i = 1; i < argc; ++i) {
        const bool value = i + 1 < argc;
        if (!std::strcmp(argv[i], "--instructions")) instructions = true;
        else if (value && !std::strcmp(argv[i], "--levels")) levels = std::atoi(argv[++i]);
        else if (value && !std::strcmp(argv[i], "--res")) res = std::atoi(argv[++i]);
        else if (value && !std::strcmp(argv[i], "--spp")) spp = std::atoi(argv[++i]);
        else if (value && !std::strcmp(argv[i], "--repeat")) repeat = std::max(1, std::atoi(argv[++i]));
        else {
            std::fprintf(stderr, "usage: bench_ray [--levels L] [--res N] [--spp S] [--repeat R] [--instructions]\n");
            return 2;
        }
    }
    auto t0 = std::chrono::steady_clock::now();
    Diagnostics diag;
    auto scene = Scene::Build(BenchScene(levels, res), diag);
    if (!scene) {
        diag.Print(std::cerr);
        return 1;
    }
    double buildSeconds = Seconds(t0);
    std::size_t triangles = 0;
    for (const Shape *s : scene->GetAccel().Shapes())
        if (s->Mesh()) triangles += s->Mesh()->TriangleCount();

    auto render = [&](int threads, int samples, uint64_t seed) {
        Film film(res, res, scene->GetDetector().Response());
        RenderOptions opt;
        opt.spp = samples;
        opt.threads = threads;
        opt.seed = seed;
        return scene->GetIntegrator().Render(*scene, film, opt);
    };

    // The rays of one single-threaded 4-spp pass, recorded, then replayed through bare Embree.
    std::vector<Ray> rays;
    rays.reserve(std::size_t(res) * res * 24);
    scene->RecordRays(&rays);
    render(1, 4, 99);
    scene->RecordRays(nullptr);
    if (instructions) {
        // The same pass again (same seed: the same paths), not recorded, and the replay: what
        // each costs per ray is the instruction count callgrind gives each function, divided by
        // the rays printed here.
        const std::size_t rawHits = CountedReplay(*scene, rays);
        const RenderStats counted = CountedRender([&] { return render(1, 4, 99); });
        std::printf("replayed_rays %zu\nreplayed_hits %zu\nrendered_rays %lld\n", rays.size(), rawHits, counted.rays);
        return 0;
    }
    // Alternating: raw replay, 1-thread render; the medians of each.
    std::vector<double> rawRates, rates1, seconds1;
    std::size_t hits = 0;
    for (int k = 0; k < repeat; ++k) {
        auto tr = std::chrono::steady_clock::now();
        hits = scene->GetAccel().RawIntersectCount(rays);
        rawRates.push_back(rays.size() / Seconds(tr));
        RenderStats one = render(1, spp, 1);
        rates1.push_back(one.rays / one.seconds);
        seconds1.push_back(one.seconds);
    }
    auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        const std::size_t n = v.size();
        return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    };
    auto list = [](const std::vector<double> &v) {
        std::string out;
        char buf[32];
        for (double r : v) {
            std::snprintf(buf, sizeof buf, "%s%.3f", out.empty() ? "" : ", ", r * 1e-6);
            out += buf;
        }
        return out;
    };
    const double rawRate = median(rawRates), rate1 = median(rates1);
    RenderStats two = render(2, spp, 1);
    const double rate2 = two.rays / two.seconds;

    std::printf("## ray integrator benchmark\n\n");
    std::printf("scene: %zu triangles (jack cage, Catmull-Clark level %d) + analytic sphere, %dx%d, %d spp, max_depth 5; build %.2f s\n\n",
                triangles, levels, res, res, spp, buildSeconds);
    std::printf("| measurement | value |\n|---|---|\n");
    std::printf("| rays recorded from one 4-spp pass | %zu (%zu hits) |\n", rays.size(), hits);
    std::printf("| Embree raw rtcIntersect1, 1 thread, median of %d | %.3f Mrays/s (%s) |\n", repeat, rawRate * 1e-6,
                list(rawRates).c_str());
    std::printf("| `ray` integrator, 1 thread, median of %d | %.3f Mrays/s (%s; median %.2f s a render) |\n",
                repeat, rate1 * 1e-6, list(rates1).c_str(), median(seconds1));
    std::printf("| `ray` integrator, 2 threads | %.3f Mrays/s (%.2f s) |\n", rate2 * 1e-6, two.seconds);
    std::printf("| integrator / raw Embree (1 thread, medians) | %.1f %% |\n", 100 * rate1 / rawRate);
    std::printf("| 2-thread speed-up | %.2fx |\n", rate2 / rate1);
    return 0;
}
