// SPDX-License-Identifier: Apache-2.0
// How a render's work is shared (core/render/work.h): the film's accumulators move in and out of
// tiles without changing a bit; TilePasses hands out each pass's tiles once, skips tiles already
// done and copies a consistent film while tiles are out; a render stopped and continued on the same
// film, or continued to more samples, equals the uninterrupted render bit for bit; and a render whose
// tiles are shared with a helper (the protocol MPI ranks follow, here on a second thread) equals
// the one-process render bit for bit.
#include <atomic>
#include <chrono>
#include <cstring>
#include <thread>

#include <gtest/gtest.h>

#include "core/render/work.h"
#include "support/scene_builder.h"

namespace phasor {
namespace {

using namespace test;

// A lit sphere seen by a camera whose image (40×24) is not a whole number of tiles.
std::unique_ptr<Scene> SmallScene(const std::string &integrator) {
    SceneBuilder b;
    b.Add("Material", "diffuse", "white").Set("reflectance", Num(0.5));
    b.Add("Shape", "sphere", "ball").Set("radius", Len(1)).Set("material", Ref("white"));
    b.Add("Shape", "rectangle", "panel")
        .Set("to_world", Value::List({Call("rotate", {Value::Number(Radians(90), Dim::Angle()), Vec(1, 0, 0)}),
                                      Call("translate", {LenVec(0, 3, 0)})}));
    b.Add("Light", "area", "lamp").Set("shape", Ref("panel")).Set("radiance", Value::Number(2, Dim::Radiance()));
    b.Add("Detector", "perspective", "cam")
        .Set("to_world", Call("lookat", {LenVec(0, 0, 5), LenVec(0, 0, 0), Vec(0, 1, 0)}))
        .Set("resolution", Value::List({Int(40), Int(24)}));
    b.Add("Integrator", integrator, "it");
    std::string log;
    auto scene = b.Build(&log);
    EXPECT_TRUE(scene) << log;
    return scene;
}

// Every channel of two images, bit for bit.
void ExpectIdentical(const Image &a, const Image &b) {
    ASSERT_EQ(a.channels, b.channels);
    ASSERT_EQ(a.data.size(), b.data.size());
    for (std::size_t i = 0; i < a.data.size(); ++i)
        ASSERT_EQ(std::memcmp(&a.data[i], &b.data[i], sizeof(float)), 0)
            << "value " << i << " (channel " << a.channels[i % a.channels.size()] << "): " << a.data[i] << " vs "
            << b.data[i];
}

Image Render(const Scene &scene, Film &film, int spp, WorkShare *work = nullptr,
             const std::atomic<bool> *cancel = nullptr, std::function<void(int, int)> progress = {}) {
    RenderOptions opt;
    opt.spp = spp;
    opt.seed = 7;
    opt.threads = 2;
    opt.work = work;
    opt.cancel = cancel;
    opt.progress = std::move(progress);
    scene.GetIntegrator().Render(scene, film, opt);
    return film.Resolve();
}

TEST(Work, PixelStatesRoundTripExactly) {
    Film film(5, 3, SensorResponse(SensorResponse::Kind::Radiometric));
    film.EnableStokes();
    SampledWavelengths wl;
    wl.delta = true;
    wl.lambda = {600e-9, 0, 0, 0};
    wl.pdf = {0.3, 0, 0, 0};
    for (int i = 0; i < 7; ++i)
        film.AddStokesSample(i % 5, i % 3,
                             {SampledSpectrum(0.1 * i + 0.01), SampledSpectrum(0.03 * i), SampledSpectrum(-0.02),
                              SampledSpectrum(0.001 * i)},
                             wl);
    film.AddInvalidSample(4, 2);
    std::vector<Film::PixelState> states(15);
    film.GetPixels(0, 0, 5, 3, states.data());
    Film copy(5, 3, film.Response());
    copy.EnableStokes();
    copy.SetPixels(0, 0, 5, 3, states.data());
    ExpectIdentical(film.Resolve(), copy.Resolve());
    EXPECT_EQ(copy.InvalidSampleCount(), 1);
    // A sub-rectangle lands where it belongs.
    std::vector<Film::PixelState> part(4);
    film.GetPixels(1, 1, 3, 3, part.data());
    EXPECT_EQ(part[0].n, film.SampleCount(1, 1));
    EXPECT_EQ(part[3].n, film.SampleCount(2, 2));
}

TEST(Work, TilePassesHandOutEachTileOnceAndSkipFinishedOnes) {
    Film film(40, 24, SensorResponse(SensorResponse::Kind::Radiometric));
    TilePasses passes(film, nullptr);
    EXPECT_EQ(passes.Tiles(), 3 * 2);
    TileTask t;
    EXPECT_FALSE(passes.Next(t)) << "nothing before the first pass";
    passes.BeginPass(2);
    std::vector<TileTask> out;
    while (passes.Next(t)) out.push_back(t);
    ASSERT_EQ(out.size(), 6u);
    EXPECT_EQ(out[2].x0, 32);
    EXPECT_EQ(out[2].x1, 40);  // the last column of tiles is 8 wide
    EXPECT_EQ(out[5].y1, 24);
    // A tile out for rendering: the film (and a snapshot of it) is as it was handed out.
    for (Film::PixelState &p : out[0].pixels) p.n = 2, p.meanI = 1;
    out[0].rays = 5;
    std::vector<Film::PixelState> snap;
    long long rays = -1;
    passes.Snapshot(snap, &rays, nullptr);
    EXPECT_EQ(snap[0].n, 0);
    EXPECT_EQ(rays, 0);
    for (TileTask &task : out) passes.Done(task);
    passes.EndPass();
    passes.Snapshot(snap, &rays, nullptr);
    EXPECT_EQ(snap[0].n, 2);
    EXPECT_EQ(rays, 5);
    EXPECT_EQ(passes.TilesDone(), 6);
    // The next pass to 2 samples has only the tiles whose pixels lack them.
    passes.BeginPass(2);
    int left = 0;
    while (passes.Next(t)) {
        EXPECT_NE(t.tile, 0);
        ++left;
        passes.Done(t);
    }
    EXPECT_EQ(left, 5);
    // A cancelled render hands out nothing more.
    std::atomic<bool> cancel{true};
    TilePasses stopped(film, &cancel);
    stopped.BeginPass(4);
    EXPECT_FALSE(stopped.Next(t));
}

// Stops a render (sets `stop`) once `tiles` tiles are back, from a watching thread.
class StopAfterTiles final : public WorkShare {
  public:
    StopAfterTiles(long long tiles, std::atomic<bool> &stop) : tiles_(tiles), stop_(stop) {}
    void BeginTiles(TilePasses &passes) override {
        watch_ = std::thread([this, &passes] {
            while (!ended_.load() && passes.TilesDone() < tiles_) std::this_thread::sleep_for(std::chrono::microseconds(50));
            stop_.store(true);
        });
    }
    void EndTiles() override {
        ended_.store(true);
        watch_.join();
    }

  private:
    long long tiles_;
    std::atomic<bool> &stop_;
    std::atomic<bool> ended_{false};
    std::thread watch_;
};

// A render stopped part-way and continued on the same film (what --resume does with a checkpoint's
// accumulators) equals the uninterrupted render, and so does one continued to more samples.
TEST(Work, StoppedAndContinuedRenderIsBitIdentical) {
    for (const char *integrator : {"grt", "ray"}) {
        SCOPED_TRACE(integrator);
        auto scene = SmallScene(integrator);
        ASSERT_TRUE(scene);
        const Detector &det = scene->GetDetector();
        Film whole(det.Width(), det.Height(), det.Response());
        const Image reference = Render(*scene, whole, 40);

        // Stopped after a whole pass (7 samples), and stopped during a pass (pixels then differ).
        Film film(det.Width(), det.Height(), det.Response());
        std::atomic<bool> cancel{false};
        Render(*scene, film, 40, nullptr, &cancel, [&](int done, int) {
            if (done >= 7) cancel.store(true);
        });
        EXPECT_EQ(film.SampleCount(0, 0), 7);
        ExpectIdentical(Render(*scene, film, 40), reference);

        Film partial(det.Width(), det.Height(), det.Response());
        std::atomic<bool> stop{false};
        StopAfterTiles stopper(20, stop);  // 18 tiles make the passes to 1, 3 and 7 samples
        Render(*scene, partial, 40, &stopper, &stop);
        long long fewest = 1 << 30;
        for (int y = 0; y < partial.Height(); ++y)
            for (int x = 0; x < partial.Width(); ++x) fewest = std::min(fewest, partial.SampleCount(x, y));
        ASSERT_LT(fewest, 40) << "the first run must stop part-way";
        ExpectIdentical(Render(*scene, partial, 40), reference);

        // 20 samples, then on to 40: the same as 40 at once (a camera's samples do not depend on the
        // sample count).
        Film shorter(det.Width(), det.Height(), det.Response());
        Render(*scene, shorter, 20);
        ExpectIdentical(Render(*scene, shorter, 40), reference);
    }
}

// The tiles of a render shared with a helper that renders with its own integrator call and film, as
// an MPI rank does (app/distributed_mpi.cpp): its tiles come from the coordinator's TilePasses
// through copies, between passes it waits, and it stops when the coordinator ends.
class HelperThreadShare final : public WorkShare {
  public:
    explicit HelperThreadShare(const Scene &scene) : scene_(scene) {}
    void BeginTiles(TilePasses &passes) override {
        passes_ = &passes;
        helper_ = std::thread([this] {
            const Detector &det = scene_.GetDetector();
            Film film(det.Width(), det.Height(), det.Response());
            Relay relay(*this);
            Render(scene_, film, 40, &relay);
        });
    }
    void EndTiles() override {
        ended_.store(true);
        helper_.join();
    }
    std::atomic<long long> helped{0};

  private:
    // The helper's side: not coordinating; its tiles are copies of the coordinator's.
    class Relay final : public WorkShare, public TileSource {
      public:
        explicit Relay(HelperThreadShare &owner) : owner_(owner) {}
        bool Coordinates() const override { return false; }
        TileSource *HelperTiles(Film &) override { return this; }
        bool Next(TileTask &task) override {
            for (;;) {
                TileTask copy;
                if (owner_.passes_->Next(copy)) {
                    task = copy;
                    return true;
                }
                if (owner_.ended_.load()) return false;
                std::this_thread::sleep_for(std::chrono::microseconds(200));
            }
        }
        void Done(TileTask &task) override {
            TileTask copy = task;
            owner_.passes_->Done(copy);
            ++owner_.helped;
        }

      private:
        HelperThreadShare &owner_;
    };
    const Scene &scene_;
    TilePasses *passes_ = nullptr;
    std::atomic<bool> ended_{false};
    std::thread helper_;
};

TEST(Work, RenderSharedWithAHelperIsBitIdentical) {
    for (const char *integrator : {"grt", "ray"}) {
        SCOPED_TRACE(integrator);
        auto scene = SmallScene(integrator);
        ASSERT_TRUE(scene);
        const Detector &det = scene->GetDetector();
        Film alone(det.Width(), det.Height(), det.Response());
        const Image reference = Render(*scene, alone, 40);
        Film shared(det.Width(), det.Height(), det.Response());
        HelperThreadShare share(*scene);
        ExpectIdentical(Render(*scene, shared, 40, &share), reference);
        EXPECT_GT(share.helped.load(), 0) << "the helper rendered no tile";
    }
}

// rs's batches in this process: in order, each once, stopped by `done` returning false.
TEST(Work, LocalBatchesCoverEveryValueOnce) {
    std::vector<double> values(1000, 0.0);
    std::vector<int> seen;
    EXPECT_TRUE(RunBatchesLocally(
        values, 7,
        [&](std::size_t b, std::size_t e) {
            for (std::size_t i = b; i < e; ++i) values[i] += double(i);
        },
        [&](int k) {
            seen.push_back(k);
            return true;
        },
        nullptr));
    for (std::size_t i = 0; i < values.size(); ++i) ASSERT_EQ(values[i], double(i));
    EXPECT_EQ(seen, (std::vector<int>{1, 2, 3, 4, 5, 6, 7}));
    EXPECT_FALSE(RunBatchesLocally(values, 7, [](std::size_t, std::size_t) {}, [](int k) { return k < 3; }, nullptr));
}

}  // namespace
}  // namespace phasor
