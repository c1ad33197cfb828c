// SPDX-License-Identifier: Apache-2.0
// White balance of RGB detectors (`white_balance`, a Bradford adaptation of the illuminant's white
// to D65): a grey diffuse wall under a 4500 K black body renders neutral when the camera is
// balanced for 4500 K, and warm when it is not.
#include <gtest/gtest.h>

#include <cmath>

#include "support/scene_builder.h"

namespace phasor::test {
namespace {

struct ChannelMeans {
    double r = 0, g = 0, b = 0;
    double seRG = 0, seBG = 0;  // standard errors of the ratios R/G and B/G (pixels independent)
};

ChannelMeans RenderGreyWall(bool balance) {
    SceneBuilder b;
    b.Add("Material", "diffuse", "grey").Set("reflectance", Num(0.5));
    b.Add("Shape", "rectangle", "wall").Set("material", Ref("grey"));
    b.Add("Light", "directional", "sun")
        .Set("direction", Vec(0, 0, -1))
        .Set("irradiance", Value::Number(1, Dim::Irradiance()))
        .Set("spectrum", Call("blackbody", {Value::Number(4500, Dim::Temperature())}));
    ParamDict &cam = b.Add("Detector", "perspective", "cam")
                         .Set("to_world", Call("lookat", {LenVec(0, 0, 3), LenVec(0, 0, 0), Vec(0, 1, 0)}))
                         .Set("fov", Value::Number(Radians(20), Dim::Angle()))
                         .Set("resolution", Value::List({Int(16), Int(16)}));
    if (balance) cam.Set("white_balance", Call("blackbody", {Value::Number(4500, Dim::Temperature())}));
    std::string log;
    auto scene = b.Build(&log);
    EXPECT_TRUE(scene) << log;
    if (!scene) return {};
    const Image img = RenderImage(*scene, 16);
    // Per-pixel ratios: each pixel is an independent estimate of the wall's (uniform) colour.
    const int n = img.width * img.height;
    double sr = 0, sg = 0, sb = 0, qrg = 0, qbg = 0;
    std::vector<double> rg, bg;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            sr += img.At(x, y, 0), sg += img.At(x, y, 1), sb += img.At(x, y, 2);
            rg.push_back(img.At(x, y, 0) / img.At(x, y, 1));
            bg.push_back(img.At(x, y, 2) / img.At(x, y, 1));
        }
    ChannelMeans m{sr / n, sg / n, sb / n};
    for (int i = 0; i < n; ++i) {
        qrg += std::pow(rg[i] - m.r / m.g, 2);
        qbg += std::pow(bg[i] - m.b / m.g, 2);
    }
    m.seRG = std::sqrt(qrg / (n - 1) / n);
    m.seBG = std::sqrt(qbg / (n - 1) / n);
    return m;
}

TEST(WhiteBalance, GreyUnderItsIlluminantIsNeutral) {
    const ChannelMeans m = RenderGreyWall(true);
    ASSERT_GT(m.g, 0);
    std::printf("balanced: R/G = %.5f ± %.5f, B/G = %.5f ± %.5f\n", m.r / m.g, m.seRG, m.b / m.g, m.seBG);
    // The only error left is the wavelength sampling's noise: 5 standard errors of the
    // pixel-to-pixel spread, plus 1e-3 for the 1 nm sums that give the illuminant's white.
    EXPECT_NEAR(m.r / m.g, 1.0, 5 * m.seRG + 1e-3);
    EXPECT_NEAR(m.b / m.g, 1.0, 5 * m.seBG + 1e-3);
}

TEST(WhiteBalance, WithoutItA4500KLightLooksWarm) {
    const ChannelMeans m = RenderGreyWall(false);
    ASSERT_GT(m.g, 0);
    std::printf("unbalanced: R/G = %.4f, B/G = %.4f\n", m.r / m.g, m.b / m.g);
    EXPECT_GT(m.r / m.g, 1.1);
    EXPECT_LT(m.b / m.g, 0.8);
}

TEST(WhiteBalance, NeedsAColourResponse) {
    SceneBuilder b;
    b.Add("Detector", "perspective", "cam")
        .Set("response", Str("radiometric"))
        .Set("white_balance", Call("blackbody", {Value::Number(4500, Dim::Temperature())}));
    std::string log;
    EXPECT_FALSE(b.Build(&log));
    EXPECT_NE(log.find("'white_balance' needs response = \"cie_xyz\""), std::string::npos) << log;
}

}  // namespace
}  // namespace phasor::test
