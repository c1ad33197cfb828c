// SPDX-License-Identifier: Apache-2.0
// The light contract suite (issue 25 §4), registry-driven like the kernel and integrator suites:
// every registered light × each of its TestPresets() (a light registered without presets fails
// `LightRegistry.EveryLightHasPresets`), built as a scene builds it with the fixtures below, is
// checked against independent references:
//   Finite        SampleLi, PdfLi, Le/L, MeasureGR, IncidenceOnGR, PowerScale and the coherent
//                 field are finite and non-negative, unit directions, the delta convention (pdf 1,
//                 PdfLi 0) matches Type();
//   SamplingMatchesPdf  continuous lights: each sample's pdf is PdfLi's and its value the light's
//                 radiance (Le or L) in that direction; the sampled directions pass a χ² test
//                 against PdfLi integrated over bins;
//   PowerMatchesRadiance  PowerScale × the spectrum = the emitted power from the light's own
//                 radiometry, by deterministic quadrature: outward flux through a sphere (delta
//                 position), flux through the scene's cross-section (delta direction), ∫∫ L cosθ
//                 dω dA over the emitter (area), πR² ∫ Le cosθ dω (distant);
//   MeasureGRMatchesQuadrature  Eq. 24 in closed form against brute-force quadrature over the
//                 GR's footprint: |∫ U ψ*|²/4π² for a light with a field (Light::Coherent), the
//                 phase-space overlap of the local plane wave from SampleLi for other delta lights,
//                 the angular-spectrum overlap ∫ Le·G d²k⊥ for distant sources; area lights are
//                 measured where GRs hit them (MeasureGR nullopt);
//   MeasuresOnlyItsSlots  a GR that measures one wavelength slot (SpectralGenRay::measured) gets
//                 that slot's value of the full measurement exactly and 0 in the others;
//   MeasuresNothingOnlyWhereZero  wherever Light::MeasuresNothing claims a GR measures nothing,
//                 MeasureGR gives nullopt or 0 (GRs over the sphere and at the edge of the light's
//                 profile, footprints of 2–200 λ, every slot or one);
// Statistics: χ² with a fixed seed, Šidák-corrected over the suite at family-wise level 1 %.
// `TamperedLight` shows the checks fail: with a PdfLi twice its sampling density, SamplingMatchesPdf
// (`LightContractPower.CatchesAPdfOffByTwo`); with a Reach of 0, ReachIsZeroOnlyWhereNothingArrives
// (`LightContractReach.ZerosAreExercisedAndALyingReachIsCaught`); measuring every slot,
// MeasuresOnlyItsSlots (`LightContractSlots.ALightThatIgnoresTheMaskIsCaught`); claiming nothing
// everywhere, MeasuresNothingOnlyWhereZero (`LightContractNothing.AClaimWhereLightArrivesIsCaught`).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <sstream>

#include "core/render/coherent_source.h"
#include "core/numerics/gauss_legendre.h"
#include "core/render/genray.h"
#include "parser/parser.h"
#include "support/genray_builder.h"
#include "support/scene_builder.h"
#include "support/stats.h"

namespace phasor::test {
namespace {

// ---- the cases ----------------------------------------------------------------------------------

struct LightCase {
    std::string light;
    int preset = 0;
    std::string Name() const { return light + "_p" + std::to_string(preset); }
};
void PrintTo(const LightCase &c, std::ostream *os) { *os << c.Name(); }

std::vector<LightCase> AllCases() {
    std::vector<LightCase> cases;
    for (const auto &e : Registry<Light>::Entries())
        for (std::size_t p = 0; p < e.presets().size(); ++p) cases.push_back({e.name, int(p)});
    return cases;
}

double Alpha() {
    static const double a = SidakAlpha(0.01, std::max<int>(1, int(AllCases().size()) * 3));
    return a;
}

/// The fixtures presets may name: @contract_panel, a 1 m square at z = 0.5 m facing −z (towards the
/// origin); @contract_ball, a sphere of radius 0.3 m at (0, 0.1, −0.2) m. A scene holds only the
/// fixtures its light names (so that nothing else occludes it), and a sensor.
SceneDesc Fixtures(const ParamDict &preset) {
    SceneDesc desc;
    auto named = [&](const std::string &name) {
        for (const Param &p : preset.All())
            if (p.value.kind == Value::Kind::Ref && p.value.text == name) return true;
        return false;
    };
    auto add = [&](const char *keyword, const char *type, const char *name, ParamDict params) {
        SceneEntity e;
        e.keyword = keyword;
        e.type = type;
        e.name = name;
        e.params = std::move(params);
        desc.entities.push_back(std::move(e));
    };
    if (named("contract_panel"))
        add("Shape", "rectangle", "contract_panel",
            ParamDict().Set("to_world", Value::List({Value::Call("scale", {Value::Number(0.5)}, {""}),
                                                     Value::Call("rotate", {Value::Number(Pi, Dim::Angle()),
                                                                            Value::Vector({1, 0, 0})},
                                                                 {"", ""}),
                                                     Value::Call("translate", {Value::Vector({0, 0, 0.5}, Dim::Length())},
                                                                 {""})})));
    if (named("contract_ball"))
        add("Shape", "sphere", "contract_ball",
            ParamDict()
                .Set("radius", Value::Number(0.3, Dim::Length()))
                .Set("to_world", Value::Call("translate", {Value::Vector({0, 0.1, -0.2}, Dim::Length())}, {""})));
    add("Detector", "virtual_plane", "contract_sensor", ParamDict().Set("resolution", Value::List({Value::Integer(2), Value::Integer(2)})));
    return desc;
}

/// A light under test in its scene (the scene owns it; infinite lights are preprocessed with the
/// scene's bounds).
struct Subject {
    std::unique_ptr<Scene> scene;
    const Light *light = nullptr;
    const Shape *emitter = nullptr;  // an area light's shape
};

Subject Build(const LightCase &c) {
    const ParamDict preset = Registry<Light>::Find(c.light)->presets()[c.preset];
    SceneDesc desc = Fixtures(preset);
    SceneEntity e;
    e.keyword = "Light";
    e.type = c.light;
    e.name = "under_test";
    e.params = preset;
    desc.entities.push_back(e);
    Diagnostics diag;
    Subject s;
    s.scene = Scene::Build(desc, diag);
    if (!s.scene) {
        std::ostringstream os;
        diag.Print(os);
        ADD_FAILURE() << c.Name() << " did not build:\n" << os.str();
        return s;
    }
    s.light = s.scene->Lights().at(0);
    for (const auto &shape : s.scene->Shapes())
        if (shape->areaLight == s.light) s.emitter = shape.get();
    return s;
}

// ---- helpers ------------------------------------------------------------------------------------

/// Wavelength samples as the renderer draws them for this light (a line: its delta sample).
std::vector<SampledWavelengths> Wavelengths(const Scene &scene) {
    std::vector<SampledWavelengths> out;
    for (double u : {0.13, 0.5, 0.87}) out.push_back(scene.Wavelengths().Sample(u));
    return out;
}

/// Receivers around the lights: points on a sphere of radius 2 m about the origin.
std::vector<Vec3> Receivers() {
    std::vector<Vec3> out;
    for (int i = 0; i < 14; ++i) {
        const double z = 1 - 2 * (i + 0.5) / 14, r = std::sqrt(1 - z * z), phi = 2.39996 * i;
        out.push_back(2.0 * Vec3(r * std::cos(phi), r * std::sin(phi), z));
    }
    out.push_back(Vec3(0, 0, 0));
    return out;
}

bool Finite(const SampledSpectrum &s, int count) {
    for (int i = 0; i < count; ++i)
        if (!std::isfinite(s[i]) || s[i] < 0) return false;
    return true;
}

/// The light's radiance towards `ctx` along −wi, and the density PdfLi gives that direction
/// (area lights: where the ray from ctx meets the emitter; 0 if it misses).
struct Towards {
    SampledSpectrum L{0.0};
    double pdf = 0;
};
Towards RadianceTowards(const Subject &s, const Light &light, const LightSampleContext &ctx, const Vec3 &wi,
                        const SampledWavelengths &wl) {
    Towards t;
    if (light.Type() == LightType::Area) {  // (the emitter is the scene's only shape)
        const auto si = s.scene->Intersect(Ray{ctx.p, wi});
        if (!si || si->shape != s.emitter) return t;
        t.L = light.L(si->p, si->n, -wi, wl);
        t.pdf = light.PdfLi(ctx, wi, si->p, si->n);
    } else {
        t.L = light.Le(wi, wl);
        t.pdf = light.PdfLi(ctx, wi, Vec3(), Vec3());
    }
    return t;
}

// ---- the checks (each returns "" or what failed, so that a test can show a check failing) -------

/// Finite, non-negative answers everywhere; the delta convention.
std::string CheckFinite(const Subject &s, const Light &light) {
    std::ostringstream bad;
    const bool delta = light.IsDelta();
    if (!std::isfinite(light.PowerScale()) || light.PowerScale() < 0) bad << "PowerScale " << light.PowerScale() << "; ";
    TestRng rng(7);
    for (const SampledWavelengths &wl : Wavelengths(*s.scene))
        for (const Vec3 &p : Receivers())
            for (int j = 0; j < 8; ++j) {
                const LightSampleContext ctx{p, j % 2 ? Vec3(0, 0, 1) : Vec3(0, 0, 0)};
                const Vec2 u(rng.Uniform(), rng.Uniform());
                const auto ls = light.SampleLi(ctx, u, wl);
                if (!ls) continue;
                if (!Finite(ls->L, wl.Count())) bad << "SampleLi L not finite/≥0; ";
                if (std::abs(Length(ls->wi) - 1) > 1e-9) bad << "SampleLi wi not unit; ";
                if (!(ls->dist > 0)) bad << "SampleLi dist " << ls->dist << "; ";
                if (ls->delta != delta) bad << "SampleLi delta flag " << ls->delta << " but Type() says " << delta << "; ";
                if (delta && ls->pdf != 1) bad << "delta sample with pdf " << ls->pdf << "; ";
                if (!delta && !(ls->pdf > 0 && std::isfinite(ls->pdf))) bad << "pdf " << ls->pdf << "; ";
                const Towards t = delta ? Towards{} : RadianceTowards(s, light, ctx, ls->wi, wl);
                if (!Finite(t.L, wl.Count()) || !std::isfinite(t.pdf) || t.pdf < 0) bad << "Le/L or PdfLi; ";
                if (delta && light.PdfLi(ctx, ls->wi, p + ls->wi, Vec3(0, 0, 1)) != 0) bad << "delta PdfLi ≠ 0; ";
                // A GR measuring it from here, along the light's direction of travel.
                const SpectralGenRay g = OneWavelengthGr(p, -ls->wi, wl.lambda[0], Sqr(30 * wl.lambda[0]), 0.3 * (j - 4));
                if (const auto m = light.MeasureGR(g, wl)) {
                    if (!Finite(m->value, 1)) bad << "MeasureGR; ";
                } else if (light.MeasuredInClosedForm() && !ls->L.IsZero() && delta) {
                    bad << "MeasureGR nullopt for a closed-form light in its beam; ";
                }
                if (const auto inc = light.IncidenceOnGR(g, wl))
                    if (!Finite(inc->irradiance, 1) || !std::isfinite(inc->angularVariance)) bad << "IncidenceOnGR; ";
                if (const CoherentSource *c = light.Coherent()) {
                    const Complex f = c->Field(p, wl.lambda[0]);
                    if (!std::isfinite(f.real()) || !std::isfinite(f.imag())) bad << "Field; ";
                }
            }
    return bad.str();
}

/// Continuous lights: pointwise agreement of the sample with PdfLi and Le/L, then χ² of the
/// sampled directions against PdfLi over bins around their mean direction.
std::string CheckSamplingMatchesPdf(const Subject &s, const Light &light, double alpha) {
    std::ostringstream bad;
    const SampledWavelengths wl = Wavelengths(*s.scene)[1];
    int receivers = 0;
    for (const Vec3 &p : {Vec3(0.4, -0.3, -1.5), Vec3(-1.2, 0.8, 1.6), Vec3(0.1, 0.2, -0.4)}) {
        const LightSampleContext ctx{p, Vec3(0, 0, 0)};
        TestRng rng(11 + receivers++);
        constexpr int N = 40000;
        std::vector<Vec3> dirs;  // (a sample that returns nothing counts in the overflow cell)
        Vec3 mean(0, 0, 0);
        bool pointwise = true;
        for (int i = 0; i < N; ++i) {
            const auto ls = light.SampleLi(ctx, Vec2(rng.Uniform(), rng.Uniform()), wl);
            if (!ls) continue;
            dirs.push_back(ls->wi);
            mean = mean + ls->wi;
            if (i < 200 && pointwise) {  // the first 200 samples, until one disagrees
                const Towards t = RadianceTowards(s, light, ctx, ls->wi, wl);
                if (std::abs(t.pdf - ls->pdf) > 1e-6 * ls->pdf) {
                    bad << "sample pdf " << ls->pdf << " vs PdfLi " << t.pdf << "; ";
                    pointwise = false;
                }
                for (int k = 0; k < wl.Count() && pointwise; ++k)
                    if (std::abs(t.L[k] - ls->L[k]) > 1e-9 * std::abs(ls->L[k])) {
                        bad << "sample L " << ls->L[k] << " vs the light's radiance " << t.L[k] << "; ";
                        pointwise = false;
                    }
            }
        }
        if (dirs.size() < N / 10) {
            if (!dirs.empty()) bad << "only " << dirs.size() << " of " << N << " samples; ";
            continue;
        }
        const Frame f = Frame::FromNormal(Normalize(mean));
        double R = 0;
        for (const Vec3 &w : dirs) R = std::max({R, std::abs(Dot(w, f.s)), std::abs(Dot(w, f.t))});
        R = std::min(1.0, R * 1.001);
        constexpr int B = 12, Sub = 8;
        std::vector<double> observed(B * B + 1, 0.0), expected(B * B + 1, 0.0);
        observed[B * B] = double(N - dirs.size());
        for (const Vec3 &w : dirs) {
            const double x = Dot(w, f.s), y = Dot(w, f.t);
            const int bx = std::clamp(int((x + R) / (2 * R) * B), 0, B - 1), by = std::clamp(int((y + R) / (2 * R) * B), 0, B - 1);
            observed[Dot(w, f.n) > 0 ? by * B + bx : B * B] += 1;
        }
        // ∫ PdfLi dω over a bin (dω = dx dy / z), by midpoint cells refined where they disagree
        // with their quarters (a sphere's rim, where the density diverges as 1/cos, or an edge).
        auto density = [&](double x, double y) {
            const double z2 = 1 - x * x - y * y;
            if (!(z2 > 0)) return 0.0;
            return RadianceTowards(s, light, ctx, f.s * x + f.t * y + f.n * std::sqrt(z2), wl).pdf / std::sqrt(z2);
        };
        std::function<double(double, double, double, double, int)> cell = [&](double x0, double y0, double w,
                                                                              double coarse, int depth) {
            const double q = 0.5 * w;
            double parts[4], sum = 0;
            for (int c = 0; c < 4; ++c) {
                const double cx = x0 + (c & 1) * q, cy = y0 + (c >> 1) * q;
                parts[c] = density(cx + 0.5 * q, cy + 0.5 * q) * q * q;
                sum += parts[c];
            }
            if (depth == 0 || std::abs(sum - coarse) <= 1e-3 / (B * B)) return sum;
            double refined = 0;
            for (int c = 0; c < 4; ++c) refined += cell(x0 + (c & 1) * q, y0 + (c >> 1) * q, q, parts[c], depth - 1);
            return refined;
        };
        double inside = 0;
        const double h = 2 * R / (B * Sub);
        for (int by = 0; by < B; ++by)
            for (int bx = 0; bx < B; ++bx) {
                double e = 0;
                for (int j = 0; j < Sub; ++j)
                    for (int i = 0; i < Sub; ++i) {
                        const double x0 = -R + (bx * Sub + i) * h, y0 = -R + (by * Sub + j) * h;
                        e += cell(x0, y0, h, density(x0 + 0.5 * h, y0 + 0.5 * h) * h * h, 6);
                    }
                expected[by * B + bx] = e * N;
                inside += e;
            }
        expected[B * B] = std::max(0.0, 1 - inside) * N;
        const Chi2Result r = Chi2Test(observed, expected);
        if (!(r.pValue >= alpha) || r.observedInEmptyCells > 0)
            bad << "χ² of the sampled directions against PdfLi at (" << p.x << ", " << p.y << ", " << p.z
                << "): " << r.ToString() << "; ";
    }
    return bad.str();
}

/// ∫∫ f(θ, φ) over the sphere about `axis`: Gauss–Legendre in cosθ on panels, uniform in φ.
template <typename F>
double SphereIntegral(const Vec3 &axis, int panels, int phiNodes, F &&f) {
    const Frame fr = Frame::FromNormal(axis);
    double sum = 0;
    for (int ip = 0; ip < phiNodes; ++ip) {
        const double phi = 2 * Pi * (ip + 0.5) / phiNodes;
        sum += IntegrateGaussLegendre(
                   [&](double c) {
                       const double st = std::sqrt(std::max(0.0, 1 - c * c));
                       return f(fr.ToWorld(Vec3(st * std::cos(phi), st * std::sin(phi), c)));
                   },
                   -1.0, 1.0, 16, panels) *
               (2 * Pi / phiNodes);
    }
    return sum;
}

/// ∫_a^b f by adaptive Simpson to `tol` of the total (a step — a disc's or a cone's edge — is
/// bisected down to where it no longer matters).
template <typename F>
double AdaptiveSimpson(F &&f, double a, double b, double fa, double fm, double fb, double whole, double tol, int depth) {
    const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
    const double flm = f(lm), frm = f(rm);
    const double left = (m - a) / 6 * (fa + 4 * flm + fm), right = (b - m) / 6 * (fm + 4 * frm + fb);
    if (depth <= 0 || std::abs(left + right - whole) <= 15 * tol) return left + right + (left + right - whole) / 15;
    return AdaptiveSimpson(f, a, m, fa, flm, fm, left, 0.5 * tol, depth - 1) +
           AdaptiveSimpson(f, m, b, fm, frm, fb, right, 0.5 * tol, depth - 1);
}

/// ∫ f over the disc of radius R about `centre` in the plane ⊥ n (f of the point): geometric
/// radial panels from 1e-9·R (so that a beam of any width is resolved), each integrated
/// adaptively (steps at a source's edge), uniform in φ (the integrands here are smooth in φ about
/// the centre, or steps in r only).
template <typename F>
double DiscIntegral(const Vec3 &centre, const Vec3 &n, double R, F &&f) {
    const Frame fr = Frame::FromNormal(n);
    const int phiNodes = 64;
    double sum = 0;
    for (int ip = 0; ip < phiNodes; ++ip) {
        const double phi = 2 * Pi * (ip + 0.5) / phiNodes;
        const Vec3 dir = fr.s * std::cos(phi) + fr.t * std::sin(phi);
        auto radial = [&](double r) { return r * f(centre + dir * r); };
        // A first pass for the scale of the total, then each panel to 1e-9 of it.
        std::vector<std::pair<double, double>> panels;
        for (double lo = 0, hi = 1e-9 * R; lo < R; lo = hi, hi = std::min(R, hi * 1.3)) panels.push_back({lo, hi});
        double scale = 0;
        for (const auto &[lo, hi] : panels) scale += std::abs(IntegrateGaussLegendre(radial, lo, hi, 8));
        for (const auto &[lo, hi] : panels) {
            const double fa = radial(lo), fm = radial(0.5 * (lo + hi)), fb = radial(hi);
            sum += AdaptiveSimpson(radial, lo, hi, fa, fm, fb, (hi - lo) / 6 * (fa + 4 * fm + fb),
                                   1e-9 * scale / panels.size(), 40) *
                   (2 * Pi / phiNodes);
        }
    }
    return sum;
}

/// A point the light reaches (the scene's centre first, then the receivers): the centre of the
/// disc through which a delta-direction light's flux is measured.
std::optional<Vec3> Reached(const Light &light, const SampledWavelengths &wl) {
    std::vector<Vec3> candidates = {Vec3(0, 0, 0)};
    for (const Vec3 &p : Receivers()) candidates.push_back(p);
    for (const Vec3 &p : candidates)
        if (const auto ls = light.SampleLi(LightSampleContext{p, Vec3()}, Vec2(0.5, 0.5), wl); ls && !ls->L.IsZero())
            return p;
    return std::nullopt;
}

/// PowerScale × the emission at the sampled wavelengths against the power the light's own
/// radiometry gives, per carried wavelength.
std::string CheckPowerMatchesRadiance(const Subject &s, const Light &light) {
    std::ostringstream bad;
    for (const SampledWavelengths &wl : Wavelengths(*s.scene)) {
        const SampledSpectrum emission = EvalEmission(light.EmissionSpectrum(), wl);
        if (emission.IsZero()) continue;
        SampledSpectrum phi(0.0);
        double tol = 1e-5;
        switch (light.Type()) {
            case LightType::DeltaPosition: {  // outward flux through a sphere about the light
                const auto ls = light.SampleLi(LightSampleContext{Vec3(2, 1, 3), Vec3()}, Vec2(0.5, 0.5), wl);
                const Vec3 pos = ls ? Vec3(2, 1, 3) + ls->wi * ls->dist : Vec3(0, 0, 0);
                for (int i = 0; i < wl.Count(); ++i)
                    phi[i] = SphereIntegral(Vec3(0, 0, 1), 64, 128, [&](const Vec3 &w) {
                        const auto l = light.SampleLi(LightSampleContext{pos + w, Vec3()}, Vec2(0.5, 0.5), wl);
                        return l ? l->L[i] * std::max(0.0, Dot(-l->wi, w)) : 0.0;  // r = 1 m
                    });
                break;
            }
            case LightType::DeltaDirection: {  // flux through the scene's cross-section
                const std::optional<Vec3> c = Reached(light, wl);
                if (!c) break;
                const auto ls = light.SampleLi(LightSampleContext{*c, Vec3()}, Vec2(0.5, 0.5), wl);
                const double R = std::sqrt(SceneCrossSection(s.scene->Bounds()) / Pi);
                for (int i = 0; i < wl.Count(); ++i)
                    phi[i] = DiscIntegral(*c, -ls->wi, R, [&](const Vec3 &x) {
                        const auto l = light.SampleLi(LightSampleContext{x, Vec3()}, Vec2(0.5, 0.5), wl);
                        return l ? l->L[i] * std::max(0.0, Dot(l->wi, ls->wi)) : 0.0;
                    });
                tol = 1e-5;
                break;
            }
            case LightType::Distant: {  // πR² × ∫ Le cosθ dω about the mean direction
                const Vec3 a = light.Coherence(Vec3()).wi;
                const double R2 = SceneCrossSection(s.scene->Bounds()) / Pi;
                for (int i = 0; i < wl.Count(); ++i) {
                    // Directions by their transverse offset u (|u| = sinθ): dω = d²u / cosθ.
                    phi[i] = Pi * R2 * DiscIntegral(Vec3(0, 0, 0), a, 1.0, [&](const Vec3 &u) {
                                 const double c2 = 1 - LengthSquared(u);
                                 if (!(c2 > 0)) return 0.0;
                                 return light.Le(Normalize(a * std::sqrt(c2) + u), wl)[i];  // × cosθ / cosθ
                             });
                }
                break;
            }
            case LightType::Area: {  // ∫∫ L(p, n, w)|cosθ| dω dA over the emitter
                constexpr int M = 16;
                for (int a = 0; a < M; ++a)
                    for (int b = 0; b < M; ++b) {
                        const ShapeSample ss = s.emitter->Sample(Vec2((a + 0.5) / M, (b + 0.5) / M));
                        for (int i = 0; i < wl.Count(); ++i)
                            phi[i] += SphereIntegral(ss.n, 2, 8, [&](const Vec3 &w) {
                                          return light.L(ss.p, ss.n, w, wl)[i] * std::abs(Dot(w, ss.n));
                                      }) /
                                      ss.pdfArea / (M * M);
                    }
                tol = 1e-6;
                break;
            }
        }
        for (int i = 0; i < wl.Count(); ++i) {
            const double want = light.PowerScale() * emission[i];
            if (!(std::abs(phi[i] - want) <= tol * want))
                bad << "λ = " << wl.lambda[i] * 1e9 << " nm: PowerScale × emission = " << want
                    << ", the radiance integrates to " << phi[i] << " (relative " << (phi[i] - want) / want << "); ";
        }
    }
    return bad.str();
}

/// Eq. 24 for GRs along the light's direction of travel, against brute-force quadrature.
std::string CheckMeasureGR(const Subject &s, const Light &light) {
    std::ostringstream bad;
    if (light.Type() == LightType::Area) {
        const SpectralGenRay g = OneWavelengthGr(Vec3(0, 0, -1), Vec3(0, 0, 1), 550e-9, 1e-10, 0);
        if (light.MeasureGR(g, Wavelengths(*s.scene)[1])) bad << "an area light answers MeasureGR; ";
        return bad.str();
    }
    const SampledWavelengths wl = Wavelengths(*s.scene)[1];  // (the GRs below carry the hero only)
    const double lambda = wl.lambda[0], k = 2 * Pi / lambda;
    const SampledSpectrum emission = EvalEmission(light.EmissionSpectrum(), wl);
    if (emission.IsZero()) return "";
    int n = 0;
    // GRs in the light's beam: about a point it reaches, before and after it along its travel.
    const std::optional<Vec3> c = Reached(light, wl);
    if (!c) return "the light reaches no test point; ";
    const auto lc = light.SampleLi(LightSampleContext{*c, Vec3()}, Vec2(0.5, 0.5), wl);
    for (const Vec3 &o : {*c + lc->wi * 0.2 + Vec3(1e-5, -2e-5, 0), *c - lc->wi * 0.3})
        for (double beta : {25 * lambda, 80 * lambda})
            for (double rho : {0.0, 0.8, -0.6}) {
                const auto ls = light.SampleLi(LightSampleContext{o, Vec3()}, Vec2(0.5, 0.5), wl);
                if (!ls || ls->L.IsZero()) continue;
                // Along the light's travel at o, turned by half the GR's angular spread.
                const double sigma = std::sqrt((1 + rho * rho) / 2) / (beta * k);
                const Frame tf = Frame::FromNormal(-ls->wi);
                const SpectralGenRay g = OneWavelengthGr(o, -ls->wi + tf.s * (0.5 * sigma), lambda, beta * beta, rho);
                const auto m = light.MeasureGR(g, wl);
                const double got = m ? m->value[0] : 0;
                const Frame f = Frame::FromNormal(g.d);
                double ref = 0, tol = 1e-3;
                if (const CoherentSource *c = light.Coherent()) {
                    // |∫ U ψ*|²/4π², ψ = (πβ²)^{-1/2} exp(−(1 − iρ)|r|²/2β²) on the plane ⊥ d at o.
                    Complex sum = 0;
                    const int N = 161;
                    const double L = 7 * beta * std::sqrt(1 + rho * rho), h = 2 * L / (N - 1);
                    for (int j = 0; j < N; ++j)
                        for (int i = 0; i < N; ++i) {
                            const double x = -L + i * h, y = -L + j * h, r2 = x * x + y * y;
                            const Complex psi = std::exp(Complex(-r2 / (2 * beta * beta), rho * r2 / (2 * beta * beta))) /
                                                std::sqrt(Pi * beta * beta);
                            sum += c->Field(o + f.s * x + f.t * y, lambda) * std::conj(psi) * (h * h);
                        }
                    ref = k * k * std::norm(sum) / (4 * Pi * Pi);
                } else if (light.IsDelta()) {
                    // The local plane wave from SampleLi (irradiance E, travel −wi) against the GR's
                    // phase-space Gaussian: k²∫ E(r) g(r, k⊥(r)) d²r.
                    const int N = 121;
                    const double L = 6 * beta, h = 2 * L / (N - 1);
                    for (int j = 0; j < N; ++j)
                        for (int i = 0; i < N; ++i) {
                            const double x = -L + i * h, y = -L + j * h;
                            const auto l = light.SampleLi(LightSampleContext{o + f.s * x + f.t * y, Vec3()}, Vec2(0.5, 0.5), wl);
                            if (!l || !(Dot(-l->wi, g.d) > 0)) continue;
                            const double kx = k * Dot(-l->wi, f.s), ky = k * Dot(-l->wi, f.t);
                            const double ax = beta * kx - rho / beta * x, ay = beta * ky - rho / beta * y;
                            ref += l->L[0] * std::exp(-(x * x + y * y) / (beta * beta) - ax * ax - ay * ay) / (Pi * Pi) * h * h;
                        }
                    ref *= k * k;
                } else {
                    // A distant source: k²∫ d²k⊥ (Le/k²)·G(k⊥), G = β²/(π(1+ρ²)) e^{−β²|k⊥|²/(1+ρ²)};
                    // directions by their transverse offset u about the source's mean direction.
                    const Vec3 a = light.Coherence(o).wi;  // towards the source
                    const double sig = std::sqrt(light.Coherence(o).omega) + sigma;
                    ref = DiscIntegral(Vec3(0, 0, 0), -a, std::min(0.5, 12 * sig), [&](const Vec3 &u) {
                        const Vec3 w = Normalize(-a * std::sqrt(std::max(0.0, 1 - LengthSquared(u))) + u);  // travel
                        if (!(Dot(w, g.d) > 0)) return 0.0;
                        const double kx = k * Dot(w, f.s), ky = k * Dot(w, f.t);
                        const double G = beta * beta / (Pi * (1 + rho * rho)) *
                                         std::exp(-beta * beta * (kx * kx + ky * ky) / (1 + rho * rho));
                        // d²k⊥ = k²·cosθ_g dω, dω = d²u / cosθ_a.
                        return light.Le(-w, wl)[0] * G * k * k * Dot(w, g.d) / Dot(w, -a);
                    });
                }
                ++n;
                if (!(std::abs(got - ref) <= tol * std::max(ref, 1e-6 * std::abs(emission[0]) * k * k * beta * beta)))
                    bad << "MeasureGR at o = (" << o.x << ", " << o.y << ", " << o.z << "), β = " << beta / lambda
                        << " λ, ρ = " << rho << ": " << got << " vs quadrature " << ref << "; ";
            }
    if (n == 0) bad << "no GR in the light's beam; ";
    return bad.str();
}

/// A GR that measures one wavelength slot (SpectralGenRay::measured, a dispersive lobe's GR) gets
/// exactly that slot's value of the full measurement and 0 in the others. `informative` counts the
/// comparisons where the full measurement is not 0 in another slot (where ignoring the mask shows).
std::string CheckMeasuresOnlyItsSlots(const Subject &s, const Light &light) {
    std::ostringstream bad;
    int informative = 0;
    for (const SampledWavelengths &wl : Wavelengths(*s.scene)) {
        const std::optional<Vec3> c = Reached(light, wl);
        if (!c) continue;
        const auto ls = light.SampleLi(LightSampleContext{*c, Vec3()}, Vec2(0.5, 0.5), wl);
        if (!ls) continue;
        // Every carried wavelength, along the light's travel turned slightly, footprint ~30 λ.
        SpectralGenRay g;
        g.o = *c + ls->wi * 0.1;
        const Frame tf = Frame::FromNormal(-ls->wi);
        g.d = Normalize(-ls->wi + tf.s * 1e-3);
        g.count = wl.Count();
        for (int i = 0; i < g.count; ++i) {  // footprints of 20–41 λ, a different one per slot
            const std::size_t k = std::size_t(i);
            g.k[k] = 2 * Pi / wl.lambda[k];
            g.beta2[k] = Sqr((20 + 7 * ((3 * i + 1) % 4)) * wl.lambda[k]);
            g.rho[k] = 0.2;
        }
        const auto all = light.MeasureGR(g, wl);
        for (int i = 0; i < g.count; ++i) {
            SpectralGenRay one = g;
            one.measured = 1u << i;
            const auto m = light.MeasureGR(one, wl);
            const double want = all ? all->value[i] : 0.0;
            if ((m ? m->value[i] : 0.0) != want)
                bad << "slot " << i << ": " << (m ? m->value[i] : 0.0) << " alone, " << want << " among all; ";
            bool others = false;
            for (int j = 0; j < g.count; ++j) {
                if (j == i) continue;
                others = others || (all && all->value[j] != 0);
                if (m && m->value[j] != 0) bad << "slot " << j << " measured though only " << i << " was asked; ";
            }
            informative += others;
        }
    }
    // (a line carries one wavelength: there is no other slot to show)
    if (informative == 0 && !light.EmissionSpectrum().LineWavelength())
        bad << "no comparison where another slot carries light (the check saw nothing); ";
    return bad.str();
}

/// Light::MeasuresNothing: wherever it claims a GR measures nothing, MeasureGR gives nullopt or a zero
/// value. GRs at a point the light reaches: directions over the sphere (a Fibonacci set) and about
/// the light's own travel direction at 0.5–3 times its angular radius (where a disc's edge and the
/// GR's window meet), footprints of 2, 20 and 200 λ (angular windows from ~0.08 to ~0.0008 rad),
/// ρ = 0.5, every slot or slot 1 only. `claims` counts the claims (true answers), each checked.
std::string CheckMeasuresNothing(const Subject &s, const Light &light, int *claims = nullptr) {
    std::ostringstream bad;
    int claimed = 0;
    for (const SampledWavelengths &wl : Wavelengths(*s.scene)) {
        const std::optional<Vec3> c = Reached(light, wl);
        if (!c) continue;
        const auto ls = light.SampleLi(LightSampleContext{*c, Vec3()}, Vec2(0.5, 0.5), wl);
        if (!ls) continue;
        const Vec3 travel = -ls->wi;
        std::vector<Vec3> dirs;
        const int fib = 200;
        for (int j = 0; j < fib; ++j) {  // a Fibonacci sphere
            const double z = 1 - 2 * (j + 0.5) / fib, r = std::sqrt(1 - z * z), phi = j * Pi * (3 - std::sqrt(5.0));
            dirs.push_back(Vec3(r * std::cos(phi), r * std::sin(phi), z));
        }
        const double alpha = std::max(std::sqrt(light.Coherence(*c).omega) * 2, 1e-3);  // ≈ the disc's radius
        const Frame tf = Frame::FromNormal(travel);
        for (double f : {0.0, 0.5, 0.9, 1.0, 1.05, 1.2, 1.5, 2.0, 3.0})
            for (double phi : {0.0, 2.0, 4.0}) {
                const double t = f * alpha;
                dirs.push_back(Normalize(travel * std::cos(t) + (tf.s * std::cos(phi) + tf.t * std::sin(phi)) * std::sin(t)));
            }
        for (const Vec3 &d : dirs)
            for (double foot : {2.0, 20.0, 200.0})
                for (unsigned mask : {~0u, 2u}) {
                    SpectralGenRay g;
                    g.o = *c;
                    g.d = d;
                    g.count = wl.Count();
                    g.measured = mask;
                    for (int i = 0; i < g.count; ++i) {
                        const std::size_t k = std::size_t(i);
                        g.k[k] = 2 * Pi / wl.lambda[k];
                        g.beta2[k] = Sqr(foot * (1 + 0.3 * i) * wl.lambda[k]);
                        g.rho[k] = 0.5;
                    }
                    if (!light.MeasuresNothing(g)) continue;
                    ++claimed;
                    const auto m = light.MeasureGR(g, wl);
                    if (m && !m->value.IsZero())
                        bad << "MeasuresNothing along (" << d.x << ", " << d.y << ", " << d.z << "), footprint " << foot
                            << " λ, but MeasureGR gives " << m->value[0] << ", " << m->value[g.count - 1] << "; ";
                }
    }
    if (claims) *claims = claimed;
    return bad.str();
}

/// Light::Reach (the exhaustive light sampler's weight): finite and ≥ 0, or NaN (no estimate);
/// and 0 only where nothing arrives, whatever the receiver's normal (a kernel weighs by its shading
/// normal, which the geometric ctx.n does not give) — wherever it is 0, no SampleLi sample (64
/// stratified u, three wavelength draws) carries light (L > 0). Receivers: Receivers() with normals
/// 0, ±z, ±x, one tilted and one perpendicular to the light's first sample there (where a receiver
/// cosine alone would vanish). `zeros` counts the receivers with Reach 0.
std::string CheckReach(const Subject &s, const Light &light, int *zeros = nullptr) {
    std::ostringstream bad;
    int zero = 0;
    const std::vector<Vec3> normals{Vec3(), Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(-1, 0, 0),
                                    Normalize(Vec3(0.3, -0.8, 0.5))};
    for (const Vec3 &p : Receivers()) {
        std::vector<Vec3> here = normals;
        if (const auto ls = light.SampleLi(LightSampleContext{p, Vec3()}, Vec2(0.5, 0.5), Wavelengths(*s.scene)[1]))
            // ⟂ the light's direction exactly (−w_y·w_x + w_x·w_y = 0 in floating point)
            here.push_back(ls->wi.x != 0 || ls->wi.y != 0 ? Vec3(-ls->wi.y, ls->wi.x, 0) : Vec3(1, 0, 0));
        for (const Vec3 &n : here) {
            const LightSampleContext ctx{p, n};
            const double r = light.Reach(ctx);
            if (std::isnan(r)) continue;  // no estimate: the sampler weighs by power there
            if (!std::isfinite(r) || r < 0) {
                bad << "Reach " << r << "; ";
                continue;
            }
            if (r > 0) continue;
            ++zero;
            for (const SampledWavelengths &wl : Wavelengths(*s.scene))
                for (int i = 0; i < 64; ++i) {
                    const auto ls = light.SampleLi(ctx, Vec2((i % 8 + 0.5) / 8, (i / 8 + 0.5) / 8), wl);
                    if (!ls || ls->L.IsZero()) continue;
                    bad << "Reach 0 at (" << p.x << ", " << p.y << ", " << p.z << ") normal (" << n.x << ", " << n.y
                        << ", " << n.z << ") but a sample arrives from (" << ls->wi.x << ", " << ls->wi.y << ", "
                        << ls->wi.z << "); ";
                    i = 64;
                }
        }
    }
    if (zeros) *zeros = zero;
    return bad.str();
}

// ---- the suite ----------------------------------------------------------------------------------

class LightContract : public ::testing::TestWithParam<LightCase> {
  protected:
    void SetUp() override {
        subject_ = Build(GetParam());
        if (!subject_.light) GTEST_SKIP() << "did not build";
    }
    Subject subject_;
};

TEST_P(LightContract, Finite) { EXPECT_EQ(CheckFinite(subject_, *subject_.light), ""); }

TEST_P(LightContract, SamplingMatchesPdf) {
    if (subject_.light->IsDelta()) GTEST_SKIP() << "a delta light has no density";
    EXPECT_EQ(CheckSamplingMatchesPdf(subject_, *subject_.light, Alpha()), "");
}

TEST_P(LightContract, PowerMatchesRadiance) { EXPECT_EQ(CheckPowerMatchesRadiance(subject_, *subject_.light), ""); }

TEST_P(LightContract, MeasureGRMatchesQuadrature) { EXPECT_EQ(CheckMeasureGR(subject_, *subject_.light), ""); }

TEST_P(LightContract, MeasuresOnlyItsSlots) {
    if (!subject_.light->MeasuredInClosedForm()) GTEST_SKIP() << "area lights are not measured in closed form";
    EXPECT_EQ(CheckMeasuresOnlyItsSlots(subject_, *subject_.light), "");
}

TEST_P(LightContract, MeasuresNothingOnlyWhereZero) {
    if (!subject_.light->MeasuredInClosedForm()) GTEST_SKIP() << "area lights are not measured in closed form";
    EXPECT_EQ(CheckMeasuresNothing(subject_, *subject_.light), "");
}

TEST_P(LightContract, ReachIsZeroOnlyWhereNothingArrives) { EXPECT_EQ(CheckReach(subject_, *subject_.light), ""); }

INSTANTIATE_TEST_SUITE_P(AllLights, LightContract, ::testing::ValuesIn(AllCases()),
                         [](const ::testing::TestParamInfo<LightCase> &i) { return i.param.Name(); });

TEST(LightRegistry, EveryLightHasPresets) {
    for (const auto &e : Registry<Light>::Entries()) {
        const std::size_t n = e.presets().size();
        EXPECT_GE(n, 1u) << "light '" << e.name << "' declares no TestPresets(): the light contract suite "
                          << "(tests/lights/light_contract_test.cpp) cannot check it";
        EXPECT_LE(n, 5u) << e.name;
    }
}

// A light that samples like `of` but tampers with what it says of itself: PdfLi times `pdfFactor`
// (a density that does not match the samples), with `hideReach` a Reach of 0 everywhere (it
// hides its light from the exhaustive sampler), with `ignoreMask` a MeasureGR of every wavelength
// whatever the GR measures, with `claimNothing` a MeasuresNothing that is true everywhere.
class TamperedLight final : public Light {
  public:
    TamperedLight(const Light &of, double pdfFactor, bool hideReach, bool ignoreMask = false, bool claimNothing = false)
        : of_(of), pdfFactor_(pdfFactor), hide_(hideReach), ignoreMask_(ignoreMask), claimNothing_(claimNothing) {}
    std::optional<LightSample> SampleLi(const LightSampleContext &c, const Vec2 &u,
                                        const SampledWavelengths &wl) const override {
        return of_.SampleLi(c, u, wl);
    }
    double PdfLi(const LightSampleContext &c, const Vec3 &wi, const Vec3 &p, const Vec3 &n) const override {
        return pdfFactor_ * of_.PdfLi(c, wi, p, n);
    }
    SampledSpectrum Le(const Vec3 &d, const SampledWavelengths &wl) const override { return of_.Le(d, wl); }
    LightType Type() const override { return of_.Type(); }
    const Spectrum &EmissionSpectrum() const override { return of_.EmissionSpectrum(); }
    double PowerScale() const override { return of_.PowerScale(); }
    double Reach(const LightSampleContext &c) const override { return hide_ ? 0.0 : of_.Reach(c); }
    std::optional<GrMeasurement> MeasureGR(const SpectralGenRay &g, const SampledWavelengths &wl) const override {
        SpectralGenRay every = g;
        if (ignoreMask_) every.measured = ~0u;
        return of_.MeasureGR(every, wl);
    }
    bool MeasuresNothing(const SpectralGenRay &g) const override { return claimNothing_ || of_.MeasuresNothing(g); }
    std::string ToString() const override { return "tampered"; }

  private:
    const Light &of_;
    double pdfFactor_;
    bool hide_, ignoreMask_, claimNothing_;
};

TEST(LightContractPower, CatchesAPdfOffByTwo) {
    const Subject s = Build({"distant", 1});
    ASSERT_TRUE(s.light);
    EXPECT_EQ(CheckSamplingMatchesPdf(s, *s.light, Alpha()), "");
    const TamperedLight wrong(*s.light, 2, false);
    const std::string why = CheckSamplingMatchesPdf(s, wrong, Alpha());
    EXPECT_NE(why.find("sample pdf"), std::string::npos) << why;
    EXPECT_NE(why.find("χ²"), std::string::npos) << why;
}

TEST(LightContractReach, ZerosAreExercisedAndALyingReachIsCaught) {
    // The one-sided panel of `area`'s first preset faces away from some receivers: Reach is 0
    // there, and the check looks at those samples.
    const Subject s = Build({"area", 0});
    ASSERT_TRUE(s.light);
    int zeros = 0;
    EXPECT_EQ(CheckReach(s, *s.light, &zeros), "");
    EXPECT_GT(zeros, 10);
    const TamperedLight hiding(*s.light, 1, true);
    const std::string why = CheckReach(s, hiding);
    EXPECT_NE(why.find("but a sample arrives"), std::string::npos) << why;
}

TEST(LightContractSlots, ALightThatIgnoresTheMaskIsCaught) {
    const Subject s = Build({"distant", 0});
    ASSERT_TRUE(s.light);
    EXPECT_EQ(CheckMeasuresOnlyItsSlots(s, *s.light), "");
    const TamperedLight every(*s.light, 1, false, true);
    const std::string why = CheckMeasuresOnlyItsSlots(s, every);
    EXPECT_NE(why.find("measured though only"), std::string::npos) << why;
}

TEST(LightContractNothing, AClaimWhereLightArrivesIsCaught) {
    // The sun-like disc of `distant` claims nothing for GRs facing away and beyond the disc's reach
    // (the check sees such claims), and a light that claims nothing everywhere is caught.
    const Subject s = Build({"distant", 0});
    ASSERT_TRUE(s.light);
    int claims = 0;
    EXPECT_EQ(CheckMeasuresNothing(s, *s.light, &claims), "");
    EXPECT_GT(claims, 100);
    const TamperedLight liar(*s.light, 1, false, false, true);
    const std::string why = CheckMeasuresNothing(s, liar);
    EXPECT_NE(why.find("but MeasureGR gives"), std::string::npos) << why;
}

}  // namespace
}  // namespace phasor::test
