// SPDX-License-Identifier: Apache-2.0
// The geometry cache (core/geometry/geometry_cache.h): one build per key across threads, entries
// kept by their users and the recent-use budget and freed after, failed builds not cached, file
// keys that follow the content; and one Embree BVH shared by Accels over different Shape objects
// of the same geometry, which answer queries with their own shapes.
#include "core/geometry/geometry_cache.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "core/diagnostics.h"
#include "core/geometry/accel.h"
#include "core/geometry/analytic.h"
#include "core/geometry/mesh_io.h"
#include "geometry_test_util.h"

namespace phasor {
namespace {

using IntCache = SharedCache<int>;

std::size_t OneByte(const int &) { return 1; }

TEST(SharedCache, ThreadsAskingForOneKeyBuildItOnce) {
    IntCache cache(100, OneByte);
    std::atomic<int> calls{0};
    std::vector<std::shared_ptr<const int>> got(8);
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < got.size(); ++t)
        threads.emplace_back([&, t] {
            got[t] = cache.GetOrBuild("k", [&] {
                ++calls;
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
                return std::make_shared<const int>(7);
            });
        });
    for (auto &th : threads) th.join();
    EXPECT_EQ(calls.load(), 1);
    EXPECT_EQ(cache.Builds(), 1);
    EXPECT_EQ(cache.Reuses(), 7);
    for (const auto &g : got) EXPECT_EQ(g.get(), got[0].get());
}

TEST(SharedCache, RecentEntriesOutliveTheirUsersUpToTheBudget) {
    IntCache cache(2, OneByte);  // two entries held strongly
    int built = 0;
    auto make = [&](int v) { return [&built, v] { ++built; return std::make_shared<const int>(v); }; };
    cache.GetOrBuild("a", make(1));
    cache.GetOrBuild("b", make(2));
    cache.GetOrBuild("c", make(3));  // drops a (the oldest)
    EXPECT_EQ(built, 3);
    EXPECT_EQ(*cache.GetOrBuild("c", make(0)), 3);
    EXPECT_EQ(*cache.GetOrBuild("b", make(0)), 2);
    EXPECT_EQ(built, 3);
    EXPECT_EQ(*cache.GetOrBuild("a", make(1)), 1);
    EXPECT_EQ(built, 4);
}

TEST(SharedCache, WithoutBudgetAnEntryLivesAsLongAsAUser) {
    IntCache cache(0, OneByte);
    int built = 0;
    auto make = [&] { ++built; return std::make_shared<const int>(5); };
    std::shared_ptr<const int> held = cache.GetOrBuild("k", make);
    std::weak_ptr<const int> watch = held;
    EXPECT_EQ(cache.GetOrBuild("k", make).get(), held.get());
    EXPECT_EQ(built, 1);
    held.reset();
    EXPECT_TRUE(watch.expired());  // the cache itself does not keep it
    cache.GetOrBuild("k", make);
    EXPECT_EQ(built, 2);
}

TEST(SharedCache, AFailedBuildIsNotCached) {
    IntCache cache(10, OneByte);
    EXPECT_THROW(cache.GetOrBuild("k", []() -> std::shared_ptr<const int> { throw Error("no"); }), Error);
    EXPECT_EQ(*cache.GetOrBuild("k", [] { return std::make_shared<const int>(1); }), 1);
    EXPECT_EQ(cache.Builds(), 1);
}

TEST(GeometryKey, FollowsTheFileContentAndEveryField) {
    const std::string path = test::WriteScratch("key.obj", "v 0 0 0\n");
    const std::string k1 = GeometryKey("obj").File("file", path).Str();
    EXPECT_EQ(GeometryKey("obj").File("file", path).Str(), k1);
    test::WriteScratch("key.obj", "v 0 0 1\n");  // same size, other content
    EXPECT_NE(GeometryKey("obj").File("file", path).Str(), k1);
    EXPECT_THROW(GeometryKey("obj").File("file", path + ".missing"), Error);

    EXPECT_NE(GeometryKey("s").Integer("levels", 2).Str(), GeometryKey("s").Integer("levels", 3).Str());
    EXPECT_NE(GeometryKey("s").Number("r", 0.1).Str(), GeometryKey("s").Number("r", std::nextafter(0.1, 1.0)).Str());
    EXPECT_NE(GeometryKey("s").Matrix("m", Transform::Scale(Vec3(1, 1, 1))).Str(),
              GeometryKey("s").Matrix("m", Transform::Scale(Vec3(1, 1, 2))).Str());
    EXPECT_NE(GeometryKey("s").Text("a", "b|c=1:d").Str(), GeometryKey("s").Text("a", "b").Text("c", "d").Str());
}

// The shapes of one "scene": a cached subdivided cube and a sphere, each scene its own objects.
struct Shapes {
    std::unique_ptr<MeshShape> cube;
    std::unique_ptr<AnalyticSphere> ball;
    Shapes() {
        cube = std::make_unique<MeshShape>(
            CachedMesh(GeometryKey("test cube").Integer("levels", 2), [] { return SubdivideCatmullClark(CubeCage(), 2); }));
        ball = std::make_unique<AnalyticSphere>(Vec3(3, 0, 0), 0.5);
    }
    std::vector<const Shape *> List() const { return {cube.get(), ball.get()}; }
};

TEST(SharedBvh, AccelsOverTheSameGeometryShareOneBvhAndQueryTheirOwnShapes) {
    ClearGeometryCache();
    auto first = std::make_unique<Shapes>();
    auto firstAccel = std::make_unique<Accel>(first->List());
    Shapes second;
    Accel accel(second.List());
    EXPECT_EQ(Accel::BvhCacheCounts().builds, 1);
    EXPECT_EQ(Accel::BvhCacheCounts().reuses, 1);
    EXPECT_EQ(first->cube->Mesh(), second.cube->Mesh());
    firstAccel.reset();
    first.reset();  // the shared BVH holds nothing of the first scene's shapes

    // A BVH of the same shapes built for this Accel alone answers the same.
    MeshShape ownCube(*second.cube->Mesh());
    AnalyticSphere ownBall(Vec3(3, 0, 0), 0.5);
    Accel fresh({&ownCube, &ownBall});
    EXPECT_EQ(Accel::BvhCacheCounts().builds, 1);  // a mesh without a key: not cached
    for (double y : {-0.9, -0.3, 0.0, 0.25, 0.8}) {
        for (const Vec3 &o : {Vec3(-5, y, 0.1), Vec3(3, y * 0.5, -5)}) {
            const Ray ray{o, Normalize(o.x < 0 ? Vec3(1, 0, 0) : Vec3(0, 0, 1))};
            auto a = accel.IntersectSurface(ray), b = fresh.IntersectSurface(ray);
            ASSERT_EQ(a.has_value(), b.has_value());
            if (!a) continue;
            EXPECT_EQ(a->t, b->t);
            EXPECT_EQ(a->shape, o.x < 0 ? static_cast<const Shape *>(second.cube.get()) : second.ball.get());
        }
    }
}

TEST(SharedBvh, MovedSphereBuildsAnotherBvh) {
    ClearGeometryCache();
    Shapes a;
    Accel first(a.List());
    Shapes b;
    b.ball = std::make_unique<AnalyticSphere>(Vec3(6, 0, 0.25), 0.5);
    Accel second(b.List());
    EXPECT_EQ(Accel::BvhCacheCounts().builds, 2);
    auto hit = second.Intersect(Ray{Vec3(6, 0, -5), Vec3(0, 0, 1)});
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 4.75, 1e-12);
}

}  // namespace
}  // namespace phasor
