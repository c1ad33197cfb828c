// SPDX-License-Identifier: Apache-2.0
// Quadrature over angular ensembles (core/numerics/ensemble_quadrature.h): the Gauss–Hermite rules
// (exactness, the A&S 25.4.46 remainder), the node counts, and EnsembleRule on Gaussian profiles,
// discs and windows against closed forms (a Gaussian's characteristic function, the disc's
// 2J₁(v)/v, a chirp's complex Gaussian integral) and against brute-force polar quadrature for a
// window straddling a disc's edge. Every case asserts the error bound the header states (tol of the
// integrand's sup) and shows that a rule built for a smaller rate than the true one misses it.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <complex>
#include <cstdio>

#include "core/math.h"
#include "core/numerics/ensemble_quadrature.h"
#include "core/numerics/gauss_legendre.h"

namespace phasor {
namespace {

TEST(GaussHermite, IsExactForPolynomialsOfDegreeUpTo2nMinus1) {
    // ∫ t^k e^{−t²} dt = Γ((k+1)/2) for even k, 0 for odd k. Relative 1e-12 (the moments grow as
    // (k/2)!, the sums stay well conditioned: the nodes are symmetric).
    for (int n = 1; n <= 40; ++n) {
        const GaussHermiteRule &r = GaussHermite(n);
        ASSERT_EQ(r.n, n);
        for (int k = 0; k <= 2 * n - 1; ++k) {
            double s = 0, size = 0;  // size: Σ|w t^k|, the scale of the sum's rounding
            for (int i = 0; i < n; ++i) {
                s += r.w[i] * std::pow(r.x[i], k);
                size += r.w[i] * std::abs(std::pow(r.x[i], k));
            }
            const double exact = k % 2 ? 0.0 : std::tgamma((k + 1) / 2.0);
            EXPECT_NEAR(s, exact, 1e-13 * size) << "n = " << n << ", t^" << k;
        }
    }
    const GaussHermiteRule &r64 = GaussHermite(64);
    double sum = 0;
    for (int i = 0; i < 64; ++i) sum += r64.w[i];
    EXPECT_NEAR(sum, std::sqrt(Pi), 1e-13);
}

TEST(GaussHermite, MeetsItsRemainderBoundOnOscillations) {
    // cos(b t): ∫ = √π e^{−b²/4}; rate b. The node count from GaussHermiteNodesFor keeps the error
    // below tol·√π; one node fewer does not, for b where it matters.
    const double tol = 1e-6;
    int rejected = 0;
    for (double b : {0.01, 0.3, 1.0, 3.0, 8.0}) {
        const int n = GaussHermiteNodesFor(b, tol);
        ASSERT_LE(n, MaxGaussHermiteNodes);
        auto rule = [&](int m) {
            const GaussHermiteRule &r = GaussHermite(m);
            double s = 0;
            for (int i = 0; i < m; ++i) s += r.w[i] * std::cos(b * r.x[i]);
            return std::abs(s - std::sqrt(Pi) * std::exp(-b * b / 4)) / std::sqrt(Pi);
        };
        EXPECT_LE(rule(n), tol) << "b = " << b << ", n = " << n;
        if (n > 2 && rule(n / 2) > tol) ++rejected;
        std::printf("MEASURED Gauss-Hermite cos(%g t): n = %d, error %.2g (n/2: %.2g)\n", b, n, rule(n),
                    n > 1 ? rule(n / 2) : 0.0);
    }
    EXPECT_GE(rejected, 3) << "half the nodes must miss the bound where more than two are needed";
    EXPECT_EQ(GaussHermiteNodesFor(15.0, tol), MaxGaussHermiteNodes + 1) << "beyond 64 nodes the caller falls back";
}

double Phi(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }
double SmallPhi(double x) { return std::exp(-0.5 * x * x) / std::sqrt(2 * Pi); }

TEST(TruncatedNormalRule, IsExactForPolynomialsOfDegreeUpTo2nMinus1) {
    // Over ±6 the recurrence coefficients are the normal's (β_k = k) but for the truncation's effect
    // on high moments: the bound asks for Gauss–Hermite's node count.
    std::vector<std::pair<double, double>> rule;
    ASSERT_TRUE(TruncatedNormalRule(-6, 6, 1.0, 1e-6, rule));
    EXPECT_EQ(int(rule.size()), GaussHermiteNodesFor(std::sqrt(2.0) * 1.0, 1e-6));
    // Truncated: exact for x^k, k ≤ 2n − 1, against the moments M_k = (k − 1)·M_{k−2} +
    // a^{k−1}φ(a) − b^{k−1}φ(b), M_0 = Φ(b) − Φ(a), M_1 = φ(a) − φ(b).
    // (Short chords about 0, as at a disc's edge, take fewer discretisation points than the longest.)
    for (const auto &[a, b] : {std::pair{-6.0, 0.5}, {-1.0, 2.0}, {-11.0, -5.0}, {0.2, 0.4}, {-3.0, 3.0}, {-6.0, 6.0},
                               {-0.3, 0.3}, {-1.5, 1.5}, {-4.0, 4.0}, {-9.0, -0.5}}) {
        for (const double rate : {0.05, 0.5, 2.0}) {
            ASSERT_TRUE(TruncatedNormalRule(a, b, rate, 1e-6, rule)) << a << " " << b << " " << rate;
            const int m = int(rule.size());
            std::vector<double> moment(std::size_t(2 * m), 0.0);
            for (int k = 0; k < 2 * m; ++k) {
                if (k == 0) moment[0] = Phi(b) - Phi(a);
                else if (k == 1) moment[1] = SmallPhi(a) - SmallPhi(b);
                else
                    moment[std::size_t(k)] = (k - 1) * moment[std::size_t(k - 2)] + std::pow(a, k - 1) * SmallPhi(a) -
                                             std::pow(b, k - 1) * SmallPhi(b);
                double got = 0;
                for (const auto &[x, w] : rule) got += w * std::pow(x, k);
                const double scale = moment[0] * std::pow(std::max(std::abs(a), std::abs(b)), k);
                EXPECT_NEAR(got, moment[std::size_t(k)], 1e-9 * scale) << "[" << a << ", " << b << "], x^" << k;
            }
        }
    }
}

TEST(TruncatedNormalRule, MeetsItsRemainderBound) {
    // cos(ω x) averaged over the truncated normal, against 40 panels × 32 Gauss–Legendre nodes: within
    // tol of the mass-normalised average at the node count the bound asks for; a rule built for a
    // third of the rate misses it somewhere.
    const double tol = 1e-6;
    int missed = 0;
    for (const auto &[a, b] : {std::pair{-6.0, 1.0}, {-2.0, 0.0}, {-11.0, -5.0}, {-6.0, 6.0}})
        for (const double omega : {0.3, 1.0, 2.0}) {
            double ref = 0, mass = 0;
            const double width = (b - a) / 40;
            for (int p = 0; p < 40; ++p) {
                const double lo = a + p * width;
                ref += IntegrateGaussLegendre([&](double x) { return SmallPhi(x) * std::cos(omega * x); }, lo, lo + width, 32);
                mass += IntegrateGaussLegendre(SmallPhi, lo, lo + width, 32);
            }
            auto average = [&](double rate) {
                std::vector<std::pair<double, double>> rule;
                if (!TruncatedNormalRule(a, b, rate, tol, rule)) return Infinity;
                double s = 0, w = 0;
                for (const auto &[x, wt] : rule) {
                    s += wt * std::cos(omega * x);
                    w += wt;
                }
                EXPECT_NEAR(w, mass, 1e-12 * mass);
                return std::abs(s / w - ref / mass);
            };
            EXPECT_LE(average(omega), tol) << "[" << a << ", " << b << "], ω = " << omega;
            if (average(omega / 3) > tol) ++missed;
        }
    EXPECT_GE(missed, 3) << "a rule for a third of the rate must miss the bound";
    std::vector<std::pair<double, double>> rule;
    EXPECT_FALSE(TruncatedNormalRule(-6, 6, 8.0, tol, rule)) << "more than 12 nodes: the caller falls back";
    EXPECT_TRUE(rule.empty());
    EXPECT_FALSE(TruncatedNormalRule(-7, 7, 0.1, tol, rule)) << "beyond 12 units the discretisation is not resolved";
    EXPECT_FALSE(TruncatedNormalRule(1, 1, 0.1, tol, rule)) << "an empty interval";
}

TEST(GaussLegendre, NodeCountMeetsThePhaseBound) {
    const double tol = 1e-6;
    for (double phase : {0.0, 0.5, 3.0, 20.0, 60.0}) {
        const int n = GaussLegendreNodesFor(phase, tol);
        ASSERT_LE(n, MaxGaussLegendreNodes);
        // ∫_{−1}^{1} cos(Φ t/2) dt = 4 sin(Φ/2)/Φ.
        const double exact = phase > 0 ? 4 * std::sin(phase / 2) / phase : 2.0;
        const double got = IntegrateGaussLegendre([&](double t) { return std::cos(phase * t / 2); }, -1, 1, n);
        EXPECT_LE(std::abs(got - exact), 2 * tol) << "Φ = " << phase << ", n = " << n;
    }
}

// ---- ensembles --------------------------------------------------------------------------------------

using C = std::complex<double>;

// Σ w g / Σ w over a rule for g(p) = e^{i(k·p + chirp·|p|²)}.
C RuleAverage(const std::vector<EnsembleNode> &nodes, Vec2 k, double chirp) {
    C s = 0;
    double norm = 0;
    for (const EnsembleNode &n : nodes) {
        s += n.w * std::exp(C(0, Dot(k, n.p) + chirp * LengthSquared(n.p)));
        norm += n.w;
    }
    return s / norm;
}

// Rates of e^{i(k·p + chirp·|p|²)} over a box: |k| plus the chirp's derivative at the box's far
// corner plus √(2|chirp|) (its second derivative as a rate).
Vec2 ChirpRates(const EnsembleBox &b, Vec2 k, double chirp) {
    const double fx = std::max(std::abs(b.lo.x), std::abs(b.hi.x)), fy = std::max(std::abs(b.lo.y), std::abs(b.hi.y));
    const double c2 = std::sqrt(2 * std::abs(chirp));
    return Vec2(std::abs(k.x) + 2 * std::abs(chirp) * fx + c2, std::abs(k.y) + 2 * std::abs(chirp) * fy + c2);
}

TEST(EnsembleRule, GaussianProfileMatchesClosedForms) {
    const double tol = 1e-6;
    for (double var : {1e-6, 1e-4, 1e-2})
        for (double kScale : {0.0, 1.0, 5.0, 10.0})
            for (double chirpScale : {0.0, 2.0}) {
                const double sigma = std::sqrt(var);
                const Vec2 k = Vec2(1.0, 0.3) * (kScale / sigma);
                const double chirp = chirpScale / var;
                std::vector<EnsembleNode> nodes;
                EnsembleShape shape;
                shape.profile = EnsembleShape::Profile::Gaussian;
                shape.variance = var;
                const EnsembleRuleInfo info =
                    BuildEnsembleRule(shape, [&](const EnsembleBox &b) { return ChirpRates(b, k, chirp); }, tol, nodes);
                // ∫N(x; 0, v)e^{i(kx + cx²)} dx = (1 − 2icv)^{−½}·exp(−k²v/(2(1 − 2icv))), per axis.
                const C a = 1.0 - C(0, 2 * chirp * var);
                const C exact = std::exp(-(k.x * k.x + k.y * k.y) * var / (2.0 * a)) / a;
                const C got = RuleAverage(nodes, k, chirp);
                EXPECT_FALSE(info.capped);
                EXPECT_LE(std::abs(got - exact), 3 * tol) << "v = " << var << ", k = " << kScale << ", chirp = " << chirpScale
                                                          << ", nodes " << info.nx << "×" << info.ny;
                if (kScale == 0 && chirpScale == 0) {
                    EXPECT_EQ(nodes.size(), 1u) << "a constant needs one node";
                }
            }
}

TEST(EnsembleRule, GaussianProfileTimesWindowIsTheProductGaussian) {
    const double tol = 1e-6, var = 4e-4, wvar = 1e-4;
    const Vec2 c(0.015, -0.01), k(300, 120);
    EnsembleShape shape;
    shape.profile = EnsembleShape::Profile::Gaussian;
    shape.variance = var;
    shape.windowCentre = c;
    shape.windowVariance = wvar;
    std::vector<EnsembleNode> nodes;
    BuildEnsembleRule(shape, [&](const EnsembleBox &b) { return ChirpRates(b, k, 0); }, tol, nodes);
    // The product of N(0, v) and N(c, w) is ∝ N(c·v/(v + w), v·w/(v + w)).
    const double v = var * wvar / (var + wvar);
    const Vec2 mu = c * (var / (var + wvar));
    const C exact = std::exp(C(-0.5 * LengthSquared(k) * v, Dot(k, mu)));
    EXPECT_LE(std::abs(RuleAverage(nodes, k, 0) - exact), 3 * tol);
}

// Rates with a cheap bound (BuildEnsembleRule asks Bound first): counts the calls of the exact rates.
struct BoundedRates {
    Vec2 exact, bound;
    int *calls;
    Vec2 operator()(const EnsembleBox &) const {
        ++*calls;
        return exact;
    }
    Vec2 Bound(const EnsembleBox &) const { return bound; }
};

bool SameRule(const std::vector<EnsembleNode> &a, const std::vector<EnsembleNode> &b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (!(a[i].p == b[i].p) || a[i].w != b[i].w || a[i].q != b[i].q) return false;
    return true;
}

TEST(EnsembleRule, ACheapBoundSkipsTheRatesOnlyWhereOneNodeSuffices) {
    const double tol = 1e-4;
    EnsembleShape gaussian;
    gaussian.profile = EnsembleShape::Profile::Gaussian;
    gaussian.variance = 1e-6;  // σ = 1e-3: one Gauss–Hermite node up to a rate of ~10/σ·√tol
    EnsembleShape inside;      // a window well inside a disc: the same Gaussian path
    inside.profile = EnsembleShape::Profile::Disc;
    inside.radius = 0.05;
    inside.windowCentre = Vec2(0.01, -0.005);
    inside.windowVariance = 1e-6;
    for (const EnsembleShape &shape : {gaussian, inside}) {
        struct Case {
            Vec2 exact, bound;
            int calls;   // of the exact rates
            bool same;   // the rule is the one the exact rates alone give
        };
        const Case cases[] = {
            {Vec2(1, 2), Vec2(2, 3), 0, true},         // the bound allows one node: the rates are not asked
            {Vec2(1, 2), Vec2(1e5, 3), 1, true},       // it does not: they are
            {Vec2(1, 2), Vec2(3, 1e5), 1, true},       // (on either axis)
            {Vec2(1e4, 10), Vec2(2e4, 20), 1, true},   // the rates need more nodes
            {Vec2(1e4, 1e4), Vec2(1, 1), 0, false},    // a "bound" below the rates changes the rule (the check can fail)
        };
        for (const Case &c : cases) {
            int calls = 0;
            std::vector<EnsembleNode> withBound, exact;
            BuildEnsembleRule(shape, BoundedRates{c.exact, c.bound, &calls}, tol, withBound);
            BuildEnsembleRule(shape, [&](const EnsembleBox &) { return c.exact; }, tol, exact);
            EXPECT_EQ(calls, c.calls) << c.exact.x << " " << c.bound.x;
            EXPECT_EQ(SameRule(withBound, exact), c.same) << c.exact.x << " " << c.bound.x;
        }
    }
}

double Jinc(double v) { return v == 0 ? 1 : 2 * std::cyl_bessel_j(1, v) / v; }

TEST(EnsembleRule, DiscMatchesTheAiryPatternAndFailsWithTooSmallARate) {
    // A uniform disc: ⟨e^{ik·p}⟩ = 2J₁(|k|r)/(|k|r). The same rule built for a tenth of the rate must
    // miss (the test can fail).
    const double tol = 1e-6, r = 0.087;
    int missed = 0;
    for (double kr : {0.0, 0.5, 5.0, 30.0, 100.0}) {
        const Vec2 k = Vec2(0.9, std::sqrt(1 - 0.81)) * (kr / r);
        EnsembleShape shape;
        shape.profile = EnsembleShape::Profile::Disc;
        shape.radius = r;
        std::vector<EnsembleNode> nodes;
        const EnsembleRuleInfo info = BuildEnsembleRule(shape, [&](const EnsembleBox &b) { return ChirpRates(b, k, 0); }, tol, nodes);
        const double exact = Jinc(kr);
        const double err = std::abs(RuleAverage(nodes, k, 0) - exact);
        EXPECT_FALSE(info.capped);
        EXPECT_LE(err, 3 * tol) << "kr = " << kr << ", nodes " << info.nx << "×" << info.ny;
        std::vector<EnsembleNode> coarse;
        BuildEnsembleRule(shape, [&](const EnsembleBox &b) { return ChirpRates(b, k * 0.1, 0); }, tol, coarse);
        if (std::abs(RuleAverage(coarse, k, 0) - exact) > 10 * tol) ++missed;
        std::printf("MEASURED disc kr = %5.1f: %3d x %2d nodes, error %.2g\n", kr, info.nx, info.ny, err);
    }
    EXPECT_GE(missed, 2);
}

// A disc of radius r under a window N(·; c, s²I).
EnsembleShape DiscUnderWindow(double r, Vec2 c, double s) {
    EnsembleShape shape;
    shape.profile = EnsembleShape::Profile::Disc;
    shape.radius = r;
    shape.windowCentre = c;
    shape.windowVariance = s * s;
    return shape;
}

// Brute force: polar coordinates about the disc's centre, composite 8-point Gauss–Legendre in ρ
// (`panels` panels) and the trapezoidal rule in ψ (`npsi` points; spectral for a periodic integrand).
C PolarDisc(double r, Vec2 c, double wvar, Vec2 k, double chirp, int panels, int npsi) {
    C s = 0;
    double norm = 0;
    const GaussLegendreRule &g = GaussLegendre(8);
    for (int p = 0; p < panels; ++p)
        for (int i = 0; i < 8; ++i) {
            const double rho = (p + 0.5 + 0.5 * g.x[i]) * r / panels, wr = 0.5 * g.w[i] * r / panels;
            for (int j = 0; j < npsi; ++j) {
                const double psi = 2 * Pi * j / npsi;
                const Vec2 q(rho * std::cos(psi), rho * std::sin(psi));
                const double w = wr * rho * std::exp(-0.5 * LengthSquared(q - c) / wvar);
                s += w * std::exp(C(0, Dot(k, q) + chirp * LengthSquared(q)));
                norm += w;
            }
        }
    return s / norm;
}

TEST(EnsembleRule, DiscTimesWindowInsideStraddlingAndOutside) {
    const double tol = 1e-6, r = 0.05, s = 0.008;
    const Vec2 k(400, 60);
    const double chirp = 300;
    for (double offset : {0.0, 0.02, 0.045, 0.05, 0.06, 0.1}) {
        const EnsembleShape shape = DiscUnderWindow(r, Vec2(offset * 0.8, offset * 0.6), s);
        std::vector<EnsembleNode> nodes;
        const EnsembleRuleInfo info =
            BuildEnsembleRule(shape, [&](const EnsembleBox &b) { return ChirpRates(b, k, chirp); }, tol, nodes);
        if (offset >= 0.1) {
            EXPECT_FALSE(info.overlap);
            EXPECT_EQ(nodes.size(), 1u);
            continue;
        }
        // 100 panels × 8 in ρ and 2048 in ψ resolve the window (s = 8e-3) and the phase (≤ 25 rad over
        // the disc) far below 1e-9 (checked: halving both changes the reference by < 1e-12).
        const C ref = PolarDisc(r, shape.windowCentre, s * s, k, chirp, 100, 2048);
        const C got = RuleAverage(nodes, k, chirp);
        EXPECT_FALSE(info.capped);
        EXPECT_LE(std::abs(got - ref), 3 * tol) << "offset = " << offset << ", nodes " << info.nx << "×" << info.ny;
        std::printf("MEASURED disc x window, offset %.3f: %3d x %2d nodes, |rule − brute force| = %.2g\n", offset, info.nx,
                    info.ny, std::abs(got - ref));
    }
}

TEST(EnsembleRule, NarrowWindowAtADiscsEdgeMeetsTheBound) {
    // A generalized ray's narrow window (s ≪ r) at the edge of a wide source (a lamp's disc, a sky),
    // centred inside, on and outside the edge: within 3·tol of brute force. A centre 5s outside
    // leaves only the window's tail over the disc, whose mass beyond d − 6s is not negligible beside
    // the overlap's (a rule over ±6s about the centre missed it by 4.8e-4). Gauss rules of the
    // (truncated) normal, radially and across, take a few nodes per axis where Gauss–Legendre with the
    // Gaussian as a factor took 16–32.
    const double tol = 1e-6, s = 0.002;
    const Vec2 k(40, 30);
    const double chirp = 30;
    for (const double r : {0.05, 0.2})
        for (const double offset : {r - 4 * s, r - s, r, r + 2 * s, r + 5 * s}) {
            const EnsembleShape shape = DiscUnderWindow(r, Vec2(offset * 0.6, -offset * 0.8), s);
            std::vector<EnsembleNode> nodes;
            const EnsembleRuleInfo info =
                BuildEnsembleRule(shape, [&](const EnsembleBox &b) { return ChirpRates(b, k, chirp); }, tol, nodes);
            // 400 panels × 8 in ρ resolve the window (0.06–0.25 s per panel) and 4096 in ψ (≤ 0.15 s of arc);
            // 1600 × 16384 changes the reference by < 1e-9.
            const C ref = PolarDisc(r, shape.windowCentre, s * s, k, chirp, 400, 4096);
            const C got = RuleAverage(nodes, k, chirp);
            EXPECT_FALSE(info.capped);
            EXPECT_LE(std::abs(got - ref), 3 * tol) << "r = " << r << ", offset = " << offset;
            // Gauss–Legendre with the Gaussian as a factor took 150–270 nodes here.
            EXPECT_LE(nodes.size(), 60u) << "r = " << r << ", offset = " << offset;
            std::printf("MEASURED narrow window at a disc's edge, r %.2f, offset %.4f: %zu nodes (%d x %d), |rule − "
                        "brute force| = %.2g\n",
                        r, offset, nodes.size(), info.nx, info.ny, std::abs(got - ref));
        }
}

// Brute force over the part of a disc a window N(·; c, s²I) reaches: polar coordinates about the
// disc's centre, ρ ∈ [max(0, min(|c|, r) − 8s), r] by composite 8-point Gauss–Legendre (`panels`),
// ψ within ±1.2·asin(8s/ρ) of c's direction (or the whole circle) by the midpoint rule (`npsi`;
// spectral: the integrand and its derivatives vanish at both ends to e^{−32}). Calls
// visit(ψ from c's direction, point, weight with the window's density) and returns Σ weights.
template <typename Visit>
double ForPolarWindowOnDisc(double r, Vec2 c, double s, int panels, int npsi, Visit &&visit) {
    const double d = Length(c), theta = std::atan2(c.y, c.x);
    const double lo = std::max(0.0, std::min(d, r) - 8 * s);
    const GaussLegendreRule &g = GaussLegendre(8);
    double norm = 0;
    for (int p = 0; p < panels; ++p)
        for (int i = 0; i < 8; ++i) {
            const double rho = lo + (p + 0.5 + 0.5 * g.x[i]) * (r - lo) / panels, wr = 0.5 * g.w[i] * (r - lo) / panels;
            const double reach = 8 * s < rho ? std::min(Pi, 1.2 * std::asin(8 * s / rho)) : Pi;
            for (int j = 0; j < npsi; ++j) {
                const double psi = -reach + (j + 0.5) * 2 * reach / npsi;
                const Vec2 q(rho * std::cos(theta + psi), rho * std::sin(theta + psi));
                const double w = wr * rho * (2 * reach / npsi) * std::exp(-0.5 * LengthSquared(q - c) / (s * s));
                visit(psi, rho, w);
                norm += w;
            }
        }
    return norm;
}

// The window's average of e^{i(k·p + chirp·|p|²)} over the disc, by ForPolarWindowOnDisc.
C PolarWindowOnDisc(double r, Vec2 c, double s, Vec2 k, double chirp, int panels, int npsi) {
    const double theta = std::atan2(c.y, c.x);
    C sum = 0;
    const double norm = ForPolarWindowOnDisc(r, c, s, panels, npsi, [&](double psi, double rho, double w) {
        const Vec2 q(rho * std::cos(theta + psi), rho * std::sin(theta + psi));
        sum += w * std::exp(C(0, Dot(k, q) + chirp * LengthSquared(q)));
    });
    return sum / norm;
}

TEST(EnsembleRule, WindowAtADiscsEdgeMeetsTheBoundOverSizesOffsetsAndRates) {
    // A window straddling a disc's edge over disc radii from half the window's width to 100 times it,
    // centred 5s inside to 5s outside, for slowly to moderately varying integrands (|k|·s from 0.01 to
    // 1.5, along and across the centre's direction, with a chirp whose rate at the edge is ~|k|/2:
    // what a grating order's or a thin film's efficiency does over a generalized ray's spectrum):
    // within 3·tol of brute force. Where g varies slowly (|k|·s ≤ 0.03 at tol = 1e-4) the four-node
    // cubic rule is taken (the tensor rules took 20–130 nodes). A rule built for a tenth of the true
    // rate misses the bound.
    const double s = 0.002;
    int cases = 0, missed = 0, four = 0, slow = 0, capped = 0;
    for (const double ratio : {0.5, 2.0, 5.0, 25.0, 100.0})
        for (const double off : {-5.0, -1.0, 0.0, 2.0, 5.0}) {
            const double r = ratio * s, d = r + off * s;
            if (d < 0) continue;
            for (const double ks : {0.01, 0.03, 0.3, 1.5})
                for (const bool across : {false, true}) {
                    const Vec2 dir(0.6, -0.8), perp(0.8, 0.6);
                    const Vec2 k = (across ? perp : dir) * (ks / s);
                    const double chirp = 0.25 * ks / (s * (r + 6 * s));
                    const C ref = PolarWindowOnDisc(r, dir * d, s, k, chirp, 48, 768);
                    for (const double tol : {1e-4, 1e-6}) {
                        const EnsembleShape shape = DiscUnderWindow(r, dir * d, s);
                        std::vector<EnsembleNode> nodes;
                        const EnsembleRuleInfo info = BuildEnsembleRule(
                            shape, [&](const EnsembleBox &b) { return ChirpRates(b, k, chirp); }, tol, nodes);
                        const double err = std::abs(RuleAverage(nodes, k, chirp) - ref);
                        capped += info.capped;
                        EXPECT_LE(err, 3 * tol) << "r/s = " << ratio << ", offset " << off << "s, |k|s = " << ks
                                                << (across ? " across" : " along") << ", tol " << tol << ", "
                                                << info.nx << " x " << info.ny << " nodes";
                        ++cases;
                        if (ks <= 0.03 && tol > 1e-5) {
                            ++slow;
                            four += nodes.size() == 4;
                        }
                        std::vector<EnsembleNode> coarse;
                        BuildEnsembleRule(
                            shape, [&](const EnsembleBox &b) { return ChirpRates(b, k, chirp) * 0.1; }, tol, coarse);
                        if (std::abs(RuleAverage(coarse, k, chirp) - ref) > 3 * tol) ++missed;
                    }
                }
        }
    std::printf("MEASURED window at a disc's edge, %d cases: four nodes in %d of the %d slowly varying ones; a "
                "tenth of the rate misses the bound in %d; %d report an unproven bound (and meet it)\n",
                cases, four, slow, missed, capped);
    EXPECT_GE(four, slow * 3 / 4);
    EXPECT_GE(missed, cases / 4);
    EXPECT_LE(capped, cases / 50);
}

TEST(EnsembleRule, BeyondThePolarRulesTheBoundHoldsOrTheRuleSaysSo) {
    // Fast efficiencies (|k|·s = 3–6, in both axes) at the edge of discs of 25s and 100s, where the
    // polar rules would need more than 20 nodes per axis and the chord rules take over: each rule
    // either meets 3·tol against brute force or reports itself capped (a review measured the chord
    // rules 700× over their bound at r = 25s, a centre 5.5s outside, |k|s = 4, tol 1e-6).
    const double s = 0.002, tol = 1e-6;
    int flagged = 0, silent = 0, flaggedMisses = 0;
    for (const double ratio : {25.0, 100.0})
        for (const double off : {-2.0, 0.0, 2.0, 5.5})
            for (const double ks : {3.0, 4.0, 6.0}) {
                const double r = ratio * s;
                const Vec2 dir(0.6, -0.8), k = Vec2(0.8, 0.6) * (ks / s) + dir * (0.5 * ks / s);
                const EnsembleShape shape = DiscUnderWindow(r, dir * (r + off * s), s);
                std::vector<EnsembleNode> nodes;
                const EnsembleRuleInfo info =
                    BuildEnsembleRule(shape, [&](const EnsembleBox &b) { return ChirpRates(b, k, 0); }, tol, nodes);
                const double err = std::abs(RuleAverage(nodes, k, 0) - PolarWindowOnDisc(r, shape.windowCentre, s, k, 0, 96, 2048));
                if (info.capped) ++flagged, flaggedMisses += err > 3 * tol;
                else if (err > 3 * tol) ++silent;
                EXPECT_TRUE(info.capped || err <= 3 * tol) << "r/s " << ratio << ", offset " << off << "s, |k|s " << ks
                                                           << ": error " << err << ", " << nodes.size() << " nodes";
            }
    std::printf("MEASURED fast efficiencies at wide discs: %d rules report an unproven bound (%d of them miss it), %d "
                "miss it silently\n",
                flagged, flaggedMisses, silent);
    EXPECT_GT(flaggedMisses, 0);  // the flag is needed: without it these would be silent
}

TEST(EnsembleRule, TinyDiscsUnderAWideWindowAndUnboundedRatesKeepTheBound) {
    // A disc far smaller than the window (r/s = 0.005–0.05: a small lamp under a wide GR's spectrum),
    // where the moments across a chord come from a short series (the closed forms cancel there), and
    // an integrand varying over the disc itself: within 3·tol of brute force. A review found the
    // six-node rule taken with a NaN bound there (error 0.28 at tol 1e-4).
    const double s = 0.1, tol = 1e-4;
    for (const double r : {5e-4, 1e-3, 5e-3})
        for (const double kr : {0.5, 3.5}) {
            const Vec2 c(0.02, 0), k = Vec2(0.8, 0.6) * (kr / r);
            const EnsembleShape shape = DiscUnderWindow(r, c, s);
            std::vector<EnsembleNode> nodes;
            BuildEnsembleRule(shape, [&](const EnsembleBox &b) { return ChirpRates(b, k, 0); }, tol, nodes);
            const C ref = PolarWindowOnDisc(r, c, s, k, 0, 48, 768);
            EXPECT_LE(std::abs(RuleAverage(nodes, k, 0) - ref), 3 * tol) << "r = " << r << ", k·r = " << kr;
        }
    // Unbounded rates (a kernel that cannot bound its efficiency's variation) never take the moment
    // rules (their bound is NaN there: 0·∞): the rule says its bound does not hold.
    std::vector<EnsembleNode> nodes;
    const EnsembleShape shape = DiscUnderWindow(0.05, Vec2(0.05, 0), 0.01);
    const EnsembleRuleInfo info = BuildEnsembleRule(shape, [](const EnsembleBox &) { return Vec2(Infinity, 0); }, 1e-4, nodes);
    EXPECT_TRUE(info.capped);
}

// Brute-force E[u^i v^j] (i, j ≤ 10) of the window N(·; c, s²I) on a disc of radius r, in axes along
// (u) and across (v) c, in units of s about c (ForPolarWindowOnDisc).
std::array<std::array<double, 11>, 11> WindowMoments(double r, Vec2 c, double s) {
    const double d = Length(c);
    std::array<std::array<double, 11>, 11> sum{};
    const double norm = ForPolarWindowOnDisc(r, c, s, 64, 1024, [&](double psi, double rho, double w) {
        const double u = rho * std::cos(psi), v = rho * std::sin(psi);
        double ui = w;
        for (std::size_t i = 0; i <= 10; ++i, ui *= (u - d) / s) {
            double term = ui;
            for (std::size_t j = 0; i + j <= 10; ++j, term *= v / s) sum[i][j] += term;
        }
    });
    for (auto &row : sum)
        for (double &m : row) m /= norm;
    return sum;
}

TEST(EnsembleRule, MomentRulesAreExactForTheirPolynomials) {
    // The four-node rule integrates every monomial u^i v^j of degree ≤ 3 over the window on the disc
    // exactly, the six-node rule every one of degree ≤ 5 but v⁴, u·v⁴ and u³v² (u along the window's
    // centre, v across, in units of s about it): against brute force, to 1e-6 relative to the
    // monomial's scale (the moments along u come from a 32-point rule: ≤ 4e-6 in the fourth).
    const double s = 0.01;
    int four = 0, six = 0;
    for (const double ratio : {0.7, 3.0, 8.0, 40.0})
        for (const double off : {-3.0, 0.0, 2.0}) {
            const double r = ratio * s, d = r + off * s;
            if (d <= 0) continue;
            const Vec2 dir(0.6, -0.8), c = dir * d, et(0.8, 0.6);
            const auto moments = WindowMoments(r, c, s);
            for (const double rate : {0.5, 8.0}) {  // per unit of the plane: s·R = 0.005 (4 nodes), 0.08 (6)
                const EnsembleShape shape = DiscUnderWindow(r, c, s);
                std::vector<EnsembleNode> nodes;
                BuildEnsembleRule(shape, [&](const EnsembleBox &) { return Vec2(rate, rate); }, 1e-4, nodes);
                ASSERT_TRUE(nodes.size() == 4 || nodes.size() == 6) << "r/s " << ratio << ", offset " << off << ", "
                                                                    << nodes.size() << " nodes";
                const int degree = nodes.size() == 4 ? 3 : 5;
                (nodes.size() == 4 ? four : six)++;
                for (int i = 0; i <= degree; ++i)
                    for (int j = 0; i + j <= degree; ++j) {
                        if (degree == 5 && ((i == 0 && j == 4) || (i == 1 && j == 4) || (i == 3 && j == 2))) continue;
                        double got = 0, norm = 0;
                        for (const EnsembleNode &n : nodes) {
                            const Vec2 q = n.p - c;
                            got += n.w * std::pow(Dot(q, dir) / s, i) * std::pow(Dot(q, et) / s, j);
                            norm += n.w;
                        }
                        got /= norm;
                        const double ref = moments[std::size_t(i)][std::size_t(j)];
                        const double scale = std::sqrt(moments[std::size_t(2 * i)][std::size_t(2 * j)]);  // E[(u^i v^j)²]^½
                        EXPECT_NEAR(got, ref, 1e-6 * scale) << "r/s " << ratio << ", offset " << off << ", u^" << i
                                                            << " v^" << j << ", " << nodes.size() << " nodes";
                    }
            }
        }
    std::printf("MEASURED moment rules: %d four-node and %d six-node rules exact for their monomials\n", four, six);
    EXPECT_GT(four, 0);
    EXPECT_GT(six, 0);
}

}  // namespace
}  // namespace phasor
