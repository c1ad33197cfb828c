// SPDX-License-Identifier: Apache-2.0
// SampledWavelengths, Spectrum::Sample, EvalEmission (line vs continuum), ConstantSpectrum.
#include <gtest/gtest.h>

#include "core/spectrum/spectrum.h"
#include "core/spectrum/test_spectra.h"

namespace phasor {
namespace {

SampledWavelengths Continuous(double l0) {
    SampledWavelengths wl;
    for (int i = 0; i < NumWavelengths; ++i) {
        wl.lambda[i] = l0 + i * 50e-9;
        wl.pdf[i] = 1e6 * (i + 1);
    }
    return wl;
}

SampledWavelengths Delta(double l, double p) {
    SampledWavelengths wl;
    wl.delta = true;
    wl.lambda.fill(l);
    wl.pdf[0] = p;
    return wl;
}

TEST(SampledWavelengths, TerminateSecondaryKeepsTheHeroUnbiased) {
    SampledWavelengths wl = Continuous(400e-9);
    EXPECT_FALSE(wl.SecondaryTerminated());
    EXPECT_EQ(wl.Count(), NumWavelengths);
    wl.TerminateSecondary();
    EXPECT_TRUE(wl.SecondaryTerminated());
    // The film averages over NumWavelengths entries, so the hero's pdf is divided by that count.
    EXPECT_DOUBLE_EQ(wl.pdf[0], 1e6 / NumWavelengths);
    for (int i = 1; i < NumWavelengths; ++i) EXPECT_EQ(wl.pdf[i], 0.0);
    EXPECT_DOUBLE_EQ(wl.lambda[0], 400e-9);
    // Idempotent.
    wl.TerminateSecondary();
    EXPECT_DOUBLE_EQ(wl.pdf[0], 1e6 / NumWavelengths);
}

TEST(SampledWavelengths, DeltaSampleIsAlreadyTerminated) {
    SampledWavelengths wl = Delta(1e-6, 0.25);
    EXPECT_TRUE(wl.SecondaryTerminated());
    EXPECT_EQ(wl.Count(), 1);
    wl.TerminateSecondary();
    EXPECT_EQ(wl.pdf[0], 0.25);
}

TEST(EvalEmission, LineOnlyAtItsDeltaSample) {
    test::TestLine line(632.8e-9, 3.0);
    SampledSpectrum s = EvalEmission(line, Delta(632.8e-9, 0.5));
    EXPECT_EQ(s[0], 3.0);
    EXPECT_TRUE(EvalEmission(line, Delta(532e-9, 0.5)).IsZero());  // another line
    SampledWavelengths wl = Continuous(632.8e-9);                  // continuous, even if equal
    EXPECT_TRUE(EvalEmission(line, wl).IsZero());
}

TEST(EvalEmission, ContinuumOnlyAtContinuousSamples) {
    ConstantSpectrum c(2.5);
    EXPECT_TRUE(EvalEmission(c, Delta(500e-9, 1)).IsZero());
    SampledSpectrum s = EvalEmission(c, Continuous(400e-9));
    for (int i = 0; i < NumWavelengths; ++i) EXPECT_EQ(s[i], 2.5);
}

TEST(Spectrum, SampleEvaluatesTheCarriedWavelengths) {
    test::TestGaussian g(500e-9, 20e-9, 2);
    SampledWavelengths wl = Continuous(450e-9);
    SampledSpectrum s = g.Sample(wl);
    for (int i = 0; i < NumWavelengths; ++i) EXPECT_DOUBLE_EQ(s[i], g.Eval(wl.lambda[i]));
    // A delta sample carries one wavelength.
    SampledSpectrum d = g.Sample(Delta(500e-9, 1));
    EXPECT_DOUBLE_EQ(d[0], 2.0);
    for (int i = 1; i < NumWavelengths; ++i) EXPECT_EQ(d[i], 0.0);
}

TEST(ConstantSpectrum, Basics) {
    ConstantSpectrum c(0.5);
    EXPECT_EQ(c.Eval(1e-3), 0.5);
    EXPECT_EQ(c.MaxValue(), 0.5);
    EXPECT_EQ(c.Support().first, 0.0);
    EXPECT_TRUE(std::isinf(c.Support().second));
    EXPECT_FALSE(c.LineWavelength());
    EXPECT_EQ(c.ToString(), "constant(0.5)");
}

}  // namespace
}  // namespace phasor
