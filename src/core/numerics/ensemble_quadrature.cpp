// SPDX-License-Identifier: Apache-2.0
// phasor — quadrature over an angular ensemble (ensemble_quadrature.h).
#include "core/numerics/ensemble_quadrature.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/numerics/gauss_legendre.h"

namespace phasor {

namespace {

// ---- Gauss–Hermite rules ----------------------------------------------------------------------------

struct HermiteTable {
    std::array<std::array<double, MaxGaussHermiteNodes>, MaxGaussHermiteNodes + 1> x{}, w{};
    std::array<GaussHermiteRule, MaxGaussHermiteNodes + 1> rules{};
};

// The orthonormal Hermite function recurrence h_j = t·√(2/j)·h_{j−1} − √((j−1)/j)·h_{j−2},
// h_0 = π^{−1/4}: returns h_n(t) and stores h_{n−1}(t) (h_n' = √(2n)·h_{n−1}).
double HermiteNormalised(int n, double t, double *previous) {
    double p1 = std::pow(Pi, -0.25), p2 = 0;
    for (int j = 1; j <= n; ++j) {
        const double p3 = p2;
        p2 = p1;
        p1 = t * std::sqrt(2.0 / j) * p2 - std::sqrt(double(j - 1) / j) * p3;
    }
    *previous = p2;
    return p1;
}

// The non-negative half of the nodes by Newton's method from the classical initial guesses
// (largest root first, each next guess from the previous roots), mirrored; weights 2/h_n'(t)².
void MakeHermiteRule(int n, double *x, double *w) {
    double z = 0;
    const int half = (n + 1) / 2;
    for (int i = 0; i < half; ++i) {
        if (i == 0) z = std::sqrt(2.0 * n + 1) - 1.85575 * std::pow(2.0 * n + 1, -1.0 / 6);
        else if (i == 1) z -= 1.14 * std::pow(double(n), 0.426) / z;
        else if (i == 2) z = 1.86 * z - 0.86 * x[n - 1];
        else if (i == 3) z = 1.91 * z - 0.91 * x[n - 2];
        else z = 2 * z - x[n - i + 1];
        double prev = 0;
        for (int it = 0; it < 100; ++it) {
            const double h = HermiteNormalised(n, z, &prev);
            const double dz = h / (std::sqrt(2.0 * n) * prev);
            z -= dz;
            if (std::abs(dz) < 1e-15 * std::max(1.0, std::abs(z))) break;
        }
        HermiteNormalised(n, z, &prev);
        const double d = std::sqrt(2.0 * n) * prev;
        x[n - 1 - i] = z;
        x[i] = -z;
        w[i] = w[n - 1 - i] = 2 / (d * d);
    }
    if (n % 2) x[n / 2] = 0;  // the middle node of an odd rule
}

const HermiteTable &HermiteRules() {
    static const HermiteTable table = [] {
        HermiteTable t;
        for (int n = 1; n <= MaxGaussHermiteNodes; ++n) {
            MakeHermiteRule(n, t.x[std::size_t(n)].data(), t.w[std::size_t(n)].data());
            t.rules[std::size_t(n)] = {n, t.x[std::size_t(n)].data(), t.w[std::size_t(n)].data()};
        }
        return t;
    }();
    return table;
}

// ---- node counts from the remainder bounds ----------------------------------------------------------

// The largest rate / phase each rule size can take at one tolerance, per thread (recomputed when
// the tolerance changes; every caller in the renderer uses one).
struct Limits {
    double tol = -1;
    std::array<double, 65> hermiteRate{}, legendrePhase{};
    void For(double t) {
        if (t == tol) return;
        tol = t;
        for (int n = 1; n <= 64; ++n) {
            // √π·n!/(2ⁿ(2n)!)·b^{2n} ≤ tol·√π  ⇔  b ≤ (tol·2ⁿ(2n)!/n!)^{1/(2n)}.
            hermiteRate[std::size_t(n)] =
                std::exp((std::log(t) + n * std::log(2.0) + std::lgamma(2 * n + 1.0) - std::lgamma(n + 1.0)) / (2 * n));
            legendrePhase[std::size_t(n)] = GaussLegendreMaxPhase(n, t);
        }
    }
};
thread_local Limits limits;

constexpr int PanelNodes = 16;          // Gauss–Legendre nodes per panel of a composite rule
constexpr double GaussianBox = 6;       // a clipped window is integrated over ±6 s (2e-9 of its mass outside)
constexpr double GaussianRate = 2.5;    // a Gaussian factor of std s on a Legendre interval counts as rate 2.5/s

// One axis of a tensor rule: positions, weights (∫ f(x)·q(x) dx ≈ Σ w f), and q at the node.
struct AxisNode {
    double x, w, q;
};

// Gauss–Legendre on [a, b] for a total phase Φ (composite panels of PanelNodes beyond that), with
// q ≡ 1. With `sqrtEnds` the axis is mapped by x = mid − h·cos t, t ∈ [0, π] (the chord of a disc
// has square-root ends there); Φ is then the phase over [a, b] and the rate in t is h·R + 2.
void LegendreAxis(double a, double b, double phase, double tol, bool sqrtEnds, std::vector<AxisNode> &out,
                  bool *capped) {
    out.clear();
    const double mid = 0.5 * (a + b), h = 0.5 * (b - a);
    const double lo = sqrtEnds ? 0 : a, hi = sqrtEnds ? Pi : b;
    const double total = sqrtEnds ? Pi * (0.5 * phase + 2) : phase;
    limits.For(tol);
    int n = GaussLegendreNodesFor(total, tol), panels = 1;
    if (n > PanelNodes) {
        n = PanelNodes;
        panels = int(std::ceil(total / limits.legendrePhase[PanelNodes]));
        if (panels * n > MaxEnsembleNodesPerAxis) {
            panels = MaxEnsembleNodesPerAxis / n;
            *capped = true;
        }
    }
    const GaussLegendreRule &r = GaussLegendre(n);
    const double width = (hi - lo) / panels;
    for (int p = 0; p < panels; ++p) {
        const double c = lo + (p + 0.5) * width;
        for (int i = 0; i < n; ++i) {
            const double t = c + 0.5 * width * r.x[i], wt = 0.5 * width * r.w[i];
            if (sqrtEnds) out.push_back({mid - h * std::cos(t), wt * h * std::sin(t), 1.0});
            else out.push_back({t, wt, 1.0});
        }
    }
}

double Normal1(double x, double mean, double var) {
    return std::exp(-0.5 * Sqr(x - mean) / var) / std::sqrt(2 * Pi * var);
}

// ∫ f(x)·N(x; mean, var) dx: Gauss–Hermite when a rule of ≤ 64 nodes meets the bound for `rate`,
// else Gauss–Legendre over mean ± 6σ with the Gaussian as a factor. q = N(x; mean, var).
void GaussianAxis(double mean, double var, double rate, double tol, std::vector<AxisNode> &out, bool *capped) {
    out.clear();
    const double sigma = std::sqrt(var);
    const int n = GaussHermiteNodesFor(std::sqrt(2.0) * sigma * rate, tol);
    if (n <= MaxGaussHermiteNodes) {
        const GaussHermiteRule &r = GaussHermite(n);
        for (int i = 0; i < n; ++i) {
            const double x = mean + std::sqrt(2.0) * sigma * r.x[i];
            out.push_back({x, r.w[i] / std::sqrt(Pi), Normal1(x, mean, var)});
        }
        return;
    }
    const double half = GaussianBox * sigma;
    LegendreAxis(mean - half, mean + half, 2 * half * (rate + GaussianRate / sigma), tol, false, out, capped);
    for (AxisNode &a : out) {
        a.q = Normal1(a.x, mean, var);
        a.w *= a.q;
    }
}

void Tensor(const std::vector<AxisNode> &xs, const std::vector<AxisNode> &ys, std::vector<EnsembleNode> &out) {
    for (const AxisNode &a : xs)
        for (const AxisNode &b : ys) out.push_back({Vec2(a.x, b.x), a.w * b.w, a.q * b.q});
}

}  // namespace

const GaussHermiteRule &GaussHermite(int n) {
    return HermiteRules().rules[std::size_t(std::clamp(n, 1, MaxGaussHermiteNodes))];
}

int GaussHermiteNodesFor(double rateT, double tol) {
    limits.For(tol);
    const double b = std::abs(rateT);
    for (int n = 1; n <= MaxGaussHermiteNodes; ++n)
        if (b <= limits.hermiteRate[std::size_t(n)]) return n;
    return MaxGaussHermiteNodes + 1;
}

int GaussLegendreNodesFor(double phase, double tol) {
    limits.For(tol);
    const double p = std::abs(phase);
    for (int n = 1; n <= MaxGaussLegendreNodes; ++n)
        if (p <= limits.legendrePhase[std::size_t(n)]) return n;
    return MaxGaussLegendreNodes + 1;
}

namespace ensemble_detail {

EnsembleRuleInfo Build(const EnsembleShape &shape, const RatesRef &rates, double tol, std::vector<EnsembleNode> &out) {
    out.clear();
    EnsembleRuleInfo info;
    bool capped = false;
    thread_local std::vector<AxisNode> xs, ys;
    using P = EnsembleShape::Profile;

    // A Gaussian ensemble (a Gaussian profile, with or without a window; or a window well inside a
    // disc): the product Gaussian N(μ, v·I), by Gauss–Hermite per axis.
    auto gaussian = [&](Vec2 mean, double var) {
        const double half = GaussianBox * std::sqrt(var);
        const Vec2 r = rates(EnsembleBox{mean - Vec2(half, half), mean + Vec2(half, half)});
        GaussianAxis(mean.x, var, r.x, tol, xs, &capped);
        GaussianAxis(mean.y, var, r.y, tol, ys, &capped);
        Tensor(xs, ys, out);
        info.nx = int(xs.size());
        info.ny = int(ys.size());
        info.capped = capped;
    };

    if (shape.profile == P::Delta) {
        out.push_back({Vec2(0, 0), 1, 1});
        return info;
    }
    if (shape.profile == P::Gaussian) {
        if (!shape.HasWindow()) {
            gaussian(Vec2(0, 0), shape.variance);
        } else {
            const double sum = shape.variance + shape.windowVariance;
            gaussian(shape.windowCentre * (shape.variance / sum), shape.variance * shape.windowVariance / sum);
        }
        return info;
    }

    // A disc of radius r.
    const double r = shape.radius;
    if (!shape.HasWindow()) {
        const Vec2 rate = rates(EnsembleBox{Vec2(-r, -r), Vec2(r, r)});
        LegendreAxis(-r, r, 2 * r * (rate.x + rate.y), tol, true, xs, &capped);
        LegendreAxis(-1, 1, 2 * r * rate.y, tol, false, ys, &capped);  // on the chord, scaled below
        for (const AxisNode &a : xs) {
            const double h = std::sqrt(std::max(0.0, r * r - a.x * a.x));
            for (const AxisNode &b : ys) out.push_back({Vec2(a.x, h * b.x), a.w * h * b.w, 1.0});
        }
        info.nx = int(xs.size());
        info.ny = int(ys.size());
        info.capped = capped;
        return info;
    }
    const Vec2 c = shape.windowCentre;
    const double var = shape.windowVariance, s = std::sqrt(var), d = Length(c);
    if (d + GaussianBox * s <= r) {  // the window lies inside the disc: the disc is 1 over it
        gaussian(c, var);
        return info;
    }
    if (d - GaussianBox * s >= r) {  // no overlap: the ensemble is empty, its nearest point stands for it
        out.push_back({c * (r / d), 1, 1});
        info.overlap = false;
        return info;
    }
    // The window straddles the disc's edge. In axes along its centre (u, radial) and across it (v,
    // tangential) — the disc is the same disc there — Gauss–Legendre over the radial extent of the
    // disc clipped to the window's box; on every chord that spans the window's ±6s box, Gauss–Hermite
    // for its Gaussian across (a few nodes where the window is narrow: the Gaussian is integrated
    // exactly, only g's rate counts), else Gauss–Legendre over the clipped chord with the Gaussian
    // as a factor. g's rate along a unit direction e is at most |e_x|·R_x + |e_y|·R_y (Bernstein per
    // axis, as the mixed derivatives of a band-limited g).
    const double half = GaussianBox * s;
    const Vec2 er = d > 0 ? c * (1 / d) : Vec2(1, 0), et(-er.y, er.x);
    const Vec2 rate = rates(EnsembleBox{Vec2(std::max(-r, c.x - half), std::max(-r, c.y - half)),
                                        Vec2(std::min(r, c.x + half), std::min(r, c.y + half))});
    const double ru = std::abs(er.x) * rate.x + std::abs(er.y) * rate.y;
    const double rv = std::abs(et.x) * rate.x + std::abs(et.y) * rate.y;
    // Radially, ±6s about the centre, or for a centre outside the disc the 6s inside its edge: the
    // overlap there is the window's tail, and what lies beyond d − 6s is not negligible beside it.
    const double u0 = std::max(-r, std::min(d, r) - half), u1 = std::min(r, d + half);
    const bool discEnds = u0 == -r || u1 == r;
    // A centre outside the disc leaves only the window's tail over it, whose logarithm falls by
    // (d − r)/s² per unit of u at the edge: that much more rate.
    const double tail = std::max(0.0, d - r) / var;
    LegendreAxis(u0, u1, (u1 - u0) * (ru + rv + GaussianRate / s + tail), tol, discEnds, xs, &capped);
    LegendreAxis(-1, 1, 2 * half * (rv + GaussianRate / s), tol, false, ys, &capped);
    const int hermite = GaussHermiteNodesFor(std::sqrt(2.0) * s * rv, tol);
    const GaussHermiteRule &gh = GaussHermite(hermite);
    int ny = 0;
    for (const AxisNode &a : xs) {
        const double h = std::sqrt(std::max(0.0, r * r - a.x * a.x));
        const double qu = Normal1(a.x, d, var);
        if (h >= half && hermite <= MaxGaussHermiteNodes) {
            for (int i = 0; i < gh.n; ++i) {
                const double v = std::sqrt(2.0) * s * gh.x[i], q = qu * Normal1(v, 0, var);
                out.push_back({er * a.x + et * v, a.w * qu * gh.w[i] / std::sqrt(Pi), q});
            }
            ny = std::max(ny, gh.n);
            continue;
        }
        const double lo = std::max(-h, -half), hi = std::min(h, half);
        if (!(hi > lo)) continue;
        const double mid = 0.5 * (lo + hi), hw = 0.5 * (hi - lo);
        for (const AxisNode &b : ys) {
            const double v = mid + hw * b.x, q = qu * Normal1(v, 0, var);
            out.push_back({er * a.x + et * v, a.w * hw * b.w * q, q});
        }
        ny = std::max(ny, int(ys.size()));
    }
    info.nx = int(xs.size());
    info.ny = ny;
    if (out.empty()) {  // round-off at a tangent edge: the nearest point of the disc
        out.push_back({c * (r / std::max(d, 1e-300)), 1, 1});
        info.overlap = false;
    }
    info.capped = capped;
    return info;
}

}  // namespace ensemble_detail

}  // namespace phasor
