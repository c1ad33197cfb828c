// SPDX-License-Identifier: Apache-2.0
// The free-space diffraction lobe under the kernel contract (docs/kernels.md's checks, applied to
// integrators/fsd/fsd_lobe.h): χ² of Sample against Pdf, the pdf's integral, weight = Eval·cos/pdf,
// energy (the flux of the lobe is the open part of the GR's |ψ|², Parseval: FSD never creates
// light) and finiteness — over presets made of meshes: a straight edge, a wedge (a box's corner),
// a circular hole in a plate and a star-shaped hole (a polygon aperture). Each statistical check is
// shown to reject a deliberately biased input.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "fsd_test_util.h"
#include "integrators/fsd/fsd_geometry.h"
#include "integrators/fsd/fsd_lobe.h"
#include "parser/parser.h"
#include "support/stats.h"

namespace phasor {
namespace {

using namespace test;

constexpr double Um = 1e-6;
constexpr double Lambda = 0.5e-6;

struct Preset {
    std::string name, shapes;
    Vec3 origin;  // of the GR (µm), travelling towards +z
    double rho;
};

std::vector<Preset> Presets() {
    const std::string edge = Box(Vec3(-200, -200, 0), Vec3(0, 200, 2)).Shape("edge");
    const std::string wedge = Box(Vec3(-200, -200, 0), Vec3(0, 0, 2)).Shape("wedge");
    const std::string hole = HolePlate(400, 0, 48, [](double) { return 4.0; }).Shape("hole");
    const std::string star = HolePlate(400, 0, 40, Star(7, 3, 5)).Shape("star");
    std::vector<Preset> p;
    for (double rho : {0.0, 3.0}) {
        p.push_back({"edge", edge, Vec3(1.5, 0, -40), rho});
        p.push_back({"wedge", wedge, Vec3(1, 1.5, -40), rho});
        p.push_back({"hole", hole, Vec3(1, -0.5, -30), rho});
        p.push_back({"star", star, Vec3(-0.5, 1, -30), rho});
    }
    return p;
}

// Family-wise level of the statistical checks (Šidák over presets × 2 tests).
double Alpha() { return SidakAlpha(0.01, int(Presets().size()) * 2); }

class FsdContract : public ::testing::TestWithParam<int> {
  protected:
    void SetUp() override {
        const Preset p = Presets()[std::size_t(GetParam())];
        scene_ = BuildFsdScene(p.shapes);
        ASSERT_TRUE(scene_);
        occ_ = std::make_unique<fsd::Occluders>(*scene_);
        st_.enabled = true;
        g_ = OneWavelengthGr(p.origin * Um, Vec3(0.01, 0.02, 1), Lambda, std::pow(2.5 * Um, 2), p.rho);
        ASSERT_EQ(fsd::FindEvent(*scene_, *occ_, g_, Infinity, nullptr, st_, &ev_), fsd::Search::Event);
        g_.Propagate(ev_.t);
        wl_ = OneWavelength(Lambda);
        lobe_ = std::make_unique<fsd::Lobe>(ev_, g_, wl_, st_);
        name_ = p.name + (p.rho != 0 ? "_curved" : "_waist");
    }
    // Direction cosines in the event frame ↔ world direction (forward hemisphere).
    Vec2 Cosines(const Vec3 &wo) const { return Vec2(Dot(wo, ev_.frame.s), Dot(wo, ev_.frame.t)); }
    Vec3 Direction(const Vec2 &c) const {
        return ev_.frame.ToWorld(Vec3(c.x, c.y, SafeSqrt(1 - LengthSquared(c))));
    }
    // Density of Sample in direction cosines (dω = d²c / cosθ).
    double PdfCosines(const Vec2 &c) const {
        const double r2 = LengthSquared(c);
        if (!(r2 < 1)) return 0;
        return lobe_->Pdf(Direction(c)) / std::sqrt(1 - r2);
    }
    // The χ² statistic's p-value for `m` draws of `draw` against Pdf on an n×n grid over
    // [−R, R]² of direction cosines plus one cell for the rest (outside, failed).
    double Chi2P(const std::function<std::optional<Vec3>(TestRng &)> &draw, long long m) const {
        const int n = 41;
        const double R = std::min(0.95 / std::sqrt(2.0), 10 * std::sqrt(0.5 * (1 + g_.rho[0] * g_.rho[0]) / g_.beta2[0]) / g_.k[0]);
        const double h = 2 * R / n;
        std::vector<double> obs(std::size_t(n * n + 1), 0), ex(obs.size(), 0);
        TestRng rng(11);
        for (long long i = 0; i < m; ++i) {
            auto wo = draw(rng);
            if (!wo) {
                obs.back() += 1;
                continue;
            }
            const Vec2 c = Cosines(*wo);
            const int a = int(std::floor((c.x + R) / h)), b = int(std::floor((c.y + R) / h));
            if (a < 0 || b < 0 || a >= n || b >= n) obs.back() += 1;
            else obs[std::size_t(a * n + b)] += 1;
        }
        // Expected counts: Simpson's rule with 4×4 sub-intervals per cell.
        constexpr int Sub = 4;
        constexpr double W[Sub + 1] = {1, 4, 2, 4, 1};
        double inside = 0;
        for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b) {
                double s = 0;
                for (int i = 0; i <= Sub; ++i)
                    for (int j = 0; j <= Sub; ++j)
                        s += W[i] * W[j] * PdfCosines(Vec2(-R + (a + double(i) / Sub) * h, -R + (b + double(j) / Sub) * h));
                const double cell = s * (h / Sub / 3) * (h / Sub / 3);
                ex[std::size_t(a * n + b)] = double(m) * cell;
                inside += cell;
            }
        ex.back() = double(m) * std::max(0.0, 1 - inside);
        const Chi2Result r = Chi2Test(obs, ex);
        return r.observedInEmptyCells > 0 ? 0.0 : r.pValue;
    }

    std::unique_ptr<Scene> scene_;
    std::unique_ptr<fsd::Occluders> occ_;
    fsd::Settings st_;
    fsd::Event ev_;
    SpectralGenRay g_;
    SampledWavelengths wl_;
    std::unique_ptr<fsd::Lobe> lobe_;
    std::string name_;
};

TEST_P(FsdContract, Chi2SamplingMatchesPdf) {
    auto draw = [&](TestRng &rng) -> std::optional<Vec3> {
        return lobe_->SampleDirection(rng.Uniform(), Vec2(rng.Uniform(), rng.Uniform()));
    };
    const double p = Chi2P(draw, 400000);
    EXPECT_GE(p, Alpha()) << name_;
}

TEST_P(FsdContract, Chi2RejectsABiasedSampler) {
    // The same test on a sampler that moves 3 % of its draws twice as far from straight through
    // must fail.
    auto draw = [&](TestRng &rng) -> std::optional<Vec3> {
        const double u0 = rng.Uniform();
        auto wo = lobe_->SampleDirection(u0, Vec2(rng.Uniform(), rng.Uniform()));
        if (!wo) return std::nullopt;
        if (rng.Uniform() < 0.03) {
            const Vec2 c = Cosines(*wo) * 2;  // pushed out into the lobe's tails
            if (LengthSquared(c) < 1) return Direction(c);
        }
        return wo;
    };
    EXPECT_LT(Chi2P(draw, 400000), Alpha()) << name_;
}

TEST_P(FsdContract, PdfIntegratesToAtMostOne) {
    // ∫ pdf dω over the forward hemisphere on a polar grid in direction cosines, graded towards
    // the lobe at the centre (r = ρ², ρ uniform): ≤ 1; equal to 1 minus the evanescent draws.
    const int nr = 400, nphi = 256;
    double total = 0, minPdf = Infinity;
    for (int i = 0; i < nr; ++i) {
        const double t0 = double(i) / nr, t1 = double(i + 1) / nr;
        const double tm = 0.5 * (t0 + t1), r = tm * tm, dr = t1 * t1 - t0 * t0;
        for (int j = 0; j < nphi; ++j) {
            const double phi = 2 * Pi * (j + 0.5) / nphi;
            const double p = PdfCosines(Vec2(r * std::cos(phi), r * std::sin(phi)));
            minPdf = std::min(minPdf, p);
            total += p * r * dr * (2 * Pi / nphi);
        }
    }
    EXPECT_GE(minPdf, 0);
    EXPECT_LE(total, 1 + 2e-3) << name_;
    // Evanescent draws of the Gaussian and Cauchy lobes are the only failures: the pdf's mass is
    // close to 1 for a footprint of several wavelengths.
    EXPECT_GE(total, 0.97) << name_;
}

TEST_P(FsdContract, SampleWeightMatchesEval) {
    TestRng rng(3);
    int n = 0;
    for (int i = 0; i < 3000; ++i) {
        auto s = lobe_->Sample(rng.Uniform(), Vec2(rng.Uniform(), rng.Uniform()));
        if (!s) continue;
        ++n;
        const double pdf = lobe_->Pdf(s->wo);
        ASSERT_NEAR(s->pdf, pdf, 1e-9 * pdf);
        const double f = lobe_->Eval(s->wo)[0];
        EXPECT_NEAR(s->weight[0], f * Dot(s->wo, ev_.frame.n) / pdf, 1e-9 * s->weight[0] + 1e-300);
    }
    EXPECT_GT(n, 2500);
}

// The lobe's flux estimated with its own sampling: mean weight and the variance of the mean.
std::pair<double, double> Flux(const fsd::Lobe &lobe, int n, uint64_t seed) {
    TestRng rng(seed);
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        auto s = lobe.Sample(rng.Uniform(), Vec2(rng.Uniform(), rng.Uniform()));
        const double w = s ? s->weight[0] : 0;
        sum += w;
        sum2 += w * w;
    }
    const double mean = sum / n;
    return {mean, (sum2 / n - mean * mean) / (n - 1)};
}

TEST_P(FsdContract, EnergyIsTheOpenPartOfTheFootprint) {
    // Parseval: ∫ f·(wo·d) dω = ∫_open |ψ|² minus the evanescent part (k⊥ > k) — never more than the
    // open mass (one-sided t-test), and within 2 % of it for footprints of several wavelengths.
    // With 2·10⁴ draws the estimate's standard deviation is ≈ 1.5 % of the open mass: the same
    // test rejects the lobe made 10 % brighter; the lower bound allows 4 standard deviations.
    const double open = 1 - ev_.coveredFraction;
    constexpr int N = 20000;
    const auto [mean, var] = Flux(*lobe_, N, 5);
    auto passes = [&](double scale) {
        const TTestResult t = MeanTTest(scale * mean, scale * scale * var, N - 1, open);
        return scale * mean <= open || 0.5 * t.pValue >= Alpha();
    };
    EXPECT_TRUE(passes(1.0)) << name_ << ": flux " << mean << " ± " << std::sqrt(var) << " > open " << open;
    EXPECT_GT(mean + 4 * std::sqrt(var), 0.98 * open) << name_ << ": flux " << mean << " ± " << std::sqrt(var) << ", open " << open;
    EXPECT_FALSE(passes(1.1)) << name_ << ": a 10 % brighter lobe passes: flux " << 1.1 * mean << " ± "
                              << 1.1 * std::sqrt(var) << ", open " << open;
}

TEST_P(FsdContract, FiniteEverywhere) {
    TestRng rng(9);
    for (int i = 0; i < 2000; ++i) {
        const double z = 2 * rng.Uniform() - 1, phi = 2 * Pi * rng.Uniform(), r = SafeSqrt(1 - z * z);
        const Vec3 wo(r * std::cos(phi), r * std::sin(phi), z);
        const double f = lobe_->Eval(wo)[0], p = lobe_->Pdf(wo);
        ASSERT_TRUE(std::isfinite(f) && f >= 0) << name_ << ": f = " << f;
        ASSERT_TRUE(std::isfinite(p) && p >= 0) << name_ << ": pdf = " << p;
        if (Dot(wo, ev_.frame.n) <= 0) {
            EXPECT_EQ(f, 0);  // only through the event plane
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Presets, FsdContract, ::testing::Range(0, int(Presets().size())),
                         [](const ::testing::TestParamInfo<int> &i) {
                             const Preset p = Presets()[std::size_t(i.param)];
                             return p.name + (p.rho != 0 ? "_curved" : "_waist");
                         });

}  // namespace
}  // namespace phasor
