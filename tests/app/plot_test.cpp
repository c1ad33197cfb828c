// SPDX-License-Identifier: Apache-2.0
// Plots through matplotlib (app/plot.h): a plot appears with the other staged files; the plot
// module's error is the error (and the set is dropped); without a Python with matplotlib nothing
// is staged, the rest stays, and MatplotlibMissing() says what to install; the disc map of
// `phasor probe` from its grid.

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "app/plot.h"
#include "core/diagnostics.h"
#include "core/image/image_io.h"
#include "core/image/output_file.h"
#include "support/temp_dir.h"

namespace phasor {
namespace {

class PlotTest : public test::TempDirTest {
  protected:
    PlotTest() : TempDirTest("phasor_app_plot") {}
    void SetUp() override {
        TempDirTest::SetUp();
        setenv("PHASOR_PLOT_MODULE", PHASOR_SOURCE_DIR "/python/phasor_plot.py", 1);
        unsetenv("PHASOR_PYTHON");
    }
    void TearDown() override {
        unsetenv("PHASOR_PLOT_MODULE");
        unsetenv("PHASOR_PYTHON");
        TempDirTest::TearDown();
    }
    std::string Head(const std::string &path, std::size_t n) {
        std::ifstream f(path, std::ios::binary);
        std::string s(n, '\0');
        f.read(s.data(), std::streamsize(n));
        return s.substr(0, std::size_t(f.gcount()));
    }
};

PlotRequest Profile() {
    PlotRequest r;
    r.command = "profile";
    r.data = "x_px,a,b,abs_diff\n0,1,2,1\n1,3,2,1\n2,2,2,0\n";
    r.args = {"--title", "test"};
    return r;
}

TEST_F(PlotTest, APlotAppearsWithTheOtherFiles) {
    OutputFiles files;
    files.Stage(Path("data.csv"), "x\n");
    ASSERT_TRUE(StagePlot(files, Path("p.png"), Profile()));
    ASSERT_TRUE(StagePlot(files, Path("p.svg"), Profile()));
    EXPECT_EQ(Listing().size(), 3u);  // staged: temporaries only
    EXPECT_FALSE(std::filesystem::exists(Path("p.png")));
    files.Commit();
    EXPECT_EQ(Head(Path("p.png"), 4), "\x89PNG");
    EXPECT_EQ(Head(Path("p.svg"), 5), "<?xml");
    const Image png = ReadImage(Path("p.png"));
    EXPECT_EQ(png.width, 1000);
    EXPECT_EQ(png.height, 600);
}

TEST_F(PlotTest, TheModulesErrorIsTheErrorAndNothingIsLeft) {
    OutputFiles files;
    files.Stage(Path("data.csv"), "x\n");
    PlotRequest bad = Profile();
    bad.data = "x_px,a\n0,1\n1,oops\n";
    try {
        StagePlot(files, Path("bad.png"), bad);
        ADD_FAILURE() << "no error";
    } catch (const Error &e) {
        EXPECT_EQ(e.Message().rfind("cannot write '" + Path("bad.png") + "': ", 0), 0u) << e.Message();
        EXPECT_NE(e.Message().find("'oops' is not a number"), std::string::npos) << e.Message();
    }
    files.Commit();
    EXPECT_TRUE(Listing().empty());  // the whole set is dropped, no temporary left

    setenv("PHASOR_PLOT_MODULE", "/nonexistent/phasor_plot.py", 1);
    OutputFiles more;
    EXPECT_THROW(StagePlot(more, Path("p.png"), Profile()), Error);
}

TEST_F(PlotTest, WithoutMatplotlibNothingIsStagedAndTheUserIsToldWhatToInstall) {
    for (const char *python : {"/nonexistent/python3", "false"}) {
        setenv("PHASOR_PYTHON", python, 1);
        OutputFiles files;
        files.Stage(Path("data.csv"), "x\n");
        // "false" starts but fails without the module's "missing" status: an error, not "missing".
        if (std::string(python) == "false") {
            EXPECT_THROW(StagePlot(files, Path("p.png"), Profile()), Error);
            continue;
        }
        EXPECT_FALSE(StagePlot(files, Path("p.png"), Profile()));
        files.Commit();
        EXPECT_EQ(Listing(), std::vector<std::string>{"data.csv"});
        EXPECT_NE(MatplotlibMissing().find("apt-get install python3-matplotlib"), std::string::npos);
        EXPECT_NE(MatplotlibMissing().find(python), std::string::npos) << MatplotlibMissing();
    }
    // A Python without site packages exits with the module's "missing" status (3).
    const std::string script = Path("python-S");
    std::ofstream(script) << "#!/bin/sh\nexec python3 -S \"$@\"\n";
    std::filesystem::permissions(script, std::filesystem::perms::owner_all);
    setenv("PHASOR_PYTHON", script.c_str(), 1);
    OutputFiles files;
    EXPECT_FALSE(StagePlot(files, Path("q.png"), Profile()));
    // Back to the default look-up: found again.
    unsetenv("PHASOR_PYTHON");
    EXPECT_TRUE(StagePlot(files, Path("q.png"), Profile()));
}

TEST_F(PlotTest, DiscMapFromGrids) {
    // Two discs (the layout of `phasor probe`): the CSV the plot module reads, cell centres and
    // the disc column; then the plot.
    DiscMap map;
    map.n = 4;
    for (const char *name : {"reflection", "transmission"}) {
        DiscMap::Disc d;
        d.name = name;
        for (int k = 0; k < 16; ++k) d.values.push_back(k);
        map.discs.push_back(d);
    }
    const std::string csv = DiscMapCsv(map);
    EXPECT_EQ(csv.substr(0, csv.find('\n', csv.find('\n') + 1) + 1), "disc,u,v,value\nreflection,-0.75,-0.75,0\n");
    EXPECT_NE(csv.find("reflection,-0.25,-0.75,1\n"), std::string::npos);  // i grows along u
    EXPECT_NE(csv.find("transmission,0.75,0.75,15\n"), std::string::npos);
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 33);

    map.n = 32;
    for (DiscMap::Disc &d : map.discs) {
        d.values.clear();
        for (int j = 0; j < map.n; ++j)
            for (int i = 0; i < map.n; ++i) d.values.push_back(i == 24 && j == 16 ? 1.0 : 1e-3);
    }
    map.markers = {{0, 0.53, 0.03, "R0", 'o', 9}, {1, -0.4, 0.2, "T, \"+1\"", 'o', 7}, {0, -0.5, 0, "", 'x', 10}};
    map.title = "probe";
    OutputFiles files;
    ASSERT_TRUE(StageDiscMap(files, Path("map.png"), map));
    files.Commit();
    const Image png = ReadImage(Path("map.png"));
    EXPECT_EQ(png.width, 80 + 2 * 420 + 130);
    EXPECT_EQ(png.height, 520);

    // Inconsistent maps are errors naming the file; nothing is written.
    auto bad = [&](DiscMap m) {
        OutputFiles more;
        EXPECT_THROW(StageDiscMap(more, Path("bad.png"), m), Error);
    };
    DiscMap short_ = map;
    short_.discs[1].values.pop_back();
    bad(short_);
    DiscMap same = map;
    same.discs[1].name = "reflection";
    bad(same);
    DiscMap lost = map;
    lost.markers.push_back({2, 0, 0, "", 'o', 7});
    bad(lost);
    EXPECT_EQ(Listing(), std::vector<std::string>{"map.png"});
}

}  // namespace
}  // namespace phasor
