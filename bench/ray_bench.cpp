// SPDX-License-Identifier: Apache-2.0
// Whole-render benchmark of the classical `ray` integrator on a ≥ 1M-triangle scene, with — in
// the same run — Embree's raw rtcIntersect1 rate on the very rays the integrator traced, and
// 1- vs 2-thread scaling. Prints a Markdown table (copied into the README).
//
//   bench_ray [--levels L] [--res N] [--spp S]
#include <chrono>
#include <cstdio>
#include <cstring>
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

}  // namespace

int main(int argc, char **argv) {
    int levels = 8, res = 256, spp = 16;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--levels")) levels = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--res")) res = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--spp")) spp = std::atoi(argv[i + 1]);
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
    RenderStats recorded = render(1, 4, 99);
    scene->RecordRays(nullptr);
    auto tr = std::chrono::steady_clock::now();
    std::size_t hits = scene->GetAccel().RawIntersectCount(rays);
    double rawSeconds = Seconds(tr);
    double rawRate = rays.size() / rawSeconds;
    // The integrator, same spp, 1 and 2 threads.
    RenderStats one = render(1, spp, 1);
    RenderStats two = render(2, spp, 1);
    double rate1 = one.rays / one.seconds, rate2 = two.rays / two.seconds;

    std::printf("## ray integrator benchmark\n\n");
    std::printf("scene: %zu triangles (jack cage, Catmull-Clark level %d) + analytic sphere, %dx%d, %d spp, max_depth 5; build %.2f s\n\n",
                triangles, levels, res, res, spp, buildSeconds);
    std::printf("| measurement | value |\n|---|---|\n");
    std::printf("| rays recorded from one 4-spp pass | %zu (%zu hits) |\n", rays.size(), hits);
    std::printf("| Embree raw rtcIntersect1, 1 thread | %.3f Mrays/s |\n", rawRate * 1e-6);
    std::printf("| `ray` integrator, 1 thread | %.3f Mrays/s (%.2f s) |\n", rate1 * 1e-6, one.seconds);
    std::printf("| `ray` integrator, 2 threads | %.3f Mrays/s (%.2f s) |\n", rate2 * 1e-6, two.seconds);
    std::printf("| integrator / raw Embree (1 thread) | %.1f %% |\n", 100 * rate1 / rawRate);
    std::printf("| 2-thread speed-up | %.2fx |\n", one.seconds / two.seconds);
    (void)recorded;
    return 0;
}
