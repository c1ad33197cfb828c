// SPDX-License-Identifier: Apache-2.0
// `grt` vs `ray` on the same non-wave scene at equal spp, in one run (issue #4 acceptance; the only
// peer, wave_tracer, reports wave tracing 5–20× slower than ray tracing). The scene is a Cornell box
// with diffuse walls, a smooth dielectric sphere, a smooth conductor sphere and an area light, so
// `grt` pays for everything a generalized ray adds on non-wave content: per-wavelength footprint
// propagation, the GR queries of the kernels and its measurement bookkeeping. Each integrator is
// timed `--repeat` times, interleaved; the table reports the fastest run of each and the ratio.
//
//   bench_grt [--res N] [--spp S] [--threads T] [--repeat R]
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>

#include "support/scene_builder.h"

using namespace phasor;
using namespace phasor::test;

namespace {

SceneDesc BenchScene(int res) {
    SceneBuilder b;
    auto rot = [](double deg, Vec3 axis) {
        return Call("rotate", {Value::Number(Radians(deg), Dim::Angle()), Vec(axis.x, axis.y, axis.z)});
    };
    b.Add("Material", "diffuse", "white").Set("reflectance", Num(0.73));
    b.Add("Material", "diffuse", "red").Set("reflectance", Num(0.4));
    b.Add("Material", "diffuse", "green").Set("reflectance", Num(0.3));
    b.Add("Material", "dielectric", "glass").Set("ior", Num(1.5));
    b.Add("Material", "conductor", "metal").Set("ior", Value::ComplexNumber({0.2, 3.4}));
    b.Add("Shape", "rectangle", "floor").Set("material", Ref("white")).Set("to_world", rot(-90, {1, 0, 0}));
    b.Add("Shape", "rectangle", "ceiling")
        .Set("material", Ref("white"))
        .Set("to_world", Value::List({rot(90, {1, 0, 0}), Call("translate", {LenVec(0, 2, 0)})}));
    b.Add("Shape", "rectangle", "back")
        .Set("material", Ref("white"))
        .Set("to_world", Call("translate", {LenVec(0, 1, -1)}));
    b.Add("Shape", "rectangle", "left")
        .Set("material", Ref("red"))
        .Set("to_world", Value::List({rot(90, {0, 1, 0}), Call("translate", {LenVec(-1, 1, 0)})}));
    b.Add("Shape", "rectangle", "right")
        .Set("material", Ref("green"))
        .Set("to_world", Value::List({rot(-90, {0, 1, 0}), Call("translate", {LenVec(1, 1, 0)})}));
    b.Add("Shape", "sphere", "glass_ball")
        .Set("center", LenVec(0.35, 0.4, 0.1))
        .Set("radius", Len(0.4))
        .Set("material", Ref("glass"));
    b.Add("Shape", "sphere", "metal_ball")
        .Set("center", LenVec(-0.45, 0.35, -0.4))
        .Set("radius", Len(0.35))
        .Set("material", Ref("metal"));
    b.Add("Shape", "rectangle", "panel")
        .Set("to_world", Value::List({Call("scale", {Num(0.4)}), rot(90, {1, 0, 0}),
                                      Call("translate", {LenVec(0, 1.99, 0)})}));
    b.Add("Light", "area")
        .Set("shape", Ref("panel"))
        .Set("radiance", Value::Number(8, Dim::Radiance()))
        .Set("spectrum", Call("blackbody", {Value::Number(4500, Dim::Temperature())}));
    b.Add("Detector", "perspective", "cam")
        .Set("resolution", Value::List({Int(res), Int(res)}))
        .Set("fov", Value::Number(Radians(39), Dim::Angle()))
        .Set("to_world", Call("lookat", {LenVec(0, 1, 3.4), LenVec(0, 1, 0), Vec(0, 1, 0)}));
    b.Add("Integrator", "ray", "ray").Set("max_depth", Int(8));
    b.Add("Integrator", "grt", "grt").Set("max_depth", Int(8));
    b.Render().Set("integrator", Ref("ray"));
    return b.Desc();
}

}  // namespace

int main(int argc, char **argv) {
    int res = 256, spp = 16, threads = 0, repeat = 3;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--res"))
            res = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--spp"))
            spp = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--threads"))
            threads = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--repeat"))
            repeat = std::atoi(argv[i + 1]);
    }
    Diagnostics diag;
    auto rayScene = Scene::Build(BenchScene(res), diag, "ray");
    auto grtScene = Scene::Build(BenchScene(res), diag, "grt");
    if (!rayScene || !grtScene) {
        diag.Print(std::cerr);
        return 1;
    }
    auto render = [&](const Scene &scene) {
        Film film(res, res, scene.GetDetector().Response());
        RenderOptions opt;
        opt.spp = spp;
        opt.threads = threads;
        opt.seed = 1;
        RenderStats s = scene.GetIntegrator().Render(scene, film, opt);
        Image img = film.Resolve();
        double mean = 0;
        const int ci = img.ChannelIndex("intensity");
        for (int y = 0; y < res; ++y)
            for (int x = 0; x < res; ++x) mean += img.At(x, y, ci);
        return std::make_pair(s, mean / (double(res) * res));
    };
    double tRay = 1e300, tGrt = 1e300, meanRay = 0, meanGrt = 0;
    long long raysRay = 0, raysGrt = 0;
    for (int r = 0; r < repeat; ++r) {
        auto [a, ma] = render(*rayScene);
        auto [g, mg] = render(*grtScene);
        tRay = std::min(tRay, a.seconds);
        tGrt = std::min(tGrt, g.seconds);
        raysRay = a.rays;
        raysGrt = g.rays;
        meanRay = ma;
        meanGrt = mg;
    }
    std::printf("## grt vs ray benchmark\n\n");
    std::printf(
        "scene: Cornell box (diffuse walls, smooth dielectric and conductor spheres, area light), %dx%d, %d "
        "spp, "
        "max_depth 8, %s threads; fastest of %d runs each\n\n",
        res, res, spp, threads > 0 ? std::to_string(threads).c_str() : "all", repeat);
    std::printf("| integrator | time | rays | mean intensity |\n|---|---|---|---|\n");
    std::printf("| `ray` | %.3f s | %lld | %.5f |\n", tRay, raysRay, meanRay);
    std::printf("| `grt` | %.3f s | %lld | %.5f |\n", tGrt, raysGrt, meanGrt);
    std::printf("\n**grt / ray time: %.2fx** (goal ≤ 1.3x)\n", tGrt / tRay);
    return 0;
}
