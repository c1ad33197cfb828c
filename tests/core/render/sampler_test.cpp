// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <set>

#include "core/render/registry.h"
#include "core/render/sampler.h"
#include "support/stats.h"

namespace phasor {
namespace {

std::vector<double> Draw(Sampler &s, int x, int y, int index, int n) {
    s.StartPixelSample(x, y, index);
    std::vector<double> v;
    Vec2 p = s.GetPixel2D();
    v.push_back(p.x);
    v.push_back(p.y);
    for (int i = 0; i < n; ++i) v.push_back(s.Get1D());
    return v;
}

// Values depend only on (seed, pixel, sample index, dimension): the same in any order, from
// any clone, and different for another seed or pixel.
TEST(Sampler, DeterministicPerPixelSampleAndSeed) {
    for (const char *name : {"sobol", "independent"}) {
        auto a = MakeSampler(name, 42), b = MakeSampler(name, 42)->Clone(), c = MakeSampler(name, 43);
        auto first = Draw(*a, 3, 5, 7, 8);
        Draw(*a, 100, 1, 0, 3);  // interleave other work
        EXPECT_EQ(first, Draw(*a, 3, 5, 7, 8)) << name;
        EXPECT_EQ(first, Draw(*b, 3, 5, 7, 8)) << name;
        EXPECT_NE(first, Draw(*c, 3, 5, 7, 8)) << name;
        EXPECT_NE(first, Draw(*a, 4, 5, 7, 8)) << name;
        for (double v : first) {
            EXPECT_GE(v, 0.0);
            EXPECT_LT(v, 1.0);
        }
    }
}

// The first 2^2k pixel samples of the Sobol' sampler form a (0,2)-net: exactly one point in
// each of the 2^k × 2^k cells (Owen scrambling preserves the net property).
TEST(Sampler, SobolPixelSamplesAreStratified) {
    auto s = MakeSobolSampler(7);
    for (int k : {2, 3, 4}) {
        int n = 1 << (2 * k), cells = 1 << k;
        for (int pixel = 0; pixel < 4; ++pixel) {
            std::set<int> seen;
            for (int i = 0; i < n; ++i) {
                s->StartPixelSample(pixel, 2 * pixel, i);
                Vec2 p = s->GetPixel2D();
                seen.insert(int(p.x * cells) * cells + int(p.y * cells));
            }
            EXPECT_EQ((int)seen.size(), n) << "k = " << k << ", pixel " << pixel;
        }
    }
}

// Every dimension is uniform: χ² over 64 bins, pooled across pixels and dimensions.
TEST(Sampler, DimensionsAreUniform) {
    for (const char *name : {"sobol", "independent"}) {
        auto s = MakeSampler(name, 3);
        const int bins = 64, dims = 6;
        for (int d = 0; d < dims; ++d) {
            std::vector<double> obs(bins, 0), exp(bins, 0);
            int n = 0;
            for (int px = 0; px < 40; ++px)
                for (int i = 0; i < 64; ++i) {
                    s->StartPixelSample(px, 1, i);
                    double v = 0;
                    for (int k = 0; k <= d; ++k) v = s->Get1D();
                    obs[std::min(bins - 1, int(v * bins))] += 1;
                    ++n;
                }
            for (double &e : exp) e = double(n) / bins;
            auto r = test::Chi2Test(obs, exp);
            EXPECT_GT(r.pValue, test::SidakAlpha(0.01, 2 * dims)) << name << " dim " << d << ": " << r.ToString();
        }
    }
}

// The samplers are plug-ins (src/samplers/), and their values are those of the implementation
// before they became plug-ins, bit for bit: renders do not change. The values below were printed
// (%a) by the previous code (commit 2f642ab's core/render/sampler.cpp) for seed 42.
TEST(Sampler, PluginsKeepTheirSequences) {
    struct Expected {
        const char *name;
        int x, y, index;
        double v[5];  // GetPixel2D, Get1D, Get2D
    };
    const Expected expected[] = {
        {"sobol", 0, 0, 0, {0x1.5a115ca8p-3, 0x1.eced8ap-6, 0x1.1fa910e8p-2, 0x1.aec53p-7, 0x1.e0c53cap-1}},
        {"sobol", 3, 7, 5, {0x1.26e12f4p-5, 0x1.68e624a8p-2, 0x1.751265bp-2, 0x1.3fcac684p-2, 0x1.3f718fecp-1}},
        {"sobol", 1000, 2, 1023, {0x1.42d8616p-3, 0x1.60546f6cp-1, 0x1.f896ae38p-1, 0x1.8d9f972p-3, 0x1.47d5f18ep-1}},
        {"independent", 0, 0, 0,
         {0x1.d1f55785b1b64p-3, 0x1.23c6ab00b3c2ep-2, 0x1.8f4f14a752468p-1, 0x1.e6a30d9353a84p-3, 0x1.51ff41cdb7378p-4}},
        {"independent", 3, 7, 5,
         {0x1.36fc0bef3537p-3, 0x1.0cc2548592be1p-1, 0x1.96578d92f299dp-1, 0x1.4f783b60a6c5ap-1, 0x1.1c592264ab15fp-1}},
        {"independent", 1000, 2, 1023,
         {0x1.a81d012847e3ep-1, 0x1.6e5cdcbe86c1p-1, 0x1.ed7fb336d773ap-1, 0x1.09bab7ee7223ep-1, 0x1.caba426792d7ep-2}},
    };
    for (const Expected &e : expected) {
        auto s = MakeSampler(e.name, 42);
        ASSERT_TRUE(s) << e.name;
        s->StartPixelSample(e.x, e.y, e.index);
        const Vec2 p = s->GetPixel2D();
        const double a = s->Get1D();
        const Vec2 b = s->Get2D();
        const double got[5] = {p.x, p.y, a, b.x, b.y};
        for (int k = 0; k < 5; ++k) EXPECT_EQ(got[k], e.v[k]) << e.name << " pixel (" << e.x << ", " << e.y << ") #" << k;
    }
}

TEST(Sampler, AFamilyWithTheDefaultSobol) {
    ASSERT_TRUE(Registry<Sampler>::Default());
    EXPECT_STREQ(Registry<Sampler>::Default()->name, "sobol");
    for (const auto &e : Registry<Sampler>::Entries()) {
        auto s = MakeSampler(e.name, 1);
        ASSERT_TRUE(s) << e.name;
        EXPECT_EQ(s->Name(), e.name);
        EXPECT_EQ(s->Seed(), 1u);
        EXPECT_EQ(s->Clone()->Seed(), 1u);
    }
    EXPECT_FALSE(MakeSampler("halton", 1));
}

}  // namespace
}  // namespace phasor
