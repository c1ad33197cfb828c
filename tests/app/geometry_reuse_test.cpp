// SPDX-License-Identifier: Apache-2.0
// The geometry cache across scenes (core/geometry/geometry_cache.h), as a sweep or a Python
// session uses it: scenes that differ only in a Define that does not touch geometry subdivide and
// build the BVH once, and render bit for bit as fresh builds; a Define that changes the subdivision
// levels or a transform, or a cage file rewritten on disk, rebuilds and renders as a fresh build.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/geometry/geometry_cache.h"
#include "core/render/scene.h"
#include "parser/parser.h"
#include "support/scene_builder.h"
#include "support/temp_dir.h"

namespace phasor {
namespace {

// The cube [−1, 1]³ as an OBJ cage, stretched along x by `sx` (counter-clockwise from outside).
std::string CubeObj(double sx) {
    const int square[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    std::ostringstream os;
    for (int z : {-1, 1})
        for (const auto &xy : square) os << "v " << sx * xy[0] << " " << xy[1] << " " << z << "\n";
    os << "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";
    return os.str();
}

// A subdivided cage (its levels, scale and colour Defines), an analytic sphere and a rectangle lamp.
const char *SceneText = R"(wscene 2
Define levels = 2
Define size = 0.3
Define grey = 0.5
Material "diffuse" "paint" { reflectance = $grey }
Material "diffuse" "white" { reflectance = 0.8 }
Shape "subdivision" "blob" { file = "cage.obj"  levels = $levels  material = @paint  to_world = scale($size) }
Shape "sphere" "ball" { center = [0.6 0 0] m  radius = 0.2 m  material = @white }
Shape "rectangle" "panel" { to_world = [scale(0.5) lookat(eye = [0 2 1] m, target = [0 0 0] m, up = [0 0 1])] }
Light "area" "lamp" { shape = @panel  radiance = 1 W/m^2/sr }
Detector "perspective" "cam" { resolution = [24 16]  fov = 40 deg  to_world = lookat(eye = [0.5 1 3] m, target = [0.2 0 0] m, up = [0 1 0]) }
Integrator "ray" "ray" { max_depth = 3 }
Render { detector = @cam  integrator = @ray  spp = 4 }
)";

class GeometryReuseTest : public test::TempDirTest {
  protected:
    GeometryReuseTest() : TempDirTest("geometry_reuse") {}
    void SetUp() override {
        TempDirTest::SetUp();
        WriteCage(1);
        ClearGeometryCache();
    }
    void WriteCage(double sx) const { std::ofstream(Path("cage.obj"), std::ios::binary) << CubeObj(sx); }

    // The scene with these Defines, built (relative files from the test's directory).
    std::unique_ptr<Scene> Build(const DefineList &defines) const {
        Diagnostics diag;
        auto desc = ParseSceneString(SceneText, Path("scene.wscene"), defines, diag);
        std::unique_ptr<Scene> scene = desc ? Scene::Build(*desc, diag) : nullptr;
        std::ostringstream os;
        diag.Print(os);
        EXPECT_TRUE(scene) << os.str();
        return scene;
    }
    // Its image (empty if it did not build).
    Image Render(const DefineList &defines) const {
        auto scene = Build(defines);
        return scene ? test::RenderImage(*scene, 4) : Image{};
    }
    // Its image from a cache emptied first: what a process that renders it alone computes.
    Image RenderFresh(const DefineList &defines) const {
        ClearGeometryCache();
        return Render(defines);
    }
};

bool SameBits(const Image &a, const Image &b) {
    return a.width == b.width && a.height == b.height && a.channels == b.channels && !a.data.empty() &&
           std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)) == 0;
}

// Three renders of a colour sweep, one scene after the other (as `phasor render --sweep` loads
// them): the cage is subdivided once, the panel triangulated once and the BVH built once; each
// image equals the one a fresh process would render.
TEST_F(GeometryReuseTest, ColourSweepBuildsGeometryOnce) {
    std::vector<Image> swept;
    for (const char *grey : {"0.2", "0.5", "0.9"}) swept.push_back(Render({{"grey", grey}}));
    const GeometryCacheStats s = GetGeometryCacheStats();
    EXPECT_EQ(s.meshBuilds, 2);  // the subdivision surface and the rectangle
    EXPECT_EQ(s.meshReuses, 4);
    EXPECT_EQ(s.bvhBuilds, 1);
    EXPECT_EQ(s.bvhReuses, 2);
    EXPECT_FALSE(SameBits(swept[0], swept[2]));  // the Define does change the image
    int i = 0;
    for (const char *grey : {"0.2", "0.5", "0.9"}) EXPECT_TRUE(SameBits(swept[std::size_t(i++)], RenderFresh({{"grey", grey}}))) << grey;
}

// Scenes alive at once (Scene.render_many loads every variant first) share one mesh and one BVH.
TEST_F(GeometryReuseTest, ScenesAliveTogetherShareGeometry) {
    auto a = Build({{"grey", "0.2"}});
    auto b = Build({{"grey", "0.7"}});
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->Shapes()[0]->Mesh(), b->Shapes()[0]->Mesh());
    EXPECT_NE(a->Shapes()[0].get(), b->Shapes()[0].get());  // each scene its own shape (material)
    EXPECT_EQ(GetGeometryCacheStats().bvhBuilds, 1);
    a.reset();  // b's BVH holds no pointer into a
    const Image img = test::RenderImage(*b, 4);
    EXPECT_TRUE(SameBits(img, RenderFresh({{"grey", "0.7"}})));
}

// A Define that changes the subdivision levels or the transform rebuilds the mesh and the BVH, and
// the image is the fresh build's, not the previous geometry's.
TEST_F(GeometryReuseTest, GeometryDefinesRebuild) {
    for (const DefineList &d : {DefineList{{"levels", "3"}}, DefineList{{"size", "0.35"}}}) {
        const Image base = Render({});  // the base geometry is in the cache
        const GeometryCacheStats before = GetGeometryCacheStats();
        const Image changed = Render(d);
        const GeometryCacheStats after = GetGeometryCacheStats();
        EXPECT_EQ(after.meshBuilds, before.meshBuilds + 1) << d[0].first;  // the blob (the panel is reused)
        EXPECT_EQ(after.bvhBuilds, before.bvhBuilds + 1) << d[0].first;
        EXPECT_FALSE(SameBits(changed, base)) << d[0].first;
        EXPECT_TRUE(SameBits(changed, RenderFresh(d))) << d[0].first;
    }
}

// The cage file rewritten with other content between two builds (same path, same Defines): the
// second build reads it again.
TEST_F(GeometryReuseTest, RewrittenCageFileRebuilds) {
    const Image before = Render({});
    WriteCage(1.5);
    const GeometryCacheStats s0 = GetGeometryCacheStats();
    const Image after = Render({});
    const GeometryCacheStats s1 = GetGeometryCacheStats();
    EXPECT_EQ(s1.meshBuilds, s0.meshBuilds + 1);
    EXPECT_EQ(s1.bvhBuilds, s0.bvhBuilds + 1);
    EXPECT_FALSE(SameBits(before, after));
    EXPECT_TRUE(SameBits(after, RenderFresh({})));
}

// An unreadable cage is the loader's error at the parameter; the failure is not cached: once the
// file is back, the scene builds.
TEST_F(GeometryReuseTest, MissingCageIsAnErrorNotACachedMesh) {
    std::filesystem::remove(Path("cage.obj"));
    Diagnostics diag;
    auto desc = ParseSceneString(SceneText, Path("scene.wscene"), DefineList{}, diag);
    ASSERT_TRUE(desc);
    EXPECT_FALSE(Scene::Build(*desc, diag));
    std::ostringstream os;
    diag.Print(os);
    EXPECT_NE(os.str().find("cage.obj"), std::string::npos) << os.str();
    WriteCage(1);
    EXPECT_TRUE(Build({}));
}

}  // namespace
}  // namespace phasor
