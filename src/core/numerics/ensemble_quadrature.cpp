// SPDX-License-Identifier: Apache-2.0
// phasor — quadrature over an angular ensemble (ensemble_quadrature.h).
#include "core/numerics/ensemble_quadrature.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

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

// ---- Gauss rules for a truncated normal --------------------------------------------------------------

constexpr int MaxTruncatedNormalNodes = 12;

// The eigenvalues of the symmetric tridiagonal n×n matrix T with diagonal d[0..n) and off-diagonal
// e[0..n−1) (e[i] = T(i, i + 1); both overwritten; eigenvalues into d) and the first component of
// each unit eigenvector, n ≤ MaxTruncatedNormalNodes: implicit QR steps with Wilkinson's shift on
// the lowest unreduced block (Golub & Van Loan, Matrix Computations, §8.3), an off-diagonal being
// dropped once it is below round-off of its neighbours. Golub–Welsch needs only the eigenvectors'
// first components, so each Givens rotation updates the first row of Q alone: O(n) per step
// instead of the O(n³) of a dense method. False if 30·n steps do not converge.
bool TridiagonalEigen(int n, double *d, double *e, double *first) {
    for (int i = 0; i < n; ++i) first[i] = i == 0 ? 1 : 0;
    constexpr double Eps = std::numeric_limits<double>::epsilon();
    auto negligible = [&](int i) { return std::abs(e[i]) <= Eps * (std::abs(d[i]) + std::abs(d[i + 1])); };
    int hi = n - 1, steps = 0;
    while (hi > 0) {
        if (negligible(hi - 1)) {  // T(hi, hi) is an eigenvalue
            e[hi - 1] = 0;
            --hi;
            continue;
        }
        int lo = hi - 1;  // the unreduced block [lo, hi]
        while (lo > 0 && !negligible(lo - 1)) --lo;
        if (++steps > 30 * n) return false;
        // Wilkinson's shift: the eigenvalue of the trailing 2×2 nearer T(hi, hi).
        const double delta = 0.5 * (d[hi - 1] - d[hi]), b = e[hi - 1];
        const double mu = d[hi] - b * b / (delta + std::copysign(std::hypot(delta, b), delta));
        // The step: G_lo from the shifted first column, then rotations chasing the bulge down.
        double x = d[lo] - mu, z = e[lo];
        for (int k = lo; k < hi; ++k) {
            const double r = std::hypot(x, z);
            const double c = r > 0 ? x / r : 1, s = r > 0 ? z / r : 0;  // Gᵀ(x, z) = (r, 0)
            if (k > lo) e[k - 1] = r;  // the bulge T(k + 1, k − 1) is gone
            // T ← GᵀTG on rows and columns k, k + 1.
            const double dk = d[k], dk1 = d[k + 1], ek = e[k];
            d[k] = c * c * dk + 2 * c * s * ek + s * s * dk1;
            d[k + 1] = s * s * dk - 2 * c * s * ek + c * c * dk1;
            e[k] = c * s * (dk1 - dk) + (c * c - s * s) * ek;
            if (k + 1 < hi) {  // the new bulge T(k + 2, k) = s·e[k + 1]
                x = e[k];
                z = s * e[k + 1];
                e[k + 1] *= c;
            }
            const double q0 = first[k], q1 = first[k + 1];  // Q ← QG, its first row
            first[k] = c * q0 + s * q1;
            first[k + 1] = c * q1 - s * q0;
        }
    }
    return true;
}

}  // namespace

bool TruncatedNormalRule(double a, double b, double rate, double tol, std::vector<std::pair<double, double>> &out) {
    out.clear();
    // The discretisation below resolves φ over at most 12 units (its stated range): refuse beyond.
    if (!(b > a) || b - a > 12 * (1 + 1e-12)) return false;
    constexpr int M = MaxGaussLegendreNodes, N = MaxTruncatedNormalNodes;
    // The weight φ on [a, b] as M Gauss–Legendre points: exact to round-off for the polynomials of
    // degree ≤ 2N + 1 the recurrence below integrates against it (φ over ≤ 12 units is resolved).
    const GaussLegendreRule &g = GaussLegendre(M);
    std::array<double, M> x{}, w{}, prev{}, cur{};
    const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    // A symmetric interval (the rules across a window's chords: a = −b): φ is even there, so every
    // α_k is 0, π_k has the parity of k and π_k² is even — the sums over the (mirrored) nodes are twice
    // those over the positive half: half the exponentials and half the recurrence.
    const bool symmetric = a == -b;
    static_assert(M % 2 == 0, "the symmetric case takes the positive half of the nodes");
    const int i0 = symmetric ? M / 2 : 0;  // the rule's nodes ascend
    const double fold = symmetric ? 2 : 1;
    double mass = 0;
    for (int i = i0; i < M; ++i) {
        x[std::size_t(i)] = mid + half * g.x[i];
        w[std::size_t(i)] = fold * half * g.w[i] * std::exp(-0.5 * x[std::size_t(i)] * x[std::size_t(i)]) / std::sqrt(2 * Pi);
        cur[std::size_t(i)] = 1;
        mass += w[std::size_t(i)];
    }
    if (!(mass > 0)) return false;
    // Stieltjes: monic orthogonal π_k with π_{k+1} = (x − α_k)π_k − β_k π_{k−1}; Gauss's remainder for
    // n nodes is f^{(2n)}/(2n)!·∫π_n² φ = f^{(2n)}/(2n)!·mass·β_1⋯β_n, so with |f^{(2n)}| ≤ rate^{2n}·sup|f|
    // the average's error is at most rate^{2n}·β_1⋯β_n/(2n)! (as Gauss–Hermite's, where β_k = k).
    std::array<double, N + 1> alpha{}, beta{};
    double normPrev = 0, norm = mass, bound = 1;
    int n = 0;
    for (int k = 0; k <= N; ++k) {
        if (k > 0) {
            beta[std::size_t(k)] = norm / normPrev;
            bound *= Sqr(rate) * beta[std::size_t(k)] / ((2.0 * k - 1) * (2.0 * k));
            if (bound <= tol) {
                n = k;
                break;
            }
        }
        if (k == N) break;
        double xs = 0;
        if (!symmetric)
            for (int i = i0; i < M; ++i) xs += w[std::size_t(i)] * x[std::size_t(i)] * Sqr(cur[std::size_t(i)]);
        alpha[std::size_t(k)] = xs / norm;
        double next = 0;
        for (int i = i0; i < M; ++i) {
            const std::size_t j = std::size_t(i);
            const double p = (x[j] - alpha[std::size_t(k)]) * cur[j] - (k > 0 ? beta[std::size_t(k)] * prev[j] : 0.0);
            prev[j] = cur[j];
            cur[j] = p;
            next += w[j] * p * p;
        }
        normPrev = norm;
        norm = next;
        if (!(norm > 0)) return false;
    }
    if (n == 0) return false;
    // Golub–Welsch: the nodes are the eigenvalues of the Jacobi matrix, the weights mass·v₀².
    double values[N], off[N], first[N];
    for (int i = 0; i < n; ++i) {
        values[i] = alpha[std::size_t(i)];
        if (i + 1 < n) off[i] = std::sqrt(beta[std::size_t(i + 1)]);
    }
    if (!TridiagonalEigen(n, values, off, first)) return false;
    for (int i = 0; i < n; ++i) out.push_back({values[i], mass * first[i] * first[i]});
    std::sort(out.begin(), out.end());
    return true;
}

namespace {

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
    // tangential) — the disc is the same disc there — the disc within ±6s of the centre radially
    // (for a centre outside the disc, the 6s inside its edge: the overlap is the window's tail, and
    // what lies beyond d − 6s is not negligible beside it). Across, on every chord that spans the
    // window's ±6s, Gauss–Hermite (the Gaussian exactly, only g's rate counts); on the shorter chords
    // near the edge, the truncated normal's Gauss rule (Gauss–Legendre with the Gaussian as a factor
    // if that needs more than 12 nodes). Radially,
    // where the chords span the window (u ≤ e, e = √(r² − 36s²)) the integrand is g's average across
    // times the Gaussian: the truncated normal's own Gauss rule; beyond e, Gauss–Legendre with the
    // Gaussian counted as a rate of 2.5/s plus the tail's log-slope (d − r)/s², and the chord's
    // square-root end mapped away. g's rate along a unit direction e is at most |e_x|·R_x + |e_y|·R_y
    // (Bernstein per axis, as the mixed derivatives of a band-limited g).
    const double half = GaussianBox * s;
    const Vec2 er = d > 0 ? c * (1 / d) : Vec2(1, 0), et(-er.y, er.x);
    const Vec2 rate = rates(EnsembleBox{Vec2(std::max(-r, c.x - half), std::max(-r, c.y - half)),
                                        Vec2(std::min(r, c.x + half), std::min(r, c.y + half))});
    const double ru = std::abs(er.x) * rate.x + std::abs(er.y) * rate.y;
    const double rv = std::abs(et.x) * rate.x + std::abs(et.y) * rate.y;
    const double u0 = std::max(-r, std::min(d, r) - half), u1 = std::min(r, d + half);
    const double e = half < r ? std::sqrt(r * r - half * half) : -r;
    const int hermite = GaussHermiteNodesFor(std::sqrt(2.0) * s * rv, tol);
    const GaussHermiteRule &gh = GaussHermite(hermite);
    int ny = 0;
    thread_local std::vector<AxisNode> chord;
    thread_local std::vector<std::pair<double, double>> tnv;
    // The nodes of the chord at u, whose radial weight (the Gaussian's factor included) is wu.
    auto across = [&](double u, double wu) {
        const double h = std::sqrt(std::max(0.0, r * r - u * u));
        const double qu = Normal1(u, d, var);
        if (h >= half && hermite <= MaxGaussHermiteNodes) {
            for (int i = 0; i < gh.n; ++i) {
                const double v = std::sqrt(2.0) * s * gh.x[i];
                out.push_back({er * u + et * v, wu * gh.w[i] / std::sqrt(Pi), qu * Normal1(v, 0, var)});
            }
            ny = std::max(ny, gh.n);
            return;
        }
        const double lo = std::max(-h, -half), hi = std::min(h, half);
        if (!(hi > lo)) return;
        if (TruncatedNormalRule(lo / s, hi / s, s * rv, tol, tnv)) {
            for (const auto &[x, w] : tnv) out.push_back({er * u + et * (s * x), wu * w, qu * Normal1(s * x, 0, var)});
            ny = std::max(ny, int(tnv.size()));
            return;
        }
        LegendreAxis(lo, hi, (hi - lo) * (rv + GaussianRate / s), tol, false, chord, &capped);
        for (const AxisNode &b : chord) {
            const double q = Normal1(b.x, 0, var);
            out.push_back({er * u + et * b.x, wu * b.w * q, qu * q});
        }
        ny = std::max(ny, int(chord.size()));
    };
    int nx = 0;
    double uB = u0;  // where the radial Gauss–Legendre part starts
    thread_local std::vector<std::pair<double, double>> tn;
    if (e > u0 && TruncatedNormalRule((u0 - d) / s, (std::min(e, u1) - d) / s, s * (ru + rv), tol, tn)) {
        for (const auto &[x, w] : tn) across(d + s * x, w);
        nx += int(tn.size());
        uB = std::min(e, u1);
    }
    if (u1 > uB) {
        const double tail = std::max(0.0, d - r) / var;
        LegendreAxis(uB, u1, (u1 - uB) * (ru + rv + GaussianRate / s + tail), tol, uB == -r || u1 == r, xs, &capped);
        for (const AxisNode &a : xs) across(a.x, a.w * Normal1(a.x, d, var));
        nx += int(xs.size());
    }
    info.nx = nx;
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
