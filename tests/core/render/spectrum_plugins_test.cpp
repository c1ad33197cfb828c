// SPDX-License-Identifier: Apache-2.0
// The spectrum plug-ins (src/spectra/): schemas, values, and errors, created through the
// registry as a scene would.
#include <gtest/gtest.h>

#include <cmath>

#include "core/render/registry.h"
#include "core/spectrum/spectrum.h"
#include "support/stats.h"

namespace phasor {
namespace {

struct Built {
    std::shared_ptr<const Spectrum> spectrum;
    std::size_t warnings = 0;
};

// Validates `d` against the plug-in's schema (which fills in defaults) and creates it.
Built Make(const std::string &name, ParamDict d) {
    const PluginEntry<Spectrum> *entry = Registry<Spectrum>::Find(name);
    if (!entry) throw std::runtime_error("no spectrum plug-in '" + name + "'");
    Diagnostics diag;
    SceneDesc desc;
    BuildContext ctx(desc, diag);
    if (!d.Validate(entry->schema(), diag)) throw Error(d.EntityLoc(), "invalid parameters for " + name);
    Built b;
    b.spectrum = std::shared_ptr<const Spectrum>(entry->create(d, ctx));
    b.warnings = diag.WarningCount();
    return b;
}

Value Nm(double v) { return Value::Number(v * 1e-9, Dim::Length()); }
Value Kelvin(double v) { return Value::Number(v, Dim::Temperature()); }

TEST(SpectrumPlugins, AllRegisteredWithTheMainParameterFirst) {
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"constant", "value"},  {"blackbody", "temperature"}, {"line", "wavelength"},
        {"gaussian", "center"}, {"table", "wavelengths"},     {"rgb", "color"},
        {"d65", "scale"}};
    for (const auto &[name, first] : expected) {
        const PluginEntry<Spectrum> *e = Registry<Spectrum>::Find(name);
        ASSERT_NE(e, nullptr) << name;
        EXPECT_EQ(e->schema().family, "spectrum");
        EXPECT_EQ(e->schema().name, name);
        ASSERT_FALSE(e->schema().params.empty());
        EXPECT_EQ(e->schema().params[0].name, first) << name;
    }
}

TEST(SpectrumPlugins, PresetsCreate) {
    for (const auto &e : Registry<Spectrum>::Entries()) {
        for (ParamDict d : e.presets()) {
            Built b = Make(e.name, d);
            ASSERT_TRUE(b.spectrum) << e.name;
            EXPECT_FALSE(b.spectrum->ToString().empty());
            EXPECT_GE(b.spectrum->MaxValue(), 0.0);
            auto [lo, hi] = b.spectrum->Support();
            EXPECT_LE(lo, hi) << e.name;
        }
    }
}

TEST(SpectrumPlugins, Constant) {
    Built b = Make("constant", ParamDict().Set("value", Value::Number(0.25)));
    EXPECT_EQ(b.spectrum->Eval(1e-6), 0.25);
    EXPECT_EQ(b.spectrum->ToString(), "constant(0.25)");
}

TEST(SpectrumPlugins, BlackbodyNormalisedToItsPeak) {
    const double T = 5800, b = 2.897771955e-3;
    Built n = Make("blackbody", ParamDict().Set("temperature", Kelvin(T)));
    EXPECT_NEAR(n.spectrum->Eval(b / T), 1.0, 1e-12);
    EXPECT_EQ(n.spectrum->MaxValue(), 1.0);
    EXPECT_NEAR(n.spectrum->Eval(400e-9) / n.spectrum->Eval(700e-9),
                Blackbody(400e-9, T) / Blackbody(700e-9, T), 1e-12);
    Built a =
        Make("blackbody", ParamDict().Set("temperature", Kelvin(T)).Set("normalize", Value::Bool(false)));
    EXPECT_DOUBLE_EQ(a.spectrum->Eval(500e-9), Blackbody(500e-9, T));
    // Support: the spectrum is ≥ 1e-6 of its peak inside and below it outside.
    auto [lo, hi] = n.spectrum->Support();
    EXPECT_NEAR(n.spectrum->Eval(lo), 1e-6, 1e-9);
    EXPECT_NEAR(n.spectrum->Eval(hi), 1e-6, 1e-9);
    EXPECT_LT(lo, 200e-9);
    EXPECT_GT(hi, 20e-6);
    EXPECT_EQ(n.spectrum->ToString(), "blackbody(5800 K, normalize = true)");
}

TEST(SpectrumPlugins, LineIsDiscrete) {
    Built b = Make("line", ParamDict().Set("wavelength", Nm(1000)).Set("power", Value::Number(2)));
    const Spectrum &s = *b.spectrum;
    ASSERT_TRUE(s.LineWavelength());
    EXPECT_DOUBLE_EQ(*s.LineWavelength(), 1e-6);
    EXPECT_EQ(s.Eval(*s.LineWavelength()), 2.0);
    EXPECT_EQ(s.Eval(1.001e-6), 0.0);
    // Rendered deterministically by the radiometric sensor (theory §0 D10).
    WavelengthSampler ws({{&s, 1.0}}, SensorResponse(SensorResponse::Kind::Radiometric));
    SampledWavelengths wl = ws.Sample(0.37);
    EXPECT_TRUE(wl.delta);
    EXPECT_EQ(wl.lambda[0], *s.LineWavelength());
    EXPECT_EQ(wl.pdf[0], 1.0);
    EXPECT_EQ(EvalEmission(s, wl)[0], 2.0);
}

TEST(SpectrumPlugins, LineWithWidthIsAGaussianOfTheSamePower) {
    Built b =
        Make("line",
             ParamDict().Set("wavelength", Nm(632.8)).Set("power", Value::Number(3)).Set("fwhm", Nm(0.002)));
    const Spectrum &s = *b.spectrum;
    EXPECT_FALSE(s.LineWavelength());
    auto [lo, hi] = s.Support();
    const int n = 20000;
    double integral = 0;
    for (int i = 0; i < n; ++i) integral += s.Eval(lo + (hi - lo) * (i + 0.5) / n);
    integral *= (hi - lo) / n;
    EXPECT_NEAR(integral, 3.0, 3.0 * 1e-5);
    EXPECT_NEAR(s.Eval(632.801e-9), 0.5 * s.MaxValue(), 1e-9 * s.MaxValue());  // half maximum at ±fwhm/2
}

TEST(SpectrumPlugins, Gaussian) {
    Built b = Make("gaussian",
                   ParamDict().Set("center", Nm(550)).Set("fwhm", Nm(40)).Set("peak", Value::Number(2)));
    EXPECT_DOUBLE_EQ(b.spectrum->Eval(550e-9), 2.0);
    EXPECT_NEAR(b.spectrum->Eval(570e-9), 1.0, 1e-12);
    EXPECT_NEAR(b.spectrum->Eval(530e-9), 1.0, 1e-12);
    auto [lo, hi] = b.spectrum->Support();
    EXPECT_NEAR(b.spectrum->Eval(lo), 2e-6, 1e-12);
    EXPECT_NEAR(b.spectrum->Eval(hi), 2e-6, 1e-12);
}

Value NmList(std::vector<double> v) {
    std::vector<Value> items;
    for (double x : v) items.push_back(Nm(x));
    return Value::List(items);
}
Value List(std::vector<double> v) {
    std::vector<Value> items;
    for (double x : v) items.push_back(Value::Number(x));
    return Value::List(items);
}

TEST(SpectrumPlugins, TableInterpolates) {
    Built b =
        Make("table", ParamDict().Set("wavelengths", NmList({400, 500, 700})).Set("values", List({1, 3, 2})));
    EXPECT_DOUBLE_EQ(b.spectrum->Eval(400e-9), 1.0);
    EXPECT_NEAR(b.spectrum->Eval(450e-9), 2.0, 1e-12);
    EXPECT_DOUBLE_EQ(b.spectrum->Eval(600e-9), 2.5);
    EXPECT_DOUBLE_EQ(b.spectrum->Eval(700e-9), 2.0);
    EXPECT_EQ(b.spectrum->Eval(399e-9), 0.0);
    EXPECT_EQ(b.spectrum->Eval(701e-9), 0.0);
    EXPECT_EQ(b.spectrum->MaxValue(), 3.0);
    EXPECT_DOUBLE_EQ(b.spectrum->Support().first, 400e-9);
    EXPECT_DOUBLE_EQ(b.spectrum->Support().second, 700e-9);
}

TEST(SpectrumPlugins, TableErrorsPointAtTheParameter) {
    const FileLoc where{"scene.wscene", 7, 12};
    ParamDict d;
    d.Add("wavelengths", NmList({400, 500, 500, 600}), where);
    d.Add("values", List({1, 2, 3, 4}), FileLoc{"scene.wscene", 8, 3});
    try {
        Make("table", d);
        FAIL() << "a non-increasing table must be rejected";
    } catch (const Error &e) {
        EXPECT_EQ(e.Loc(), where);
        EXPECT_NE(e.Message().find("strictly increase"), std::string::npos) << e.Message();
    }
    ParamDict m;
    m.Add("wavelengths", NmList({400, 500}), where);
    const FileLoc valuesLoc{"scene.wscene", 9, 4};
    m.Add("values", List({1, 2, 3}), valuesLoc);
    try {
        Make("table", m);
        FAIL() << "mismatched sizes must be rejected";
    } catch (const Error &e) {
        EXPECT_EQ(e.Loc(), valuesLoc);
    }
    // A single sample is a constant, with a warning.
    Built one = Make("table", ParamDict().Set("wavelengths", NmList({500})).Set("values", List({0.7})));
    EXPECT_EQ(one.warnings, 1u);
    EXPECT_EQ(one.spectrum->Eval(1e-6), 0.7);
}

TEST(SpectrumPlugins, RgbUpliftIsBoundedAndWhiteIsOne) {
    test::TestRng rng(9);
    for (int k = 0; k < 2000; ++k) {
        const Vec3 c(rng.Uniform(), rng.Uniform(), rng.Uniform());
        Built b = Make("rgb", ParamDict().Set("color", Value::Vector(c)));
        for (double l = 300e-9; l <= 1000e-9; l += 2.5e-9) {
            const double v = b.spectrum->Eval(l);
            ASSERT_GE(v, 0.0) << ToString(c) << " at " << l;
            ASSERT_LE(v, 1.0) << ToString(c) << " at " << l;
        }
    }
    Built white = Make("rgb", ParamDict().Set("color", Value::Vector({1, 1, 1})));
    Built grey = Make("rgb", ParamDict().Set("color", Value::Vector({0.5, 0.5, 0.5})));
    Built black = Make("rgb", ParamDict().Set("color", Value::Vector({0, 0, 0})));
    for (double l = 300e-9; l <= 1000e-9; l += 1e-9) {
        EXPECT_NEAR(white.spectrum->Eval(l), 1.0, 1e-3);
        EXPECT_NEAR(grey.spectrum->Eval(l), 0.5, 1e-3);
        EXPECT_EQ(black.spectrum->Eval(l), 0.0);
    }
}

TEST(SpectrumPlugins, RgbUpliftKeepsTheHue) {
    // Reflectance under an equal-energy illuminant seen by the CIE observer, in linear sRGB: the
    // dominant input channel stays dominant.
    auto toRgb = [](const Spectrum &s) {
        Vec3 xyz;
        for (double l = CieLambdaMin; l <= CieLambdaMax; l += 1e-9) xyz += CieXyz(l) * s.Eval(l);
        return XyzToLinearSrgb(xyz * (1e-9 / CieYIntegral()));
    };
    for (int ch = 0; ch < 3; ++ch) {
        Vec3 c(0.1, 0.1, 0.1);
        c[ch] = 0.9;
        const Vec3 rgb = toRgb(*Make("rgb", ParamDict().Set("color", Value::Vector(c))).spectrum);
        for (int o = 0; o < 3; ++o) {
            if (o == ch) continue;
            EXPECT_GT(rgb[ch], rgb[o] + 0.3) << "channel " << ch << ": " << ToString(rgb);
        }
    }
}

TEST(SpectrumPlugins, D65) {
    Built b = Make("d65", ParamDict().Set("scale", Value::Number(2)));
    EXPECT_DOUBLE_EQ(b.spectrum->Eval(560e-9), 2.0);
    EXPECT_NEAR(b.spectrum->MaxValue(), 2 * 1.17812, 1e-12);
    EXPECT_EQ(b.spectrum->Eval(850e-9), 0.0);
}

TEST(SpectrumPlugins, CallsBindPositionalArguments) {
    // blackbody(5800 K) and line(632.8 nm, fwhm = 0.002 nm), as the scene builder sees them.
    Diagnostics diag;
    SceneDesc desc;
    BuildContext ctx(desc, diag);
    auto bb = ctx.SpectrumFromValue(Value::Call("blackbody", {Kelvin(5800)}, {""}));
    EXPECT_NEAR(bb->Eval(2.897771955e-3 / 5800), 1.0, 1e-12);
    auto line = ctx.SpectrumFromValue(Value::Call("line", {Nm(632.8), Nm(0.002)}, {"", "fwhm"}));
    EXPECT_FALSE(line->LineWavelength());
    auto laser = ctx.SpectrumFromValue(Value::Call("line", {Nm(1064)}, {""}));
    ASSERT_TRUE(laser->LineWavelength());
    EXPECT_DOUBLE_EQ(*laser->LineWavelength(), 1064e-9);
    EXPECT_FALSE(diag.HasErrors());
}

}  // namespace
}  // namespace phasor
