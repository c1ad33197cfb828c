// SPDX-License-Identifier: Apache-2.0
// A virtual_plane without `aim` behind an aperture plate is aimed at the plate automatically
// (Scene::Build, theory §0 D4b): the double slit renders the same as with `aim = @plate`; with
// auto_aim = false it samples the whole cone and gives zeros and spikes (the failure this fixes).
#include <fstream>
#include <sstream>

#include "render_row.h"
#include "support/temp_dir.h"

namespace phasor::test {
namespace {

class AutoAim : public TempDirTest {
  protected:
    AutoAim() : TempDirTest("auto_aim") {}
    /// double_slit.wscene with its `aim = @plate` line replaced by `replacement`.
    std::string SceneWith(const std::string &replacement, const std::string &name) {
        std::ifstream in(ValidationScene("double_slit.wscene"));
        std::ostringstream out;
        int replaced = 0;
        for (std::string line; std::getline(in, line);) {
            if (line.find("aim = @plate") != std::string::npos) {
                line = "    " + replacement;
                ++replaced;
            }
            out << line << "\n";
        }
        EXPECT_EQ(replaced, 1);
        std::ofstream(Path(name)) << out.str();
        return Path(name);
    }
};

TEST_F(AutoAim, DoubleSlitWithoutAimMatchesTheExplicitAim) {
    const int spp = 256;
    const Row aimed = RenderRow(ValidationScene("double_slit.wscene"), {}, "grt", spp);
    const Row automatic = RenderRow(SceneWith("", "no_aim.wscene"), {}, "grt", spp);
    ASSERT_EQ(automatic.v.size(), aimed.v.size());
    const double e = MaxDiffOfPeak(automatic, aimed);
    std::printf("no aim vs aim = @plate: max diff = %.2e of peak %.4g\n", e, aimed.Peak());
    EXPECT_LE(e, 1e-12);

    const Row cone = RenderRow(SceneWith("auto_aim = false", "cone.wscene"), {}, "grt", spp);
    const double eCone = MaxDiffOfPeak(cone, aimed);
    std::printf("auto_aim = false: max diff = %.2e of peak\n", eCone);
    EXPECT_GT(eCone, 0.1);
}

// A light on the sensor's side of the plate (a point source behind the sensor): the plate is not
// aimed at automatically, and the scene says why and how to aim explicitly.
TEST_F(AutoAim, LightOnTheSensorSideWarnsInstead) {
    Diagnostics diag;
    auto desc = ParseSceneFile(SceneWith("", "no_aim.wscene"), {{"source", "point"}, {"distance", "-50mm"}}, diag);
    ASSERT_TRUE(desc);
    auto scene = Scene::Build(*desc, diag);
    std::ostringstream os;
    diag.Print(os);
    ASSERT_TRUE(scene) << os.str();
    EXPECT_EQ(diag.WarningCount(), 1u) << os.str();
    EXPECT_NE(os.str().find("sensor 'sensor' has no 'aim' and samples its whole acceptance cone (light 'pinhole' is "
                            "not beyond 'plate')"),
              std::string::npos)
        << os.str();
    EXPECT_NE(os.str().find("add aim = @plate"), std::string::npos) << os.str();
}

}  // namespace
}  // namespace phasor::test
