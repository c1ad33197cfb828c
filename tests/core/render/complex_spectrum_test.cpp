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
    EXPECT_EQ(Read(Value::String("water"))->Eval(550e-9), Complex(1.333, 0));
    EXPECT_EQ(Read(Value::String("chitin"))->Eval(550e-9), Complex(1.56, 0));
    // Every named material is a passive medium over the visible (GetComplexSpectrum accepts it).
    for (const std::string &name : NamedIndexNames()) EXPECT_NO_THROW(Read(Value::String(name))) << name;
}

TEST(ComplexSpectrum, ErrorsNameTheTextAndThePlace) {
    // Validation catches a misspelt material (params_test.cpp); a value that skipped validation
    // gets the same answer from the accessor.
    EXPECT_EQ(ErrorOf(Value::String("fused_silca")),
              "t.wscene:2:3: 'ior': unknown material \"fused_silca\" (known: \"Al\", \"Ag\", \"Au\", \"Cu\", "
              "\"BK7\", \"fused_silica\", \"water\", \"chitin\"); did you mean \"fused_silica\"?");
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

}  // namespace
}  // namespace phasor
