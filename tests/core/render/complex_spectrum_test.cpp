// SPDX-License-Identifier: Apache-2.0
// Complex spectra (core/spectrum/complex_spectrum.h, core/spectrum/named_ior.h) read through
// BuildContext::GetComplexSpectrum, as a kernel reads its `ior`, including a field of a record.
#include <gtest/gtest.h>

#include "core/spectrum/complex_spectrum.h"
#include "core/render/registry.h"

namespace phasor {
namespace {

Value Nm(double v) { return Value::Number(v * 1e-9, Dim::Length()); }

// Reads `ior = v` through a one-parameter schema; throws phasor::Error like a kernel's Create.
std::shared_ptr<const ComplexSpectrum> Read(const Value &v, Diagnostics &diag) {
    static const Schema s{"material", "test", "", {P::ComplexSpectrum("ior", "index")}};
    ParamDict d(FileLoc{"t.wscene", 1, 1, 1});
    d.Add("ior", v, FileLoc{"t.wscene", 2, 3, 3});
    SceneDesc desc;
    BuildContext ctx(desc, diag);
    if (!d.Validate(s, diag)) throw Error(d.EntityLoc(), "invalid");
    return ctx.GetComplexSpectrum(d, "ior");
}
std::shared_ptr<const ComplexSpectrum> Read(const Value &v) {
    Diagnostics diag;
    return Read(v, diag);
}

// The validation errors, or else the error GetComplexSpectrum throws, with its location.
std::string ErrorOf(const Value &v) {
    Diagnostics diag;
    std::string thrown = "(no error)";
    try {
        Read(v, diag);
    } catch (const Error &e) {
        thrown = e.Loc().ToString() + ": " + e.Message();
    }
    std::string all;
    for (const auto &x : diag.All()) all += x.loc.ToString() + ": " + x.message;
    return all.empty() ? thrown : all;
}

TEST(ComplexSpectrum, ConstantsAndRealSpectraHaveTheirValues) {
    EXPECT_EQ(Read(Value::Number(1.5))->Eval(500e-9), Complex(1.5, 0));
    EXPECT_EQ(Read(Value::ComplexNumber({0.2, 3.4}))->Eval(700e-9), Complex(0.2, 3.4));
    EXPECT_EQ(Read(Value::ComplexNumber({0.2, 3.4}))->ToString(), "0.20000000000000001+3.3999999999999999i");
    // A real spectrum call: κ = 0, n interpolated by the table.
    const Value table = Value::Call("table", {Value::List({Nm(300), Nm(1100)}), Value::List({Value::Number(1.4), Value::Number(1.6)})}, {});
    const auto t = Read(table);
    EXPECT_NEAR(t->Eval(700e-9).real(), 1.5, 1e-15);
    EXPECT_EQ(t->Eval(700e-9).imag(), 0);
    // nk(n = …, k = …): two tables (here a table and a constant); k defaults to 0.
    const auto nk = Read(Value::Call("nk", {table, Value::Number(0.25)}, {"n", "k"}));
    EXPECT_NEAR(nk->Eval(300e-9 + 200e-9).real(), 1.45, 1e-15);
    EXPECT_EQ(nk->Eval(500e-9).imag(), 0.25);
    EXPECT_EQ(Read(Value::Call("nk", {Value::Number(2)}, {"n"}))->Eval(1e-6), Complex(2, 0));
}

TEST(ComplexSpectrum, NamedMaterialsMatchTheirSources) {
    // The metals are the tables of named_ior.h (tested against Johnson & Christy rows in
    // fresnel_test.cpp); here: the names reach them.
    EXPECT_EQ(Read(Value::String("Au"))->Eval(600e-9), MetalIndex(Metal::Au, 600e-9));
    EXPECT_EQ(Read(Value::String("Al"))->Eval(450e-9), MetalIndex(Metal::Al, 450e-9));
    // Glasses against their published n_d (587.56 nm), n_F (486.13 nm), n_C (656.27 nm):
    // N-BK7 1.5168 / 1.5224 / 1.5143 (Schott), fused silica 1.4585 / 1.4632 / 1.4564 (Malitson);
    // the data sheets give 4 decimals, so 1e-4.
    const auto bk7 = Read(Value::String("BK7")), silica = Read(Value::String("fused_silica"));
    EXPECT_NEAR(bk7->Eval(587.56e-9).real(), 1.5168, 1e-4);
    EXPECT_NEAR(bk7->Eval(486.13e-9).real(), 1.5224, 1e-4);
    EXPECT_NEAR(bk7->Eval(656.27e-9).real(), 1.5143, 1e-4);
    EXPECT_NEAR(silica->Eval(587.56e-9).real(), 1.4585, 1e-4);
    EXPECT_NEAR(silica->Eval(486.13e-9).real(), 1.4632, 1e-4);
    EXPECT_NEAR(silica->Eval(656.27e-9).real(), 1.4564, 1e-4);
    EXPECT_EQ(bk7->Eval(550e-9).imag(), 0);
    // The dispersive tables against the values their sources publish: water n = 1.3334 at
    // 587.6 nm, 20 °C, absolute (Daimon & Masumura 2007; relative to air the handbooks' 1.33299,
    // × n_air = 1.000277) with dn/dλ = −0.0313 µm⁻¹ there;
    // MgF₂ n_o = 1.3777 at 589.3 nm (Dodge 1984); rutile TiO₂ n_o = 2.613 at 589.3 nm (DeVore
    // 1951, 3 decimals: 1e-3); chitin 1.572 / 1.552 / 1.541 at 400 / 500 / 600 nm (Leertouwer et al.
    // 2011, 3 decimals); SiO2 is Malitson's fused silica; Cu₂O the SOPRA table at its nodes.
    const auto water = Read(Value::String("water"));
    EXPECT_NEAR(water->Eval(587.6e-9).real(), 1.3334, 1e-4);
    EXPECT_NEAR((water->Eval(588.6e-9).real() - water->Eval(586.6e-9).real()) / 2e-3, -0.0313, 5e-4);  // per µm
    EXPECT_NEAR(Read(Value::String("MgF2"))->Eval(589.3e-9).real(), 1.3777, 1e-4);
    EXPECT_NEAR(Read(Value::String("TiO2"))->Eval(589.3e-9).real(), 2.613, 1e-3);
    const auto chitin = Read(Value::String("chitin"));
    EXPECT_NEAR(chitin->Eval(400e-9).real(), 1.572, 1e-3);
    EXPECT_NEAR(chitin->Eval(500e-9).real(), 1.552, 1e-3);
    EXPECT_NEAR(chitin->Eval(600e-9).real(), 1.541, 1e-3);
    EXPECT_EQ(Read(Value::String("SiO2"))->Eval(587.56e-9), silica->Eval(587.56e-9));
    const auto cu2o = Read(Value::String("Cu2O"));
    EXPECT_LT(std::abs(cu2o->Eval(551.05e-9) - Complex(3.09867, 0.187747)), 1e-9);
    EXPECT_LT(std::abs(cu2o->Eval(399.95e-9) - Complex(2.8, 0.99)), 1e-9);
    EXPECT_GT(cu2o->Eval(450e-9).imag(), 3 * cu2o->Eval(650e-9).imag());  // absorbs the blue
    for (const char *glass : {"water", "MgF2", "TiO2", "chitin", "SiO2"})
        EXPECT_EQ(Read(Value::String(glass))->Eval(500e-9).imag(), 0) << glass;
    // Every named material is a passive medium over the visible (GetComplexSpectrum accepts it).
    for (const std::string &name : NamedIndexNames()) EXPECT_NO_THROW(Read(Value::String(name))) << name;
}

TEST(ComplexSpectrum, ErrorsNameTheTextAndThePlace) {
    // Validation catches a misspelt material (params_test.cpp); a value that skipped validation
    // gets the same answer from the accessor.
    EXPECT_EQ(ErrorOf(Value::String("fused_silca")),
              "t.wscene:2:3: 'ior': unknown material \"fused_silca\" (known: \"Al\", \"Ag\", \"Au\", \"Cu\", "
              "\"BK7\", \"fused_silica\", \"SiO2\", \"MgF2\", \"TiO2\", \"Cu2O\", \"water\", \"chitin\"); did you mean \"fused_silica\"?");
    Diagnostics diag;
    SceneDesc desc;
    BuildContext ctx(desc, diag);
    try {
        ctx.ComplexSpectrumFromValue(Value::String("Cuu", FileLoc{"t.wscene", 3, 4, 5}));
        ADD_FAILURE() << "no error";
    } catch (const Error &e) {
        EXPECT_EQ(e.Loc().line, 3);
        EXPECT_EQ(e.Message(), "unknown material \"Cuu\"; did you mean \"Cu\"?");
    }
    EXPECT_EQ(ErrorOf(Value::ComplexNumber({0.2, -3})),
              "t.wscene:2:3: 'ior' must be n + iκ with n > 0 and κ ≥ 0; it is 0.2-3i at 360 nm");
    EXPECT_NE(ErrorOf(Value::Number(0)).find("must be n + iκ with n > 0"), std::string::npos);
    EXPECT_NE(ErrorOf(Value::Call("nk", {Value::Number(1)}, {"kappa"})).find("'nk' has no argument 'kappa'"),
              std::string::npos) << ErrorOf(Value::Call("nk", {Value::Number(1)}, {"kappa"}));
    EXPECT_NE(ErrorOf(Value::Call("nk", {}, {})).find("'nk' needs argument 'n'"), std::string::npos);
    EXPECT_NE(ErrorOf(Value::Call("nx", {Value::Number(1)}, {})).find("unknown complex spectrum 'nx'"), std::string::npos);
    // A table that ends inside the checked band gives n = 0 there (tables are 0 outside).
    const Value shortTable = Value::Call("table", {Value::List({Nm(400), Nm(700)}), Value::List({Value::Number(1.4), Value::Number(1.6)})}, {});
    EXPECT_NE(ErrorOf(shortTable).find("it is 0+0i at 360 nm"), std::string::npos) << ErrorOf(shortTable);
}

TEST(ComplexSpectrum, AFieldOfARecordIsReadLikeAParameter) {
    const Schema s{"material", "stack", "", {P::RecordList("layers", "layers", "layer", "a layer",
                                                           {P::ComplexSpectrum("ior", "index").Required(),
                                                            P::Length("thickness", "thickness").Required()})}};
    ParamDict d;
    d.Add("layers", Value::List({Value::Call("layer", {Value::String("BK7"), Nm(100)}, {"ior", "thickness"}),
                                 Value::Call("layer", {Value::ComplexNumber({2.9, 0.1}), Nm(50)}, {})}));
    Diagnostics diag;
    ASSERT_TRUE(d.Validate(s, diag));
    SceneDesc desc;
    BuildContext ctx(desc, diag);
    const std::vector<ParamDict> layers = d.GetRecords("layers");
    ASSERT_EQ(layers.size(), 2u);
    EXPECT_NEAR(ctx.GetComplexSpectrum(layers[0], "ior")->Eval(587.56e-9).real(), 1.5168, 1e-4);
    EXPECT_EQ(ctx.GetComplexSpectrum(layers[1], "ior")->Eval(500e-9), Complex(2.9, 0.1));
    EXPECT_DOUBLE_EQ(layers[1].GetNumber("thickness"), 50e-9);
}


// ---- the `sellmeier` and `cauchy` spectra (src/spectra/, core/spectrum/dispersion.h) ---------------

Value Um2(double v) { return Value::Number(v * 1e-12, Dim::Area()); }

TEST(DispersionSpectra, SellmeierIsTheNamedGlassesFormula) {
    // Schott's N-BK7 coefficients written in a scene equal the named glass (the same formula, one
    // implementation) over the glass's band, and reproduce its n_d = 1.5168.
    const Value bk7 = Value::Call("sellmeier",
                                  {Value::Number(1.03961212), Value::Number(0.231792344), Value::Number(1.01046945),
                                   Um2(0.00600069867), Um2(0.0200179144), Um2(103.560653)},
                                  {});
    const auto s = Read(bk7), named = Read(Value::String("BK7"));
    for (double l = 300e-9; l <= 2500e-9; l *= 1.1) EXPECT_EQ(s->Eval(l), named->Eval(l)) << l;
    EXPECT_NEAR(s->Eval(587.56e-9).real(), 1.5168, 1e-4);
    // Outside 'range' (default 200 nm–3.7 µm) the value at the nearer end.
    EXPECT_EQ(s->Eval(100e-9), s->Eval(200e-9));
    EXPECT_EQ(s->Eval(5e-6), s->Eval(3.7e-6));
    // A one-term fit, by name, with its own band.
    const auto one = Read(Value::Call("sellmeier", {Value::Number(1.2), Um2(0.01), Value::List({Nm(400), Nm(800)})},
                                      {"b1", "c1", "range"}));
    EXPECT_NEAR(one->Eval(500e-9).real(), std::sqrt(1 + 1.2 * 0.25 / (0.25 - 0.01)), 1e-15);
    EXPECT_EQ(one->Eval(300e-9), one->Eval(400e-9));
}

TEST(DispersionSpectra, CauchyTakesItsTermsWithUnits) {
    // n = A + B/λ² + C/λ⁴ with B and C carrying their units: 0.0042 um^2 = 4200 nm^2.
    const auto a = Read(Value::Call("cauchy", {Value::Number(1.5046), Um2(0.0042)}, {}));
    const auto b = Read(Value::Call("cauchy", {Value::Number(1.5046), Value::Number(4200e-18, Dim::Area())}, {}));
    EXPECT_NEAR(a->Eval(500e-9).real(), 1.5046 + 0.0042 / 0.25, 1e-15);
    EXPECT_NEAR(a->Eval(500e-9).real(), b->Eval(500e-9).real(), 1e-15);
    const auto c = Read(Value::Call("cauchy", {Value::Number(1.5), Um2(0), Value::Number(1e-3 * 1e-24, Dim::Length().Pow(4))},
                                    {"a", "b", "c"}));
    EXPECT_NEAR(c->Eval(500e-9).real(), 1.5 + 1e-3 / 0.0625, 1e-15);
    // Leertouwer's chitin fit written as a cauchy is the named chitin over its 400–700 nm band.
    const auto chitin = Read(Value::Call("cauchy", {Value::Number(1.517), Value::Number(8.8e3 * 1e-18, Dim::Area())}, {}));
    for (double l = 400e-9; l <= 700e-9; l += 50e-9)
        EXPECT_NEAR(chitin->Eval(l).real(), Read(Value::String("chitin"))->Eval(l).real(), 1e-15) << l;
    // A dielectric built on it disperses (its refraction lobe is dispersive).
    EXPECT_GT(a->Eval(400e-9).real() - a->Eval(700e-9).real(), 0.01);
}

TEST(DispersionSpectra, BadCoefficientsAreErrorsAtTheirParameters) {
    auto has = [](const std::string &all, const std::string &text) { return all.find(text) != std::string::npos; };
    // A resonance (√C₁ = 500 nm) inside the default band.
    EXPECT_TRUE(has(ErrorOf(Value::Call("sellmeier", {Value::Number(1), Um2(0.25)}, {"b1", "c1"})), "the resonance √c1 = 500 nm lies inside 'range'"))
        << ErrorOf(Value::Call("sellmeier", {Value::Number(1), Um2(0.25)}, {"b1", "c1"}));
    // C without a unit.
    EXPECT_TRUE(has(ErrorOf(Value::Call("sellmeier", {Value::Number(1), Value::Number(0.01)}, {"b1", "c1"})), "'c1' expects an area"))
        << ErrorOf(Value::Call("sellmeier", {Value::Number(1), Value::Number(0.01)}, {"b1", "c1"}));
    // An inverted band; a fit that goes non-positive inside its band.
    EXPECT_TRUE(has(ErrorOf(Value::Call("cauchy", {Value::Number(1.5), Um2(0), Value::Number(0, Dim::Length().Pow(4)),
                                                   Value::List({Nm(800), Nm(400)})},
                                        {})),
                    "'range' must be [lo, hi] with lo < hi"));
    EXPECT_TRUE(has(ErrorOf(Value::Call("cauchy", {Value::Number(0.5), Um2(-0.05)}, {})), "the formula gives no positive index"))
        << ErrorOf(Value::Call("cauchy", {Value::Number(0.5), Um2(-0.05)}, {}));
}

}  // namespace
}  // namespace phasor
