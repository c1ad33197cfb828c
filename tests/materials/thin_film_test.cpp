// SPDX-License-Identifier: Apache-2.0
// `thin_film`: physics beyond the contract suite, against references written here — the bare
// interface at zero thickness, energy conservation, the quarter-wave anti-reflection minimum, an
// independent two-interface Airy formula (reflection, transmission, Jones amplitudes, from above
// and from the substrate), the incoherent ray-optics limit (an independent formula and the phase
// average of the coherent response), the coherence terms, textured thickness, and bad input.
#include <gtest/gtest.h>

#include "materials/fresnel.h"
#include "materials/layer_stack.h"
#include "stack_kernel_test_util.h"

namespace phasor::test {
namespace {

// ---- an independent reference: Snell's invariant, interface amplitudes, Airy's sum -------------
// Written from the textbook (Born & Wolf §1.5–1.6) with the normal wave-vector q = n·cosθ =
// √(n² − β²), β = n₀sinθ₀, on the decaying (Im q > 0) or outgoing (q > 0) branch; no phasor optics.

Complex Q(Complex n, double beta) {
    Complex q = std::sqrt(n * n - beta * beta);
    if (q.imag() < 0 || (q.imag() == 0 && q.real() < 0)) q = -q;
    return q;
}

struct Amplitudes {
    Complex rs, rp, ts, tp;
};
// The interface medium 1 → medium 2 (theory §4.1's r and t, written with q = n cosθ):
// r_s = (q₁ − q₂)/(q₁ + q₂), r_p = (n₂²q₁ − n₁²q₂)/(n₂²q₁ + n₁²q₂), t_s = 2q₁/(q₁ + q₂),
// t_p = 2n₁n₂q₁/(n₂²q₁ + n₁²q₂).
Amplitudes Face(Complex n1, Complex q1, Complex n2, Complex q2) {
    const Complex ps = n2 * n2 * q1 + n1 * n1 * q2;
    return {(q1 - q2) / (q1 + q2), (n2 * n2 * q1 - n1 * n1 * q2) / ps, 2.0 * q1 / (q1 + q2), 2.0 * n1 * n2 * q1 / ps};
}

struct Airy {
    Complex rs, rp;
    double Rs, Rp, Ts, Tp;
    double R() const { return 0.5 * (Rs + Rp); }
    double T() const { return 0.5 * (Ts + Tp); }
};
// A film (index nf, thickness d) between an incident medium n0 (real) and an exit medium n2, for
// incidence cosθ₀ = cos0 at vacuum wavelength lambda:
//   r = (r₀₁ + r₁₂e^{2iδ})/(1 + r₀₁r₁₂e^{2iδ}),  t = t₀₁t₁₂e^{iδ}/(1 + r₀₁r₁₂e^{2iδ}),  δ = (2π/λ)·q_f·d,
// T = Re(q₂)/q₀·|t|² for a real exit medium (0 when it is evanescent).
Airy AiryFilm(double lambda, double n0, double cos0, Complex nf, double d, Complex n2) {
    const double beta = n0 * std::sqrt(1 - cos0 * cos0);
    const Complex q0 = n0 * cos0, qf = Q(nf, beta), q2 = Q(n2, beta);
    const Amplitudes a = Face(n0, q0, nf, qf), b = Face(nf, qf, n2, q2);
    const Complex e1 = std::exp(Complex(0, 2 * Pi / lambda) * qf * d), e2 = e1 * e1;
    Airy out;
    out.rs = (a.rs + b.rs * e2) / (1.0 + a.rs * b.rs * e2);
    out.rp = (a.rp + b.rp * e2) / (1.0 + a.rp * b.rp * e2);
    const Complex ts = a.ts * b.ts * e1 / (1.0 + a.rs * b.rs * e2), tp = a.tp * b.tp * e1 / (1.0 + a.rp * b.rp * e2);
    out.Rs = std::norm(out.rs);
    out.Rp = std::norm(out.rp);
    const double factor = n2.imag() == 0 ? q2.real() / q0.real() : 0;
    out.Ts = factor * std::norm(ts);
    out.Tp = factor * std::norm(tp);
    return out;
}

// The incoherent sum for one film (theory §4.4): the face reflections added in power,
//   R = R₀₁ + |t₀₁t₁₀|²·A²·R₁₂ / (1 − R₁₀R₁₂A²),  T = |t₀₁t₁₂|²·A·(q₂/q₀) / (1 − R₁₀R₁₂A²),
// per polarisation, A = |e^{iδ}|² the film's single-pass attenuation, t₁₀ = 2q_f/(q_f + q₀) etc.
Airy IncoherentFilm(double lambda, double n0, double cos0, Complex nf, double d, Complex n2) {
    const double beta = n0 * std::sqrt(1 - cos0 * cos0);
    const Complex q0 = n0 * cos0, qf = Q(nf, beta), q2 = Q(n2, beta);
    const Amplitudes a = Face(n0, q0, nf, qf), back = Face(nf, qf, n0, q0), b = Face(nf, qf, n2, q2);
    const double att = std::exp(-2 * (2 * Pi / lambda * qf * d).imag());
    auto one = [&](Complex r01, Complex t01, Complex t10, Complex r10, Complex r12, Complex t12, double *R, double *T) {
        const double denom = 1 - std::norm(r10) * std::norm(r12) * att * att;
        *R = std::norm(r01) + std::norm(t01 * t10) * att * att * std::norm(r12) / denom;
        *T = (n2.imag() == 0 ? q2.real() / q0.real() : 0) * std::norm(t01 * t12) * att / denom;
    };
    Airy out{};
    one(a.rs, a.ts, back.ts, back.rs, b.rs, b.ts, &out.Rs, &out.Ts);
    one(a.rp, a.tp, back.tp, back.rp, b.rp, b.tp, &out.Rp, &out.Tp);
    return out;
}

ParamDict Film(Value ior, double thicknessNm, std::optional<Value> substrate = std::nullopt) {
    ParamDict d;
    d.Set("ior", std::move(ior)).Set("thickness", Nm(thicknessNm));
    if (substrate) d.Set("substrate_ior", *substrate);
    return d;
}

// ---- the tests ------------------------------------------------------------------------------------

TEST(ThinFilm, ZeroThicknessIsTheBareInterface) {
    // d = 0: the film vanishes whatever its index — in both regimes (in the incoherent sum a layer
    // of zero thickness is no layer).
    for (const Value &sub : {Value::String("Cu"), Value::String("BK7"), Value::Number(1.33)}) {
        auto film = Kernel("thin_film", Film(Value::ComplexNumber(Complex(2.0, 0.3)), 0, sub));
        ASSERT_TRUE(film);
        for (double lambda : {420e-9, 560e-9, 690e-9})
            for (double c : {1.0, 0.7, 0.3, 0.05})
                for (bool ray : {false, true}) {
                    const Listed l = List(*film, OneWave(lambda, c, 0.4, ray));
                    const Complex n = SurfaceOf(*film).SubstrateIndex(lambda);
                    const double bare = FresnelComplex(c, 1.0, n);
                    // 1e-14: the same Fresnel equations evaluated through the stack recursion.
                    EXPECT_NEAR(l.R, bare, 1e-14) << sub.ToString() << " λ " << lambda << " cos " << c;
                    if (n.imag() == 0) EXPECT_NEAR(l.T, 1 - bare, 1e-14);
                    else EXPECT_EQ(l.T, 0);
                }
    }
}

TEST(ThinFilm, LosslessFilmsConserveEnergy) {
    // R + T = 1 for lossless layers, from above and from the substrate, coherent and incoherent,
    // including total internal reflection from inside (T = 0, R = 1).
    const ParamDict cases[] = {Film(Value::Number(1.33), 300),                      // soap film in air
                               Film(Value::String("MgF2"), 100, Value::String("BK7")),  // AR coat
                               Film(Value::String("TiO2"), 5000, Value::String("fused_silica"))};
    for (const ParamDict &p : cases) {
        auto film = Kernel("thin_film", p);
        ASSERT_TRUE(film);
        for (double lambda = 400e-9; lambda <= 700e-9; lambda += 37e-9)
            for (double c : {1.0, 0.83, 0.5, 0.2, 0.02, -0.02, -0.4, -0.8, -1.0})
                for (bool ray : {false, true}) {
                    const Listed l = List(*film, OneWave(lambda, c, 1.1, ray));
                    // 1e-12: a few dozen complex operations on O(1) amplitudes.
                    EXPECT_NEAR(l.R + l.T, 1, 1e-12) << film->ToString() << " λ " << lambda << " cos " << c << " ray " << ray;
                }
    }
}

TEST(ThinFilm, QuarterWaveAntiReflection) {
    // A film of index n_f and optical thickness λ₀/4 on a substrate n_s, at normal incidence:
    // R(λ₀) = ((n_s − n_f²)/(n_s + n_f²))² (Heavens 1955; Macleod §3.2), and λ₀ is R's minimum.
    const double nf = 1.38, ns = 1.52, lambda0 = 550e-9;
    auto film = Kernel("thin_film", Film(Value::Number(nf), lambda0 / (4 * nf) * 1e9, Value::Number(ns)));
    ASSERT_TRUE(film);
    const double expected = Sqr((ns - nf * nf) / (ns + nf * nf));
    const double r0 = List(*film, OneWave(lambda0, 1.0)).R;
    EXPECT_NEAR(r0, expected, 1e-12);
    EXPECT_LT(r0, 0.0127);  // vs 4.3 % bare glass
    for (double lambda = 400e-9; lambda <= 750e-9; lambda += 2e-9)
        EXPECT_GE(List(*film, OneWave(lambda, 1.0)).R, r0 - 1e-15) << lambda;
    // A minimum, not a plateau: 20 nm away R has clearly risen.
    EXPECT_GT(List(*film, OneWave(lambda0 - 20e-9, 1.0)).R, r0 + 1e-5);
    EXPECT_GT(List(*film, OneWave(lambda0 + 20e-9, 1.0)).R, r0 + 1e-5);
}

TEST(ThinFilm, LobeChoiceSeesTheCompanions) {
    // A free-standing soap film (n = 1.33) half a wave thick at 550 nm reflects nothing there at
    // normal incidence (the two faces cancel), yet 1–8 % at the companions. Picking the lobe by the
    // hero alone would never reflect (probability 0: the companions' reflected light lost, or with
    // a tiny probability, fireflies); the kernel's mixture (smooth_kernel.h) reflects with
    // probability ½·R̄/(R̄ + T̄), and each companion's sampled weight R_i/p averages to R_i.
    const double n = 1.33, lambda0 = 550e-9;
    auto film = Kernel("thin_film", Film(Value::Number(n), lambda0 / (2 * n) * 1e9));
    ASSERT_TRUE(film);
    const SampledWavelengths wl = TestWavelengths(lambda0);
    ScatterQuery q;
    q.wi = DirectionFromCosTheta(1.0, 0.0);
    q.wl = &wl;
    q.rayOptics = false;
    double r[NumWavelengths], t[NumWavelengths], meanR = 0, meanT = 0;
    for (int i = 0; i < NumWavelengths; ++i) {
        const Listed l = List(*film, OneWave(wl.lambda[i], 1.0));
        r[i] = l.R, t[i] = l.T;
        meanR += r[i] / NumWavelengths, meanT += t[i] / NumWavelengths;
    }
    EXPECT_LT(r[0], 1e-15) << "the hero is the film's zero";
    for (int i = 1; i < NumWavelengths; ++i) EXPECT_GT(r[i], 1e-3) << "companion " << i;
    const Prep k(*film, q);
    const std::span<const NearDeltaLobe> lobes = k->ListNearDelta();
    ASSERT_EQ(lobes.size(), 2u);
    const double pR = 0.5 * meanR / (meanR + meanT);
    EXPECT_NEAR(lobes[0].prob, pR, 1e-12);
    EXPECT_NEAR(lobes[1].prob, 1 - pR, 1e-12);
    // Sample with u0 below / above pR: each lobe's weights are its listed weights over its probability.
    auto refl = k->Sample(0.5 * pR, Vec2(0.5, 0.5)), tran = k->Sample(0.5 + 0.5 * pR, Vec2(0.5, 0.5));
    ASSERT_TRUE(refl && tran);
    EXPECT_TRUE(refl->flags & ScatterReflection);
    EXPECT_TRUE(tran->flags & ScatterTransmission);
    for (int i = 0; i < NumWavelengths; ++i) {
        EXPECT_NEAR(refl->weight[i] * pR, r[i], 1e-12) << i;
        EXPECT_NEAR(tran->weight[i] * (1 - pR), t[i], 1e-12) << i;
        // No weight exceeds twice the mean-only rule's (r_i/(R̄/(R̄ + T̄)), t_i likewise).
        EXPECT_LE(refl->weight[i], 2 * r[i] * (meanR + meanT) / meanR + 1e-12) << i;
    }
}

TEST(ThinFilm, MatchesAnIndependentAiryFormula) {
    // R, T and the Jones amplitudes r_s, r_p of the kernel against AiryFilm above, over 400–700 nm
    // and 0–86°: an absorbing Cu₂O-like film on copper (opaque), a dielectric film on glass seen
    // from above and from the glass (where the exit into air goes evanescent past 43°), and a
    // weakly absorbing film on glass.
    struct Case {
        Complex film;
        double d;  // nm
        Complex sub;
    } cases[] = {{{2.95, 0.12}, 120, {0.94, 2.6}}, {{2.3, 0}, 160, {1.5, 0}}, {{1.9, 0.02}, 730, {1.6, 0}}};
    for (const Case &c : cases) {
        auto film = Kernel("thin_film", Film(Value::ComplexNumber(c.film), c.d, Value::ComplexNumber(c.sub)));
        ASSERT_TRUE(film);
        const bool transparent = c.sub.imag() == 0;
        for (double lambda = 400e-9; lambda <= 700e-9; lambda += 25e-9)
            for (double deg = 0; deg <= 86; deg += 7) {
                const double cosI = std::cos(deg * Pi / 180);
                for (bool below : {false, true}) {
                    if (below && !transparent) continue;  // an opaque substrate is two-sided (tested below)
                    const OneWave w(lambda, below ? -cosI : cosI);
                    const Airy ref = below ? AiryFilm(lambda, c.sub.real(), cosI, c.film, c.d * 1e-9, 1.0)
                                           : AiryFilm(lambda, 1.0, cosI, c.film, c.d * 1e-9, c.sub);
                    const Listed l = List(*film, w);
                    // 1e-9 (the bound); the two evaluations agree to ~1e-14 in practice.
                    EXPECT_NEAR(l.R, ref.R(), 1e-9) << c.film << " λ " << lambda << " θ " << deg << " below " << below;
                    EXPECT_NEAR(l.T, transparent ? ref.T() : 0, 1e-9) << c.film << " λ " << lambda << " θ " << deg;
                    auto r = Response(*film, w, 0);
                    ASSERT_TRUE(r && r->hasJones);
                    EXPECT_LT(std::abs(r->jones[0].m[0][0] - ref.rs), 1e-9);
                    EXPECT_LT(std::abs(r->jones[0].m[1][1] - ref.rp), 1e-9);
                    EXPECT_EQ(r->jones[0].m[0][1], Complex(0, 0));
                }
            }
    }
    // The opaque kernel hit from below reflects as from above (two-sided, like `conductor`).
    auto cu = Kernel("thin_film", Film(Value::ComplexNumber(Complex(2.95, 0.12)), 120, Value::ComplexNumber(Complex(0.94, 2.6))));
    EXPECT_EQ(List(*cu, OneWave(500e-9, -0.6)).R, List(*cu, OneWave(500e-9, 0.6)).R);
}

TEST(ThinFilm, RayOpticsLimitIsTheIncoherentSum) {
    // In the ray-optics limit (`ray`) the film's reflections add in power: the kernel's R and T
    // equal IncoherentFilm above and, for a lossless film, the average of the coherent R and T
    // over one period of the film phase δ (thickness varied by λ/(2 q_f)): the interference term
    // averages out exactly. Periodic and smooth in δ, so a 256-point average is exact to round-off.
    struct Case {
        Complex film;
        double d;
        Complex sub;
    } cases[] = {{{1.38, 0}, 100, {1.52, 0}}, {{2.3, 0}, 370, {1.0, 0}}, {{2.95, 0.12}, 120, {0.94, 2.6}}};
    for (const Case &c : cases) {
        auto film = Kernel("thin_film", Film(Value::ComplexNumber(c.film), c.d, Value::ComplexNumber(c.sub)));
        ASSERT_TRUE(film);
        for (double lambda : {450e-9, 610e-9})
            for (double cosI : {1.0, 0.6, 0.15}) {
                const Listed l = List(*film, OneWave(lambda, cosI, 0.3, /*rayOptics=*/true));
                const Airy inc = IncoherentFilm(lambda, 1.0, cosI, c.film, c.d * 1e-9, c.sub);
                EXPECT_NEAR(l.R, inc.R(), 1e-12) << c.film << " λ " << lambda << " cos " << cosI;
                EXPECT_NEAR(l.T, inc.T(), 1e-12);
                if (c.film.imag() != 0) continue;
                const double beta = std::sqrt(1 - cosI * cosI);
                const double period = lambda / (2 * Q(c.film, beta).real());
                double rSum = 0, tSum = 0;
                constexpr int N = 256;
                for (int k = 0; k < N; ++k) {
                    const Airy a = AiryFilm(lambda, 1.0, cosI, c.film, c.d * 1e-9 + period * k / N, c.sub);
                    rSum += a.R();
                    tSum += a.T();
                }
                EXPECT_NEAR(l.R, rSum / N, 1e-12) << c.film << " λ " << lambda << " cos " << cosI;
                EXPECT_NEAR(l.T, tSum / N, 1e-12);
                // …and it is not the coherent response (the test can tell the regimes apart).
                EXPECT_GT(std::abs(l.R - List(*film, OneWave(lambda, cosI)).R), 1e-4);
            }
    }
}

TEST(ThinFilm, LobeCoherenceHoldsTheIncoherentSumAndTheShear) {
    // EvalLobe (a generalized ray): Jones = the coherent amplitudes; `incoherent` = the Mueller
    // matrix of the incoherent sum (M00 = its R, partially depolarising); `shear` = 2·d·tanθ_f
    // along the incident wave's travel (−wi.xy) for reflection and transmission (theory §4.4).
    const double d = 250e-9, nf = 1.45, lambda = 520e-9;
    auto film = Kernel("thin_film", Film(Value::Number(nf), d * 1e9, Value::Number(1.6)));
    ASSERT_TRUE(film);
    const double cosI = 0.5, phi = 0.8;
    const OneWave w(lambda, cosI, phi);
    const double sinF = std::sqrt(1 - cosI * cosI) / nf;
    const double shear = 2 * d * sinF / std::sqrt(1 - sinF * sinF);
    const Airy inc = IncoherentFilm(lambda, 1.0, cosI, nf, d, 1.6);
    for (int id : {0, 1}) {
        auto r = Response(*film, w, id);
        ASSERT_TRUE(r);
        EXPECT_TRUE(r->hasJones);
        EXPECT_TRUE(r->coherence.any);
        const Mueller &m = r->coherence.incoherent[0];
        EXPECT_NEAR(m.m[0][0] * (id == 1 ? Sqr(1.6) : 1.0), id == 0 ? inc.R() : inc.T(), 1e-12);
        EXPECT_NEAR(m.m[0][1] * (id == 1 ? Sqr(1.6) : 1.0), id == 0 ? 0.5 * (inc.Rs - inc.Rp) : 0.5 * (inc.Ts - inc.Tp), 1e-12);
        // Partial depolarisation: the incoherent sum is no Jones matrix (C² + S² < A² − B²).
        EXPECT_LT(Sqr(m.m[2][2]) + Sqr(m.m[2][3]), Sqr(m.m[0][0]) - Sqr(m.m[0][1]) - 1e-8);
        const Vec2 s = r->coherence.shear[0];
        EXPECT_NEAR(std::hypot(s.x, s.y), shear, 1e-18) << id;
        EXPECT_NEAR(s.x / std::hypot(s.x, s.y), -std::cos(phi), 1e-12);
        EXPECT_NEAR(s.y / std::hypot(s.x, s.y), -std::sin(phi), 1e-12);
    }
    // Normal incidence: no shear. The ray-optics limit answers with the incoherent matrix itself.
    auto normal = Response(*film, OneWave(lambda, 1.0), 0);
    ASSERT_TRUE(normal);
    EXPECT_EQ(normal->coherence.shear[0], Vec2(0, 0));
    auto ray = Response(*film, OneWave(lambda, cosI, phi, true), 0);
    ASSERT_TRUE(ray);
    EXPECT_FALSE(ray->hasJones);
    EXPECT_NEAR(ray->mueller[0].m[0][0], inc.R(), 1e-12);
    // A bare surface has no coherence terms.
    auto bare = Response(*Kernel("dielectric", ParamDict()), OneWave(lambda, cosI), 0);
    ASSERT_TRUE(bare);
    EXPECT_FALSE(bare->coherence.any);
}

TEST(ThinFilm, TexturedThicknessIsEvaluatedAtTheHit) {
    // thickness_texture = @contract_thickness (80 nm at u = 0 → 250 nm at u = 1): at each uv the
    // kernel reflects like a constant film of the texture's thickness there.
    ParamDict p;
    p.Set("ior", Value::Number(2.1)).Set("thickness_texture", Value::Ref("contract_thickness")).Set("substrate_ior", Value::Number(1.5));
    auto textured = Kernel("thin_film", p);
    ASSERT_TRUE(textured);
    for (double u : {0.0, 0.3, 0.77, 1.0}) {
        auto constant = Kernel("thin_film", Film(Value::Number(2.1), 80 + 170 * u, Value::Number(1.5)));
        OneWave w(560e-9, 0.7);
        w.q.tex.uv = Vec2(u, 0.5);
        const Listed a = List(*textured, w), b = List(*constant, w);
        EXPECT_NEAR(a.R, b.R, 1e-12) << u;
        EXPECT_NEAR(a.T, b.T, 1e-12) << u;
    }
    OneWave w0(560e-9, 0.7), w1(560e-9, 0.7);
    w1.q.tex.uv = Vec2(1, 0);
    EXPECT_GT(std::abs(List(*textured, w0).R - List(*textured, w1).R), 1e-3);
}

TEST(ThinFilm, IsACoatingOfOneLayer) {
    auto film = Kernel("thin_film", Film(Value::String("Cu2O"), 150));
    ASSERT_TRUE(film && LayersOf(*film));
    ASSERT_EQ(LayersOf(*film)->layers.size(), 1u);
    EXPECT_DOUBLE_EQ(LayersOf(*film)->layers[0].thickness.Eval(TextureEvalContext()), 150e-9);
    EXPECT_LT(std::abs(LayersOf(*film)->layers[0].ior->Eval(551.05e-9) - Complex(3.09867, 0.187747)), 1e-9);
    EXPECT_EQ(SurfaceOf(*film).LayerCount(), 1);
}

std::string BuildError(const std::string &type, const ParamDict &p) {
    Diagnostics diag;
    auto m = BuildMaterial(type, p, diag);
    std::ostringstream os;
    diag.Print(os);
    EXPECT_FALSE(m) << type << " built from invalid parameters";
    EXPECT_TRUE(diag.HasErrors());
    return os.str();
}

TEST(ThinFilm, BadInputIsAnErrorAtTheParameter) {
    auto has = [](const std::string &all, const std::string &text) { return all.find(text) != std::string::npos; };
    ParamDict both = Film(Value::Number(1.4), 100);
    both.Set("thickness_texture", Value::Ref("contract_thickness"));
    EXPECT_TRUE(has(BuildError("thin_film", both), "give either 'thickness' or 'thickness_texture', not both"));
    EXPECT_TRUE(has(BuildError("thin_film", ParamDict().Set("ior", Value::Number(1.4))), "thin_film needs 'thickness'"));
    EXPECT_TRUE(has(BuildError("thin_film", Film(Value::Number(1.4), -10)), "'thickness' is out of range"));
    EXPECT_TRUE(has(BuildError("thin_film", ParamDict().Set("ior", Value::Number(1.4)).Set("thickness_texture", Nm(100))),
                    "'thickness_texture' expects @name of a texture"));
    EXPECT_TRUE(has(BuildError("thin_film", Film(Value::String("Cu2"), 100)), "unknown material \"Cu2\""));
    EXPECT_TRUE(has(BuildError("thin_film", ParamDict().Set("thickness", Nm(100))), "missing required parameter 'ior'"));
    // A texture of another dimension, and one that goes negative.
    ParamDict angle;
    angle.Set("ior", Value::Number(1.4)).Set("thickness_texture", Value::Ref("contract_checker"));
    EXPECT_TRUE(has(BuildError("thin_film", angle), "'thickness_texture' expects a length"));
}

}  // namespace
}  // namespace phasor::test
