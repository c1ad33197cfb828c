// SPDX-License-Identifier: Apache-2.0
// phasor — `phasor probe` (probe.h): a kernel explorer for kernel authors.
//
// The probe surface is the plane z = 0 seen in its local shading frame: z = the normal, x = the
// frame's first tangent dp/du = +x, y = dp/dv = +y; the texture context is uv = --uv (default
// (0.5, 0.5)), p = (u, v, 0) m, n = +z, β = 0. Light of vacuum wavelength λ arrives from
// wi = (sinθ cosφ, sinθ sinφ, cosθ) (θ from the normal, φ from x; θ > 90° = from below) out of a
// medium of index 1, where x is the kernel's reference direction if it has one (ReferenceDirection::
// ReferenceAngle: a grating's grating vector, so φ = 0 is the classical mount), else dp/du. Per
// discrete lobe and in total, probe reports *power* fractions:
//   * a near-delta lobe's listed weight a_j is a radiance throughput that includes the factor
//     (n_in/n_out)² on refraction (core/render/material.h), so its efficiency is a_j·(n_out/n_in)²
//     — a lossless interface gives R + T = 1 (the contract suite's energy test counts the same way);
//   * the continuous lobes by Monte Carlo: `--samples` i.i.d. samples of Sample() under the mask
//     LobeContinuous (the masked estimator is unbiased for the continuous part alone), each counting
//     weight·η² on transmission (η = ScatterSample::eta), from a fixed seed (--seed, default 0), with
//     the standard error of the mean;
//   * R = every reflected lobe + the continuous reflection (wo on wi's side), T the rest;
//   * a kernel that conserves energy per incident direction (Material::
//     ConservesEnergyPerIncidentDirection: grating, harvey_shack, a mix of them) lists per query
//     what arrives at wi and evaluates f(wi → wo) for light arriving from wo; its lobes' efficiencies
//     are read from the queries at their directions, towards wi, and its continuous part is the
//     light from wi leaving into every w, ∫ f(w → wi)·|cosθ_w| dω_w — estimated by multi-sample MIS
//     (balance heuristic) of cosine-weighted directions on either side and the kernel's own
//     continuous samples at wi, one of each per sample (Sample's integral, ∫ f(wi → wo)·|cosθo| dωo,
//     is what a camera at wi gathers instead);
// Default: the wave-optical answer, a generalized-ray query (rayOptics = false) for a plane wave
// (no GR footprint: q.gr = nullptr, β = 0). `--ray`: the ray-optics limit (rayOptics = true).
// Footprint-aware kernels (the aperture) answer only for a given GR on a given shape — a plane-wave
// probe has neither — and are refused with an explanation.
// The plot (MakeMap, drawn by matplotlib through app/plot.h) maps over both hemispheres the
// continuous light from the source into each direction w: Eval(wi → w)·|cosθ_w| [1/sr], or for a
// kernel that conserves energy per incident direction Eval(w → wi)·|cosθ_w|.

#include "app/probe.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "app/plot.h"
#include "app/render_common.h"
#include "app/text.h"
#include "core/diagnostics.h"
#include "core/image/image_io.h"
#include "core/render/material.h"
#include "core/render/registry.h"
#include "core/render/sampler.h"
#include "core/render/sampling.h"
#include "parser/parser.h"

namespace phasor {

double ProbeTheta(const Vec3 &w) { return std::acos(Clamp(w.z, -1.0, 1.0)); }
double ProbePhi(const Vec3 &w) {
    const double r = std::hypot(w.x, w.y);
    if (r < 1e-15) return 0.0;
    // A component below 1e-12 of the transverse length is round-off (a direction turned back from
    // the kernel's frame by −ψ), not an angle: φ = 0 or π exactly, never 3.5e-15 or −π. (+0.0 for
    // y on the −x axis: atan2(+0, x < 0) = π.)
    const double x = std::abs(w.x) <= 1e-12 * r ? 0.0 : w.x, y = std::abs(w.y) <= 1e-12 * r ? 0.0 : w.y;
    return std::atan2(y + 0.0, x);
}

namespace {

// A command-line problem: printed as "error: <message>", exit status 1.
struct ProbeError {
    std::string message;
};

std::string Num(double v, int digits) {
    if (v == 0) v = 0;  // no "-0"
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}

// A .wscene quantity given on the command line ("550nm", "30 deg", "0.25*pi rad"), in SI, which
// must have dimension `dim`.
double ParseQuantity(const std::string &flag, const std::string &text, Dim dim, const char *example) {
    Diagnostics diag;
    std::optional<Value> v = ParseValueString(text, flag, diag);
    std::string why;
    for (const Diagnostic &d : diag.All())
        if (d.severity == Severity::Error && why.empty()) why = d.message;
    const std::string expects = "'" + flag + "' expects " + dim.Describe() + " such as " + example + "; got '" +
                                text + "'";
    if (!v || !why.empty()) throw ProbeError{expects + (why.empty() ? "" : " (" + why + ")")};
    if (v->kind != Value::Kind::Number) throw ProbeError{expects + ", " + v->DescribeKind()};
    if (!(v->dim == dim))
        throw ProbeError{expects + ", " +
                         (v->dim.IsNone() ? std::string("a number without a unit") : v->dim.Describe())};
    if (!std::isfinite(v->number)) throw ProbeError{expects + ", which is not finite"};
    return v->number;
}

// w turned by ψ [rad] about the normal (counter-clockwise).
Vec3 RotateZ(const Vec3 &w, double psi) {
    const double c = std::cos(psi), s = std::sin(psi);
    return {c * w.x - s * w.y, s * w.x + c * w.y, w.z};
}

// Progress of the Monte-Carlo loop, as `render` shows it: a bar with the ETA on a terminal
// (`bar`), and once, after a quarter of a second of sampling, the whole run's time extrapolated
// from it — a warning (WorkWarning) when it is far beyond the usual.
class SampleProgress {
  public:
    SampleProgress(long long total, bool bar) : total_(total), bar_(bar), start_(Clock::now()), last_(start_) {}
    ~SampleProgress() {
        if (drawn_) std::fputc('\n', stderr);
    }
    /// After `done` samples (called every Stride samples).
    void operator()(long long done) {
        const auto now = Clock::now();
        const double t = std::chrono::duration<double>(now - start_).count();
        if (!estimated_ && t > 0.25) {
            estimated_ = true;
            char what[128];
            std::snprintf(what, sizeof what, "%.3g samples at %.3g us per sample, one thread", double(total_),
                          t / double(done) * 1e6);
            const std::string w = WorkWarning(t / double(done) * double(total_), what,
                                              "lower --samples (its standard error falls only as 1/sqrt(samples); "
                                              "the report states it)",
                                              "probe");
            if (!w.empty()) std::fprintf(stderr, "%swarning: %s\n", drawn_ ? "\r" : "", w.c_str());
        }
        if (!bar_ || std::chrono::duration<double>(now - last_).count() < 0.1) return;
        last_ = now;
        drawn_ = true;
        const double frac = double(done) / double(total_);
        const int width = 30, filled = int(frac * width);
        std::fprintf(stderr, "\rprobe [%s%s] %3d%% %.3g/%.3g samples  %s elapsed  ETA %s   ",
                     std::string(filled, '=').c_str(), std::string(width - filled, ' ').c_str(), int(frac * 100),
                     double(done), double(total_), FormatDuration(t).c_str(),
                     FormatDuration(frac > 0 ? t / frac - t : 0).c_str());
        std::fflush(stderr);
    }
    static constexpr long long Stride = 4096;

  private:
    using Clock = std::chrono::steady_clock;
    long long total_;
    bool bar_, estimated_ = false, drawn_ = false;
    Clock::time_point start_, last_;
};

ProbeResult Measure(const Material &m, const ScatterQuery &q, long long samples, uint64_t seed, bool bar) {
    ProbeResult r;
    ScratchBuffer scratch, other;  // the kernel prepared for q; for other queries, one at a time
    const PreparedKernel &k = m.Prepare(q, scratch);
    // A kernel that conserves energy per incident direction (a grating) lists, for a query at wi,
    // what arrives *at* wi along each lobe; the light *from* wi into lobe l's direction is what the
    // query there lists along its lobe of the same id back towards wi (material.h).
    const bool fromSource = !m.IsReciprocal() && m.ConservesEnergyPerIncidentDirection();
    for (const NearDeltaLobe &l : k.ListNearDelta()) {
        ProbeLobe p;
        p.id = l.id;
        p.name = m.LobeName(l.id);
        p.transmission = (l.flags & ScatterTransmission) != 0;
        p.wo = l.wo[0];
        const NearDeltaLobe *carrier = &l;
        if (fromSource) {
            ScatterQuery there = q;
            there.wi = l.wo[0];
            other.Reset();
            carrier = nullptr;
            for (const NearDeltaLobe &b : m.Prepare(there, other).ListNearDelta())
                if (b.id == l.id && SameDirection(b.wo[0], q.wi)) carrier = &b;
            if (!carrier) continue;  // nothing reaches that direction from wi
        }
        const double power = carrier->nOut[0] / carrier->nIn[0];  // undo the radiance factor (n_in/n_out)²
        p.efficiency = carrier->Weight()[0] * power * power;
        (p.transmission ? r.discreteT : r.discreteR) += p.efficiency;
        r.lobes.push_back(p);
    }
    r.continuous = (k.Capabilities() & CapContinuous) != 0;
    if (!r.continuous) return r;
    Pcg32 rng(seed, 0x70726f6265ull);  // "probe"
    double meanR = 0, meanT = 0, m2R = 0, m2T = 0;  // Welford, per sample (0 when it went elsewhere)
    ScatterQuery qw = q;                            // a query at w (fromSource)
    double etaFar = 0;  // η_t/η_i into the far side, from the kernel's transmitted samples (fromSource)
    bool farUnknown = false;
    SampleProgress progress(samples, bar);
    for (long long n = 1; n <= samples; ++n) {
        if (n % SampleProgress::Stride == 0) progress(n);
        const double u0 = rng.Uniform(), u1 = rng.Uniform(), u2 = rng.Uniform();
        double xr = 0, xt = 0;
        const std::optional<ScatterSample> s = k.Sample(u0, Vec2(u1, u2), LobeContinuous);
        if (s && (!std::isfinite(s->weight[0]) || !std::isfinite(s->eta))) {
            ++r.nonFinite;  // counted as 0
        } else if (!fromSource) {
            if (s && s->wo.z * q.wi.z > 0) xr = s->weight[0];
            else if (s) xt = s->weight[0] * s->eta * s->eta;
        } else {
            // The light from wi into w: f(w → wi)·|cosθ_w| over the mixture density of the two
            // techniques (cosine-weighted on a random side, |cosθ|/(2π); the kernel's samples, Pdf).
            // On the far side the power factor (n_wi/n_w)² = 1/η² undoes f's radiance factor.
            if (s && s->wo.z * q.wi.z < 0) etaFar = s->eta;
            const Vec2 c = ConcentricDisc(Vec2(rng.Uniform(), rng.Uniform()));
            const double side = rng.Uniform() < 0.5 ? 1 : -1;
            const Vec3 w1(c.x, c.y, side * std::sqrt(std::max(0.0, 1 - c.x * c.x - c.y * c.y)));
            for (const Vec3 &w : {w1, s ? s->wo : Vec3(0, 0, 0)}) {
                if (w.z == 0) continue;  // no sample (or exactly grazing)
                const double density = std::abs(w.z) / (2 * Pi) + k.Pdf(w);
                qw.wi = w;
                other.Reset();
                const double f = m.Prepare(qw, other).Eval(q.wi)[0];
                if (!(density > 0) || !(f > 0)) continue;
                const double x = f * std::abs(w.z) / density;
                if (!std::isfinite(x)) ++r.nonFinite;
                else if (w.z * q.wi.z > 0) xr += x;
                else if (etaFar > 0) xt += x / (etaFar * etaFar);
                else farUnknown = true;
            }
        }
        const double dr = xr - meanR, dt = xt - meanT;
        meanR += dr / double(n);
        meanT += dt / double(n);
        m2R += dr * (xr - meanR);
        m2T += dt * (xt - meanT);
    }
    if (farUnknown)
        throw Error("the kernel sends light from the source through the surface into a continuous lobe, but none "
                    "of its own samples crossed there: probe cannot tell the media's indices for the power "
                    "factor (a kernel that conserves energy per incident direction with continuous "
                    "transmission)");
    r.contR = meanR;
    r.contT = meanT;
    if (samples > 1) {
        r.seR = std::sqrt(m2R / double(samples - 1) / double(samples));
        r.seT = std::sqrt(m2T / double(samples - 1) / double(samples));
    }
    return r;
}

}  // namespace

std::string ProbeCsv(const ProbeResult &r) {
    std::ostringstream os;
    os << "kind,order,theta_o,phi_o,value,stderr\n";
    os << "R,,,," << Num(r.R(), 12) << ',' << Num(r.seR, 12) << '\n';
    os << "T,,,," << Num(r.T(), 12) << ',' << Num(r.seT, 12) << '\n';
    for (const ProbeLobe &l : r.lobes)
        os << "lobe," << CsvField(l.name) << ',' << Num(ProbeTheta(l.wo), 15) << ',' << Num(ProbePhi(l.wo), 15) << ','
           << Num(l.efficiency, 12) << ",0\n";
    return os.str();
}

namespace {

std::string DegText(double rad) { return Num(Degrees(rad), 6); }

std::string ReportText(const std::string &material, const std::string &type, const CliOptions &o,
                       const ProbeResult &r, const std::string &xAxis, const ProbeRequest &q) {
    const double theta = q.theta, phi = q.phi, lambda = q.lambda;
    const Vec2 uv = q.uv;
    const uint64_t seed = q.seed;
    std::ostringstream os;
    os << "probe: material '" << material << "' (" << type << ") of " << o.scene << "\n"
       << "  light from theta = " << DegText(theta) << " deg, phi = " << DegText(phi)
       << " deg (local frame: z = normal, x = " << xAxis << "), lambda = " << Num(lambda * 1e9, 6) << " nm, uv = ("
       << Num(uv.x, 6) << ", " << Num(uv.y, 6) << "), "
       << (o.probe.rayOptics ? "ray-optics limit" : "wave optics (plane wave)") << "\n"
       << "  power fractions; near-delta lobes exact";
    if (r.continuous)
        os << ", continuous lobes by Monte Carlo (" << o.probe.samples << " samples, seed " << seed
           << ", +- = standard error)";
    os << "\n";
    auto total = [&](const char *name, double all, double discrete, double cont, double se) {
        os << "  " << name << " = " << Num(all, 9);
        if (r.continuous)
            os << " +- " << Num(se, 3) << "  (near-delta " << Num(discrete, 9) << ", continuous " << Num(cont, 9)
               << ")";
        os << "\n";
    };
    total("R", r.R(), r.discreteR, r.contR, r.seR);
    total("T", r.T(), r.discreteT, r.contT, r.seT);
    if (r.nonFinite > 0)
        os << "  warning: " << r.nonFinite << " of " << o.probe.samples
           << " samples had a NaN or infinite weight (counted as 0): the kernel has a bug\n";
    if (r.lobes.empty()) {
        os << "  no near-delta lobe\n";
        return os.str();
    }
    os << "  kind          order  theta_o [deg]  phi_o [deg]  efficiency\n";
    for (const ProbeLobe &l : r.lobes) {
        char line[160];
        std::snprintf(line, sizeof line, "  %-12s  %5s  %13s  %11s  %s\n",
                      l.transmission ? "transmission" : "reflection", l.name.c_str(), DegText(ProbeTheta(l.wo)).c_str(),
                      DegText(ProbePhi(l.wo)).c_str(), Num(l.efficiency, 9).c_str());
        os << line;
    }
    return os.str();
}

// ---- The angular plot --------------------------------------------------------------------------

// Eval·|cosθo| [1/sr] over the projected hemispheres, (u, v) = (sinθ cosφ, sinθ sinφ): the disc
// "reflection" on wi's side, "transmission" on the far side, `size` × `size` cells each; the
// near-delta lobes as rings (bigger for larger efficiency, labelled with it) and the direction
// towards the source as a cross on the reflection disc. Drawn by the plot module (app/plot.h
// StageDiscMap): one dB scale (0 dB = the maximum, 40 dB), θ = 30° and 60° circles, a colour bar.
DiscMap MakeMap(const Material &m, const ScatterQuery &q, const ProbeResult &r, int size, double psi) {
    DiscMap map;
    map.n = size;
    // What the light from the source sends into wo: f(wi → wo), or for a kernel that conserves
    // energy per incident direction (f(wi → wo) is then the light arriving from wo) f(wo → wi).
    const bool fromSource = !m.IsReciprocal() && m.ConservesEnergyPerIncidentDirection();
    map.valueLabel = fromSource ? "Eval(wo → source)·|cosθo| [1/sr]" : "Eval·|cosθo| [1/sr]";
    ScratchBuffer scratch, atWo;  // the kernel prepared for q; at each wo (fromSource)
    const PreparedKernel &k = m.Prepare(q, scratch);
    ScatterQuery qo = q;
    const double side = q.wi.z > 0 ? 1 : -1;
    for (int disc = 0; disc < 2; ++disc) {
        DiscMap::Disc d;
        d.name = disc == 0 ? "reflection" : "transmission";
        d.values.assign(std::size_t(size) * size, 0.0);
        for (int j = 0; j < size; ++j)
            for (int i = 0; i < size; ++i) {
                const double x = 2 * (i + 0.5) / size - 1, y = 2 * (j + 0.5) / size - 1;
                const double s2 = x * x + y * y;
                if (s2 >= 1) continue;  // (not drawn)
                // (x, y) in the probe's frame; the kernel's local frame is turned by ψ from it.
                const Vec3 wo = RotateZ(Vec3(x, y, (disc == 0 ? side : -side) * std::sqrt(1 - s2)), psi);
                qo.wi = wo;
                atWo.Reset();
                const double f = !r.continuous ? 0.0
                                 : fromSource  ? m.Prepare(qo, atWo).Eval(q.wi)[0] * std::abs(wo.z)
                                               : k.Eval(wo)[0] * std::abs(wo.z);
                d.values[std::size_t(j) * size + i] = std::isfinite(f) ? f : 0.0;
            }
        map.discs.push_back(std::move(d));
    }
    for (const ProbeLobe &l : r.lobes) {
        // 6 pt for an efficiency of 1e-6 or less, 14 pt for 1.
        const double size = 6 + 8 * Clamp(1 + std::log10(std::max(l.efficiency, 1e-12)) / 6, 0.0, 1.0);
        map.markers.push_back({l.transmission ? 1 : 0, l.wo.x, l.wo.y, Num(l.efficiency, 3), 'o', size});
    }
    const Vec3 source = RotateZ(q.wi, -psi);
    map.markers.push_back({0, source.x, source.y, "source", 'x', 10});
    return map;
}

// The scene's named materials, for messages.
std::vector<std::string> MaterialNames(const SceneDesc &desc) {
    std::vector<std::string> names;
    for (const SceneEntity &e : desc.entities)
        if (e.keyword == "Material" && !e.name.empty()) names.push_back(e.name);
    std::sort(names.begin(), names.end());
    return names;
}

// The query: the plane z = 0, first tangent +x (see the file comment), in the kernel's frame,
// which is turned by ψ = `psi` (its reference angle) from the probe's; `wl` holds λ.
ScatterQuery MakeQuery(const Material &m, const ProbeRequest &r, SampledWavelengths &wl, double *psi,
                       bool *hasReference) {
    wl.lambda[0] = r.lambda;
    wl.pdf[0] = 1;
    wl.delta = true;
    ScatterQuery q;
    q.wi = Vec3(std::sin(r.theta) * std::cos(r.phi), std::sin(r.theta) * std::sin(r.phi), std::cos(r.theta));
    q.wl = &wl;
    q.etaOutside = 1;
    q.rayOptics = r.rayOptics;
    q.tex.uv = r.uv;
    q.tex.p = Vec3(r.uv.x, r.uv.y, 0);
    q.tex.dpdu = Vec3(1, 0, 0);
    q.tex.dpdv = Vec3(0, 1, 0);
    q.tex.n = Vec3(0, 0, 1);
    // φ is measured from the kernel's reference direction (a grating's grating vector), which
    // lies at ψ from dp/du: the kernel is asked in its own frame, its answers turned back by −ψ.
    const std::optional<double> reference = ReferenceAngleOf(m, q.tex);
    *psi = reference.value_or(0.0);
    *hasReference = reference.has_value();
    q.wi = RotateZ(q.wi, *psi);
    return q;
}

}  // namespace

ProbedMaterial BuildProbedMaterial(const SceneDesc &desc, const std::string &material, const std::string &scenePath,
                                   Diagnostics &diag) {
    ProbedMaterial out;
    out.name = !material.empty() && material[0] == '@' ? material.substr(1) : material;
    const SceneEntity *entity = nullptr;
    for (const SceneEntity &e : desc.entities)
        if (e.name == out.name) entity = &e;
    if (!entity || entity->keyword != "Material") {
        const std::vector<std::string> names = MaterialNames(desc);
        const std::string sug = Suggest(out.name, names);
        std::string msg = entity ? "'" + out.name + "' in '" + scenePath + "' is a " + entity->keyword +
                                       ", not a Material"
                                 : "no material named '" + out.name + "' in '" + scenePath + "'";
        if (!sug.empty()) msg += "; did you mean '" + sug + "'?";
        else if (names.empty()) msg += " (it defines no named material)";
        throw Error(msg);
    }
    out.type = entity->type;
    BuildContext ctx(desc, diag);
    ParamDict ref;
    ref.Set("material", Value::Ref(out.name, FileLoc{"<command line>", 0, 0, 1}));
    try {
        out.material = ctx.GetRef<Material>(ref, "material");
    } catch (const Error &e) {
        diag.Report(e);
    }
    if (diag.HasErrors()) out.material.reset();
    return out;
}

ProbeResult ProbeKernel(const ProbedMaterial &m, const ProbeRequest &r) {
    if (m.material->IsFootprintAware())
        throw Error("material '" + m.name + "' (" + m.type + ") is footprint-aware: its response depends on the "
                    "incident generalized ray's footprint on the shape it lies on (theory §9), which a "
                    "plane-wave probe does not have; render a scene with it instead (docs/aperture.md)");
    SampledWavelengths wl;
    double psi = 0;
    bool hasReference = false;
    const ScatterQuery q = MakeQuery(*m.material, r, wl, &psi, &hasReference);
    ProbeResult result = Measure(*m.material, q, r.samples, r.seed, r.progressBar);
    for (ProbeLobe &l : result.lobes) l.wo = RotateZ(l.wo, -psi);
    result.psi = psi;
    result.hasReference = hasReference;
    return result;
}

std::string StageProbeMap(OutputFiles &files, const std::string &path, const ProbedMaterial &m,
                          const ProbeRequest &r, const ProbeResult &result) {
    SampledWavelengths wl;
    double psi = 0;
    bool hasReference = false;
    const ScatterQuery q = MakeQuery(*m.material, r, wl, &psi, &hasReference);
    DiscMap map = MakeMap(*m.material, q, result, 300, psi);
    map.title = "phasor probe " + m.name + " (" + m.type + "), theta = " + DegText(r.theta) + " deg, phi = " +
                DegText(r.phi) + " deg, lambda = " + Num(r.lambda * 1e9, 6) + " nm";
    MakeParentDirectory(path);
    if (StageDiscMap(files, path, map)) return path;
    const std::string data = std::filesystem::path(path).replace_extension(".map.csv").string();
    files.Stage(data, DiscMapCsv(map));
    return data;
}

int RunProbe(const CliOptions &o) {
    const CliOptions::ProbeOptions &p = o.probe;
    const bool colour = isatty(2) && !std::getenv("NO_COLOR");
    try {
        // The quantities first: a typo there needs no scene.
        ProbeRequest r;
        r.theta = ParseQuantity("--theta", p.theta, Dim::Angle(), "30deg");
        r.phi = p.phi.empty() ? 0.0 : ParseQuantity("--phi", p.phi, Dim::Angle(), "45deg");
        r.lambda = ParseQuantity("--lambda", p.lambda, Dim::Length(), "550nm");
        if (r.theta < 0 || r.theta > Pi)
            throw ProbeError{"'--theta' must lie in [0deg, 180deg] (from the normal; above 90deg the light comes "
                             "from below); got '" + p.theta + "'"};
        if (std::abs(std::cos(r.theta)) < 1e-6)
            throw ProbeError{"'--theta' " + p.theta + " is grazing (the light runs along the surface): no "
                             "kernel scatters it; use an angle below or above 90deg"};
        if (!(r.lambda > 0)) throw ProbeError{"'--lambda' must be positive; got '" + p.lambda + "'"};
        // Far outside the optical range the kernels (thin surfaces, smooth interfaces) and their
        // index data (named materials: 200 nm – a few µm) are written for: a warning, the answer anyway.
        if (r.lambda < 100e-9 || r.lambda > 1e-3)
            std::cerr << "warning: '--lambda' " << p.lambda
                      << " is far outside the optical range phasor's kernels model (100 nm – 1 mm): their surface "
                         "models assume wavelengths far above atomic scales and the named materials' indices are "
                         "tabulated from 200 nm to a few um (docs/kernels.md)\n";
        r.uv = Vec2(p.u, p.v);
        r.samples = p.samples;
        r.seed = o.seed >= 0 ? uint64_t(o.seed) : 0;
        r.rayOptics = p.rayOptics;
        r.progressBar = !o.quiet && isatty(2);

        // The scene: parsed and resolved whole, but only the material (and what it refers to) is built,
        // so a scene without lights or a detector (a material library) can be probed.
        Diagnostics diag(o.strict);
        diag.SetPermissive(o.permissive);
        ParseOptions parse;
        parse.defines = o.defines;
        std::optional<SceneDesc> desc = ParseSceneFile(o.scene, parse, diag);
        ProbedMaterial m;
        if (desc && !diag.HasErrors()) {
            try {
                m = BuildProbedMaterial(*desc, p.material, o.scene, diag);
            } catch (const Error &e) {
                throw ProbeError{e.Message()};
            }
        }
        diag.Print(std::cerr, colour);
        if (!m.material || diag.HasErrors()) {
            if (diag.HasErrors())
                std::cerr << diag.ErrorCount() << " error" << (diag.ErrorCount() == 1 ? "" : "s") << " in '"
                          << o.scene << "'\n";
            return 1;
        }
        const ProbeResult result = ProbeKernel(m, r);

        const std::string report = ReportText(m.name, m.type, o, result,
                                              result.hasReference ? "the kernel's reference direction (" +
                                                                        DegText(result.psi) + " deg from dp/du)"
                                                                  : std::string("dp/du"),
                                              r);
        const std::string csv = ProbeCsv(result);
        const bool csvToStdout = p.csv == "-";
        OutputFiles files;
        if (!p.csv.empty() && !csvToStdout) {
            MakeParentDirectory(p.csv);
            files.Stage(p.csv, csv);
        }
        std::string plotted;  // the plot, or its data without matplotlib
        if (!p.plot.empty()) {
            plotted = StageProbeMap(files, p.plot, m, r, result);
            if (plotted != p.plot)
                std::cerr << "warning: " << MatplotlibMissing() << "; '" << p.plot << "' not drawn, its data is in '"
                          << plotted << "'\n";
        }
        files.Commit();
        (csvToStdout ? std::cerr : std::cout) << report;
        if (csvToStdout) std::cout << csv;
        if (!o.quiet) {
            if (!p.csv.empty() && !csvToStdout) std::cerr << "wrote " << p.csv << "\n";
            if (!p.plot.empty()) std::cerr << "wrote " << plotted << "\n";
        }
        return 0;
    } catch (const ProbeError &e) {
        std::cerr << "error: " << e.message << "\n";
        return 1;
    } catch (const Error &e) {  // a failed write, a kernel's error
        std::cerr << (e.Loc().Known() && e.Loc().line > 0 ? e.Loc().ToString() + ": " : "") << "error: " << e.Message()
                  << "\n";
        return 1;
    }
}

}  // namespace phasor
