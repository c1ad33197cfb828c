// SPDX-License-Identifier: Apache-2.0
// Textures with dimensions (src/core/render/texture.h, src/textures): `constant` by value kind,
// `gradient`, `uv_ramp`, `noise`, `scale`, `mix`; the constant-or-texture accessors
// BuildContext::GetFloatTexture / GetSpectrumTexture and their dimension and range checks; the
// angle → tangent rule; diffuse's reflectance driven by a scalar texture.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "material_test_util.h"
#include "support/stats.h"

namespace phasor::test {
namespace {

std::shared_ptr<const ScalarTexture> Scalar(const std::shared_ptr<Texture> &t) {
    return std::dynamic_pointer_cast<const ScalarTexture>(t);
}

TextureEvalContext AtUv(double u, double v) { return TextureEvalContext::AtUV(Vec2(u, v)); }
TextureEvalContext AtP(const Vec3 &p) {
    TextureEvalContext c;
    c.p = p;
    return c;
}

TEST(ScalarTextures, AreRegistered) {
    for (const char *n : {"constant", "checkerboard", "gradient", "uv_ramp", "noise", "scale", "mix", "bitmap"})
        EXPECT_NE(Registry<Texture>::Find(n), nullptr) << n;
}

TEST(ScalarTextures, ConstantTakesItsKindFromTheValue) {
    MiniScene s;
    s.Add("Texture", "constant", "len", ParamDict().Set("value", Value::Number(300e-9, Dim::Length())))
        .Add("Texture", "constant", "plain", ParamDict().Set("value", Value::Number(0.25)))
        .Add("Texture", "constant", "spec",
             ParamDict().Set("value", Value::Call("blackbody", {Value::Number(5000, Dim::Temperature())}, {})));
    auto len = Scalar(s.Build<Texture>("len"));
    auto plain = s.Build<Texture>("plain");
    auto spec = s.Build<Texture>("spec");
    ASSERT_TRUE(len && plain && spec) << s.FirstError();
    EXPECT_EQ(len->GetDim(), Dim::Length());
    EXPECT_EQ(len->EvalScalar(AtUv(0.3, 0.2)), 300e-9);
    EXPECT_EQ(plain->ScalarDim(), Dim::None());
    const SampledWavelengths wl = TestWavelengths(500e-9);
    EXPECT_EQ(plain->Eval(AtUv(0.1, 0.9), wl)[2], 0.25);  // a plain number serves as a spectrum
    EXPECT_FALSE(spec->ScalarDim().has_value());
    EXPECT_GT(spec->Eval(AtUv(0, 0), wl)[0], 0);
}

TEST(ScalarTextures, GradientAlongUAndAlongAWorldAxis) {
    MiniScene s;
    s.Add("Texture", "gradient", "u",
          ParamDict()
              .Set("value0", Value::Number(100e-9, Dim::Length()))
              .Set("value1", Value::Number(300e-9, Dim::Length())))
        .Add("Texture", "gradient", "x",
             ParamDict()
                 .Set("value0", Value::Number(0, Dim::Angle()))
                 .Set("value1", Value::Number(Pi / 2, Dim::Angle()))
                 .Set("axis", Value::String("x"))
                 .Set("start", Value::Number(-1, Dim::Length()))
                 .Set("end", Value::Number(3, Dim::Length())));
    auto u = Scalar(s.Build<Texture>("u"));
    auto x = Scalar(s.Build<Texture>("x"));
    ASSERT_TRUE(u && x) << s.FirstError();
    EXPECT_EQ(u->GetDim(), Dim::Length());  // from its values
    EXPECT_NEAR(u->EvalScalar(AtUv(0.25, 0.9)), 150e-9, 1e-22);
    EXPECT_EQ(u->EvalScalar(AtUv(-2, 0)), 100e-9);  // held before start
    EXPECT_EQ(u->EvalScalar(AtUv(7, 0)), 300e-9);   // and after end
    EXPECT_EQ(u->MinValue(), 100e-9);
    EXPECT_EQ(u->MaxValue(), 300e-9);
    EXPECT_EQ(x->GetDim(), Dim::Angle());
    EXPECT_NEAR(x->EvalScalar(AtP(Vec3(0, 5, 5))), Pi / 8, 1e-15);  // (0 − (−1))/4 of the way
}

TEST(ScalarTextures, GradientDimensionErrors) {
    MiniScene mixed;
    mixed.Add("Texture", "gradient", "g",
              ParamDict()
                  .Set("value0", Value::Number(100e-9, Dim::Length()))
                  .Set("value1", Value::Number(0.1, Dim::Angle())));
    EXPECT_FALSE(mixed.Build<Texture>("g"));
    EXPECT_NE(mixed.FirstError().find("'value1' is an angle, but 'value0' is a length"), std::string::npos)
        << mixed.FirstError();
    MiniScene world;
    world.Add("Texture", "gradient", "g",
              ParamDict().Set("value0", Value::Number(0)).Set("value1", Value::Number(1)).Set("axis", Value::String("z")));
    EXPECT_FALSE(world.Build<Texture>("g"));
    EXPECT_NE(world.FirstError().find("'start' along axis \"z\" must be a length"), std::string::npos)
        << world.FirstError();
}

// uv_ramp: along u at angle 0 and along v at 90 deg it is gradient's ramp along u and v (the
// same values, bit for bit); at 30 deg the coordinate is u·cos 30° + v·sin 30° (by hand below).
TEST(ScalarTextures, UvRampAlongADirectionInUv) {
    auto ramp = [](double angleDeg) {
        return ParamDict()
            .Set("value0", Value::Number(50e-9, Dim::Length()))
            .Set("value1", Value::Number(250e-9, Dim::Length()))
            .Set("angle", Value::Number(angleDeg * Pi / 180, Dim::Angle()))
            .Set("start", Value::Number(0.2))
            .Set("end", Value::Number(0.7));
    };
    auto gradient = [](const char *axis) {
        return ParamDict()
            .Set("value0", Value::Number(50e-9, Dim::Length()))
            .Set("value1", Value::Number(250e-9, Dim::Length()))
            .Set("axis", Value::String(axis))
            .Set("start", Value::Number(0.2))
            .Set("end", Value::Number(0.7));
    };
    MiniScene s;
    s.Add("Texture", "uv_ramp", "r0", ramp(0))
        .Add("Texture", "uv_ramp", "r90", ramp(90))
        .Add("Texture", "uv_ramp", "r30", ramp(30))
        .Add("Texture", "gradient", "gu", gradient("u"))
        .Add("Texture", "gradient", "gv", gradient("v"));
    auto r0 = Scalar(s.Build<Texture>("r0")), r90 = Scalar(s.Build<Texture>("r90")), r30 = Scalar(s.Build<Texture>("r30"));
    auto gu = Scalar(s.Build<Texture>("gu")), gv = Scalar(s.Build<Texture>("gv"));
    ASSERT_TRUE(r0 && r90 && r30 && gu && gv) << s.FirstError();
    EXPECT_EQ(r30->GetDim(), Dim::Length());
    for (double u : {-0.5, 0.1, 0.3, 0.45, 0.69, 1.3})
        for (double v : {-0.2, 0.25, 0.6, 0.9}) {
            EXPECT_EQ(r0->EvalScalar(AtUv(u, v)), gu->EvalScalar(AtUv(u, v)));
            EXPECT_EQ(r90->EvalScalar(AtUv(u, v)), gv->EvalScalar(AtUv(u, v)));
            const double c = u * std::sqrt(3.0) / 2 + v / 2;
            const double t = std::clamp((c - 0.2) / 0.5, 0.0, 1.0);
            EXPECT_NEAR(r30->EvalScalar(AtUv(u, v)), 50e-9 + t * 200e-9, 1e-21) << u << ", " << v;
        }
    EXPECT_EQ(r30->MinValue(), 50e-9);
    EXPECT_EQ(r30->MaxValue(), 250e-9);

    MiniScene bad;
    bad.Add("Texture", "uv_ramp", "r",
            ParamDict().Set("value0", Value::Number(0)).Set("value1", Value::Number(1)).Set("start", Value::Number(0.5)).Set("end", Value::Number(0.5)));
    EXPECT_FALSE(bad.Build<Texture>("r"));
    EXPECT_NE(bad.FirstError().find("'end' must differ from 'start'"), std::string::npos) << bad.FirstError();
}

// A scalar texture drives any constant-or-texture parameter of its dimension: noise and a scaled
// noise as mix's weight (dimensionless), as they drive diffuse's reflectance (below) and an angle
// or a thickness (FloatTextureAccessor).
TEST(ScalarTextures, NoiseAndScaleDriveAMixWeight) {
    MiniScene s;
    s.WithFixtures()
        .Add("Texture", "noise", "n", ParamDict().Set("offset", Value::Number(0.5)).Set("amplitude", Value::Number(0.4)))
        .Add("Texture", "scale", "half", ParamDict().Set("tex", Value::Ref("n")).Set("factor", Value::Number(0.5)))
        .Add("Material", "mix", "m1",
             ParamDict().Set("a", Value::Ref("contract_gold")).Set("b", Value::Ref("contract_matte")).Set("weight", Value::Ref("n")))
        .Add("Material", "mix", "m2",
             ParamDict().Set("a", Value::Ref("contract_gold")).Set("b", Value::Ref("contract_matte")).Set("weight", Value::Ref("half")));
    auto n = Scalar(s.Build<Texture>("n"));
    auto m1 = s.Build<Material>("m1"), m2 = s.Build<Material>("m2");
    ASSERT_TRUE(n && m1 && m2) << s.FirstError();
    const SampledWavelengths wl = TestWavelengths(550e-9);
    ScatterQuery q;
    q.wi = Vec3(0, 0, 1);
    q.wl = &wl;
    for (int i = 0; i < 20; ++i) {
        q.tex.uv = Vec2(0.37 * i, 0.11 * i);
        // Eval towards the normal: the matte child's share only (the gold mirror has no density).
        const double w = n->EvalScalar(q.tex), factor = 0.5;
        EXPECT_NEAR(Prep(*m1, q)->Eval(Vec3(0, 0, 1))[0], w * 0.6 / Pi, 1e-15);
        EXPECT_NEAR(Prep(*m2, q)->Eval(Vec3(0, 0, 1))[0], factor * w * 0.6 / Pi, 1e-15);
    }
}

std::shared_ptr<const ScalarTexture> Noise(ParamDict p, MiniScene &s) {
    s.Add("Texture", "noise", "n", std::move(p));
    return Scalar(s.Build<Texture>("n"));
}

ParamDict ThicknessNoise() {
    return ParamDict()
        .Set("offset", Value::Number(300e-9, Dim::Length()))
        .Set("amplitude", Value::Number(50e-9, Dim::Length()))
        .Set("scale", Value::Number(0.05));
}

// |value − offset| ≤ amplitude everywhere (the fBm is bounded by 1, see noise.cpp). The bound is
// not attained (as usual for gradient noise: 10⁵ points reach ≈ ±0.5·amplitude), but the range
// is not vacuous: they reach beyond ±0.4·amplitude on both sides. MinValue/MaxValue report
// the bound.
TEST(Noise, StaysWithinOffsetPlusMinusAmplitude) {
    MiniScene s;
    auto n = Noise(ThicknessNoise(), s);
    ASSERT_TRUE(n) << s.FirstError();
    EXPECT_EQ(n->GetDim(), Dim::Length());
    TestRng rng(3);
    double lo = Infinity, hi = -Infinity;
    for (int i = 0; i < 100000; ++i) {
        const double v = n->EvalScalar(AtUv(20 * rng.Uniform() - 10, 20 * rng.Uniform() - 10));
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    EXPECT_GE(lo, 250e-9);
    EXPECT_LE(hi, 350e-9);
    EXPECT_LT(lo, 280e-9);
    EXPECT_GT(hi, 320e-9);
    EXPECT_EQ(n->MinValue(), 250e-9);
    EXPECT_EQ(n->MaxValue(), 350e-9);
}

// Mean over points in 40,000 different cells ≈ offset. The per-point std of the fBm is 0.126
// (measured; printed on failure); with independent cells the standard error of the mean is
// 0.126/√40000 = 6.3e-4 of the amplitude; 5e-3 (8 standard errors) still catches a 1 % bias.
TEST(Noise, MeanIsTheOffset) {
    MiniScene s;
    auto n = Noise(ThicknessNoise(), s);
    ASSERT_TRUE(n);
    TestRng rng(9);
    double sum = 0, sum2 = 0;
    const int count = 40000;
    for (int i = 0; i < count; ++i) {
        const double f = (n->EvalScalar(AtUv(1000 * rng.Uniform(), 1000 * rng.Uniform())) - 300e-9) / 50e-9;
        sum += f;
        sum2 += f * f;
    }
    const double mean = sum / count, sd = std::sqrt(sum2 / count - mean * mean);
    EXPECT_LT(std::abs(mean), 5e-3) << "sd " << sd;
    EXPECT_GT(sd, 0.05);  // it does vary
}

// Continuous: steps of 1e-7 cells change the value by ≲ |∇f|·1e-7 (|∇f| ≲ 10 per cell over four
// octaves), far below 1e-5 of the amplitude; no jumps across cell boundaries (u = k·scale).
// Deterministic: the same parameters give bit-identical values; another seed another pattern.
TEST(Noise, ContinuousAndDeterministic) {
    MiniScene a, b, c;
    auto n1 = Noise(ThicknessNoise(), a);
    auto n2 = Noise(ThicknessNoise(), b);
    auto n3 = Noise(ThicknessNoise().Set("seed", Value::Integer(7)), c);
    ASSERT_TRUE(n1 && n2 && n3);
    TestRng rng(4);
    int differ = 0;
    for (int i = 0; i < 2000; ++i) {
        // Every 4th point sits on a cell boundary of the first octave (scale 0.05).
        const double u = i % 4 == 0 ? 0.05 * double(i / 4 - 250) : 20 * rng.Uniform() - 10;
        const double v = 20 * rng.Uniform() - 10;
        const double x = n1->EvalScalar(AtUv(u, v));
        EXPECT_LT(std::abs(n1->EvalScalar(AtUv(u + 5e-9, v)) - n1->EvalScalar(AtUv(u - 5e-9, v))), 1e-5 * 50e-9);
        EXPECT_EQ(x, n2->EvalScalar(AtUv(u, v)));
        differ += std::abs(x - n3->EvalScalar(AtUv(u, v))) > 1e-3 * 50e-9;
    }
    EXPECT_GT(differ, 1900);
}

TEST(Noise, WorldSpaceAndClamps) {
    MiniScene s;
    auto n = Noise(ParamDict()
                       .Set("space", Value::String("world"))
                       .Set("scale", Value::Number(1e-3, Dim::Length()))
                       .Set("offset", Value::Number(0.5))
                       .Set("amplitude", Value::Number(1))
                       .Set("min", Value::Number(0.2))
                       .Set("max", Value::Number(0.7)),
                   s);
    ASSERT_TRUE(n) << s.FirstError();
    TestRng rng(2);
    int atMin = 0, atMax = 0;
    for (int i = 0; i < 4000; ++i) {
        const Vec3 p(0.01 * rng.Uniform(), 0.01 * rng.Uniform(), 0.01 * rng.Uniform());
        const double v = n->EvalScalar(AtP(p));
        EXPECT_GE(v, 0.2);
        EXPECT_LE(v, 0.7);
        atMin += v == 0.2;
        atMax += v == 0.7;
    }
    EXPECT_GT(atMin, 0);
    EXPECT_GT(atMax, 0);
    EXPECT_EQ(n->MinValue(), 0.2);
    EXPECT_EQ(n->MaxValue(), 0.7);
}

TEST(Noise, DimensionErrors) {
    MiniScene mixed;
    EXPECT_FALSE(Noise(ParamDict()
                           .Set("offset", Value::Number(300e-9, Dim::Length()))
                           .Set("amplitude", Value::Number(0.1, Dim::Angle())),
                       mixed));
    EXPECT_NE(mixed.FirstError().find("'amplitude' is an angle, but 'offset' is a length"), std::string::npos)
        << mixed.FirstError();
    MiniScene world;
    EXPECT_FALSE(Noise(ParamDict().Set("space", Value::String("world")).Set("amplitude", Value::Number(1)), world));
    EXPECT_NE(world.FirstError().find("'scale' in world space must be a length"), std::string::npos)
        << world.FirstError();
}

TEST(ScalarTextures, ScaleAndMix) {
    MiniScene s;
    s.Add("Texture", "gradient", "g",
          ParamDict()
              .Set("value0", Value::Number(100e-9, Dim::Length()))
              .Set("value1", Value::Number(300e-9, Dim::Length())))
        .Add("Texture", "scale", "half", ParamDict().Set("tex", Value::Ref("g")).Set("factor", Value::Number(0.5)))
        .Add("Texture", "mix", "m",
             ParamDict()
                 .Set("tex0", Value::Ref("g"))
                 .Set("tex1", Value::Number(1e-6, Dim::Length()))
                 .Set("amount", Value::Number(0.25)));
    auto half = Scalar(s.Build<Texture>("half"));
    auto m = Scalar(s.Build<Texture>("m"));
    ASSERT_TRUE(half && m) << s.FirstError();
    EXPECT_EQ(half->GetDim(), Dim::Length());
    EXPECT_NEAR(half->EvalScalar(AtUv(0.5, 0)), 100e-9, 1e-22);
    EXPECT_NEAR(half->MaxValue(), 150e-9, 1e-22);
    EXPECT_NEAR(m->EvalScalar(AtUv(0.5, 0)), 0.75 * 200e-9 + 0.25 * 1e-6, 1e-21);
    EXPECT_NEAR(m->MinValue(), 100e-9, 1e-22);
    EXPECT_NEAR(m->MaxValue(), 1e-6, 1e-21);

    MiniScene bad;
    bad.Add("Texture", "constant", "a", ParamDict().Set("value", Value::Number(0.1, Dim::Angle())))
        .Add("Texture", "mix", "m", ParamDict().Set("tex0", Value::Number(1e-6, Dim::Length())).Set("tex1", Value::Ref("a")));
    EXPECT_FALSE(bad.Build<Texture>("m"));
    EXPECT_NE(bad.FirstError().find("'tex1' is an angle, but 'tex0' is a length"), std::string::npos) << bad.FirstError();
}

// A schema with an angle parameter (as a grating's groove direction would have), read through
// the accessor.
const Schema &AngleSchema() {
    static const Schema s{"material", "test", "", {P::FloatTexture("groove_angle", "", Dim::Angle()).Min(0).Max(Pi)}};
    return s;
}

// Validates `dict` against AngleSchema in a scene holding `textures` and reads the parameter.
std::optional<FloatTexture> ReadAngle(ParamDict dict, MiniScene &s, std::string *error) {
    BuildContext ctx(s.desc, s.diag);
    if (!dict.Validate(AngleSchema(), s.diag)) {
        *error = s.LastError();
        return std::nullopt;
    }
    try {
        return ctx.GetFloatTexture(dict, "groove_angle");
    } catch (const Error &e) {
        *error = std::string(e.what());
        return std::nullopt;
    }
}

TEST(FloatTextureAccessor, ANumberIsAConstant) {
    MiniScene s;
    std::string err;
    auto t = ReadAngle(ParamDict().Set("groove_angle", Value::Number(0.3, Dim::Angle())), s, &err);
    ASSERT_TRUE(t) << err;
    EXPECT_TRUE(t->IsConstant());
    EXPECT_EQ(t->GetDim(), Dim::Angle());
    EXPECT_EQ(t->Eval(AtUv(0.7, 0.1)), 0.3);
    EXPECT_EQ(t->MinValue(), 0.3);
}

TEST(FloatTextureAccessor, ATextureOfTheRightDimension) {
    MiniScene s;
    s.Add("Texture", "gradient", "ang",
          ParamDict().Set("value0", Value::Number(0, Dim::Angle())).Set("value1", Value::Number(1, Dim::Angle())));
    std::string err;
    auto t = ReadAngle(ParamDict().Set("groove_angle", Value::Ref("ang")), s, &err);
    ASSERT_TRUE(t) << err;
    EXPECT_FALSE(t->IsConstant());
    EXPECT_EQ(t->Eval(AtUv(0.4, 0)), 0.4);
}

TEST(FloatTextureAccessor, ALengthTextureWhereAnAngleIsExpected) {
    MiniScene s;
    s.Add("Texture", "constant", "thick", ParamDict().Set("value", Value::Number(300e-9, Dim::Length())));
    std::string err;
    FileLoc loc{"scene.wscene", 7, 20};
    ParamDict d;
    d.Add("groove_angle", Value::Ref("thick", loc), loc);
    EXPECT_FALSE(ReadAngle(d, s, &err));
    EXPECT_NE(err.find("'groove_angle' expects an angle (or a texture of an angle); texture '@thick' yields a length"),
              std::string::npos)
        << err;
    // The error carries the reference's location.
    try {
        BuildContext ctx(s.desc, s.diag);
        d.Validate(AngleSchema(), s.diag);
        ctx.GetFloatTexture(d, "groove_angle");
        FAIL();
    } catch (const Error &e) {
        EXPECT_EQ(e.Loc().line, 7);
        EXPECT_EQ(e.Loc().col, 20);
    }
}

TEST(FloatTextureAccessor, NumbersAndTexturesAreRangeChecked) {
    MiniScene s;
    s.Add("Texture", "gradient", "wide",
          ParamDict().Set("value0", Value::Number(0, Dim::Angle())).Set("value1", Value::Number(4, Dim::Angle())));
    std::string err;
    EXPECT_FALSE(ReadAngle(ParamDict().Set("groove_angle", Value::Number(4, Dim::Angle())), s, &err));
    EXPECT_NE(err.find("out of range"), std::string::npos) << err;
    EXPECT_FALSE(ReadAngle(ParamDict().Set("groove_angle", Value::Ref("wide")), s, &err));
    EXPECT_NE(err.find("must be ≥ 0 deg and ≤ 180 deg everywhere, but texture '@wide' ranges over"), std::string::npos)
        << err;
    EXPECT_FALSE(ReadAngle(ParamDict().Set("groove_angle", Value::Number(0.3)), s, &err));
    EXPECT_NE(err.find("expects an angle; got bare number"), std::string::npos) << err;
}

// What the integrators pass (ScatterQuery::tex = TextureEvalContext(*si, β)): the hit's fields.
TEST(ScalarTextures, ContextFromAnInteraction) {
    SurfaceInteraction si;
    si.p = Vec3(1, 2, 3);
    si.uv = Vec2(0.25, 0.75);
    si.dpdu = Vec3(0, 2, 0);
    si.dpdv = Vec3(0, 0, -1);
    si.shading = Frame::FromNormalTangent(Vec3(1, 0, 0), si.dpdu);
    const TextureEvalContext c(si, 3e-6);
    EXPECT_EQ(c.p, si.p);
    EXPECT_EQ(c.uv, si.uv);
    EXPECT_EQ(c.dpdu, si.dpdu);
    EXPECT_EQ(c.dpdv, si.dpdv);
    EXPECT_EQ(c.n, Vec3(1, 0, 0));
    EXPECT_EQ(c.beta, 3e-6);
    EXPECT_EQ(TextureEvalContext(si).beta, 0);  // a classical ray
}

// The angle → direction rule: angle 0 is dp/du projected onto the tangent plane, π/2 is n × that.
TEST(ScalarTextures, TangentAtAngleRotatesDpduAboutTheNormal) {
    const Vec3 n = Normalize(Vec3(0.2, -0.1, 1)), dpdu(2, 0.5, 0.3);
    const Frame f = Frame::FromNormalTangent(n, dpdu);
    const Vec3 s = Normalize(dpdu - Dot(dpdu, n) * n);
    EXPECT_LT(Length(f.ToWorld(TangentAtAngle(0)) - s), 1e-15);
    EXPECT_LT(Length(f.ToWorld(TangentAtAngle(Pi / 2)) - Cross(n, s)), 1e-15);
    const Vec3 d = f.ToWorld(TangentAtAngle(0.4));
    EXPECT_NEAR(Dot(d, n), 0, 1e-15);
    EXPECT_NEAR(Dot(d, s), std::cos(0.4), 1e-15);
}

// diffuse's reflectance accepts a dimensionless scalar texture (noise): the sampled weight is
// the texture's value at the hit; a length texture or one that leaves [0, 1] is an error.
TEST(ScalarTextures, DiffuseReflectanceFromNoise) {
    MiniScene s;
    s.Add("Texture", "noise", "n",
          ParamDict().Set("offset", Value::Number(0.5)).Set("amplitude", Value::Number(0.3)).Set("scale", Value::Number(0.2)))
        .Add("Material", "diffuse", "m", ParamDict().Set("reflectance", Value::Ref("n")));
    auto m = s.Build<Material>("m");
    ASSERT_TRUE(m) << s.FirstError();
    auto n = Scalar(s.Build<Texture>("n"));
    const SampledWavelengths wl = TestWavelengths(550e-9);
    ScatterQuery q;
    q.wi = Vec3(0, 0, 1);
    q.wl = &wl;
    double lo = 1, hi = 0;
    for (int i = 0; i < 50; ++i) {
        q.tex.uv = Vec2(0.37 * i, 0.11 * i);
        const double w = Prep(*m, q)->Sample(0.5, Vec2(0.5, 0.5))->weight[0];
        EXPECT_EQ(w, n->EvalScalar(q.tex));
        lo = std::min(lo, w), hi = std::max(hi, w);
    }
    EXPECT_GT(hi - lo, 0.1);

    MiniScene len;
    len.Add("Texture", "constant", "t", ParamDict().Set("value", Value::Number(1e-7, Dim::Length())))
        .Add("Material", "diffuse", "m", ParamDict().Set("reflectance", Value::Ref("t")));
    EXPECT_FALSE(len.Build<Material>("m"));
    EXPECT_NE(len.FirstError().find("'reflectance' expects a spectrum or a dimensionless texture; texture '@t' "
                                    "yields a length"),
              std::string::npos)
        << len.FirstError();

    MiniScene wide;
    wide.Add("Texture", "noise", "n", ParamDict().Set("offset", Value::Number(0.5)).Set("amplitude", Value::Number(0.8)))
        .Add("Material", "diffuse", "m", ParamDict().Set("texture", Value::Ref("n")));
    EXPECT_FALSE(wide.Build<Material>("m"));
    EXPECT_NE(wide.FirstError().find("'texture' must be ≥ 0 and ≤ 1 everywhere"), std::string::npos)
        << wide.FirstError();
}

}  // namespace
}  // namespace phasor::test
