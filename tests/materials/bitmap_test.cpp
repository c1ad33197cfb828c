// SPDX-License-Identifier: Apache-2.0
// `bitmap` texture: small images written here with OpenImageIO and read back at known uvs —
// texel centres, bilinear values worked out by hand, the four wrap modes, the uv mapping; the
// sRGB decoding against the IEC 61966-2-1 formula; the spectral kind against the `rgb` spectrum;
// scalar kinds with a dimension; honest bounds; bad files and parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <OpenImageIO/imageio.h>

#include "core/spectrum/rgb_uplift.h"
#include "material_test_util.h"
#include "support/temp_dir.h"

namespace phasor::test {
namespace {

// The 3 × 2 test image (row 0 at the top): R = V[row][column], G = 2·R, B = 3·R (float EXR).
constexpr float V[2][3] = {{0.1f, 0.4f, 0.2f}, {0.7f, 0.3f, 0.9f}};

class Bitmap : public TempDirTest {
  protected:
    Bitmap() : TempDirTest("phasor_bitmap") {}

    /// Writes `pixels` (width × height × channels, rows from the top) as `name` in `type`.
    std::string Write(const std::string &name, int width, int height, int channels, const std::vector<float> &pixels,
                      OIIO::TypeDesc type = OIIO::TypeDesc::FLOAT) {
        const std::string path = Path(name);
        OIIO::ImageSpec spec(width, height, channels, type);
        auto out = OIIO::ImageOutput::create(path);
        EXPECT_TRUE(out && out->open(path, spec)) << OIIO::geterror();
        EXPECT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data())) << out->geterror();
        out->close();
        return path;
    }
    std::string WriteTestExr() {
        std::vector<float> px;
        for (int row = 0; row < 2; ++row)
            for (int col = 0; col < 3; ++col) px.insert(px.end(), {V[row][col], 2 * V[row][col], 3 * V[row][col]});
        return Write("test.exr", 3, 2, 3, px);
    }

    /// Builds a bitmap texture named "b" from `params` (plus the entities of `extra`).
    std::shared_ptr<Texture> Build(ParamDict params, std::string *error = nullptr) {
        scene_ = std::make_unique<MiniScene>();
        scene_->Add("Texture", "bitmap", "b", std::move(params));
        auto t = scene_->Build<Texture>("b");
        if (error) *error = scene_->FirstError();
        else EXPECT_TRUE(t) << scene_->FirstError();
        return t;
    }
    std::unique_ptr<MiniScene> scene_;
};

double At(const Texture &t, double u, double v) {
    return static_cast<const ScalarTexture &>(t).EvalScalar(TextureEvalContext::AtUV(Vec2(u, v)));
}

// Texel centres give the stored values; between them the bilinear blend (by hand below); v = 0 is
// the image's bottom row.
TEST_F(Bitmap, TexelCentresAndBilinearValues) {
    auto t = Build(ParamDict().Set("filename", Value::String(WriteTestExr())).Set("channel", Value::String("R")));
    ASSERT_TRUE(t);
    ASSERT_EQ(t->ScalarDim(), Dim::None());
    for (int row = 0; row < 2; ++row)
        for (int col = 0; col < 3; ++col)
            EXPECT_NEAR(At(*t, (col + 0.5) / 3, 1 - (row + 0.5) / 2), V[row][col], 1e-7) << row << ", " << col;
    // u = 0.3 → x = 0.3·3 − 0.5 = 0.4 (columns 0, 1, weight 0.4 on 1); v = 0.4 → y = (1 − 0.4)·2 − 0.5
    // = 0.7 (rows 0, 1, weight 0.7 on row 1).
    const double top = 0.6 * V[0][0] + 0.4 * V[0][1], bottom = 0.6 * V[1][0] + 0.4 * V[1][1];
    EXPECT_NEAR(At(*t, 0.3, 0.4), 0.3 * top + 0.7 * bottom, 1e-7);
    // Exact bounds: the smallest and largest texel.
    EXPECT_NEAR(t->MinValue(), 0.1, 1e-7);
    EXPECT_NEAR(t->MaxValue(), 0.9, 1e-7);
}

// Outside [0, 1]: repeat, clamp, mirror, black, along u at the bottom row's centre (v = 0.25).
// u = −0.1 → x = −0.8: texels −1 and 0, weight 0.2 on texel 0; u = 1.1 → x = 2.8: texels 2 and 3,
// weight 0.8 on texel 3; u = 1.6 → x = 4.3: texels 4 and 5, weight 0.3 on texel 5.
TEST_F(Bitmap, WrapModes) {
    const std::string file = WriteTestExr();
    const float *r = V[1];  // the bottom row
    struct Case {
        const char *wrap;
        double atMinus01, at11, at16;
    };
    const Case cases[] = {
        {"repeat", 0.8 * r[2] + 0.2 * r[0], 0.2 * r[2] + 0.8 * r[0], 0.7 * r[1] + 0.3 * r[2]},
        {"clamp", r[0], r[2], r[2]},
        {"mirror", r[0], r[2], 0.7 * r[1] + 0.3 * r[0]},  // texels −1 → 0, 3 → 2, 4 → 1, 5 → 0
        {"black", 0.2 * r[0], 0.2 * r[2], 0.0},
    };
    for (const Case &c : cases) {
        auto t = Build(ParamDict()
                           .Set("filename", Value::String(file))
                           .Set("channel", Value::String("R"))
                           .Set("wrap", Value::String(c.wrap)));
        ASSERT_TRUE(t);
        EXPECT_NEAR(At(*t, -0.1, 0.25), c.atMinus01, 1e-7) << c.wrap;
        EXPECT_NEAR(At(*t, 1.1, 0.25), c.at11, 1e-7) << c.wrap;
        EXPECT_NEAR(At(*t, 1.6, 0.25), c.at16, 1e-7) << c.wrap;
        // Far away and non-finite coordinates stay finite.
        EXPECT_TRUE(std::isfinite(At(*t, 1e300, -1e300)));
        EXPECT_TRUE(std::isfinite(At(*t, std::nan(""), Infinity)));
        EXPECT_EQ(t->MinValue(), std::string(c.wrap) == "black" ? 0.0 : double(0.1f));
    }
    // Periodic far from the origin: u = 1000.5 is u = 0.5.
    auto rep = Build(ParamDict().Set("filename", Value::String(file)).Set("channel", Value::String("R")));
    EXPECT_NEAR(At(*rep, 1000.5, 0.25), r[1], 1e-7);
}

// s = uscale·u + udelta, t = vscale·v + vdelta.
TEST_F(Bitmap, UvMapping) {
    auto t = Build(ParamDict()
                       .Set("filename", Value::String(WriteTestExr()))
                       .Set("channel", Value::String("R"))
                       .Set("uscale", Value::Number(2))
                       .Set("udelta", Value::Number(0.25))
                       .Set("vscale", Value::Number(-1))
                       .Set("vdelta", Value::Number(1)));
    ASSERT_TRUE(t);
    // u = 0.125 → s = 0.5, column 1's centre; v = 0.25 → t = 0.75, the top row's centre.
    EXPECT_NEAR(At(*t, 0.125, 0.25), V[0][1], 1e-7);
    EXPECT_NEAR(At(*t, 0.125 + 0.5, 0.25), V[0][1], 1e-7);  // two repeats per unit of u
}

// Channels G and B (2R and 3R), Y the Rec.709 luminance of the linear colour, A as stored.
TEST_F(Bitmap, ChannelsAndLuminance) {
    const std::string file = WriteTestExr();
    const double u = 0.5 / 3, v = 0.75;  // texel (0, 0)
    for (const auto &[ch, expected] : {std::pair{"G", 2.0 * V[0][0]}, std::pair{"B", 3.0 * V[0][0]},
                                      std::pair{"Y", (0.2126 + 0.7152 * 2 + 0.0722 * 3) * V[0][0]}}) {
        auto t = Build(ParamDict().Set("filename", Value::String(file)).Set("channel", Value::String(ch)));
        ASSERT_TRUE(t);
        EXPECT_NEAR(At(*t, u, v), expected, 1e-6) << ch;
    }
    const std::string rgba = Write("rgba.exr", 1, 1, 4, {0.2f, 0.3f, 0.4f, 0.25f});
    auto a = Build(ParamDict().Set("filename", Value::String(rgba)).Set("channel", Value::String("A")));
    ASSERT_TRUE(a);
    EXPECT_NEAR(At(*a, 0.5, 0.5), 0.25, 1e-7);
}

// An 8-bit PNG is sRGB-encoded (OIIO tags it so): "auto" decodes it as a colour (AsColour: what a
// reflectance reads) with the IEC 61966-2-1 formula, c ≤ 0.04045 ? c/12.92 : ((c + 0.055)/1.055)^2.4,
// and reads it as data (a scalar parameter) raw. OCIO's ExponentWithLinearTransform
// derives its own toe (break 0.00303993, slope 12.9232, core/image/color.cpp), which differs from
// the formula by at most 9.8e-6 over [0, 1] (7.5e-7 at the 256 8-bit codes, measured); values are
// stored as floats (6e-8): tolerance 1.2e-5 (a gamma-2.2 decoding would be off by ~1e-2). "raw"
// gives code/255.
TEST_F(Bitmap, SrgbDecodingFollowsTheFormula) {
    const int codes[] = {0, 3, 10, 60, 128, 200, 255};
    std::vector<float> px;
    for (int c : codes) px.insert(px.end(), {c / 255.0f, 0.0f, 0.0f});
    const std::string png = Write("ramp.png", 7, 1, 3, px, OIIO::TypeDesc::UINT8);
    auto autoData = Build(ParamDict().Set("filename", Value::String(png)).Set("channel", Value::String("R")));
    ASSERT_TRUE(autoData && autoData->AsColour());
    std::shared_ptr<const Texture> srgb = autoData->AsColour();
    auto named = Build(ParamDict()
                           .Set("filename", Value::String(png))
                           .Set("channel", Value::String("R"))
                           .Set("colorspace", Value::String("sRGB")));
    auto raw = Build(ParamDict()
                         .Set("filename", Value::String(png))
                         .Set("channel", Value::String("R"))
                         .Set("colorspace", Value::String("raw")));
    ASSERT_TRUE(srgb && named && raw);
    for (int i = 0; i < 7; ++i) {
        const double c = codes[i] / 255.0, u = (i + 0.5) / 7;
        const double linear = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
        EXPECT_NEAR(At(*srgb, u, 0.5), linear, 1.2e-5) << "code " << codes[i];
        EXPECT_EQ(At(*named, u, 0.5), At(*srgb, u, 0.5));
        EXPECT_NEAR(At(*raw, u, 0.5), c, 1e-7);
        EXPECT_EQ(At(*autoData, u, 0.5), At(*raw, u, 0.5));
    }
    EXPECT_FALSE(named->AsColour());  // an explicit colour space reads alike as data and as colour
}

// "auto" reads a bitmap by what reads it: a one-channel 8-bit PNG is data (raw) as a thickness
// map and as a plain scalar, and a colour (sRGB-decoded) as a diffuse reflectance. Code 128:
// raw 128/255 = 0.50196, decoded ((0.50196 + 0.055)/1.055)^2.4 = 0.21586.
TEST_F(Bitmap, AutoReadsDataRawAndColoursDecoded) {
    const std::string grey = Write("grey_auto.png", 1, 1, 1, {128 / 255.0f}, OIIO::TypeDesc::UINT8);
    scene_ = std::make_unique<MiniScene>();
    scene_->Add("Texture", "bitmap", "g", ParamDict().Set("filename", Value::String(grey)))
        .Add("Texture", "bitmap", "t",
             ParamDict().Set("filename", Value::String(grey)).Set("scale", Value::Number(400e-9, Dim::Length())))
        .Add("Material", "diffuse", "paint", ParamDict().Set("reflectance", Value::Ref("g")))
        .Add("Material", "thin_film", "film", ParamDict().Set("ior", Value::Number(1.33)).Set("thickness_texture", Value::Ref("t")));
    auto g = scene_->Build<Texture>("g"), t = scene_->Build<Texture>("t");
    auto paint = scene_->Build<Material>("paint"), film = scene_->Build<Material>("film");
    ASSERT_TRUE(g && t && paint && film) << scene_->FirstError();
    const double raw = 128 / 255.0, decoded = std::pow((raw + 0.055) / 1.055, 2.4);
    EXPECT_NEAR(At(*g, 0.5, 0.5), raw, 1e-7);
    EXPECT_NEAR(At(*t, 0.5, 0.5), 400e-9 * raw, 400e-9 * 1.2e-7);  // not bent by a gamma (float32: ε = 1.2e-7)
    ASSERT_TRUE(g->AsColour());
    EXPECT_NEAR(At(*g->AsColour(), 0.5, 0.5), decoded, 1.2e-5);
    // The reflectance the diffuse kernel reads: f = R/π.
    SampledWavelengths wl = TestWavelengths(550e-9);
    ScatterQuery q;
    q.wi = Vec3(0, 0, 1);
    q.wl = &wl;
    q.tex = TextureEvalContext::AtUV(Vec2(0.5, 0.5));
    EXPECT_NEAR(Prep(*paint, q)->Eval(Vec3(0, 0, 1))[0] * Pi, decoded, 1.2e-5);
}

// The spectral kind: an RGB image without channel/scale/offset; its value is Smits' uplift of the
// linear colour, the same as the `rgb` spectrum of that colour; bounds 0 and ≥ every value.
TEST_F(Bitmap, SpectralKindIsTheRgbSpectrumOfTheLinearColour) {
    const std::string png = Write("colour.png", 2, 1, 3, {0.8f, 0.3f, 0.1f, 0.2f, 0.5f, 0.9f}, OIIO::TypeDesc::UINT8);
    auto t = Build(ParamDict().Set("filename", Value::String(png)));
    ASSERT_TRUE(t);
    EXPECT_FALSE(t->ScalarDim());
    auto decode = [](float x) {
        const double c = std::round(x * 255) / 255;  // the stored 8-bit code
        return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    };
    const Vec3 linear[2] = {Vec3(decode(0.8f), decode(0.3f), decode(0.1f)), Vec3(decode(0.2f), decode(0.5f), decode(0.9f))};
    SampledWavelengths wl = TestWavelengths(450e-9);
    for (int px = 0; px < 2; ++px) {
        scene_->Add("Spectrum", "rgb", "ref" + std::to_string(px), ParamDict().Set("color", Value::Vector(linear[px])));
        auto ref = scene_->Build<Spectrum>("ref" + std::to_string(px));
        ASSERT_TRUE(ref) << scene_->FirstError();
        const SampledSpectrum s = t->Eval(TextureEvalContext::AtUV(Vec2((px + 0.5) / 2, 0.5)), wl);
        for (int j = 0; j < NumWavelengths; ++j) {
            // Uplift is piecewise linear in RGB with slopes ≤ ~1: the 1.2e-5 decoding tolerance carries over.
            EXPECT_NEAR(s[j], ref->Eval(wl.lambda[j]), 2e-5) << "pixel " << px << ", λ " << wl.lambda[j];
            EXPECT_LE(s[j], t->MaxValue());
            EXPECT_GE(s[j], t->MinValue());
        }
    }
    EXPECT_LE(t->MaxValue(), 1);
    EXPECT_NEAR(t->MaxValue(), SmitsSpectrum::UpperBound(decode(0.9f)), 1e-6);
}

// A grey PNG is a dimensionless scalar texture (channel Y) without being asked, and serves as a
// diffuse reflectance; scale and offset give a scalar texture a dimension (a thickness map).
TEST_F(Bitmap, ScalarKindsAndDimensions) {
    const std::string grey = Write("grey.png", 2, 1, 1, {0.5f, 1.0f}, OIIO::TypeDesc::UINT8);
    scene_ = std::make_unique<MiniScene>();
    scene_->Add("Texture", "bitmap", "g", ParamDict().Set("filename", Value::String(grey)).Set("colorspace", Value::String("raw")))
        .Add("Material", "diffuse", "paint", ParamDict().Set("reflectance", Value::Ref("g")))
        .Add("Texture", "bitmap", "thick",
             ParamDict()
                 .Set("filename", Value::String(grey))
                 .Set("colorspace", Value::String("raw"))
                 .Set("scale", Value::Number(400e-9, Dim::Length()))
                 .Set("offset", Value::Number(100e-9, Dim::Length())))
        .Add("Texture", "scale", "thin", ParamDict().Set("tex", Value::Ref("thick")).Set("factor", Value::Number(0.5)));
    auto g = scene_->Build<Texture>("g");
    ASSERT_TRUE(g) << scene_->FirstError();
    EXPECT_EQ(g->ScalarDim(), Dim::None());
    EXPECT_NEAR(At(*g, 0.25, 0.5), 128 / 255.0, 1e-7);
    EXPECT_TRUE(scene_->Build<Material>("paint")) << scene_->FirstError();
    auto thick = scene_->Build<Texture>("thick"), thin = scene_->Build<Texture>("thin");
    ASSERT_TRUE(thick && thin);
    EXPECT_EQ(thick->ScalarDim(), Dim::Length());
    EXPECT_NEAR(At(*thick, 0.75, 0.5), 500e-9, 1e-15);
    // Texels are floats (relative error 6e-8 of 128/255): 3e-14 m on 400 nm.
    EXPECT_NEAR(thick->MinValue(), 100e-9 + 400e-9 * 128 / 255.0, 3e-14);
    EXPECT_NEAR(thick->MaxValue(), 500e-9, 1e-15);
    EXPECT_NEAR(At(*thin, 0.75, 0.5), 250e-9, 1e-15);
    // A negative scale swaps the bounds.
    auto neg = Build(ParamDict().Set("filename", Value::String(grey)).Set("colorspace", Value::String("raw")).Set("scale", Value::Number(-2)));
    ASSERT_TRUE(neg);
    EXPECT_NEAR(neg->MinValue(), -2, 1e-7);
    EXPECT_NEAR(neg->MaxValue(), -2 * 128 / 255.0, 1e-7);
}

// Bad files and parameters: a message that names the problem (locations: the diagnostics corpus,
// tests/parser/diagnostics/bitmap_bad_file.wscene).
TEST_F(Bitmap, BadInput) {
    const std::string exr = WriteTestExr();
    auto expectError = [&](ParamDict d, const std::string &fragment) {
        std::string error;
        EXPECT_FALSE(Build(std::move(d), &error)) << fragment;
        EXPECT_NE(error.find(fragment), std::string::npos) << error;
    };
    expectError(ParamDict().Set("filename", Value::String(Path("missing.png"))), "no such file");
    {
        std::ofstream(Path("garbage.png")) << "not an image";
    }
    expectError(ParamDict().Set("filename", Value::String(Path("garbage.png"))), "cannot read");
    expectError(ParamDict().Set("filename", Value::String(exr)).Set("channel", Value::String("Q")),
                "has no channel 'Q'; it has R, G, B (and Y, the luminance of its colour)");
    expectError(ParamDict().Set("filename", Value::String(exr)).Set("colorspace", Value::String("bogus")),
                "unknown colour space 'bogus'");
    expectError(ParamDict().Set("filename", Value::String(exr)).Set("uscale", Value::Number(0)), "'uscale' must not be 0");
    expectError(ParamDict()
                    .Set("filename", Value::String(exr))
                    .Set("scale", Value::Number(1e-7, Dim::Length()))
                    .Set("offset", Value::Number(0.1, Dim::Angle())),
                "'offset' is an angle, but 'scale' is a length");
    // A spectral bitmap is a reflectance: linear values above 1 are refused.
    const std::string bright = Write("bright.exr", 1, 1, 3, {0.5f, 1.5f, 0.2f});
    expectError(ParamDict().Set("filename", Value::String(bright)), "has linear G = 1.5");
    const std::string nan = Write("nan.exr", 1, 1, 3, {0.5f, std::nanf(""), 0.2f});
    expectError(ParamDict().Set("filename", Value::String(nan)), "non-finite value (channel G of pixel 0)");
    const std::string rgba = Write("rgba.exr", 1, 1, 4, {0.2f, 0.3f, 0.4f, 0.25f});
    expectError(ParamDict().Set("filename", Value::String(rgba)).Set("channel", Value::String("A")).Set("colorspace", Value::String("sRGB")),
                "'colorspace' does not apply");
    expectError(ParamDict().Set("filename", Value::String(rgba)).Set("scale", Value::Number(2)),
                "name the one the scalar texture reads with 'channel'");
}

}  // namespace
}  // namespace phasor::test
