// SPDX-License-Identifier: Apache-2.0
// phasor — a lobe's efficiency averaged over an angular ensemble (lobe_average.h).
#include "core/render/lobe_average.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <vector>

#include "core/numerics/ensemble_quadrature.h"
#include "core/scratch_buffer.h"

namespace phasor {

namespace {

constexpr double Tolerance = LobeAverageTolerance;
/// A rate every efficiency has at least [rad per unit of the direction cosines]: the smooth
/// envelope of Fresnel coefficients, power factors and Jacobians (curvature O(1) per rad²).
constexpr double EnvelopeRate = 2;

std::atomic<bool> disabledForTesting{false};
thread_local LobeAverageCounters counters;

/// The coordinates of one wavelength's ensemble: u = direction cosines transverse to `a` (the
/// profile's centre) in the basis (e1, e2), e1 in the plane of `a` and the normal, pointing away
/// from the normal (|ω.xy| grows along +x).
struct EnsembleFrame {
    Vec3 a, e1, e2;
    explicit EnsembleFrame(const Vec3 &centre) : a(centre) {
        const Vec3 t(a.x, a.y, 0);
        Vec3 e = t - a * Dot(t, a);
        if (LengthSquared(e) < 1e-24) e = Vec3(1, 0, 0) - a * a.x;  // along the normal: any direction
        if (LengthSquared(e) < 1e-24) e = Vec3(0, 1, 0) - a * a.y;
        e1 = Normalize(e);
        e2 = Cross(a, e1);
    }
    Vec3 Direction(const Vec2 &u) const {
        return e1 * u.x + e2 * u.y + a * std::sqrt(std::max(0.0, 1 - LengthSquared(u)));
    }
    Vec2 Coordinates(const Vec3 &w) const { return Vec2(Dot(w, e1), Dot(w, e2)); }
};

/// The query direction wi′ whose lobe (indices nIn → nOut, tangential shift) points at ω at
/// wavelength λ (the vector grating equation inverted), on wi's side; false if none propagates.
bool QueryDirection(const Vec3 &omega, const Vec3 &wi, double nIn, double nOut, const Vec2 &shift, double lambda,
                    Vec3 *out) {
    const double k = lambda / (2 * Pi);
    const Vec2 xy = (Vec2(omega.x, omega.y) * (-nOut) + shift * k) / nIn;
    const double s2 = LengthSquared(xy);
    if (!(s2 < 1)) return false;
    *out = Vec3(xy.x, xy.y, std::copysign(std::sqrt(1 - s2), wi.z));
    return true;
}

/// The lobe's direction for a query at wi′ (forward vector grating equation), at the hero.
Vec3 LobeDirection(const Vec3 &wiPrime, const NearDeltaLobe &l, double lambda) {
    const Vec2 xy = (Vec2(wiPrime.x, wiPrime.y) * (-l.nIn[0]) + l.shift * (lambda / (2 * Pi))) / l.nOut[0];
    const double z = std::sqrt(std::max(0.0, 1 - LengthSquared(xy)));
    const bool transmitted = (l.flags & ScatterTransmission) != 0;
    return Vec3(xy.x, xy.y, (transmitted ? -1.0 : 1.0) * std::copysign(z, wiPrime.z));
}

/// (n_out/n_in)²·|cosθ_o|/|cosθ_i|: the irradiance a plane wave from ω delivers through the lobe per
/// unit irradiance, up to the lobe's efficiency (LobeTransfer::Irradiance).
double IrradianceTransfer(const Vec3 &omega, const Vec3 &wiPrime, double nIn, double nOut) {
    return Sqr(nOut / nIn) * std::abs(omega.z) / std::max(std::abs(wiPrime.z), 1e-300);
}

/// The transfer of a plane wave from ω relative to the ensemble's centre (LobeTransfer::Irradiance):
/// the lobe's irradiance transfer, and for a localized light (a beam narrower than the surface: every
/// plane wave's whole power crosses it) the obliquity |cosθ_ω|/|cosθ_centre| with which that power
/// crosses the surface — what the sensor's pixels, mapped onto the surface along the ensemble's
/// central direction, collect of it in total.
double RelativeTransfer(const Vec3 &omega, const Vec3 &wiPrime, const NearDeltaLobe &l, int i,
                        const LobeEnsemble::Wave &w, const Vec3 &wi) {
    double t = IrradianceTransfer(omega, wiPrime, l.nIn[i], l.nOut[i]) / IrradianceTransfer(w.source, wi, l.nIn[i], l.nOut[i]);
    if (w.profile.localized) t *= std::abs(omega.z) / std::max(std::abs(w.source.z), 1e-300);
    return t;
}

/// The ensemble shape of one wave in its frame.
EnsembleShape ShapeOf(const LobeEnsemble::Wave &w, const EnsembleFrame &f) {
    EnsembleShape s;
    switch (w.profile.kind) {
    case AngularProfile::Kind::Delta: s.profile = EnsembleShape::Profile::Delta; break;
    case AngularProfile::Kind::Disc:
        s.profile = EnsembleShape::Profile::Disc;
        s.radius = w.profile.radius;
        break;
    case AngularProfile::Kind::Gaussian:
        s.profile = EnsembleShape::Profile::Gaussian;
        s.variance = w.profile.variance;
        break;
    }
    if (std::isfinite(w.windowVariance) && !w.profile.windowed) {
        s.windowCentre = f.Coordinates(w.windowAxis);
        s.windowVariance = w.windowVariance;
    }
    return s;
}

/// Rates (R_x, R_y) of a lobe's efficiency over a box of ensemble coordinates: the kernel's bandwidth
/// B (per unit of |ω.xy|) times the largest derivative of s = |ω.xy| along each axis, plus the
/// rate of the phase's curvature √(B·(∂²s + (∂s)²/s)) (the chirp near normal incidence, where
/// ∂s vanishes) and the envelope's rate.
struct RateBound {
    const PreparedKernel &k;
    const EnsembleFrame &f;
    double nOut;  // index of the light's medium (κ = nOut·s)
    Vec2 operator()(const EnsembleBox &b) const {
        double grad[N][N][2];
        Vec2 g1(0, 0);
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < N; ++j) {
                const Point p = At(b, i, j);
                const Vec3 dx = f.e1 - f.a * (p.u.x / p.z), dy = f.e2 - f.a * (p.u.y / p.z);
                for (int c = 0; c < 2; ++c) {
                    const Vec3 &d = c == 0 ? dx : dy;
                    const double ds = p.s > 1e-12 ? (p.w.x * d.x + p.w.y * d.y) / p.s : std::sqrt(d.x * d.x + d.y * d.y);
                    grad[i][j][c] = ds;
                    g1[c] = std::max(g1[c], std::abs(ds));
                }
            }
        Vec2 g2(0, 0);
        const double hx = (b.hi.x - b.lo.x) / (N - 1), hy = (b.hi.y - b.lo.y) / (N - 1);
        for (int i = 0; i + 1 < N; ++i)
            for (int j = 0; j + 1 < N; ++j) {
                if (hx > 0) g2.x = std::max(g2.x, std::abs(grad[i + 1][j][0] - grad[i][j][0]) / hx);
                if (hy > 0) g2.y = std::max(g2.y, std::abs(grad[i][j + 1][1] - grad[i][j][1]) / hy);
            }
        const double smax = SampledMaxS(b), B = Bandwidth(smax), sRef = std::max(smax, 1e-6);
        Vec2 r;
        for (int c = 0; c < 2; ++c) r[c] = Rate(B, g1[c], g2[c], sRef);
        return r;
    }

    /// Rates at least operator()'s over b with only s sampled (BuildEnsembleRule asks this first):
    /// the kernel's bandwidth and sRef exactly as operator() has them (the same samples of s; the
    /// bandwidth need not grow with κ), and bounds of s's derivatives over the whole box in place of
    /// its sampled ones, for a box off the normal (s > 0: s is smooth there) and inside |u| ≤ 0.99
    /// (operator() clamps nothing there); Infinity elsewhere. With z = √(1 − |u|²) ≥ z₋ over the
    /// box and ω′ = ∂ω/∂u_c = e_c − a·u_c/z:
    ///   |∂s/∂u_c| ≤ |ω′| = √(1 + u_c²/z²) ≤ 1/z₋ = G₁,
    ///   |∂²s/∂u_c²| ≤ |∂²ω/∂u_c²| + |ω′|²/s ≤ 1/z₋³ + G₁²/s₋ (≥ the sampled differences of ∂s,
    ///   by the mean value theorem), s ≥ s(centre) − √2·G₁·(half the box's diagonal) = s₋.
    Vec2 Bound(const EnsembleBox &b) const {
        const double u2 = MaxU2(b);
        if (!(u2 <= 0.99 * 0.99)) return Vec2(Infinity, Infinity);
        const double zMin = std::sqrt(1 - u2);
        constexpr double Slack = 1 + 1e-9;  // over the sampled values' rounding
        const double g1 = Slack / zMin;
        const Vec3 w = f.Direction((b.lo + b.hi) * 0.5);
        const double sLo = std::sqrt(w.x * w.x + w.y * w.y) - std::sqrt(2.0) * g1 * 0.5 * Length(b.hi - b.lo) - 1e-12;
        if (!(sLo > 1e-9)) return Vec2(Infinity, Infinity);
        // The sampled ∂s = (ω.xy·ω′.xy)/s carries a rounding of a few ε·G₁/s, their differences
        // twice that over the step.
        const double hMin = std::min(b.hi.x - b.lo.x, b.hi.y - b.lo.y) / (N - 1);
        const double g2 = Slack / (zMin * zMin * zMin) + g1 * g1 / sLo + (hMin > 0 ? 1e-14 * g1 / (sLo * hMin) : 0.0);
        const double smax = SampledMaxS(b);
        const double r = Slack * Rate(Bandwidth(smax), g1, g2, std::max(smax, 1e-6));
        return Vec2(r, r);
    }

  private:
    static constexpr int N = 5;  // samples per axis
    /// The largest |u|² over the box.
    static double MaxU2(const EnsembleBox &b) {
        const double ux = std::max(std::abs(b.lo.x), std::abs(b.hi.x)), uy = std::max(std::abs(b.lo.y), std::abs(b.hi.y));
        return ux * ux + uy * uy;
    }
    /// Sample (i, j) of the box: u (pulled in to |u| = 0.999 beyond it), z = √(1 − |u|²), ω and
    /// s = |ω.xy|. (Unit-scale components throughout: plain square roots, no hypot.)
    struct Point {
        Vec2 u;
        double z;
        Vec3 w;
        double s;
    };
    /// The i-th of N sample coordinates over [lo, hi].
    static double Grid(double lo, double hi, int i) { return lo + (hi - lo) * i / (N - 1); }
    /// Sample (i, j)'s u and z.
    static Vec2 SampleU(const EnsembleBox &b, int i, int j, double *z) {
        Vec2 u(Grid(b.lo.x, b.hi.x, i), Grid(b.lo.y, b.hi.y, j));
        double l2 = LengthSquared(u);
        if (l2 > 0.999 * 0.999) {
            u = u * (0.999 / std::sqrt(l2));
            l2 = LengthSquared(u);
        }
        *z = std::sqrt(1 - l2);
        return u;
    }
    Point At(const EnsembleBox &b, int i, int j) const {
        Point p;
        p.u = SampleU(b, i, j, &p.z);
        p.w = f.e1 * p.u.x + f.e2 * p.u.y + f.a * p.z;  // f.Direction(u)
        p.s = std::sqrt(p.w.x * p.w.x + p.w.y * p.w.y);
        return p;
    }
    /// The largest s over the samples (At's): the κ = nOut·s at which both ask the kernel's bandwidth.
    double SampledMaxS(const EnsembleBox &b) const {
        // Where no sample is pulled in, At's products from per-row and per-column terms, and √ of
        // the largest s² (√ is monotone): the same value, ~200 fewer instructions.
        if (MaxU2(b) <= 0.99 * 0.99) {
            double s2 = 0;
            std::array<double, N> x2, y2, e1x, e1y, e2x, e2y;
            for (int i = 0; i < N; ++i) {
                const double x = Grid(b.lo.x, b.hi.x, i), y = Grid(b.lo.y, b.hi.y, i);
                x2[i] = x * x;
                y2[i] = y * y;
                e1x[i] = f.e1.x * x;
                e1y[i] = f.e1.y * x;
                e2x[i] = f.e2.x * y;
                e2y[i] = f.e2.y * y;
            }
            for (int i = 0; i < N; ++i)
                for (int j = 0; j < N; ++j) {
                    const double z = std::sqrt(1 - (x2[i] + y2[j]));
                    const double wx = e1x[i] + e2x[j] + f.a.x * z, wy = e1y[i] + e2y[j] + f.a.y * z;
                    s2 = std::max(s2, wx * wx + wy * wy);
                }
            return std::sqrt(s2);
        }
        double smax = 0;
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < N; ++j) smax = std::max(smax, At(b, i, j).s);
        return smax;
    }
    double Bandwidth(double smax) const { return nOut * k.AngularBandwidth(std::min(nOut * smax, nOut)); }
    /// The rate from the bandwidth B, |∂s| ≤ g1, |∂²s| ≤ g2 and s ≥ sRef (see above).
    static double Rate(double B, double g1, double g2, double sRef) {
        return B * g1 + std::sqrt(B * (g2 + g1 * g1 / sRef)) + EnvelopeRate;
    }
};

/// Wavelengths that share one rule with wavelength i: the same ensemble and a lobe whose map
/// between ω and wi′ does not depend on λ.
bool SameMap(const NearDeltaLobe &l, int i, int j) {
    return l.shift == Vec2(0, 0) && l.nIn[i] == l.nIn[j] && l.nOut[i] == l.nOut[j] && l.wo[i] == l.wo[j];
}

/// Calls visit(ω, wi′, weight) for every node of wavelength i's rule (wi′ invalid nodes are
/// skipped, their weight still counted in the returned normalisation); returns Σ weights.
template <typename Visit>
double ForEachNode(const PreparedKernel &k, const NearDeltaLobe &l, const LobeEnsemble::Wave &w, int i, Visit &&visit) {
    const ScatterQuery &q = k.Query();
    const EnsembleFrame f(w.source);
    const EnsembleShape shape = ShapeOf(w, f);
    thread_local std::vector<EnsembleNode> nodes;
    const RateBound rates{k, f, l.nOut[i]};
    const EnsembleRuleInfo info = BuildEnsembleRule(shape, rates, Tolerance, nodes);
    ++counters.rules;
    counters.capped += info.capped;
    double norm = 0;
    for (const EnsembleNode &n : nodes) {
        norm += n.w;
        const Vec3 omega = f.Direction(n.p);
        Vec3 wiPrime;
        if (!QueryDirection(omega, q.wi, l.nIn[i], l.nOut[i], l.shift, q.wl->lambda[i], &wiPrime)) continue;
        visit(omega, wiPrime, n.w, nodes.size() == 1);
    }
    return norm;
}

/// m prepared for the hit's query with wi′ in place of wi, in this thread's buffer for nodes (reset
/// here: valid until the next node). The hit's own kernel lives in the integrator's buffer.
const PreparedKernel &PrepareAt(const Material &m, const PreparedKernel &k, const Vec3 &wiPrime) {
    thread_local ScratchBuffer scratch;
    scratch.Reset();
    ScatterQuery qn = k.Query();
    qn.wi = wiPrime;
    return m.Prepare(qn, scratch);
}

}  // namespace

LobeEnsemble MeasurementEnsemble(const Frame &shading, const SpectralGenRay &g, const NearDeltaLobe &lobe,
                                 const Vec3 &toLight, const AngularProfile &profile) {
    LobeEnsemble e;
    // A profile with its own centre (a beam's overlap with the GR) is centred there.
    const Vec3 source = shading.ToLocal(LengthSquared(profile.centre) > 0 ? -profile.centre : toLight);
    for (int i = 0; i < g.count; ++i) {
        LobeEnsemble::Wave &w = e.wave[std::size_t(i)];
        w.source = source;
        w.profile = profile;
        w.windowAxis = lobe.wo[std::size_t(i)];
        const double k = g.k[std::size_t(i)] * lobe.Eta(i);
        w.windowVariance = 0.5 * (1 + Sqr(g.rho[std::size_t(i)])) / (g.beta2[std::size_t(i)] * k * k);
    }
    return e;
}

LobeEnsemble SourceEnsemble(const Frame &shading, const Vec3 &toLight, const AngularProfile &profile) {
    LobeEnsemble e;
    for (LobeEnsemble::Wave &w : e.wave) {
        w.source = shading.ToLocal(toLight);
        w.profile = profile;
    }
    return e;
}

SampledSpectrum AverageLobeWeight(const Material &m, const PreparedKernel &k, const NearDeltaLobe &lobe,
                                  const LobeEnsemble &e, LobeTransfer transfer, int wavelength) {
    const ScatterQuery &q = k.Query();
    SampledSpectrum out(0.0);
    ++counters.averages;
    const int count = q.wl->Count();
    if (disabledForTesting.load(std::memory_order_relaxed)) {
        for (int i = 0; i < count; ++i)
            if (wavelength < 0 || i == wavelength) out[i] = lobe.Weight()[i];
        return out;
    }
    std::array<bool, NumWavelengths> done{};
    for (int i = 0; i < count; ++i) {
        if ((wavelength >= 0 && i != wavelength) || done[std::size_t(i)]) continue;
        // The wavelengths this rule serves.
        std::array<int, NumWavelengths> group{};
        int members = 0;
        for (int j = i; j < count; ++j)
            if (j == i || (wavelength < 0 && !done[std::size_t(j)] && SameMap(lobe, i, j) &&
                           e.wave[std::size_t(j)] == e.wave[std::size_t(i)])) {
                group[std::size_t(members++)] = j;
                done[std::size_t(j)] = true;
            }
        const LobeEnsemble::Wave &w = e.wave[std::size_t(i)];
        unsigned slots = 0;
        for (int k = 0; k < members; ++k) slots |= 1u << group[std::size_t(k)];
        std::array<double, NumWavelengths> sum{};
        const double norm = ForEachNode(k, lobe, w, i, [&](const Vec3 &omega, const Vec3 &wiPrime, double weight, bool single) {
            SampledSpectrum a(0.0);
            if (single && SameDirection(omega, lobe.wo[std::size_t(i)], 1e-12)) {
                a = lobe.Weight(slots);  // the lobe's own direction: its listed weight
            } else {
                // The kernel's answer for this lobe alone where it gives one, else a new preparation.
                if (const std::optional<SampledSpectrum> at = k.LobeWeightAt(lobe.id, wiPrime, slots)) a = *at;
                else if (const NearDeltaLobe *l = PrepareAt(m, k, wiPrime).FindLobe(lobe.id)) a = l->Weight();
                ++counters.evaluations;
            }
            const double t = transfer == LobeTransfer::Irradiance ? RelativeTransfer(omega, wiPrime, lobe, i, w, q.wi) : 1.0;
            for (int k = 0; k < members; ++k) sum[std::size_t(k)] += weight * t * a[group[std::size_t(k)]];
        });
        for (int k = 0; k < members; ++k) out[group[std::size_t(k)]] = norm > 0 ? sum[std::size_t(k)] / norm : 0;
    }
    return out;
}

std::optional<LobeResponse> AverageLobeResponse(const Material &m, const PreparedKernel &k, int lobeId,
                                                const LobeEnsemble &e, LobeTransfer transfer) {
    const ScatterQuery &q = k.Query();
    const NearDeltaLobe *lobe = k.FindLobe(lobeId);
    if (!lobe) return std::nullopt;
    ++counters.averages;
    if (disabledForTesting.load(std::memory_order_relaxed)) return k.EvalLobe(lobeId, lobe->wo[0]);
    const int count = q.wl->Count();
    LobeResponse out;
    bool jones = true;  // every rule had one node, with a Jones matrix
    std::array<bool, NumWavelengths> done{};
    for (int i = 0; i < count; ++i) {
        if (done[std::size_t(i)]) continue;
        std::array<int, NumWavelengths> group{};
        int members = 0;
        for (int j = i; j < count; ++j)
            if (j == i || (!done[std::size_t(j)] && SameMap(*lobe, i, j) && e.wave[std::size_t(j)] == e.wave[std::size_t(i)])) {
                group[std::size_t(members++)] = j;
                done[std::size_t(j)] = true;
            }
        std::array<Mueller, NumWavelengths> sum{};
        std::optional<LobeResponse> only;  // the single node's response (keeps its Jones matrix)
        int nodes = 0;
        const LobeEnsemble::Wave &w = e.wave[std::size_t(i)];
        const double norm = ForEachNode(k, *lobe, w, i, [&](const Vec3 &omega, const Vec3 &wiPrime, double weight, bool single) {
            std::optional<LobeResponse> r =
                PrepareAt(m, k, wiPrime).EvalLobe(lobeId, LobeDirection(wiPrime, *lobe, q.wl->lambda[0]));
            ++counters.evaluations;
            if (!r) return;
            ++nodes;
            if (single) only = r;
            const double t = transfer == LobeTransfer::Irradiance ? RelativeTransfer(omega, wiPrime, *lobe, i, w, q.wi) : 1.0;
            for (int k = 0; k < members; ++k) {
                const std::size_t s = std::size_t(group[std::size_t(k)]);
                sum[std::size_t(k)] = sum[std::size_t(k)] + r->mueller[s] * (weight * t);
            }
        });
        for (int k = 0; k < members; ++k) {
            const std::size_t s = std::size_t(group[std::size_t(k)]);
            out.mueller[s] = norm > 0 ? sum[std::size_t(k)] * (1 / norm) : Mueller::Zero();
            if (only && nodes == 1) out.jones[s] = only->jones[s];
        }
        jones = jones && nodes == 1 && only && only->hasJones;
    }
    out.hasJones = jones;
    return out;
}

double HeroToShortest(const SampledWavelengths &wl) {
    double shortest = wl.lambda[0];
    for (int i = 1; i < wl.Count(); ++i) shortest = std::min(shortest, wl.lambda[i]);
    return 1.1 * wl.lambda[0] / shortest;
}

LobeAverageCounters &LobeAverageCost() { return counters; }

void SetLobeAverageDisabledForTesting(bool disabled) { disabledForTesting.store(disabled); }

std::pair<Vec2, Vec2> LobeAverageRatesForTesting(const PreparedKernel &k, const Vec3 &centre, double nOut,
                                                 const Vec2 &lo, const Vec2 &hi) {
    const EnsembleFrame f(centre);
    const RateBound rates{k, f, nOut};
    const EnsembleBox box{lo, hi};
    return {rates(box), rates.Bound(box)};
}

}  // namespace phasor
