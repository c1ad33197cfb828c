// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <set>

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

}  // namespace
}  // namespace phasor
