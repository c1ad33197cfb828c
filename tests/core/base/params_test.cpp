// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include "core/params.h"

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

}  // namespace
}  // namespace phasor
