// SPDX-License-Identifier: Apache-2.0
// OBJ and glTF import: exact content of small known files, .gltf/.glb equivalence, the demo
// asset, and errors (naming the file) for corrupt, missing and malformed input.
#include "core/geometry/mesh_io.h"

#include <gtest/gtest.h>

#include "core/diagnostics.h"
#include "geometry_test_util.h"

namespace phasor {
namespace {

using test::AssetPath;
using test::WriteScratch;

/// Expects `f` to throw phasor::Error whose message contains every string in `parts`.
template <typename F>
void ExpectError(F f, const std::vector<std::string> &parts) {
    try {
        f();
        ADD_FAILURE() << "no phasor::Error thrown";
    } catch (const Error &e) {
        for (const auto &p : parts) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
    }
}

// ---- OBJ ------------------------------------------------------------------------------------

TEST(Obj, LoadsPolygonsAttributesAndNegativeIndices) {
    std::string path = WriteScratch("good.obj",
                                    "# a quad and a triangle\r\n"
                                    "mtllib none.mtl\n"
                                    "v 0 0 0\nv 1 0 0\r\nv 1 1 0 1.0\nv 0 1 0\n"
                                    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                    "vn 0 0 2\n"
                                    "o thing\ng grp\nusemtl foo\ns off\n"
                                    "f 1/1/1 2/2/1 3/3/1 4/4/1\n"
                                    "f -4//1 -2//1 \\\n -1//1\n");
    TriangleMesh m = LoadObj(path);
    ASSERT_EQ(m.TriangleCount(), 3u);
    ASSERT_EQ(m.positions.size(), 7u);  // 4 welded corners + 3 without texture coordinates
    EXPECT_EQ(m.positions[2], Vec3(1, 1, 0));
    ASSERT_EQ(m.normals.size(), 7u);
    EXPECT_EQ(m.normals[0], Vec3(0, 0, 1));  // normalised
    ASSERT_EQ(m.uvs.size(), 7u);
    EXPECT_EQ(m.uvs[2], Vec2(1, 1));
    EXPECT_EQ(m.uvs[5], Vec2(0, 0));  // missing vt
    EXPECT_EQ(std::vector<uint32_t>(m.indices.begin(), m.indices.begin() + 6),
              (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    EXPECT_EQ(m.positions[m.indices[7]], Vec3(1, 1, 0));  // −2 → vertex 3
    EXPECT_DOUBLE_EQ(m.Area(), 1.5);

    // A subdivision cage takes uvs at every corner or at none: the triangle lacks them.
    ExpectError([&] { LoadObjPolygons(path); }, {"good.obj:17:", "lacks texture coordinates"});
    PolyMesh pm = LoadObjPolygons(WriteScratch("cage.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                                           "f 1 2 3 4\nf -4 -2 -1\n"));
    EXPECT_EQ(pm.faceSizes, (std::vector<int>{4, 3}));
    EXPECT_EQ(pm.faceIndices, (std::vector<int>{0, 1, 2, 3, 0, 2, 3}));
    EXPECT_EQ(pm.positions.size(), 4u);
    EXPECT_TRUE(pm.uvs.empty());
    EXPECT_TRUE(pm.faceUvIndices.empty());
    // With uvs at every corner: kept face-varying (the triangle reuses vt 1 and 3 and adds 5).
    pm = LoadObjPolygons(WriteScratch("cage_uv.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                                     "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n"
                                                     "f 1/1 2/2 3/3 4/4\nf 1/1 3/3 4/5\n"));
    EXPECT_EQ(pm.faceUvIndices, (std::vector<int>{0, 1, 2, 3, 0, 2, 4}));
    ASSERT_EQ(pm.uvs.size(), 5u);
    EXPECT_EQ(pm.uvs[4], Vec2(0.5, 0.5));
}

TEST(Obj, NormalsDroppedUnlessEveryCornerHasOne) {
    TriangleMesh m =
        LoadObj(WriteScratch("partial.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2 3\n"));
    EXPECT_TRUE(m.normals.empty());
    EXPECT_TRUE(m.uvs.empty());
    EXPECT_EQ(m.positions.size(), 3u);
}

TEST(Obj, BadLinesNameFileAndLine) {
    const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    struct Case {
        std::string body, reason;
    };
    std::vector<Case> cases = {
        {"v 1 2\n", "needs 3 coordinates"}, {"v 1 2 abc\n", "expected a number"},
        {"v 1 2 nan\n", "not finite"},      {"vn 1 0\n", "needs 3 coordinates"},
        {"f 1 2\n", "at least 3 vertices"}, {"f 1 2 x\n", "expected an integer"},
        {"f 1 2 9\n", "out of range"},      {"f 1 2 0\n", "index 0 is invalid"},
        {"f 1/1 2 3\n", "out of range"},  // no vt defined
        {"f 1// 2 3\n", "malformed"},       {"f -4 2 3\n", "out of range"},
    };
    for (std::size_t i = 0; i < cases.size(); ++i) {
        std::string name = "bad" + std::to_string(i) + ".obj";
        std::string path = WriteScratch(name, head + cases[i].body);
        ExpectError([&] { LoadObj(path); }, {name + ":4:", cases[i].reason});
    }
    ExpectError([&] { LoadObjPolygons(WriteScratch("dup.obj", head + "f 1 2 1\n")); },
                {"dup.obj:4:", "twice"});
    ExpectError([&] { LoadObj(WriteScratch("nofaces.obj", head)); }, {"nofaces.obj", "no faces"});
    ExpectError([&] { LoadObj("/nonexistent/missing_mesh.obj"); }, {"missing_mesh.obj", "cannot open"});
}

// ---- glTF -----------------------------------------------------------------------------------

/// What test_node_transform.gltf must load as (derivation in tools/make_assets.cpp): node
/// "child" under "parent" (T(1,2,3)·R_z(180°)·S(2) · T(0,0,1)·R_x(90°)), node "plain"
/// (identity), node "scaled" (matrix diag(1,2,3) + T(−1,0,0)), node "mirrored" (scale −1 in x:
/// the strip's winding is reversed); node "orphan" is not in the scene.
void ExpectTestAsset(const TriangleMesh &m) {
    std::vector<Vec3> pos = {{1, 2, 5},  {-1, 2, 5}, {-1, 2, 7}, {1, 2, 7},    // child
                             {0, 0, 0},  {1, 0, 0},  {1, 1, 0},  {0, 1, 0},    // plain
                             {-1, 0, 0}, {0, 0, 0},  {0, 2, 0},  {-1, 2, 0},   // scaled
                             {0, 0, 0},  {-1, 0, 0}, {0, 1, 0},  {-1, 1, 0}};  // mirrored strip
    ASSERT_EQ(m.positions.size(), pos.size());
    for (std::size_t i = 0; i < pos.size(); ++i)
        EXPECT_NEAR(Length(m.positions[i] - pos[i]), 0, 1e-15)
            << "vertex " << i << ": " << ToString(m.positions[i]);
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2,  0, 2,  3,  4,  5,  6,  4,  6,  7,
                                                8, 9, 10, 8, 10, 11, 12, 14, 13, 13, 14, 15}));
    ASSERT_EQ(m.normals.size(), pos.size());
    // Normals by the inverse transpose: (0.6, 0, 0.8) under diag(1,2,3) → ∝ (0.6, 0, 0.8/3).
    Vec3 tilted = Normalize(Vec3(double(0.6f), 0, double(0.8f) / 3));
    for (std::size_t i = 0; i < pos.size(); ++i) {
        Vec3 expect = i < 4 ? Vec3(0, 1, 0) : (i >= 8 && i < 12 ? tilted : Vec3(0, 0, 1));
        EXPECT_NEAR(Length(m.normals[i] - expect), 0, 1e-15)
            << "normal " << i << ": " << ToString(m.normals[i]);
    }
    // Every triangle is wound counter-clockwise about its vertex normals.
    for (std::size_t t = 0; t < m.TriangleCount(); ++t) {
        const Vec3 &a = m.positions[m.indices[3 * t]], &b = m.positions[m.indices[3 * t + 1]],
                   &c = m.positions[m.indices[3 * t + 2]];
        EXPECT_GT(Dot(Cross(b - a, c - a), m.normals[m.indices[3 * t]]), 0) << "triangle " << t;
    }
    ASSERT_EQ(m.uvs.size(), pos.size());
    EXPECT_EQ(m.uvs[2], Vec2(1, 1));
    EXPECT_EQ(m.uvs[6], Vec2(0, 0));
}

TEST(Gltf, TestAssetLoadsExactly) {
    std::string skipped;
    TriangleMesh m = LoadGltf(AssetPath("test_node_transform.gltf"), &skipped);
    ExpectTestAsset(m);
    EXPECT_NE(skipped.find("POINTS"), std::string::npos) << skipped;
}

TEST(Gltf, BinaryAndTextGiveTheSameMesh) {
    TriangleMesh a = LoadGltf(AssetPath("test_node_transform.gltf"));
    TriangleMesh b = LoadGltf(AssetPath("test_node_transform.glb"));
    ExpectTestAsset(b);
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.normals, b.normals);
    EXPECT_EQ(a.uvs, b.uvs);
    EXPECT_EQ(a.indices, b.indices);
}

TEST(Gltf, DemoTorusKnot) {
    TriangleMesh m = LoadGltf(AssetPath("torus_knot.glb"));
    EXPECT_EQ(m.TriangleCount(), 4608u);
    EXPECT_EQ(m.positions.size(), 193u * 13u);
    Bounds3 b = m.Bounds();
    // The knot spans about ±3.45 local units × 0.15 (root scale).
    EXPECT_GT(b.hi.x, 0.45);
    EXPECT_LT(b.hi.x, 0.56);
    for (const Vec3 &n : m.normals) ASSERT_NEAR(Length(n), 1, 1e-12);
    for (std::size_t t = 0; t < m.TriangleCount(); ++t) {
        const Vec3 &a = m.positions[m.indices[3 * t]], &p1 = m.positions[m.indices[3 * t + 1]],
                   &c = m.positions[m.indices[3 * t + 2]];
        ASSERT_GT(Dot(Cross(p1 - a, c - a), m.normals[m.indices[3 * t]]), 0) << "triangle " << t;
    }
}

TEST(Gltf, CorruptAndMissingFilesThrowWithFileName) {
    std::string text = test::ReadFile(AssetPath("test_node_transform.gltf"));
    std::string glb = test::ReadFile(AssetPath("test_node_transform.glb"));
    ASSERT_FALSE(text.empty());
    ASSERT_FALSE(glb.empty());
    auto replaced = [&](const std::string &from, const std::string &to) {
        std::string s = text;
        auto pos = s.find(from);
        EXPECT_NE(pos, std::string::npos) << from;
        if (pos != std::string::npos) s.replace(pos, from.size(), to);
        return s;
    };
    struct Case {
        std::string name, content, reason;
    };
    std::vector<Case> cases = {
        {"truncated.glb", glb.substr(0, 100), ""},
        {"garbage.gltf", "{ this is not json", ""},
        {"empty.gltf", "", ""},
        {"huge_count.gltf",
         replaced("\"count\":4,\"type\":\"VEC3\",\"min\"", "\"count\":4000,\"type\":\"VEC3\",\"min\""), ""},
        {"bad_indices.gltf", replaced("\"indices\":5", "\"indices\":0"), "indices"},
        {"no_buffer.gltf",
         "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":12,\"uri\":\"missing.bin\"}]}", ""},
        {"cycle.gltf", replaced("{\"name\":\"child\",", "{\"name\":\"child\",\"children\":[0],"), ""},
        {"bad_node.gltf", replaced("\"children\":[1]", "\"children\":[42]"), ""},
    };
    for (const auto &c : cases) {
        std::string path = WriteScratch(c.name, c.content);
        ExpectError([&] { LoadGltf(path); }, {c.name, c.reason});
    }
    ExpectError([&] { LoadGltf("/nonexistent/missing_object.glb"); }, {"missing_object.glb"});
}

}  // namespace
}  // namespace phasor
