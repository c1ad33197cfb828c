// SPDX-License-Identifier: Apache-2.0
// phasor — the free-space diffraction lobe of one event (fsd_lobe.h).
#include "integrators/fsd/fsd_lobe.h"

#include <algorithm>
#include <cmath>

#include "core/render/sampling.h"
#include "materials/aperture_integral.h"

namespace phasor::fsd {

namespace {

constexpr double SqrtPi = 1.77245385090551602730;

// The proxy's forward lobe: the GR's σ_k widened (as the aperture kernel's).
constexpr double ForwardWidening = 1.5;
// At most this many edge lobes (the heaviest).
constexpr std::size_t MaxEdgeLobes = 32;

// ∫_a^b N(x) dx for N the normal density of variance β²/2 (|ψ|² per axis), accurate in the tails.
double GaussInterval(double a, double b, double beta) {
    const double x = a / beta, y = b / beta;
    if (x >= 0) return 0.5 * (std::erfc(x) - std::erfc(y));
    if (y <= 0) return 0.5 * (std::erfc(-y) - std::erfc(-x));
    return 0.5 * (std::erf(y) - std::erf(x));
}

// The v in [a, b] with ∫_a^v N = target (0 ≤ target ≤ ∫_a^b N): safeguarded Newton.
double GaussInvert(double a, double b, double target, double beta) {
    double lo = a, hi = b, v = 0.5 * (a + b);
    for (int it = 0; it < 100; ++it) {
        const double g = GaussInterval(a, v, beta) - target;
        if (g > 0) hi = v;
        else lo = v;
        const double n = std::exp(-v * v / (beta * beta)) / (SqrtPi * beta);
        double next = n > 0 ? v - g / n : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (std::abs(next - v) <= 1e-14 * (std::abs(v) + beta)) return next;
        v = next;
    }
    return v;
}

}  // namespace

Lobe::Lobe(const Event &ev, const SpectralGenRay &g, const SampledWavelengths &wl, const Settings &s)
    : ev_(ev), wl_(wl) {
    count_ = std::min(wl.Count(), g.count);
    for (int i = 0; i < count_; ++i) {
        k_[i] = g.k[i];
        beta2_[i] = g.beta2[i];
        rho_[i] = g.rho[i];
        // The integration radius ϱ as MakePlateGaussian wants it: in units of β.
        window_[i] = s.radius > 0 ? s.radius / std::sqrt(g.beta2[i]) : s.window;
    }
    babinet_ = ev.mask.covered.size() + 1 < ev.mask.open.size();

    // The proxy, for the hero.
    k0_ = k_[0];
    const double beta2 = beta2_[0], beta = std::sqrt(beta2), rho = rho_[0];
    sigmaF_ = ForwardWidening * std::sqrt(0.5 * (1 + rho * rho) / beta2);
    gamma_ = std::sqrt(std::max(1.0, std::abs(rho))) / beta;
    // Edge lobes: each boundary segment (clipped to the box), weighted by the GR's amplitude at
    // its nearest point and its length within a few β.
    const double hu = 2 * ev.halfWidth, hv = ev.halfWidth;
    struct Weighted {
        EdgeLobe e;
        double w;
    };
    std::vector<Weighted> cand;
    for (const OrientedSegment &sg : ev.edges) {
        // Clip to the box (Liang–Barsky).
        Vec2 a = sg.a, d = sg.b - sg.a;
        double t0 = 0, t1 = 1;
        bool inside = true;
        const double p[4] = {-d.x, d.x, -d.y, d.y}, qv[4] = {a.x + hu, hu - a.x, a.y + hv, hv - a.y};
        for (int j = 0; j < 4 && inside; ++j) {
            if (p[j] == 0) {
                if (qv[j] < 0) inside = false;
            } else {
                const double r = qv[j] / p[j];
                if (p[j] < 0) t0 = std::max(t0, r);
                else t1 = std::min(t1, r);
            }
        }
        if (!inside || !(t1 > t0)) continue;
        const Vec2 pa = a + d * t0, pb = a + d * t1, e = pb - pa;
        const double len = Length(e);
        if (!(len > 0)) continue;
        const Vec2 tt = e / len;
        const double along = std::clamp(-Dot(pa, tt), 0.0, len);
        const Vec2 x = pa + tt * along;  // nearest point to the GR's centre
        const double w = std::exp(-LengthSquared(x) / beta2) * std::min(len, 4 * beta) / beta;
        if (!(w > 1e-8)) continue;
        Weighted c;
        c.e.c = x * (rho / beta2);  // the traced GR's local wavevector there (ρ > 0 diverging)
        c.e.t = tt;
        c.e.m = Vec2(-tt.y, tt.x);
        c.w = w;
        cand.push_back(c);
    }
    std::sort(cand.begin(), cand.end(), [](const Weighted &a, const Weighted &b) { return a.w > b.w; });
    if (cand.size() > MaxEdgeLobes) cand.resize(MaxEdgeLobes);
    double wsum = 0;
    for (const Weighted &c : cand) wsum += c.w;
    const double open = std::clamp(1 - ev.coveredFraction, 0.0, 1.0);
    probCosine_ = 0.1;
    if (cand.empty()) {
        probForward_ = 0.9;
        probEdges_ = 0;
    } else {
        probForward_ = 0.1 + 0.4 * open;
        probEdges_ = 1 - probCosine_ - probForward_;
        for (const Weighted &c : cand) {
            EdgeLobe e = c.e;
            e.prob = c.w / wsum;
            edges_.push_back(e);
        }
    }
}

Complex Lobe::Amplitude(int i, const Vec3 &s, const IncidentWave &w) const {
    const Frame &f = ev_.frame;
    PlateGaussian g = MakePlateGaussian(f.n, s, f.s, f.t, f.n, k_[i], beta2_[i], rho_[i],
                                        w.beam ? Infinity : w.dist, window_[i]);
    if (w.beam) AddIncidentBeam(&g, *w.beam, ev_.p, f.s, f.t);
    const double hu = 2 * ev_.halfWidth, hv = ev_.halfWidth;
    // Each trapezoid in slabs at most 2β high: one window-high piece (8β) of a strongly curved
    // GR (ρ ≳ 20) is integrated wrongly by IntegrateTrapezoid (|A|² of the open box 0.8 % off at
    // ρ = 20, 3× at ρ = 320); in slabs of 2β it agrees with the closed form to 10⁻⁵.
    auto piece = [&](double v0, double v1, double a0, double a1, double b0, double b1) {
        v0 = std::max(v0, -hv);
        v1 = std::min(v1, hv);
        if (!(v1 > v0)) return Complex(0);
        const int n = std::max(1, int(std::ceil((v1 - v0) / (2 * std::sqrt(beta2_[i])))));
        Complex sum = 0;
        for (int j = 0; j < n; ++j)
            sum += IntegrateTrapezoid(g, v0 + (v1 - v0) * j / n, v0 + (v1 - v0) * (j + 1) / n, a0, a1, b0, b1);
        return sum;
    };
    Complex a = 0;
    if (babinet_) {
        a = piece(-hv, hv, -hu, 0, hu, 0);
        for (const Trapezoid &t : ev_.mask.covered) a -= piece(t.v0, t.v1, t.loA, t.loB, t.hiA, t.hiB);
    } else {
        for (const Trapezoid &t : ev_.mask.open) a += piece(t.v0, t.v1, t.loA, t.loB, t.hiA, t.hiB);
    }
    // The GR's normalisation on a plane ⊥ d: (πβ²)^{−1/2} (unit norm, theory §1.3).
    return a / std::sqrt(Pi * beta2_[i]);
}

SampledSpectrum Lobe::Eval(const Vec3 &wo, const IncidentWave &w) const {
    SampledSpectrum f(0.0);
    const double cosO = Dot(wo, ev_.frame.n);
    if (!(cosO > 0)) return f;
    for (int i = 0; i < count_; ++i) {
        if (!(beta2_[i] > 0 && k_[i] > 0)) continue;
        const double lambda = 2 * Pi / k_[i];
        f[i] = std::norm(Amplitude(i, -wo, w)) / (lambda * lambda * cosO);
    }
    return f;
}

double Lobe::ProxyPdfQ(const Vec2 &q) const {
    const double s2 = sigmaF_ * sigmaF_;
    double p = probForward_ * std::exp(-0.5 * LengthSquared(q) / s2) / (2 * Pi * s2);
    if (probEdges_ > 0) {
        double pe = 0;
        for (const EdgeLobe &e : edges_) {
            const Vec2 r = q - e.c;
            const double qt = Dot(r, e.t), qm = Dot(r, e.m);
            pe += e.prob * std::exp(-0.5 * qt * qt / s2) / (std::sqrt(2 * Pi) * sigmaF_) * gamma_ /
                  (Pi * (gamma_ * gamma_ + qm * qm));
        }
        p += probEdges_ * pe;
    }
    return p;
}

double Lobe::Pdf(const Vec3 &wo) const {
    const Frame &f = ev_.frame;
    const double cosO = Dot(wo, f.n);
    if (!(cosO > 0)) return 0;
    const Vec2 q = Vec2(Dot(wo, f.s), Dot(wo, f.t)) * k0_;
    return ProxyPdfQ(q) * k0_ * k0_ * cosO + probCosine_ * cosO * InvPi;
}

std::optional<Vec3> Lobe::SampleDirection(double u0, const Vec2 &u) const {
    const Frame &f = ev_.frame;
    Vec3 wo;
    if (u0 < probForward_ + probEdges_) {
        Vec2 q;
        if (u0 < probForward_) {
            const double r = std::sqrt(-2 * std::log(std::max(1 - u.x, 1e-300))), phi = 2 * Pi * u.y;
            q = Vec2(r * std::cos(phi), r * std::sin(phi)) * sigmaF_;
        } else {
            // Pick an edge with the remainder of u0, and reuse what is left of it as a third number.
            double x = (u0 - probForward_) / probEdges_;
            std::size_t j = 0;
            while (j + 1 < edges_.size() && x >= edges_[j].prob) x -= edges_[j].prob, ++j;
            const double ur = std::clamp(x / edges_[j].prob, 0.0, 1.0 - 1e-16);
            const EdgeLobe &e = edges_[j];
            const double qt = std::sqrt(-2 * std::log(std::max(1 - u.x, 1e-300))) * std::cos(2 * Pi * ur) * sigmaF_;
            const double qm = gamma_ * std::tan(Pi * (u.y - 0.5));
            q = e.c + e.t * qt + e.m * qm;
        }
        const Vec2 sdir = q / k0_;
        const double s2 = LengthSquared(sdir);
        if (!(s2 < 1)) return std::nullopt;  // evanescent
        wo = f.s * sdir.x + f.t * sdir.y + f.n * std::sqrt(1 - s2);
    } else {
        const Vec2 c = ConcentricDisc(u);
        const double z = SafeSqrt(1 - LengthSquared(c));
        if (!(z > 0)) return std::nullopt;
        wo = f.s * c.x + f.t * c.y + f.n * z;
    }
    return Normalize(wo);
}

std::optional<LobeSample> Lobe::Sample(double u0, const Vec2 &u) const {
    const std::optional<Vec3> wo = SampleDirection(u0, u);
    if (!wo) return std::nullopt;
    const Frame &f = ev_.frame;
    LobeSample s;
    s.wo = *wo;
    s.pdf = Pdf(s.wo);
    if (!(s.pdf > 0) || !std::isfinite(s.pdf)) return std::nullopt;
    s.weight = Eval(s.wo) * (Dot(s.wo, f.n) / s.pdf);
    return s;
}

std::optional<Vec2> SampleCovered(const Event &ev, double u0, const Vec2 &u, double *weight) {
    if (!(ev.coveredFraction > 0) || ev.mask.covered.empty()) return std::nullopt;
    const double beta = std::sqrt(ev.heroBeta2);
    // The trapezoid, with probability ∝ its mass.
    double x = u0 * ev.coveredFraction;
    std::size_t j = 0;
    while (j + 1 < ev.coveredMass.size() && x >= ev.coveredMass[j]) x -= ev.coveredMass[j], ++j;
    const Trapezoid &tr = ev.mask.covered[j];
    const double mj = ev.coveredMass[j];
    if (!(mj > 0)) return std::nullopt;
    // v from the per-axis normal truncated to the trapezoid's v-range (clipped to ±8β, where
    // GaussianMass stops), then u from it truncated to [lo(v), hi(v)].
    const double v0 = std::max(tr.v0, -8 * beta), v1 = std::min(tr.v1, 8 * beta);
    if (!(v1 > v0)) return std::nullopt;
    const double zv = GaussInterval(v0, v1, beta);
    if (!(zv > 0)) return std::nullopt;
    const double v = GaussInvert(v0, v1, u.x * zv, beta);
    const double lo = tr.Lo(v), hi = tr.Hi(v);
    if (!(hi > lo)) return std::nullopt;
    const double zu = GaussInterval(lo, hi, beta);
    if (!(zu > 0)) return std::nullopt;
    const double uu = GaussInvert(lo, hi, u.y * zu, beta);
    // Density of (u, v): (m_j/M)·N(v)N(u)/(z_v z_u); |ψ|² = N(u)N(v); branch probability M.
    *weight = zv * zu / mj;
    return Vec2(uu, v);
}

}  // namespace phasor::fsd
