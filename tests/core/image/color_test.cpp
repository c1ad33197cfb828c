// SPDX-License-Identifier: Apache-2.0
// Display transforms through OpenColorIO: the built-in config's sRGB views against the
// IEC 61966-2-1 formula, exposure, error reporting, and $OCIO handling.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <utility>
#include <fstream>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "core/diagnostics.h"
#include "core/image/image_io.h"

namespace phasor {
namespace {

// Sets (or unsets) $OCIO for the lifetime of the guard and restores the previous value.
class OcioEnv {
  public:
    explicit OcioEnv(const std::optional<std::string> &value) {
        if (const char *old = std::getenv("OCIO")) old_ = old;
        if (value) setenv("OCIO", value->c_str(), 1);
        else unsetenv("OCIO");
    }
    ~OcioEnv() {
        if (old_) setenv("OCIO", old_->c_str(), 1);
        else unsetenv("OCIO");
    }

  private:
    std::optional<std::string> old_;
};

// IEC 61966-2-1 sRGB encoding (linear → non-linear), the reference for the "Standard" view.
double SrgbEncode(double x) {
    return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
}

// Largest |display − formula| over a dense sweep of [0,1] (plus the neighbourhood of the toe),
// with three different values per triple so that channel mix-ups would show. `.first` is over
// the whole sweep, `.second` over the power segment only (x ≥ 0.0032), where OCIO's
// ExponentWithLinearTransform is the IEC formula itself; below, its linear toe is derived from
// gamma/offset (break 0.00303993, slope 12.9232 instead of 0.0031308, 12.92), which alone
// differs from the standard by up to 9.76e-6 near x = 0.00304.
std::pair<double, double> MaxSrgbError(const DisplayOptions &opt) {
    double maxErr = 0, maxErrPower = 0;
    auto check = [&](double x) {
        Vec3 in(x, x * x, 1 - x);
        Vec3 out = ApplyDisplayTransform(in, opt);
        for (int c = 0; c < 3; ++c) {
            double lin = double(float(in[c]));  // the transform sees floats
            double err = std::abs(out[c] - SrgbEncode(lin));
            maxErr = std::max(maxErr, err);
            if (lin >= 0.0032) maxErrPower = std::max(maxErrPower, err);
        }
    };
    constexpr int N = 20000;
    for (int i = 0; i <= N; ++i) check(double(i) / N);
    for (int i = 0; i <= 1000; ++i) check(0.006 * i / 1000);  // the linear toe and the break
    return {maxErr, maxErrPower};
}

TEST(ColorTransform, StandardViewMatchesIecSrgbFormula) {
    OcioEnv env(std::nullopt);
    auto [err, errPower] = MaxSrgbError({"sRGB", "Standard", 0});
    std::printf("sRGB/Standard: max |OCIO - IEC 61966-2-1| = %.3g (power segment %.3g)\n", err,
                errPower);
    EXPECT_LT(err, 1e-5);
    EXPECT_LT(errPower, 4 * std::numeric_limits<float>::epsilon());  // float arithmetic only
}

TEST(ColorTransform, BuiltinViewMatchesIecSrgbFormula) {
    // Rec.709 → XYZ → (OCIO builtin) sRGB display: the same encoding through the XYZ route.
    OcioEnv env(std::nullopt);
    auto [err, errPower] = MaxSrgbError({"sRGB", "Builtin", 0});
    std::printf("sRGB/Builtin: max |OCIO - IEC 61966-2-1| = %.3g (power segment %.3g)\n", err,
                errPower);
    EXPECT_LT(err, 1e-5);
    EXPECT_LT(errPower, 1e-6);  // + the 10-digit Rec.709 ↔ XYZ matrices of the config
}

TEST(ColorTransform, RawViewIsIdentity) {
    OcioEnv env(std::nullopt);
    Vec3 in(0.25, 3.5, -0.125);
    Vec3 out = ApplyDisplayTransform(in, {"sRGB", "Raw", 0});
    EXPECT_EQ(out, in);
}

TEST(ColorTransform, ExposureIsAGainInStops) {
    OcioEnv env(std::nullopt);
    Vec3 a = ApplyDisplayTransform({0.05, 0.1, 0.2}, {"sRGB", "Standard", 2});
    Vec3 b = ApplyDisplayTransform({0.2, 0.4, 0.8}, {"sRGB", "Standard", 0});
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(a[c], b[c]);
}

TEST(ColorTransform, UnknownViewThrowsNamingIt) {
    OcioEnv env(std::nullopt);
    try {
        ApplyDisplayTransform({0.5, 0.5, 0.5}, {"sRGB", "Filmic", 0});
        FAIL() << "expected phasor::Error";
    } catch (const Error &e) {
        EXPECT_NE(e.Message().find("'Filmic'"), std::string::npos) << e.Message();
        EXPECT_NE(e.Message().find("Standard"), std::string::npos) << e.Message();  // suggests views
    }
}

TEST(ColorConfig, BuiltInWhenOcioUnset) {
    OcioEnv env(std::nullopt);
    EXPECT_EQ(ColorConfigDescription(), "built-in");
}

TEST(ColorConfig, BadOcioThrowsNamingIt) {
    const std::string bad = "/nonexistent-phasor-dir/config.ocio";
    OcioEnv env(bad);
    EXPECT_EQ(ColorConfigDescription(), "$OCIO: " + bad);
    try {
        ApplyDisplayTransform({0.5, 0.5, 0.5});
        FAIL() << "expected phasor::Error";
    } catch (const Error &e) {
        EXPECT_NE(e.Message().find(bad), std::string::npos) << e.Message();
        EXPECT_NE(e.Message().find("$OCIO"), std::string::npos) << e.Message();
    }
}

TEST(ColorConfig, OcioConfigIsUsedAndSwitchingBackWorks) {
    // A user config with one display whose only view halves the scene-linear values.
    namespace fs = std::filesystem;
    fs::path dir = fs::path(testing::TempDir()) / "phasor_color_test";
    fs::create_directories(dir);
    fs::path cfg = dir / "half.ocio";
    std::ofstream(cfg) << R"(ocio_profile_version: 2
roles:
  default: lin
  scene_linear: lin
displays:
  Test:
    - !<View> {name: Half, colorspace: half}
colorspaces:
  - !<ColorSpace>
    name: lin
    isdata: false
  - !<ColorSpace>
    name: half
    isdata: false
    from_scene_reference: !<MatrixTransform> {matrix: [0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 1]}
)";
    {
        OcioEnv env(cfg.string());
        EXPECT_EQ(ColorConfigDescription(), "$OCIO: " + cfg.string());
        Vec3 out = ApplyDisplayTransform({1, 2, 4}, {"Test", "Half", 0});
        EXPECT_DOUBLE_EQ(out.x, 0.5);
        EXPECT_DOUBLE_EQ(out.y, 1.0);
        EXPECT_DOUBLE_EQ(out.z, 2.0);
        EXPECT_THROW(ApplyDisplayTransform({1, 1, 1}, {"sRGB", "Standard", 0}), Error);
    }
    {
        OcioEnv env(std::nullopt);
        Vec3 out = ApplyDisplayTransform({1, 1, 1}, {"sRGB", "Standard", 0});
        EXPECT_NEAR(out.x, 1.0, 1e-6);
    }
    fs::remove_all(dir);
}

}  // namespace
}  // namespace phasor
