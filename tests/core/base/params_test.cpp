// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include "core/params/dict.h"

namespace phasor {
namespace {

Schema TestSchema() {
    return Schema{"shape", "thing", "a test schema",
                  {P::Length("radius", "radius").Required().Min(0, true),
                   P::Angle("tilt", "tilt").Default(Value::Number(0.5, Dim::Angle())),
                   P::Integer("levels", "levels").Default(Value::Integer(2)).Min(0).Max(8),
                   P::String("mode", "mode").Default(Value::String("a")).Choices({"a", "b"}),
                   P::Vector("center", "centre", Dim::Length()).Default(Value::Vector({0, 0, 0}, Dim::Length()))}};
}

TEST(Units, ParseSimpleAndCompoundUnits) {
    EXPECT_DOUBLE_EQ(ParseUnit("nm")->scale, 1e-9);
    EXPECT_DOUBLE_EQ(ParseUnit("\xC2\xB5m")->scale, 1e-6);  // U+00B5
    EXPECT_DOUBLE_EQ(ParseUnit("\xCE\xBCm")->scale, 1e-6);  // U+03BC
    EXPECT_EQ(ParseUnit("W/m^2/sr")->dim, Dim::Radiance());
    EXPECT_DOUBLE_EQ(ParseUnit("mm^2")->scale, 1e-6);
    EXPECT_EQ(ParseUnit("mm^2")->dim, Dim::Area());
    EXPECT_NEAR(ParseUnit("deg")->scale, Pi / 180, 1e-18);
    EXPECT_FALSE(ParseUnit("furlong"));
    EXPECT_FALSE(ParseUnit("m^"));
}

TEST(ParamDict, ValidatesKindDimensionRangeAndRequired) {
    Schema s = TestSchema();
    {
        Diagnostics d;
        ParamDict p(FileLoc{"f", 1, 1, 1});
        p.Add("radius", Value::Number(2));  // bare number for a length
        p.Add("levels", Value::Integer(9));  // out of range
        p.Add("mode", Value::String("c"));  // not a choice
        p.Add("tilt", Value::Number(1, Dim::Length()));  // wrong dimension
        EXPECT_FALSE(p.Validate(s, d));
        EXPECT_EQ(d.ErrorCount(), 4u);
        std::string all;
        for (const auto &x : d.All()) all += x.message + "\n";
        EXPECT_NE(all.find("'radius' expects a length; got bare number 2 (write e.g. 2 um)"), std::string::npos) << all;
        EXPECT_NE(all.find("'levels' is out of range"), std::string::npos) << all;
        EXPECT_NE(all.find("'mode' must be one of"), std::string::npos) << all;
        EXPECT_NE(all.find("'tilt' expects an angle"), std::string::npos) << all;
    }
    {
        Diagnostics d;
        ParamDict p(FileLoc{"f", 1, 1, 1});
        EXPECT_FALSE(p.Validate(s, d));
        EXPECT_NE(d.All()[0].message.find("missing required parameter 'radius'"), std::string::npos);
    }
}

TEST(ParamDict, UnknownParameterIsAnErrorWithSuggestion) {
    Schema s = TestSchema();
    Diagnostics d;
    ParamDict p;
    p.Add("radius", Value::Number(1, Dim::Length()));
    p.Add("radus", Value::Number(1, Dim::Length()));
    EXPECT_FALSE(p.Validate(s, d));
    ASSERT_EQ(d.ErrorCount(), 1u);
    EXPECT_NE(d.All()[0].message.find("unknown parameter 'radus'"), std::string::npos);
    EXPECT_NE(d.All()[0].message.find("did you mean 'radius'?"), std::string::npos);
}

TEST(ParamDict, PermissiveUnknownParameterWarnsAndUnusedIsReported) {
    Schema s = TestSchema();
    Diagnostics d;
    d.SetPermissive(true);
    ParamDict p;
    p.Add("radius", Value::Number(1, Dim::Length()));
    p.Add("radus", Value::Number(1, Dim::Length()));
    p.Add("levels", Value::Integer(3));
    EXPECT_TRUE(p.Validate(s, d));
    ASSERT_EQ(d.WarningCount(), 1u);
    EXPECT_NE(d.All()[0].message.find("did you mean 'radius'?"), std::string::npos);
    EXPECT_DOUBLE_EQ(p.GetNumber("radius"), 1);
    EXPECT_DOUBLE_EQ(p.GetNumber("tilt"), 0.5);  // schema default
    p.ReportUnused(d, "shape");
    ASSERT_EQ(d.WarningCount(), 2u);
    EXPECT_NE(d.All()[1].message.find("'levels'"), std::string::npos);
}

// ---- list-of-records parameters (ParamKind::RecordList) ----------------------------------------

// A schema with a record list, as a thin-film kernel would declare it.
Schema StackSchema() {
    return Schema{"material", "stack", "a test schema with layers",
                  {P::RecordList("layers", "the layers, top first", "layer", "one homogeneous layer",
                                 {P::ComplexSpectrum("ior", "layer index").Required(),
                                  P::Length("thickness", "geometric thickness").Required().Min(0),
                                  P::Integer("repeat", "copies").Default(Value::Integer(1)).Min(1)})}};
}

FileLoc At(int line, int col) { return FileLoc{"f.wscene", line, col, 1}; }

// layer(ior = …, thickness = …) as the parser makes it: each named argument with its name's location.
Value Layer(std::vector<std::pair<std::string, Value>> fields, FileLoc loc) {
    std::vector<Value> args;
    std::vector<std::string> names;
    std::vector<FileLoc> locs;
    int col = loc.col + 6;
    for (auto &[n, v] : fields) {
        names.push_back(n);
        locs.push_back(FileLoc{loc.file, loc.line, col, (int)n.size()});
        v.loc = FileLoc{loc.file, loc.line, col + (int)n.size() + 3, 1};
        args.push_back(v);
        col += 20;
    }
    Value call = Value::Call("layer", std::move(args), std::move(names), loc);
    call.argLocs = std::move(locs);
    return call;
}

std::string Messages(const Diagnostics &d) {
    std::string all;
    for (const auto &x : d.All()) all += x.loc.ToString() + ": " + x.message + "\n";
    return all;
}

TEST(RecordList, ValidRecordsReadBackOneDictionaryPerRecordWithDefaultsAndLocations) {
    const Schema s = StackSchema();
    ParamDict p(At(1, 1));
    p.Add("layers", Value::List({Layer({{"ior", Value::Number(1.55)}, {"thickness", Value::Number(85e-9, Dim::Length())}}, At(2, 5)),
                                 Layer({{"ior", Value::String("BK7")}, {"thickness", Value::Number(1e-7, Dim::Length())},
                                        {"repeat", Value::Integer(3)}}, At(3, 5))}));
    Diagnostics d;
    ASSERT_TRUE(p.Validate(s, d)) << Messages(d);
    const std::vector<ParamDict> layers = p.GetRecords("layers");
    ASSERT_EQ(layers.size(), 2u);
    EXPECT_DOUBLE_EQ(layers[0].GetNumber("thickness"), 85e-9);
    EXPECT_EQ(layers[0].GetInt("repeat"), 1);  // the field's default
    EXPECT_EQ(layers[1].GetInt("repeat"), 3);
    EXPECT_EQ(layers[1].GetValue("ior").text, "BK7");
    // A location per field (the field's value), and the record's own for absent fields.
    EXPECT_EQ(layers[1].Loc("thickness").line, 3);
    EXPECT_EQ(layers[1].Loc("thickness").col, 5 + 6 + 20 + 9 + 3);
    EXPECT_EQ(layers[0].Loc("repeat").line, 2);
    EXPECT_EQ(layers[0].EntityLoc().col, 5);
    ASSERT_EQ(layers[0].GetSchema(), s.Find("layers")->record.get());
    // Positional arguments bind to the fields in order; a single record is a list of one.
    ParamDict q;
    q.Add("layers", Value::Call("layer", {Value::Number(1.38), Value::Number(1e-7, Dim::Length())}, {}));
    ASSERT_TRUE(q.Validate(s, d)) << Messages(d);
    const std::vector<ParamDict> one = q.GetRecords("layers");
    ASSERT_EQ(one.size(), 1u);
    EXPECT_DOUBLE_EQ(one[0].GetNumber("thickness"), 1e-7);
    EXPECT_DOUBLE_EQ(one[0].GetComplex("ior").real(), 1.38);
}

TEST(RecordList, EachRecordIsValidatedLikeAnEntity) {
    const Schema s = StackSchema();
    ParamDict p(At(1, 1));
    p.Add("layers",
          Value::List({Layer({{"ior", Value::Number(1.55)}, {"thicknes", Value::Number(85e-9, Dim::Length())}}, At(2, 5)),
                       Layer({{"ior", Value::Number(1.55)}, {"thickness", Value::Number(2)}}, At(3, 5)),
                       Layer({{"ior", Value::String("Auu")}, {"thickness", Value::Number(-1e-9, Dim::Length())}}, At(4, 5)),
                       Value::Call("layr", {}, {}, At(5, 5)), Value::Number(3, Dim::None(), At(6, 5))}));
    Diagnostics d;
    EXPECT_FALSE(p.Validate(s, d));
    const std::string all = Messages(d);
    // Unknown field, at the field's name, with a suggestion; then the field it was meant to be.
    EXPECT_NE(all.find("f.wscene:2:31: unknown parameter 'thicknes' for record \"layer\"; did you mean 'thickness'?"),
              std::string::npos) << all;
    EXPECT_NE(all.find("f.wscene:2:5: missing required parameter 'thickness' for record \"layer\""), std::string::npos)
        << all;
    // Wrong dimension, at the value.
    EXPECT_NE(all.find("f.wscene:3:43: 'thickness' expects a length; got bare number 2"), std::string::npos) << all;
    // A field's own kind rules: unknown material with suggestion, range.
    EXPECT_NE(all.find("f.wscene:4:17: 'ior': unknown material \"Auu\""), std::string::npos) << all;
    EXPECT_NE(all.find("did you mean \"Au\"?"), std::string::npos) << all;
    EXPECT_NE(all.find("'thickness' is out of range"), std::string::npos) << all;
    // Not a record of this kind.
    EXPECT_NE(all.find("f.wscene:5:5: 'layers' expects a list of layer(…) records; got a call to 'layr'; did you "
                       "mean 'layer'?"),
              std::string::npos) << all;
    EXPECT_NE(all.find("f.wscene:6:5: 'layers' expects a list of layer(…) records; got a plain number"),
              std::string::npos) << all;
    EXPECT_EQ(d.ErrorCount(), 7u) << all;
    // Too many positional arguments.
    ParamDict q;
    q.Add("layers", Value::Call("layer", {Value::Number(1), Value::Number(1e-9, Dim::Length()), Value::Integer(1),
                                          Value::Integer(2)}, {}));
    Diagnostics d2;
    EXPECT_FALSE(q.Validate(s, d2));
    EXPECT_NE(Messages(d2).find("too many arguments to 'layer'"), std::string::npos) << Messages(d2);
}

TEST(RecordList, DescribeAndMarkdownListTheRecordFields) {
    const Schema s = StackSchema();
    const std::string text = s.Describe(), md = s.Markdown();
    EXPECT_NE(text.find("layers : list of layer(…) = -"), std::string::npos) << text;
    EXPECT_NE(text.find("layer(…) — one homogeneous layer"), std::string::npos) << text;
    EXPECT_NE(text.find("    thickness : number [m] = required  (≥ 0)"), std::string::npos) << text;
    EXPECT_NE(md.find("Fields of each `layer(…)` record in `layers`"), std::string::npos) << md;
    EXPECT_NE(md.find("| `repeat` | integer | `1` | ≥ 1 | copies |"), std::string::npos) << md;
}

TEST(ComplexSpectrumParam, AcceptsEveryFormAndNamesUnknownMaterials) {
    const Schema s{"material", "m", "", {P::ComplexSpectrum("ior", "index")}};
    for (const Value &v : {Value::Number(1.5), Value::ComplexNumber({0.2, 3.4}), Value::String("Au"),
                           Value::String("fused_silica"), Value::Call("nk", {Value::Number(1)}, {"n"}),
                           Value::Ref("glass")}) {
        ParamDict p;
        p.Add("ior", v);
        Diagnostics d;
        EXPECT_TRUE(p.Validate(s, d)) << v.ToString() << ": " << Messages(d);
    }
    for (const Value &v : {Value::Number(1.5, Dim::Length()), Value::Bool(true), Value::String("silver")}) {
        ParamDict p;
        p.Add("ior", v);
        Diagnostics d;
        EXPECT_FALSE(p.Validate(s, d)) << v.ToString();
    }
    ParamDict p;
    p.Add("ior", Value::String("Ag "));
    Diagnostics d;
    EXPECT_FALSE(p.Validate(s, d));
    EXPECT_NE(Messages(d).find("unknown material \"Ag \" (known: \"Al\", \"Ag\""), std::string::npos) << Messages(d);
    EXPECT_NE(Messages(d).find("did you mean \"Ag\"?"), std::string::npos) << Messages(d);
    EXPECT_NE(s.Markdown().find("or a named material: Al Ag Au Cu BK7"), std::string::npos) << s.Markdown();
}

}  // namespace
}  // namespace phasor
