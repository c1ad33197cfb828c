// SPDX-License-Identifier: Apache-2.0
// Validation tests: render a scene file with -D overrides and an integrator, read back one row.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <sstream>
#include <string>
#include <vector>

#include "core/render/scene.h"
#include "parser/parser.h"
#include "support/replicas.h"
#include "support/scene_builder.h"

namespace phasor::test {

inline std::string ValidationScene(const std::string &name) {
    return std::string(PHASOR_SOURCE_DIR) + "/scenes/validation/" + name;
}

struct Row {
    std::vector<double> x, v;  // pixel centres [m], intensity (flux / E)
    double seconds = 0;
    double Peak() const { return *std::max_element(v.begin(), v.end()); }
};

/// Builds a validation scene with -D overrides and the given integrator (nullptr on errors,
/// which fail the calling test).
inline std::unique_ptr<Scene> BuildValidation(const std::string &scene, const DefineList &defines,
                                              const std::string &integrator) {
    Diagnostics diag;
    auto desc = ParseSceneFile(scene, defines, diag);
    std::ostringstream os;
    diag.Print(os);
    EXPECT_TRUE(desc) << os.str();
    if (!desc) return nullptr;
    auto built = Scene::Build(*desc, diag, integrator);
    diag.Print(os);
    EXPECT_TRUE(built) << os.str();
    return built;
}

/// Builds a scene given as text (named `name` in diagnostics) with -D overrides and the given
/// integrator ("" : the scene's own); nullptr on errors, which fail the calling test.
inline std::unique_ptr<Scene> BuildSceneText(const std::string &text, const std::string &integrator = "",
                                             const DefineList &defines = {}, const std::string &name = "test.wscene") {
    Diagnostics diag;
    auto desc = ParseSceneString(text, name, defines, diag);
    std::unique_ptr<Scene> scene;
    if (desc) scene = Scene::Build(*desc, diag, integrator);
    std::ostringstream os;
    diag.Print(os);
    EXPECT_TRUE(scene) << os.str();
    return scene;
}

/// Renders the scene with -D overrides and the given integrator; the middle row's intensity.
inline Row RenderRow(const std::string &scene, const DefineList &defines, const std::string &integrator, int spp = 0) {
    auto built = BuildValidation(scene, defines, integrator);
    if (!built) return {};
    const auto start = std::chrono::steady_clock::now();
    const Image img = test::RenderImage(*built, spp > 0 ? spp : built->Settings().options.spp);
    Row r;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const SensorPlaneGeometry *sp = built->GetDetector().SensorPlane();
    EXPECT_TRUE(sp);
    const int c = img.ChannelIndex("intensity"), y = img.height / 2;
    for (int i = 0; i < img.width; ++i) {
        r.x.push_back(sp ? sp->PixelCenter(i, y).x : i);
        r.v.push_back(img.At(i, y, c));
    }
    return r;
}

/// Each pixel of the middle row from `replicas` independent Sobol' scrambles of `spp` samples
/// (seeds seed0, seed0 + 1, …): the mean and its honest error (support/replicas.h).
inline std::vector<ReplicaEstimate> RenderRowReplicas(const std::string &scene, const DefineList &defines,
                                                      const std::string &integrator, int spp, int replicas,
                                                      uint64_t seed0) {
    auto built = BuildValidation(scene, defines, integrator);
    if (!built) return {};
    const auto images = RenderReplicas(*built, spp, replicas, seed0);
    std::vector<ReplicaEstimate> row;
    const int y = images[0].height / 2;
    for (int i = 0; i < images[0].width; ++i) row.push_back(BlockOverReplicas(images, i, y, i + 1, y + 1));
    return row;
}

inline double MaxDiffOfPeak(const Row &a, const Row &ref) {
    EXPECT_EQ(a.v.size(), ref.v.size());
    double m = 0;
    for (std::size_t i = 0; i < std::min(a.v.size(), ref.v.size()); ++i) m = std::max(m, std::abs(a.v[i] - ref.v[i]));
    return m / ref.Peak();
}

}  // namespace phasor::test
