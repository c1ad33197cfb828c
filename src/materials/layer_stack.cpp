// SPDX-License-Identifier: Apache-2.0
// phasor — layer-stack response (layer_stack.h).
//
// Coherent response: the characteristic-matrix (Abelès) product of the stack, evaluated as the
// equivalent Rouard recursion from the substrate up (theory §4.5):
//   Γ_N = r_{N,N+1};   Γ_{j−1} = (r_{j−1,j} + Γ_j e^{2iδ_j}) / (1 + r_{j−1,j} Γ_j e^{2iδ_j}),
//   δ_j = (2π/λ) n_j d_j cosθ_j,  r = Γ₀,
// with the transmitted amplitude accumulated alongside (multiple reflections inside layer j sum
// to the geometric series 1/(1 + r_{j−1,j} Γ_j e^{2iδ_j})):
//   t = t_{N,N+1} · Π_j t_{j−1,j} e^{iδ_j} / (1 + r_{j−1,j} Γ_j e^{2iδ_j}).
// Every factor has |e^{iδ}| ≤ 1 because Im(n_j cosθ_j) ≥ 0 (RefractedCos), so thick absorbing
// or evanescent layers underflow to an opaque layer instead of overflowing as the 2×2 matrix
// product's e^{−iδ} entries do. The interface coefficients are fresnel.h's, so a stack without
// layers is FresnelAmplitudes itself and the conventions (signs, branches) are shared.
//
// Incoherent response: the same recursion in power. Every wave that leaves the top of a layer
// is a product of amplitude factors (face coefficients, e^{iδ} per pass), and the set of waves is
// a free product of choices (how often to go round inside each layer), so the sum over waves of
// a_u·conj(a_v) (u, v ∈ {s, p}) factorises into geometric series of the same form, with every
// factor x replaced by x_u·conj(x_v) ("channels" ss, pp, sp below):
//   G ← ρ + τ·G·A² / (1 − ρ'·G·A²),   T ← t·T·A / (1 − ρ'·G·A²),
// where ρ, ρ' are the effective interface's reflection (from above, from below), τ = t·t', and
// A = |e^{iδ}|² is the layer's single-pass power attenuation (δ is the same for s and p, so
// e^{iδ}·conj(e^{iδ}) = A in every channel). The effective interfaces are the coherent runs of
// non-propagating layers with their faces (a bare face when the run is empty), computed by the
// coherent recursion from both sides.
#include "materials/layer_stack.h"

#include <array>
#include <type_traits>
#include <vector>

#include "materials/fresnel.h"

namespace phasor {

namespace {

// A buffer of n elements on the stack for the common short stacks, on the heap beyond. The inline
// storage is not initialised (every caller writes an element before reading it): zeroing ten
// Fresnel coefficients cost more than a one-layer stack's recursion.
template <typename T, std::size_t Small = 10>
class Scratch {
    static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);

  public:
    explicit Scratch(std::size_t n) {
        if (n > Small) big_.resize(n);
        data_ = n > Small ? big_.data() : reinterpret_cast<T *>(small_);
    }
    Scratch(const Scratch &) = delete;  // data_ may point into the object itself
    Scratch &operator=(const Scratch &) = delete;
    T &operator[](std::size_t i) { return data_[i]; }
    const T &operator[](std::size_t i) const { return data_[i]; }

  private:
    alignas(T) unsigned char small_[Small * sizeof(T)];
    std::vector<T> big_;
    T *data_;
};

// Media 0 … N+1 (incident, layers, substrate) with cosθ from Snell's invariant n·sinθ = n₀sinθ₀,
// each computed from the incident medium: chaining j → j+1 would accumulate round-off in the
// imaginary parts behind a complex layer, enough to flip the branch of a nearly grazing wave in
// the exit medium (a negative transmittance).
struct Media {
    Scratch<Complex> n, cosT;
    Media(Complex nIncident, Complex cosIncident, std::span<const Layer> layers, Complex nSubstrate)
        : n(layers.size() + 2), cosT(layers.size() + 2) {
        const std::size_t count = layers.size();
        n[0] = nIncident;
        cosT[0] = cosIncident;
        for (std::size_t j = 0; j < count; ++j) n[j + 1] = layers[j].n;
        n[count + 1] = nSubstrate;
        for (std::size_t j = 1; j <= count + 1; ++j) cosT[j] = RefractedCos(n[0], cosT[0], n[j]);
    }
};

// The same for lossless media (real indices and cosθ_i) in which every wave propagates
// (cos²θ > 0): cosθ in real arithmetic. `valid` is false when a medium absorbs or a wave is
// evanescent (or grazing); the complex Media then applies.
struct RealMedia {
    Scratch<double> n, cosT;
    bool valid = true;
    RealMedia(Complex nIncident, Complex cosIncident, std::span<const Layer> layers, Complex nSubstrate)
        : n(layers.size() + 2), cosT(layers.size() + 2) {
        const std::size_t count = layers.size();
        valid = nIncident.imag() == 0 && cosIncident.imag() == 0 && nSubstrate.imag() == 0;
        n[0] = nIncident.real();
        cosT[0] = cosIncident.real();
        for (std::size_t j = 0; j < count; ++j) {
            n[j + 1] = layers[j].n.real();
            valid = valid && layers[j].n.imag() == 0;
        }
        n[count + 1] = nSubstrate.real();
        for (std::size_t j = 1; j <= count + 1 && valid; ++j) {
            // RefractedCos's (1 − r²) + r²cos²θ₀, r = n₀/n_j; its principal root is the propagating branch.
            const double r = n[0] / n[j], cos2 = (1 - r * r) + r * r * cosT[0] * cosT[0];
            valid = n[j] > 0 && cos2 > 0;
            cosT[j] = std::sqrt(cos2);
        }
    }
};

// e^{iδ} for δ = k₀·(n cosθ)·d: real n cosθ (a propagating wave in a lossless layer) by sincos.
Complex PhaseFactor(double nCos, double k0d) {
    const double delta = k0d * nCos;
    return {std::cos(delta), std::sin(delta)};
}
Complex PhaseFactor(Complex nCos, double k0d) { return std::exp(Complex(0, k0d) * nCos); }

// The Rouard recursion of the file comment over media m (Media or RealMedia; the face coefficients
// in the media's arithmetic, Γ and t complex).
template <typename M>
StackResponse Rouard(double lambda, const M &m, std::span<const Layer> layers) {
    const std::size_t count = layers.size();
    Scratch<FresnelCoefficients> face(count + 1);  // face[j]: medium j → medium j+1
    for (std::size_t j = 0; j <= count; ++j) face[j] = FresnelAmplitudes(m.n[j], m.cosT[j], m.n[j + 1], m.cosT[j + 1]);

    const double k0 = 2 * Pi / lambda;
    Complex gs = face[count].rs, gp = face[count].rp;  // Γ below the last layer
    Complex ts = face[count].ts, tp = face[count].tp;
    for (std::size_t j = count; j-- > 0;) {  // layer j+1 (1-based), its top face is face[j]
        const Complex phase = PhaseFactor(m.n[j + 1] * m.cosT[j + 1], k0 * layers[j].thickness);  // e^{iδ}
        const Complex round = phase * phase;                                                       // e^{2iδ}
        const Complex ds = 1.0 + face[j].rs * gs * round, dp = 1.0 + face[j].rp * gp * round;
        ts *= face[j].ts * phase / ds;
        tp *= face[j].tp * phase / dp;
        gs = (face[j].rs + gs * round) / ds;
        gp = (face[j].rp + gp * round) / dp;
    }

    StackResponse out;
    const Complex n0 = m.n[0], cos0 = m.cosT[0], nLast = m.n[count + 1], cosLast = m.cosT[count + 1];
    out.rs = gs;
    out.rp = gp;
    out.ts = ts;
    out.tp = tp;
    out.cosSubstrate = cosLast;
    out.Rs = std::norm(gs);
    out.Rp = std::norm(gp);
    out.Ts = FresnelPowerFactorS(n0, cos0, nLast, cosLast) * std::norm(ts);
    out.Tp = FresnelPowerFactorP(n0, cos0, nLast, cosLast) * std::norm(tp);
    return out;
}

// The s–p channels of a sum over waves of a_u·conj(a_v): ss, pp (real) and sp.
struct Channels {
    double ss, pp;
    Complex sp;
    static Channels Of(Complex s, Complex p) { return {std::norm(s), std::norm(p), s * std::conj(p)}; }
    Channels operator*(const Channels &o) const { return {ss * o.ss, pp * o.pp, sp * o.sp}; }
    Channels operator*(double a) const { return {ss * a, pp * a, sp * a}; }
    Channels operator/(const Channels &o) const { return {ss / o.ss, pp / o.pp, sp / o.sp}; }
    Channels operator+(const Channels &o) const { return {ss + o.ss, pp + o.pp, sp + o.sp}; }
    Channels OneMinus() const { return {1.0 - ss, 1.0 - pp, 1.0 - sp}; }
};

// A bare interface (no layers): fresnel.h's amplitudes with the power factors — the response
// both functions below reduce to, computed without the stack's bookkeeping (the hot path of
// every uncoated conductor and dielectric).
StackResponse Bare(Complex nIncident, Complex cosIncident, Complex nSubstrate) {
    const FresnelCoefficients f = FresnelAmplitudes(nIncident, cosIncident, nSubstrate);
    StackResponse out;
    out.rs = f.rs;
    out.rp = f.rp;
    out.ts = f.ts;
    out.tp = f.tp;
    out.cosSubstrate = f.cosThetaT;
    out.Rs = std::norm(f.rs);
    out.Rp = std::norm(f.rp);
    out.Ts = FresnelPowerFactorS(nIncident, cosIncident, nSubstrate, f.cosThetaT) * std::norm(f.ts);
    out.Tp = FresnelPowerFactorP(nIncident, cosIncident, nSubstrate, f.cosThetaT) * std::norm(f.tp);
    return out;
}

}  // namespace

StackResponse LayerStackResponse(double lambda, Complex nIncident, Complex cosIncident,
                                 std::span<const Layer> layers, Complex nSubstrate) {
    if (layers.empty()) return Bare(nIncident, cosIncident, nSubstrate);
    // A soap film or a dielectric coating lit from outside: real arithmetic (−45 % of the
    // recursion's instructions, docs/architecture.md).
    if (const RealMedia real(nIncident, cosIncident, layers, nSubstrate); real.valid) return Rouard(lambda, real, layers);
    return Rouard(lambda, Media(nIncident, cosIncident, layers, nSubstrate), layers);
}

double LayerStackBandwidth(double lambda, Complex nIncident, Complex cosIncident, std::span<const Layer> layers,
                           Complex nSubstrate, double tol) {
    const double k0 = 2 * Pi / lambda;
    const double kappa = std::abs((nIncident * std::sqrt(1.0 - cosIncident * cosIncident)).real());
    // The branch points of the half-spaces' √(n² − κ²) (grazing, critical angle).
    double envelope = 0;
    for (const Complex n : {nIncident, nSubstrate}) envelope += kappa / std::max(std::abs(n * n - kappa * kappa), 1e-9);
    if (layers.empty()) return envelope;
    const std::size_t count = layers.size();
    const Media m(nIncident, cosIncident, layers, nSubstrate);
    double phase = 0;
    for (std::size_t j = 1; j <= count; ++j)
        phase += 2 * k0 * layers[j - 1].thickness * kappa / std::max(std::abs(m.n[j] * m.cosT[j]), 1e-9);
    // ρ_j from the recursion of LayerStackResponse: the ratio of the series 1/(1 + r_{j−1,j}Γ_j e^{2iδ_j}).
    const Complex i(0, 1);
    FresnelCoefficients face = FresnelAmplitudes(m.n[count], m.cosT[count], m.n[count + 1], m.cosT[count + 1]);
    Complex gs = face.rs, gp = face.rp;
    double ratio = 0;
    for (std::size_t j = count; j-- > 0;) {
        face = FresnelAmplitudes(m.n[j], m.cosT[j], m.n[j + 1], m.cosT[j + 1]);
        const Complex phaseFactor = std::exp(i * k0 * m.n[j + 1] * m.cosT[j + 1] * layers[j].thickness);
        const Complex round = phaseFactor * phaseFactor;
        const Complex xs = face.rs * gs * round, xp = face.rp * gp * round;
        ratio = std::max({ratio, std::abs(xs), std::abs(xp)});
        gs = (face.rs + gs * round) / (1.0 + xs);
        gp = (face.rp + gp * round) / (1.0 + xp);
    }
    double harmonics = 1;
    if (ratio >= 1) harmonics = 64;
    else if (ratio > tol) harmonics = std::min(64.0, std::ceil(std::log(tol) / std::log(ratio)));
    return harmonics * phase + envelope;
}

IncoherentStackResponse LayerStackIncoherent(double lambda, Complex nIncident, Complex cosIncident,
                                             std::span<const Layer> layers, Complex nSubstrate) {
    if (layers.empty()) {
        const StackResponse b = Bare(nIncident, cosIncident, nSubstrate);
        const double scale = std::sqrt(std::max(0.0, b.Ts * b.Tp) / std::max(std::norm(b.ts) * std::norm(b.tp), 1e-300));
        return {b.Rs, b.Rp, b.Ts, b.Tp, b.rs * std::conj(b.rp), b.ts * std::conj(b.tp) * scale};
    }
    const std::size_t count = layers.size();
    const Media m(nIncident, cosIncident, layers, nSubstrate);
    // The layers summed in power (1-based indices into the media), top first.
    Scratch<std::size_t> summed(count);
    std::size_t k = 0;
    for (std::size_t j = 1; j <= count; ++j)
        if (layers[j - 1].thickness > 0 && LayerPropagates(m.n[j] * m.cosT[j])) summed[k++] = j;

    // Effective interface between media a < b (the coherent layers a+1 … b−1 with both faces):
    // seen from above (reflection ρ, transmission t) and from below (ρ'), and τ = t·t' (down and
    // back up).
    struct Effective {
        Channels rho, rhoBelow, t, tau;
    };
    auto effective = [&](std::size_t a, std::size_t b) {
        if (b == a + 1) {
            // A bare face: Stokes' relations r' = −r, t·t' = 1 − r² (fresnel.h) give the view from below.
            const FresnelCoefficients f = FresnelAmplitudes(m.n[a], m.cosT[a], m.n[b], m.cosT[b]);
            const Channels rho = Channels::Of(f.rs, f.rp);
            return Effective{rho, rho, Channels::Of(f.ts, f.tp), Channels::Of(1.0 - f.rs * f.rs, 1.0 - f.rp * f.rp)};
        }
        const std::span<const Layer> run = layers.subspan(a, b - a - 1);  // layers a+1 … b−1 (1-based)
        Scratch<Layer> reversed(run.size());
        for (std::size_t j = 0; j < run.size(); ++j) reversed[j] = run[run.size() - 1 - j];
        const StackResponse down = LayerStackResponse(lambda, m.n[a], m.cosT[a], run, m.n[b]);
        const StackResponse up = LayerStackResponse(lambda, m.n[b], m.cosT[b],
                                                    std::span<const Layer>(&reversed[0], run.size()), m.n[a]);
        return Effective{Channels::Of(down.rs, down.rp), Channels::Of(up.rs, up.rp), Channels::Of(down.ts, down.tp),
                         Channels::Of(down.ts * up.ts, down.tp * up.tp)};
    };

    // From the substrate up: G and T below summed layer `summed[s]`, then through it.
    const double k0 = 2 * Pi / lambda;
    const Effective bottom = effective(k ? summed[k - 1] : 0, count + 1);
    Channels g = bottom.rho, t = bottom.t;
    for (std::size_t s = k; s-- > 0;) {
        const std::size_t j = summed[s];
        const double a = std::exp(-2 * (k0 * m.n[j] * m.cosT[j] * layers[j - 1].thickness).imag());  // |e^{iδ}|²
        const Effective above = effective(s ? summed[s - 1] : 0, j);
        const Channels back = g * (a * a);                          // down through the layer, G, back up
        const Channels denom = (above.rhoBelow * back).OneMinus();  // Σ_m (ρ'·G·A²)^m
        g = above.rho + above.tau * back / denom;
        t = above.t * t * a / denom;
    }

    IncoherentStackResponse out;
    const std::size_t last = count + 1;
    const double ps = FresnelPowerFactorS(m.n[0], m.cosT[0], m.n[last], m.cosT[last]);
    const double pp = FresnelPowerFactorP(m.n[0], m.cosT[0], m.n[last], m.cosT[last]);
    out.Rs = g.ss;
    out.Rp = g.pp;
    out.Rsp = g.sp;
    out.Ts = ps * t.ss;
    out.Tp = pp * t.pp;
    out.Tsp = std::sqrt(std::max(0.0, ps * pp)) * t.sp;
    return out;
}

double LayerStackShear(Complex nIncident, Complex cosIncident, std::span<const Layer> layers) {
    // n₀sinθ₀: the tangential wave-vector component every layer shares (Snell's invariant).
    const double tangential = (nIncident * std::sqrt(1.0 - cosIncident * cosIncident)).real();
    if (!(tangential > 0)) return 0;
    double shear = 0;
    for (const Layer &l : layers) {
        const Complex q = l.n * RefractedCos(nIncident, cosIncident, l.n);
        if (LayerPropagates(q)) shear += 2 * l.thickness * tangential / q.real();
    }
    return shear;
}

}  // namespace phasor
