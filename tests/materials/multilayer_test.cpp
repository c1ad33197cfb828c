// SPDX-License-Identifier: Apache-2.0
// `multilayer`: one layer is a thin_film; N quarter-wave pairs reflect the closed-form peak
// (Macleod §5.2) to 1e-9; the two ways of writing a stack agree; energy; bad input.
#include <gtest/gtest.h>

#include "stack_kernel_test_util.h"

namespace phasor::test {
namespace {

ParamDict Pairs(double na, double nb, double daNm, double dbNm, int pairs, Value substrate) {
    ParamDict p;
    p.Set("n_a", Value::Number(na))
        .Set("n_b", Value::Number(nb))
        .Set("d_a", Nm(daNm))
        .Set("d_b", Nm(dbNm))
        .Set("pairs", Value::Integer(pairs))
        .Set("substrate_ior", std::move(substrate));
    return p;
}

TEST(Multilayer, OneLayerIsAThinFilm) {
    // The same film written as a one-layer stack: identical kernels, coherent and incoherent, from
    // above and below (glass) and on a metal.
    for (const Value &sub : {Value::String("Cu"), Value::Number(1.5)}) {
        ParamDict ml;
        ml.Set("layers", Value::List({LayerCall(Value::ComplexNumber(Complex(2.4, 0.05)), 135)})).Set("substrate_ior", sub);
        ParamDict tf;
        tf.Set("ior", Value::ComplexNumber(Complex(2.4, 0.05))).Set("thickness", Nm(135)).Set("substrate_ior", sub);
        auto a = Kernel("multilayer", ml), b = Kernel("thin_film", tf);
        ASSERT_TRUE(a && b);
        for (double lambda = 400e-9; lambda <= 700e-9; lambda += 50e-9)
            for (double c : {1.0, 0.6, 0.1, -0.5})
                for (bool ray : {false, true}) {
                    const OneWave w(lambda, c, 0.9, ray);
                    const Listed la = List(*a, w), lb = List(*b, w);
                    EXPECT_EQ(la.R, lb.R);  // the same code path: bit-identical
                    EXPECT_EQ(la.T, lb.T);
                    EXPECT_EQ(la.count, lb.count);
                }
    }
}

TEST(Multilayer, QuarterWavePairsReflectTheClosedFormPeak) {
    // N pairs (a, b) of quarter-wave layers (n d = λ₀/4) at normal incidence: each layer maps the
    // admittance Y below it to n²/Y, so the stack (a on top) has Y = (n_a/n_b)^{2N}·n_s and
    //   R(λ₀) = ((1 − (n_s/n₀)(n_a/n_b)^{2N}) / (1 + (n_s/n₀)(n_a/n_b)^{2N}))²;
    // with b on top, ((1 − (n_s/n₀)(n_b/n_a)^{2N}) / (1 + …))² (Macleod, Thin-Film Optical Filters
    // §5.2; the form). Chitin-like 1.55/1.70 pairs at 530 nm (theory §4.5) on 1.52 glass.
    const double n0 = 1, na = 1.55, nb = 1.70, ns = 1.52, lambda0 = 530e-9;
    const double da = lambda0 / (4 * na) * 1e9, db = lambda0 / (4 * nb) * 1e9;
    for (int pairs : {1, 3, 8, 15}) {
        auto aTop = Kernel("multilayer", Pairs(na, nb, da, db, pairs, Value::Number(ns)));
        auto bTop = Kernel("multilayer", Pairs(nb, na, db, da, pairs, Value::Number(ns)));
        ASSERT_TRUE(aTop && bTop);
        const double xa = ns / n0 * std::pow(na / nb, 2 * pairs), xb = ns / n0 * std::pow(nb / na, 2 * pairs);
        const double ra = Sqr((1 - xa) / (1 + xa)), rb = Sqr((1 - xb) / (1 + xb));
        EXPECT_NEAR(List(*aTop, OneWave(lambda0, 1.0)).R, ra, 1e-9) << pairs;
        EXPECT_NEAR(List(*bTop, OneWave(lambda0, 1.0)).R, rb, 1e-9) << pairs;
        // The peak: neighbouring wavelengths reflect less (for N ≥ 3 the band is narrow enough to
        // see it 10 nm away).
        if (pairs >= 3) {
            EXPECT_LT(List(*bTop, OneWave(lambda0 - 10e-9, 1.0)).R, rb);
            EXPECT_LT(List(*bTop, OneWave(lambda0 + 10e-9, 1.0)).R, rb);
        }
    }
    // 15 pairs of this weak contrast already reflect > 80 %, the beetle's metallic green.
    auto beetle = Kernel("multilayer", Pairs(nb, na, db, da, 15, Value::Number(ns)));
    EXPECT_GT(List(*beetle, OneWave(lambda0, 1.0)).R, 0.8);
}

TEST(Multilayer, PairsEqualTheWrittenOutList) {
    auto pairs = Kernel("multilayer", Pairs(1.38, 2.3, 100, 60, 3, Value::String("BK7")));
    ParamDict list;
    std::vector<Value> layers;
    for (int k = 0; k < 3; ++k) {
        layers.push_back(LayerCall(Value::Number(1.38), 100));
        layers.push_back(LayerCall(Value::Number(2.3), 60));
    }
    list.Set("layers", Value::List(layers)).Set("substrate_ior", Value::String("BK7"));
    auto written = Kernel("multilayer", list);
    ASSERT_TRUE(pairs && written);
    ASSERT_EQ(LayersOf(*pairs)->layers.size(), 6u);
    for (double c : {0.9, 0.3, -0.7}) {
        const OneWave w(480e-9, c);
        EXPECT_EQ(List(*pairs, w).R, List(*written, w).R);
        EXPECT_EQ(List(*pairs, w).T, List(*written, w).T);
    }
}

TEST(Multilayer, LosslessStacksConserveEnergyInBothRegimes) {
    auto stack = Kernel("multilayer", Pairs(1.38, 2.3, 97, 61, 6, Value::String("BK7")));
    ASSERT_TRUE(stack);
    for (double lambda = 400e-9; lambda <= 700e-9; lambda += 43e-9)
        for (double c : {1.0, 0.7, 0.25, 0.03, -0.3, -0.95})
            for (bool ray : {false, true}) {
                const Listed l = List(*stack, OneWave(lambda, c, 2.0, ray));
                EXPECT_NEAR(l.R + l.T, 1, 1e-12) << lambda << " " << c << " " << ray;
            }
}

std::string BuildError(const ParamDict &p) {
    Diagnostics diag;
    auto m = BuildMaterial("multilayer", p, diag);
    std::ostringstream os;
    diag.Print(os);
    EXPECT_FALSE(m);
    EXPECT_TRUE(diag.HasErrors());
    return os.str();
}

TEST(Multilayer, BadInputIsAnError) {
    auto has = [](const std::string &all, const std::string &text) { return all.find(text) != std::string::npos; };
    EXPECT_TRUE(has(BuildError(ParamDict().Set("layers", Value::List({}))), "'layers' is empty"));
    EXPECT_TRUE(has(BuildError(ParamDict()), "multilayer needs 'layers'"));
    ParamDict both = Pairs(1.4, 2.0, 90, 60, 3, Value::Number(1.5));
    both.Set("layers", Value::List({LayerCall(Value::Number(1.4), 90)}));
    EXPECT_TRUE(has(BuildError(both), "give either 'layers' or the repeated pair"));
    ParamDict partial;
    partial.Set("n_a", Value::Number(1.4)).Set("n_b", Value::Number(2.0)).Set("d_a", Nm(90)).Set("pairs", Value::Integer(3));
    EXPECT_TRUE(has(BuildError(partial), "missing 'd_b'"));
    EXPECT_TRUE(has(BuildError(ParamDict().Set("layers", Value::List({LayerCall(Value::Number(1.4), -5)}))), "out of range"));
    EXPECT_TRUE(has(BuildError(ParamDict().Set("layers", Value::List({LayerCall(Value::String("unobtainium"), 5)}))),
                    "unknown material \"unobtainium\""));
    EXPECT_TRUE(has(BuildError(Pairs(1.4, 2.0, 90, 60, 0, Value::Number(1.5))), "'pairs' is out of range"));
    EXPECT_TRUE(has(BuildError(Pairs(1.4, 2.0, 90, 60, 129, Value::Number(1.5))), "'pairs' is out of range"));
}

}  // namespace
}  // namespace phasor::test
