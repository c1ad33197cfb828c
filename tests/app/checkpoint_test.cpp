// SPDX-License-Identifier: Apache-2.0
// Checkpoints (app/checkpoint.h): a written checkpoint reads back exactly; a truncated, corrupted or
// foreign file is an error that says which, never a crash; CheckpointMismatch names what differs
// (phasor version included, which the end-to-end test cannot change); the scene fingerprint follows
// the resolved scene (Defines, the files it reads) but not the spp, seed, sampler or output. And the
// sweep's renders and file names (app/render.h), and render's options at scale on the command line.
#include <cstring>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "app/checkpoint.h"
#include "app/cli.h"
#include "app/render.h"
#include "parser/parser.h"
#include "support/temp_dir.h"

namespace phasor {
namespace {

class CheckpointTest : public test::TempDirTest {
  protected:
    CheckpointTest() : TempDirTest("checkpoint") {}

    static Checkpoint Example() {
        Checkpoint c;
        CheckpointRender &r = c.render;
        r.version = "0.1.0";
        r.fingerprint = "0123456789abcdef";
        r.width = 3;
        r.height = 2;
        r.integrator = "grt { max_depth = 5 }";
        r.sampler = "sobol";
        r.seed = 42;
        r.stokes = true;
        r.scene = "/some/where/scene.wscene";
        r.output = "/some/where/out.exr";
        r.defines = {{"d", "400um"}, {"film", "\"Cu2O\""}};
        r.integratorName = "grt";
        r.spp = 64;
        r.checkpointSeconds = 600;
        c.pixels.resize(6);
        for (int i = 0; i < 6; ++i) {
            Film::PixelState &p = c.pixels[std::size_t(i)];
            p.mean[0] = 0.1 * i, p.mean[1] = 1.0 / 3, p.mean[2] = -0.0;
            p.meanI = 1e-300 * i, p.m2I = 7.5, p.n = 10 + i, p.invalid = i % 2;
            p.stokes[2] = -0.25, p.stokesN = 10 + i;
        }
        c.rays = 123456789012;
        c.counters.n[0] = 3;
        c.seconds = 12.5;
        return c;
    }
    std::string Bytes(const std::string &path) const {
        std::ifstream in(path, std::ios::binary);
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    }
    void Put(const std::string &path, const std::string &bytes) const {
        std::ofstream(path, std::ios::binary) << bytes;
    }
    // The message of ReadCheckpoint's error ("" if it read the file).
    std::string ReadError(const std::string &path) const {
        try {
            ReadCheckpoint(path);
        } catch (const Error &e) {
            return e.Message();
        }
        return "";
    }
};

TEST_F(CheckpointTest, ReadsBackExactly) {
    const Checkpoint c = Example();
    WriteCheckpoint(Path("a.ckpt"), c);
    EXPECT_EQ(Listing(), std::vector<std::string>{"a.ckpt"}) << "no temporary left";
    const Checkpoint r = ReadCheckpoint(Path("a.ckpt"));
    EXPECT_EQ(CheckpointMismatch(c.render, r.render), "");
    EXPECT_EQ(r.render.scene, c.render.scene);
    EXPECT_EQ(r.render.output, c.render.output);
    EXPECT_EQ(r.render.defines, c.render.defines);
    EXPECT_EQ(r.render.integratorName, "grt");
    EXPECT_EQ(r.render.spp, 64);
    EXPECT_EQ(r.render.checkpointSeconds, 600);
    EXPECT_EQ(r.rays, c.rays);
    EXPECT_EQ(r.counters.n, c.counters.n);
    EXPECT_EQ(r.seconds, 12.5);
    ASSERT_EQ(r.pixels.size(), c.pixels.size());
    EXPECT_EQ(std::memcmp(r.pixels.data(), c.pixels.data(), c.pixels.size() * sizeof(Film::PixelState)), 0);
}

TEST_F(CheckpointTest, DamagedFilesAreErrorsThatSayWhy) {
    WriteCheckpoint(Path("a.ckpt"), Example());
    const std::string good = Bytes(Path("a.ckpt"));
    // Every truncation: "truncated", or "not a phasor checkpoint" before the magic is complete.
    for (std::size_t n = 0; n < good.size(); n += n < 64 ? 1 : 97) {
        Put(Path("t.ckpt"), good.substr(0, n));
        const std::string e = ReadError(Path("t.ckpt"));
        EXPECT_TRUE(e.find(n < 8 ? "not a phasor checkpoint" : "truncated") != std::string::npos)
            << n << " bytes: '" << e << "'";
    }
    // Every single flipped byte after the magic and format: "corrupt" (checksum, or a header that no
    // longer parses), never a crash or a silent read.
    for (std::size_t at = 12; at < good.size(); at += at < 200 ? 1 : 13) {
        std::string bad = good;
        bad[at] = char(bad[at] ^ 0x5a);
        Put(Path("c.ckpt"), bad);
        const std::string e = ReadError(Path("c.ckpt"));
        EXPECT_FALSE(e.empty()) << "byte " << at << " flipped went unnoticed";
        EXPECT_TRUE(e.find("corrupt") != std::string::npos || e.find("truncated") != std::string::npos)
            << "byte " << at << ": '" << e << "'";
    }
    std::string future = good;
    future[8] = 9;  // the format number
    Put(Path("f.ckpt"), future);
    EXPECT_NE(ReadError(Path("f.ckpt")).find("format 9, but this phasor reads format 1"), std::string::npos);
    EXPECT_NE(ReadError(Path("none.ckpt")).find("no such file"), std::string::npos);
    EXPECT_NE(ReadError(dir_.string()).find("not a regular file"), std::string::npos);
}

TEST(Checkpoint, MismatchNamesWhatDiffers) {
    CheckpointRender a;
    a.version = "0.1.0", a.fingerprint = "aa", a.width = 4, a.height = 3, a.integrator = "grt { }";
    a.sampler = "sobol", a.seed = 1, a.scene = "/x/scene.wscene";
    EXPECT_EQ(CheckpointMismatch(a, a), "");
    auto with = [&](auto change) {
        CheckpointRender b = a;
        change(b);
        return CheckpointMismatch(a, b);
    };
    EXPECT_EQ(with([](auto &b) { b.version = "0.2.0"; }), "its phasor version is 0.1.0, this render's is 0.2.0");
    EXPECT_EQ(with([](auto &b) { b.height = 5; }), "its resolution is 4x3, this render's is 4x5");
    EXPECT_EQ(with([](auto &b) { b.integrator = "ray { }"; }), "its integrator is grt { }, this render's is ray { }");
    EXPECT_EQ(with([](auto &b) { b.sampler = "independent"; }), "its sampler is sobol, this render's is independent");
    EXPECT_EQ(with([](auto &b) { b.seed = 2; }), "its seed is 1, this render's is 2");
    EXPECT_EQ(with([](auto &b) { b.stokes = true; }), "its Stokes output is off, this render's is on");
    EXPECT_NE(with([](auto &b) { b.fingerprint = "bb"; }).find("it was made from another scene"), std::string::npos);
    // The scene's path alone may differ (a copy of the same scene).
    EXPECT_EQ(with([](auto &b) { b.scene = "/elsewhere/scene.wscene"; }), "");
}

class FingerprintTest : public test::TempDirTest {
  protected:
    FingerprintTest() : TempDirTest("fingerprint") {}
    std::string Of(const std::string &text, const DefineList &defines = {}) {
        Diagnostics diag;
        std::ofstream(Path("s.wscene")) << text;
        auto desc = ParseSceneFile(Path("s.wscene"), defines, diag);
        EXPECT_TRUE(desc);
        return desc ? SceneFingerprint(*desc) : "";
    }
};

TEST_F(FingerprintTest, FollowsTheResolvedSceneAndTheFilesItReads) {
    std::ofstream(Path("m.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const std::string scene =
        "wscene 1\nDefine r = 1 m\nShape \"sphere\" \"s\" { radius = $r }\nShape \"obj\" \"m\" { file = \"m.obj\" }\n"
        "Detector \"perspective\" \"cam\" { resolution = [8 8] }\nRender { spp = 4  seed = 1 }\n";
    const std::string base = Of(scene);
    EXPECT_EQ(base.size(), 16u);
    EXPECT_EQ(Of(scene), base);
    EXPECT_NE(Of(scene, {{"r", "2 m"}}), base) << "a -D value";
    EXPECT_EQ(Of(scene, {{"r", "100 cm"}}), base) << "the same value in other units";
    EXPECT_NE(Of(std::string(scene).replace(scene.find("resolution = [8 8]"), 18, "resolution = [8 9]")), base);
    // The Render block's spp, seed (compared on their own) and output may change.
    EXPECT_EQ(Of(std::string(scene).replace(scene.find("spp = 4  seed = 1"), 17, "spp = 9  seed = 3  output = \"x.exr\"")),
              base);
    // The mesh file's contents.
    std::ofstream(Path("m.obj")) << "v 0 0 0\nv 1 0 0\nv 0 2 0\nf 1 2 3\n";
    EXPECT_NE(Of(scene), base) << "a changed mesh file";
}

TEST(Sweep, CombinationsInOrderWithFileSafeNames) {
    const auto r = SweepRenders({{"d", {"400um", "1 mm"}}, {"m", {"\"Cu2O\"", "a/b"}}});
    ASSERT_EQ(r.size(), 4u);
    EXPECT_EQ(r[0].second, "-d=400um-m=Cu2O");
    EXPECT_EQ(r[1].second, "-d=400um-m=a_b");
    EXPECT_EQ(r[2].second, "-d=1_mm-m=Cu2O");
    EXPECT_EQ(r[3].first, (std::vector<std::pair<std::string, std::string>>{{"d", "1 mm"}, {"m", "a/b"}}));
    EXPECT_EQ(SweepRenders({}).size(), 1u);  // no sweep: the one render
}

TEST(Sweep, CommandLine) {
    auto parse = [](std::vector<std::string> args, CliOptions &o, std::string &err) {
        std::vector<char *> argv{const_cast<char *>("phasor")};
        for (std::string &a : args) argv.push_back(a.data());
        return ParseCommandLine(int(argv.size()), argv.data(), o, err);
    };
    CliOptions o;
    std::string err;
    ASSERT_TRUE(parse({"render", "s.wscene", "--sweep", "t=rotate(90 deg, [1 0 0]),2,\"a,b\"", "--sweep", "n=1"}, o, err))
        << err;
    ASSERT_EQ(o.run.sweeps.size(), 2u);
    EXPECT_EQ(o.run.sweeps[0].second, (std::vector<std::string>{"rotate(90 deg, [1 0 0])", "2", "\"a,b\""}));
    CliOptions r;
    ASSERT_TRUE(parse({"render", "--resume", "x.ckpt", "--spp", "80", "--checkpoint", "60"}, r, err)) << err;
    EXPECT_EQ(r.run.resume, "x.ckpt");
    EXPECT_EQ(r.run.checkpoint, 60);
    EXPECT_TRUE(r.scene.empty());
    for (std::vector<std::string> bad : {std::vector<std::string>{"render", "s", "--sweep", "=1,2"},
                                         {"render", "s", "--sweep", "n=1,,2"},
                                         {"render", "s", "--sweep", "n=1,1"},
                                         {"render", "s", "--checkpoint", "0"},
                                         {"render", "s", "--sweep", "n=1", "--resume", "x.ckpt"},
                                         {"render", "--checkpoint", "5"},
                                         {"check", "s", "--sweep", "n=1"}}) {
        CliOptions b;
        EXPECT_FALSE(parse(bad, b, err)) << bad.back();
    }
}

}  // namespace
}  // namespace phasor
