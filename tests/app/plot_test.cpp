// SPDX-License-Identifier: Apache-2.0
// Plots through matplotlib (app/plot.h): a plot appears with the other staged files; the plot
// module's error is the error (and the set is dropped); without a Python with matplotlib nothing
// is staged, the rest stays, and MatplotlibMissing() says what to install; the disc map of
// `phasor probe` from its grid.

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

TEST_F(PlotTest, DiscMapFromAGrid) {
    DiscMap map;
    map.n = 32;
    for (int j = 0; j < map.n; ++j)
        for (int i = 0; i < map.n; ++i) map.values.push_back(i == 24 && j == 16 ? 1.0 : 1e-3);
    map.markers = {{0.53, 0.03, "R0"}, {-0.4, 0.2, "T, \"+1\""}};
    map.title = "probe";
    OutputFiles files;
    ASSERT_TRUE(StageDiscMap(files, Path("map.png"), map));
    files.Commit();
    const Image png = ReadImage(Path("map.png"));
    EXPECT_EQ(png.width, 700);
    EXPECT_EQ(png.height, 600);
    map.values.pop_back();
    OutputFiles more;
    EXPECT_THROW(StageDiscMap(more, Path("bad.png"), map), Error);
}

}  // namespace
}  // namespace phasor
