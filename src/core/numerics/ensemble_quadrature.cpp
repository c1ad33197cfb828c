// SPDX-License-Identifier: Apache-2.0
// phasor — quadrature over an angular ensemble (ensemble_quadrature.h).
#include "core/numerics/ensemble_quadrature.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/numerics/bessel.h"
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
constexpr double PolarMinRadius = 10;   // discs of at least 10s: a straddling window in polar coordinates

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
        // (in floating point: an unbounded or NaN phase — no rate bound — is capped, not converted)
        const double wanted = std::ceil(total / limits.legendrePhase[PanelNodes]);
        if (wanted * n <= MaxEnsembleNodesPerAxis) {
            panels = int(wanted);
        } else {
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

// The Gauss–Hermite nodes GaussianAxis takes for N(mean, var) and a function of rate `rate`
// (MaxGaussHermiteNodes + 1: more than a Hermite rule has; Gauss–Legendre then).
int GaussianAxisNodes(double var, double rate, double tol) {
    return GaussHermiteNodesFor(std::sqrt(2.0) * std::sqrt(var) * rate, tol);
}

// ∫ f(x)·N(x; mean, var) dx: Gauss–Hermite when a rule of ≤ 64 nodes meets the bound for `rate`,
// else Gauss–Legendre over mean ± 6σ with the Gaussian as a factor. q = N(x; mean, var).
void GaussianAxis(double mean, double var, double rate, double tol, std::vector<AxisNode> &out, bool *capped) {
    out.clear();
    const double sigma = std::sqrt(var);
    const int n = GaussianAxisNodes(var, rate, tol);
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
// Largest node count of a Gauss rule built from a discrete measure (GaussRuleOfMeasure).
constexpr int MaxMeasureNodes = 20;

// The eigenvalues of the symmetric tridiagonal n×n matrix T with diagonal d[0..n) and off-diagonal
// e[0..n−1) (e[i] = T(i, i + 1); both overwritten; eigenvalues into d) and the first component of
// each unit eigenvector, n ≤ MaxMeasureNodes: implicit QR steps with Wilkinson's shift on
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

namespace {

// T_m(a) = Σ_k S(m, k)·a^k, m ≤ 2·MaxMeasureNodes (the Stirling numbers of the second kind from
// S(m, k) = k·S(m − 1, k) + S(m − 1, k − 1), once).
double Touchard(int m, double a) {
    constexpr int Max = 2 * MaxMeasureNodes;
    static const auto stirling = [] {
        std::array<std::array<double, Max + 1>, Max + 1> t{};
        t[0][0] = 1;
        for (std::size_t i = 1; i <= Max; ++i)
            for (std::size_t k = 1; k <= i; ++k) t[i][k] = double(k) * t[i - 1][k] + t[i - 1][k - 1];
        return t;
    }();
    double sum = 0, power = 1;
    for (int k = 1; k <= m; ++k) sum += stirling[std::size_t(m)][std::size_t(k)] * (power *= a);
    return sum;
}

// A bound on the m-th derivative of the integrand relative to its sup:
//   * rate^m — a band-limited function (Bernstein), or, with `circle`, T_m(rate): g of rate R (in every
//     direction) along a circle of radius ρ, rate = ρR — by Faà di Bruno (each derivative of the
//     circle has length ρ) T_m(ρR), the Touchard polynomial: ~ρR for ρR ≪ 1, where (ρR)^m would claim
//     far less (e^{ia·cos ψ} has the harmonic e^{iψ} with amplitude ~a at any a);
//   * plus amplitude·frequency^m — a part of that size modulated at that rate (an average over a law
//     that changes along the axis).
struct DerivativeBound {
    double rate = 0;
    bool circle = false;
    double amplitude = 0, frequency = 0;
    double At(int m) const {
        const double own = circle ? Touchard(m, rate) : std::pow(rate, m);
        return amplitude > 0 ? own + amplitude * std::pow(frequency, m) : own;
    }
};

// The Gauss rule of a positive weight given as a discrete measure (points x[0..m), masses w[0..m))
// that integrates the polynomials the recurrence meets (degree ≤ 2·maxNodes + 1) exactly to
// round-off: the fewest nodes n ≤ maxNodes (≤ MaxMeasureNodes) whose remainder is ≤ tol relative to
// the measure's mass, D_{2n}·β_1⋯β_n/(2n)! with D_{2n} the DerivativeBound. `symmetric`: the measure
// is the positive half of one that is even about 0 (masses already doubled), so every α_k is 0 and
// the sums over the positive half are the whole. Stieltjes: monic orthogonal π_k with
// π_{k+1} = (x − α_k)π_k − β_k π_{k−1}; Gauss's remainder for n nodes is
// f^{(2n)}/(2n)!·∫π_n² = f^{(2n)}/(2n)!·mass·β_1⋯β_n (for the normal, β_k = k: Gauss–Hermite's).
// Golub–Welsch: the nodes are the eigenvalues of the Jacobi matrix, the weights mass·v₀².
bool GaussRuleOfMeasure(const double *x, const double *w, int m, bool symmetric, const DerivativeBound &derivative,
                        double tol, int maxNodes, std::vector<std::pair<double, double>> &out) {
    out.clear();
    constexpr int N = MaxMeasureNodes, M = MaxGaussLegendreNodes;
    maxNodes = std::min(maxNodes, N);
    if (m > M) return false;
    std::array<double, M> prev{}, cur{};
    double mass = 0;
    for (int i = 0; i < m; ++i) {
        cur[std::size_t(i)] = 1;
        mass += w[i];
    }
    if (!(mass > 0)) return false;
    std::array<double, N + 1> alpha{}, beta{};
    double normPrev = 0, norm = mass, bound = 1;
    int n = 0;
    for (int k = 0; k <= maxNodes; ++k) {
        if (k > 0) {
            beta[std::size_t(k)] = norm / normPrev;
            bound *= beta[std::size_t(k)] / ((2.0 * k - 1) * (2.0 * k));
            if (derivative.At(2 * k) * bound <= tol) {
                n = k;
                break;
            }
        }
        if (k == maxNodes) break;
        double xs = 0;
        if (!symmetric)
            for (int i = 0; i < m; ++i) xs += w[i] * x[i] * Sqr(cur[std::size_t(i)]);
        alpha[std::size_t(k)] = xs / norm;
        double next = 0;
        for (int i = 0; i < m; ++i) {
            const std::size_t j = std::size_t(i);
            const double p = (x[i] - alpha[std::size_t(k)]) * cur[j] - (k > 0 ? beta[std::size_t(k)] * prev[j] : 0.0);
            prev[j] = cur[j];
            cur[j] = p;
            next += w[i] * p * p;
        }
        normPrev = norm;
        norm = next;
        if (!(norm > 0)) return false;
    }
    if (n == 0) return false;
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

}  // namespace

bool TruncatedNormalRule(double a, double b, double rate, double tol, std::vector<std::pair<double, double>> &out) {
    out.clear();
    // The discretisation below resolves φ over at most 12 units (its stated range): refuse beyond.
    if (!(b > a) || b - a > 12 * (1 + 1e-12)) return false;
    constexpr int M = MaxGaussLegendreNodes;
    // The weight φ on [a, b] as M Gauss–Legendre points: exact to round-off for the polynomials of
    // degree ≤ 2N + 1 the recurrence integrates against it (φ over ≤ 12 units is resolved).
    const GaussLegendreRule &g = GaussLegendre(M);
    std::array<double, M> x{}, w{};
    const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    // A symmetric interval (the rules across a window's chords: a = −b): φ is even there, so every
    // α_k is 0, π_k has the parity of k and π_k² is even — the sums over the (mirrored) nodes are twice
    // those over the positive half: half the exponentials and half the recurrence.
    const bool symmetric = a == -b;
    static_assert(M % 2 == 0, "the symmetric case takes the positive half of the nodes");
    const int i0 = symmetric ? M / 2 : 0;  // the rule's nodes ascend
    const double fold = symmetric ? 2 : 1;
    for (int i = i0; i < M; ++i) {
        x[std::size_t(i)] = mid + half * g.x[i];
        w[std::size_t(i)] = fold * half * g.w[i] * std::exp(-0.5 * x[std::size_t(i)] * x[std::size_t(i)]) / std::sqrt(2 * Pi);
    }
    return GaussRuleOfMeasure(x.data() + i0, w.data() + i0, M - i0, symmetric, DerivativeBound{rate}, tol,
                              MaxTruncatedNormalNodes, out);
}

namespace {

// A window N(·; (d, 0), s²I) straddling the edge of a disc of radius r about the origin, in axes
// along (u) and across (v) the window's centre, on [u0, u1]: rules of 4 and 6 nodes from the
// moments of the measure μ (the window on the disc), taken where g's Taylor remainder keeps them
// within tol. In standardised coordinates x = (u − d)/s − x̄ (x̄ the mean), y = v/s, and with
// a = s·R_u, b = s·R_v (g's rates along and across, the header's directional model: a derivative of
// order m along a unit direction e is at most (|e_u|R_u + |e_v|R_v)^m·sup|g|):
//   * 4 nodes: the u-marginal's two-point Gauss rule (standardised nodes (γ ∓ √(γ² + 4))/2, γ the
//     skewness), one ±y pair at each with y_k² solving Σ W_k y_k² = ∫y² dμ, Σ W_k x_k y_k² = ∫x y² dμ:
//     exact for every cubic in (x, y) (odd powers of y by symmetry). Error ≤ (E_μ + E_rule)
//     [(a|x| + b|y|)⁴]/4!.
//   * 6 nodes: the three-point Gauss rule of the u-marginal (Stieltjes on the discretisation below,
//     Golub–Welsch), one ±y pair at each with W_k y_k² = ∫ℓ_k(x) y² dμ (ℓ_k the Lagrange basis on
//     the three nodes, so ∫x^j y² dμ is matched for j ≤ 2): exact for every monomial of degree ≤ 5
//     except y⁴, x·y⁴ and x³y². Error ≤ b⁴|Δ(y⁴)|/4! + (5ab⁴|Δ(xy⁴)| + 10a³b²|Δ(x³y²)|)/5! +
//     (E_μ + E_rule)[(a|x| + b|y|)⁶]/6!, Δ(·) = ∫· dμ − rule.
// Each E[(a|x| + b|y|)^m] ≤ ((a^m E|x|^m)^{1/m} + (b^m E|y|^m)^{1/m})^m (Minkowski), all relative to
// μ's mass. The moments: across each chord |v| ≤ H = min(√(r² − u²), 6s) in closed form
// (∫z^{2j}φ(z) dz over |z| ≤ h = H/s: M = erf(h/√2), M − 2hφ(h), 3M − 2h(h² + 3)φ(h),
// 15M − 2h(h⁴ + 5h² + 15)φ(h)); along u by 32-point Gauss–Legendre on each piece between the tips'
// transitions (u = ±√(r² − 36s²), where H stops being 6s), mapped by u = mid − h·cos t (the
// square-root end of a chord at a tip is analytic in t). False (the caller builds its tensor rule)
// where neither bound is met or the measure is degenerate.
bool MomentStraddleRule(double u0, double u1, double d, double s, double r, double ru, double rv, double tol, Vec2 er,
                        Vec2 et, std::vector<EnsembleNode> &out) {
    constexpr int P = 32, MaxPoints = 3 * P;
    struct Tables {  // the mapped rule's t-nodes: weight (π/2)·w_i·sin t_i and −cos t_i
        std::array<double, P> w{}, c{};
    };
    static const Tables map = [] {
        Tables t;
        const GaussLegendreRule &g = GaussLegendre(P);
        for (int i = 0; i < P; ++i) {
            const double ti = 0.5 * Pi * (1 + g.x[i]);
            t.w[std::size_t(i)] = 0.5 * Pi * g.w[i] * std::sin(ti);
            t.c[std::size_t(i)] = -std::cos(ti);
        }
        return t;
    }();
    const double half = GaussianBox * s, var = s * s;
    const double e = half < r ? std::sqrt(r * r - half * half) : 0.0;
    double cuts[4] = {u0, 0, 0, 0};
    int pieces = 0;
    for (const double cut : {-e, e})
        if (e > 0 && cut > u0 && cut < u1) cuts[++pieces] = cut;
    cuts[++pieces] = u1;
    // Across a chord |y| ≤ h: its mass M and E[y²], E[y⁴], E[y⁶] under the normal restricted to it
    // (the same for every chord that spans ±6s).
    struct Across {
        double m0, y2, y4, y6;
    };
    // Short chords (h < 1), where the closed forms cancel to nothing (E[y⁶] ~ h⁶/7 against terms ~1):
    // E[y^{2j}] = h^{2j}·S_j/S_0, S_j = Σ_m (−h²/2)^m/(m!(2j + 2m + 1)) (∫₀^h z^{2j}e^{−z²/2} dz / h^{2j+1}),
    // 18 terms (the next below 1e-20 of the first).
    const auto AcrossChord = [](double h) {
        const double h2 = h * h, m0 = std::erf(h / std::sqrt(2.0));
        if (h < 1) {
            double sj[4] = {}, term = 1;
            for (int m = 0; m < 18; ++m, term *= -0.5 * h2 / m)
                for (int j = 0; j < 4; ++j) sj[j] += term / (2 * j + 2 * m + 1);
            return Across{m0, h2 * sj[1] / sj[0], h2 * h2 * sj[2] / sj[0], h2 * h2 * h2 * sj[3] / sj[0]};
        }
        const double phi = std::exp(-0.5 * h2) / std::sqrt(2 * Pi), inv = 1 / m0;
        return Across{m0, (m0 - 2 * h * phi) * inv, (3 * m0 - 2 * h * (h2 + 3) * phi) * inv,
                      (15 * m0 - 2 * h * (h2 * h2 + 5 * h2 + 15) * phi) * inv};
    };
    static const Across full = AcrossChord(GaussianBox);
    Across clipped{};
    // Per point: x (not yet centred), the u-weight times M, and the chord's E[y²], E[y⁴], E[y⁶].
    std::array<double, MaxPoints> px{}, pw{}, p2{}, p4{}, p6{};
    int n = 0;
    double mass = 0, first = 0;
    for (int p = 0; p < pieces; ++p) {
        const double mid = 0.5 * (cuts[p] + cuts[p + 1]), h = 0.5 * (cuts[p + 1] - cuts[p]);
        for (int i = 0; i < P; ++i, ++n) {
            const double u = mid + h * map.c[std::size_t(i)], x = (u - d) / s;
            const std::size_t k = std::size_t(n);
            const double chord = std::sqrt(std::max(0.0, r * r - u * u));
            const Across &across = chord >= half ? full : (clipped = AcrossChord(chord / s));
            px[k] = x;
            pw[k] = h * map.w[std::size_t(i)] / s * std::exp(-0.5 * x * x) / std::sqrt(2 * Pi) * across.m0;
            p2[k] = across.y2;
            p4[k] = across.y4;
            p6[k] = across.y6;
            mass += pw[k];
            first += pw[k] * x;
        }
    }
    if (!(mass > 0)) return false;
    const double mean = first / mass;
    // Central moments (relative to the mass): ex[j] = E[x^j] (j ≤ 6), ey[j] = E[x^j y²] (j ≤ 3),
    // e4[j] = E[x^j y⁴] (j ≤ 1), E[y⁶], E|x|⁵ unused (even orders bound the odd ones by Minkowski).
    double ex[7] = {}, ey[4] = {}, e4[2] = {}, e6 = 0;
    for (int i = 0; i < n; ++i) {
        const std::size_t k = std::size_t(i);
        px[k] -= mean;
        const double w = pw[k] / mass, x = px[k];
        double xj = w;
        for (int j = 0; j <= 6; ++j, xj *= x) {
            ex[j] += xj;
            if (j <= 3) ey[j] += xj * p2[k];
            if (j <= 1) e4[j] += xj * p4[k];
        }
        e6 += w * p6[k];
    }
    const double c2 = ex[2];
    if (!(c2 > 1e-12)) return false;
    const double a = s * ru, b = s * rv;
    auto minkowski = [](double ax, double by, int m) {  // ((ax)^{1/m} + (by)^{1/m})^m, arguments a^m·E|x|^m, b^m·E|y|^m
        return std::pow(std::pow(ax, 1.0 / m) + std::pow(by, 1.0 / m), m);
    };
    auto emit = [&](const double *x, const double *prob, const double *y2, int count) {
        for (int k = 0; k < count; ++k) {
            const double u = d + s * (mean + x[k]), v = s * std::sqrt(y2[k]);
            const double q = Normal1(u, d, var) * Normal1(v, 0, var);
            for (const double sign : {-1.0, 1.0}) out.push_back({er * u + et * (sign * v), 0.5 * mass * prob[k], q});
        }
    };
    // Four nodes.
    {
        const double sigma = std::sqrt(c2), gamma = ex[3] / (c2 * sigma), root = std::sqrt(gamma * gamma + 4);
        const double z[2] = {0.5 * (gamma - root), 0.5 * (gamma + root)};
        const double prob[2] = {z[1] / (z[1] - z[0]), -z[0] / (z[1] - z[0])};
        const double x[2] = {sigma * z[0], sigma * z[1]};
        const double y2[2] = {(ey[0] * x[1] - ey[1]) / (prob[0] * (x[1] - x[0])),
                              (ey[1] - ey[0] * x[0]) / (prob[1] * (x[1] - x[0]))};
        if (y2[0] >= 0 && y2[1] >= 0) {
            double rx4 = 0, ry4 = 0;
            for (int k = 0; k < 2; ++k) {
                rx4 += prob[k] * Sqr(Sqr(x[k]));
                ry4 += prob[k] * Sqr(y2[k]);
            }
            const double a4 = Sqr(Sqr(a)), b4 = Sqr(Sqr(b));
            if ((minkowski(a4 * ex[4], b4 * e4[0], 4) + minkowski(a4 * rx4, b4 * ry4, 4)) / 24 <= tol) {
                emit(x, prob, y2, 2);
                return true;
            }
        }
    }
    // Six nodes: the marginal's three-point Gauss rule by Stieltjes on the points (x centred: α₀ = 0).
    double alpha[3] = {0, 0, 0}, beta[3] = {0, c2, 0};
    {
        double n1 = 0, n2 = 0, xs1 = 0, xs2 = 0;
        for (int i = 0; i < n; ++i) {
            const std::size_t k = std::size_t(i);
            const double w = pw[k] / mass, x = px[k];
            xs1 += w * x * x * x;  // Σ w x π₁², π₁ = x
            n1 += w * x * x;
        }
        alpha[1] = xs1 / n1;
        for (int i = 0; i < n; ++i) {
            const std::size_t k = std::size_t(i);
            const double w = pw[k] / mass, x = px[k], pi2 = (x - alpha[1]) * x - beta[1];
            n2 += w * pi2 * pi2;
            xs2 += w * x * pi2 * pi2;
        }
        if (!(n2 > 0)) return false;
        alpha[2] = xs2 / n2;
        beta[2] = n2 / n1;
    }
    double x[3] = {alpha[0], alpha[1], alpha[2]}, off[2] = {std::sqrt(beta[1]), std::sqrt(beta[2])}, v0[3];
    if (!TridiagonalEigen(3, x, off, v0)) return false;
    double prob[3], y2[3];
    for (int k = 0; k < 3; ++k) {
        prob[k] = v0[k] * v0[k];
        // ℓ_k(x) = Π_{j≠k}(x − x_j)/(x_k − x_j) = (x² − S·x + P)/D.
        const double xa = x[(k + 1) % 3], xb = x[(k + 2) % 3];
        const double D = (x[k] - xa) * (x[k] - xb);
        if (!(std::abs(D) > 0) || !(prob[k] > 0)) return false;
        y2[k] = (ey[2] - (xa + xb) * ey[1] + xa * xb * ey[0]) / (D * prob[k]);
        if (!(y2[k] >= 0)) return false;
    }
    double rule[5] = {};  // Σ p x⁶, Σ p y⁶, Σ p y⁴, Σ p x y⁴, Σ p x³ y²
    for (int k = 0; k < 3; ++k) {
        const double x2 = x[k] * x[k];
        rule[0] += prob[k] * x2 * x2 * x2;
        rule[1] += prob[k] * y2[k] * y2[k] * y2[k];
        rule[2] += prob[k] * y2[k] * y2[k];
        rule[3] += prob[k] * x[k] * y2[k] * y2[k];
        rule[4] += prob[k] * x2 * x[k] * y2[k];
    }
    const double a6 = std::pow(a, 6), b6 = std::pow(b, 6);
    const double bound = Sqr(Sqr(b)) * std::abs(e4[0] - rule[2]) / 24 +
                         (5 * a * Sqr(Sqr(b)) * std::abs(e4[1] - rule[3]) + 10 * a * a * a * b * b * std::abs(ey[3] - rule[4])) / 120 +
                         (minkowski(a6 * ex[6], b6 * e6, 6) + minkowski(a6 * rule[0], b6 * rule[1], 6)) / 720;
    if (!(bound <= tol)) return false;  // (a NaN bound — infinite rates — declines too)
    emit(x, prob, y2, 3);
    return true;
}

// A window N(·; c, s²I), |c| = d, straddling the edge of a disc of radius r about the origin, in
// polar coordinates (ρ, ψ) about the disc's centre, ψ from c's direction: the disc is the rectangle
// ρ ≤ r, and no chord is clipped. At radius ρ the window's weight along the circle is a von Mises
// law exp(κ(cos ψ − 1)), κ = ρd/s², and its mass on the circle, ρ·e^{−(ρ−d)²/2s²}·I₀(κ)e^{−κ}/s², is
// the Rice density: radially the Gauss rule of the Rice density on [ρ₀, r] (ρ₀ = max(0, min(d, r) − 6s):
// the disc within 6s of the centre, or the 6s inside the edge where the window's tail lies), along
// each circle the Gauss rule of its von Mises law over |ψ| ≤ ψ_max (the weight below e^{−18} beyond,
// ψ_max ≤ π), both from 64-point Gauss–Legendre discretisations (GaussRuleOfMeasure). g is integrated
// only against these weights, so the node counts follow g's rate alone. Derivative bounds
// (DerivativeBound): along a circle of radius ρ the Touchard polynomial T_m(ρ·R_c), R_c g's largest
// rate over the directions the circle takes within ±ψ_max (Faà di Bruno: proven for that model);
// radially (s·(R_ρ + R_t))^m per unit of (ρ − d)/s — g along the radius and the von Mises law's
// widening with ρ, which moves the average on the circle as g's variation across does — plus the
// law's change itself, g's variation around the circle (≤ 2ρR_cψ_max, at most 2) times
// ((d/s)(1 − cos ψ_max))^m (a model, checked against brute force by the tests). Nodes into `out`
// (masses: Σ w = the window's mass on the disc), false if a rule needs more than MaxMeasureNodes.
bool PolarStraddle(Vec2 c, double s, double r, Vec2 rate, double tol, std::vector<EnsembleNode> &out, int *nr,
                   int *npsi) {
    constexpr int M = MaxGaussLegendreNodes;
    const double var = s * s, d = Length(c);
    const double theta = d > 0 ? std::atan2(c.y, c.x) : 0.0;
    auto psiMax = [&](double rho) {
        const double kappa = rho * d / var;
        return 18 < 2 * kappa ? std::acos(1 - 18 / kappa) : Pi;
    };
    // g's rate along a unit direction turned by at most ψ from (cos φ, sin φ): per axis (Bernstein),
    // |e_x|·R_x + |e_y|·R_y, which changes by at most ψ·(R_x + R_y).
    auto along = [&](double phi, double psi) {
        const double full = rate.x + rate.y;
        return std::min(full, std::abs(std::cos(phi)) * rate.x + std::abs(std::sin(phi)) * rate.y + psi * full);
    };
    const double rho0 = std::max(0.0, std::min(d, r) - GaussianBox * s);
    if (!(r > rho0)) return false;
    const double widest = psiMax(std::max(rho0, 1e-300 * r));
    const double rRadial = along(theta, widest), rTangent = along(theta + Pi / 2, widest);
    const double rCircle = std::max(rTangent, along(theta, widest));  // every direction the circle takes within ±ψ_max
    const GaussLegendreRule &g = GaussLegendre(M);
    std::array<double, M> x{}, w{};
    const double mid = 0.5 * (rho0 + r), half = 0.5 * (r - rho0);
    for (int i = 0; i < M; ++i) {
        const double rho = mid + half * g.x[i];
        x[std::size_t(i)] = (rho - d) / s;
        w[std::size_t(i)] = half * g.w[i] * rho / var * std::exp(-0.5 * Sqr(x[std::size_t(i)])) * BesselI0Scaled(rho * d / var);
    }
    thread_local std::vector<std::pair<double, double>> radial, around;
    // Radially: g along the radius and across (the law's widening), and g's variation around the circle
    // (≤ ρ·R·2ψ_max) weighted by the law's change, whose log-derivative per unit of (ρ − d)/s is
    // (d/s)·(cos ψ − 1), within (d/s)·(1 − cos ψ_max) of its mean.
    const DerivativeBound radialBound{s * (rRadial + rTangent), false, std::min(2.0, r * rCircle * 2 * widest),
                                      d / s * (1 - std::cos(widest))};
    if (!GaussRuleOfMeasure(x.data(), w.data(), M, false, radialBound, tol, MaxMeasureNodes, radial)) return false;
    *nr = int(radial.size());
    *npsi = 0;
    const std::size_t start = out.size();
    for (const auto &[xr, wr] : radial) {
        const double rho = d + s * xr, kappa = rho * d / var, pm = psiMax(rho);
        // The von Mises law on [−ψ_max, ψ_max], even: the positive half of a 64-point rule, masses doubled.
        for (int i = M / 2; i < M; ++i) {
            const double psi = pm * g.x[i];
            x[std::size_t(i)] = psi;
            w[std::size_t(i)] = 2 * pm * g.w[i] * std::exp(kappa * (std::cos(psi) - 1));
        }
        if (!GaussRuleOfMeasure(x.data() + M / 2, w.data() + M / 2, M / 2, true, DerivativeBound{rho * rCircle, true}, tol,
                                MaxMeasureNodes, around)) {
            out.resize(start);
            return false;
        }
        double sum = 0;
        for (const auto &[psi, wp] : around) sum += wp;
        for (const auto &[psi, wp] : around) {
            const Vec2 p(rho * std::cos(theta + psi), rho * std::sin(theta + psi));
            out.push_back({p, wr * wp / sum, std::exp(-0.5 * LengthSquared(p - c) / var) / (2 * Pi * var)});
        }
        *npsi = std::max(*npsi, int(around.size()));
    }
    return true;
}


}  // namespace

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
        const EnsembleBox box{mean - Vec2(half, half), mean + Vec2(half, half)};
        // The cheap bound first: where it needs one Gauss–Hermite node per axis, so do the rates
        // (GaussianAxis's rule depends on the rate only through the node count).
        Vec2 r(Infinity, Infinity);
        if (rates.bound) r = rates.bound(rates.ctx, box);
        if (!(GaussianAxisNodes(var, r.x, tol) == 1 && GaussianAxisNodes(var, r.y, tol) == 1)) r = rates(box);
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
    // A slowly varying g (a grating order's or a thin film's efficiency over a GR's spectrum, s·R ≲ 0.2):
    // four or six nodes from the measure's moments, where g's Taylor remainder is within tol.
    if (MomentStraddleRule(u0, u1, d, s, r, ru, rv, tol, er, et, out)) {
        info.nx = int(out.size()) / 2;
        info.ny = 2;
        return info;
    }
    // A narrow window at a wide disc's edge (r ≥ 10s): polar coordinates about the disc's centre, where
    // no chord is clipped (the tensor rules below under-resolve the average across a clipped chord near
    // its tip, whose width there is ~s²/r).
    if (r >= PolarMinRadius * s) {
        int nr = 0, npsi = 0;
        if (PolarStraddle(c, s, r, rate, tol, out, &nr, &npsi)) {
            info.nx = nr;
            info.ny = npsi;
            return info;
        }
        // Beyond the polar rules' nodes the chord rules below do not resolve the average across a
        // clipped chord near the tip (misses of up to ~700× their bound measured). Where the window's
        // mass beyond e = √(r² − 36s²) (the clipped chords) is below tol of its mass before it, that
        // part's error is below 2·tol·sup|g| whatever the rule does; else the bound is not proven.
        const double spans = std::sqrt(r * r - half * half), z = (spans - d) / (s * std::sqrt(2.0));
        if (0.5 * std::erfc(z) > tol * 0.5 * std::erfc(-z)) capped = true;
    }
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
