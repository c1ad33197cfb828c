// SPDX-License-Identifier: Apache-2.0
// phasor — `phasor probe` (probe.h): a kernel explorer for kernel authors.
//
// The probe surface is the plane z = 0 seen in its local shading frame: z = the normal, x = the
// frame's first tangent dp/du = +x, y = dp/dv = +y; the texture context is uv = --uv (default
// (0.5, 0.5)), p = (u, v, 0) m, n = +z, β = 0. Light of vacuum wavelength λ arrives from
// wi = (sinθ cosφ, sinθ sinφ, cosθ) (θ from the normal, φ from x; θ > 90° = from below) out of a
// medium of index 1. Per discrete lobe and in total, probe reports *power* fractions:
//   * a near-delta lobe's listed weight a_j is a radiance throughput that includes the factor
//     (n_in/n_out)² on refraction (core/render/material.h), so its efficiency is a_j·(n_out/n_in)²
//     — a lossless interface gives R + T = 1 (the contract suite's energy test counts the same way);
//   * the continuous lobes by Monte Carlo: `--samples` i.i.d. samples of Sample() under the mask
//     LobeContinuous (the masked estimator is unbiased for the continuous part alone), each counting
//     weight·η² on transmission (η = ScatterSample::eta), from a fixed seed (--seed, default 0), with
//     the standard error of the mean;
//   * R = every reflected lobe + the continuous reflection (wo on wi's side), T the rest.
// Default: the wave-optical answer, a generalized-ray query (rayOptics = false) for a plane wave
// (no GR footprint: q.gr = nullptr, β = 0). `--ray`: the ray-optics limit (rayOptics = true).
// Footprint-aware kernels (the aperture) answer only for a given GR on a given shape — a plane-wave
// probe has neither — and are refused with an explanation.
// The plot (one function, WriteProbePlot) maps Eval·|cosθo| [1/sr] over both hemispheres.

#include "app/probe.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "core/image/image_io.h"
#include "core/image/plot.h"
#include "core/render/material.h"
#include "core/render/registry.h"
#include "core/render/sampler.h"
#include "parser/parser.h"

namespace phasor {
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

// What probe measured.
struct ProbeLobe {
    int id = 0;
    bool transmission = false;
    Vec3 wo;
    double efficiency = 0;  // power fraction
};
struct ProbeResult {
    bool continuous = false;  // the kernel has a continuous lobe for this query (Monte Carlo ran)
    double discreteR = 0, discreteT = 0;
    double contR = 0, contT = 0, seR = 0, seT = 0;  // continuous part, standard errors of the mean
    long long nonFinite = 0;                        // samples with a NaN/Inf weight (a kernel bug)
    std::vector<ProbeLobe> lobes;
    double R() const { return discreteR + contR; }
    double T() const { return discreteT + contT; }
};

// θ from the +z normal [0, π] and φ from +x in (−π, π] (0 on the normal, where it is undefined).
double ThetaOf(const Vec3 &w) { return std::acos(Clamp(w.z, -1.0, 1.0)); }
double PhiOf(const Vec3 &w) {
    if (std::hypot(w.x, w.y) < 1e-15) return 0.0;
    return std::atan2(w.y + 0.0, w.x);  // + 0.0: −0 → +0, so the −x axis is π, not −π
}

ProbeResult Measure(const Material &m, ScatterQuery q, long long samples, uint64_t seed) {
    ProbeResult r;
    NearDeltaLobes lobes;
    m.ListNearDelta(q, lobes);
    for (const NearDeltaLobe &l : lobes) {
        ProbeLobe p;
        p.id = l.id;
        p.transmission = (l.flags & ScatterTransmission) != 0;
        p.wo = l.wo[0];
        const double power = l.nOut[0] / l.nIn[0];  // undo the radiance factor (n_in/n_out)²
        p.efficiency = l.weight[0] * power * power;
        (p.transmission ? r.discreteT : r.discreteR) += p.efficiency;
        r.lobes.push_back(p);
    }
    r.continuous = (m.Capabilities(q) & CapContinuous) != 0;
    if (!r.continuous) return r;
    q.lobes = LobeContinuous;
    Pcg32 rng(seed, 0x70726f6265ull);  // "probe"
    double meanR = 0, meanT = 0, m2R = 0, m2T = 0;  // Welford, per sample (0 when it went elsewhere)
    for (long long n = 1; n <= samples; ++n) {
        const double u0 = rng.Uniform(), u1 = rng.Uniform(), u2 = rng.Uniform();
        double xr = 0, xt = 0;
        if (auto s = m.Sample(q, u0, Vec2(u1, u2))) {
            if (!std::isfinite(s->weight[0]) || !std::isfinite(s->eta)) ++r.nonFinite;  // counted as 0
            else if (s->wo.z * q.wi.z > 0) xr = s->weight[0];
            else xt = s->weight[0] * s->eta * s->eta;
        }
        const double dr = xr - meanR, dt = xt - meanT;
        meanR += dr / double(n);
        meanT += dt / double(n);
        m2R += dr * (xr - meanR);
        m2T += dt * (xt - meanT);
    }
    r.contR = meanR;
    r.contT = meanT;
    if (samples > 1) {
        r.seR = std::sqrt(m2R / double(samples - 1) / double(samples));
        r.seT = std::sqrt(m2T / double(samples - 1) / double(samples));
    }
    return r;
}

// The CSV that scripts read: exactly this header, R and T, then one row per discrete lobe.
std::string CsvText(const ProbeResult &r) {
    std::ostringstream os;
    os << "kind,order,theta_o,phi_o,value,stderr\n";
    os << "R,,,," << Num(r.R(), 12) << ',' << Num(r.seR, 12) << '\n';
    os << "T,,,," << Num(r.T(), 12) << ',' << Num(r.seT, 12) << '\n';
    for (const ProbeLobe &l : r.lobes)
        os << "lobe," << l.id << ',' << Num(ThetaOf(l.wo), 15) << ',' << Num(PhiOf(l.wo), 15) << ','
           << Num(l.efficiency, 12) << ",0\n";
    return os.str();
}

std::string DegText(double rad) { return Num(Degrees(rad), 6); }

std::string ReportText(const std::string &material, const std::string &type, const CliOptions &o, double theta,
                       double phi, double lambda, const Vec2 &uv, uint64_t seed, const ProbeResult &r) {
    std::ostringstream os;
    os << "probe: material '" << material << "' (" << type << ") of " << o.scene << "\n"
       << "  light from theta = " << DegText(theta) << " deg, phi = " << DegText(phi)
       << " deg (local frame: z = normal, x = dp/du), lambda = " << Num(lambda * 1e9, 6) << " nm, uv = ("
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
        std::snprintf(line, sizeof line, "  %-12s  %5d  %13s  %11s  %s\n",
                      l.transmission ? "transmission" : "reflection", l.id, DegText(ThetaOf(l.wo)).c_str(),
                      DegText(PhiOf(l.wo)).c_str(), Num(l.efficiency, 9).c_str());
        os << line;
    }
    return os.str();
}

// ---- The angular plot --------------------------------------------------------------------------

// Eval·|cosθo| over the projected hemispheres, (x, y) = (sinθ cosφ, sinθ sinφ): disc 0 is wi's
// side (reflection), disc 1 the far side (transmission); each disc `size` × `size` pixels, x to
// the right, y up. Discrete lobes and the source direction as points on the discs.
struct ProbeMap {
    int size = 0;
    std::vector<double> value[2];  // row-major, row 0 at y = +1; NaN outside the disc
    struct Mark {
        int disc = 0;
        double x = 0, y = 0;
        double efficiency = 0;
    };
    std::vector<Mark> lobes;
    double sourceX = 0, sourceY = 0;  // wi, on disc 0
    std::string title;                // what the map shows (material, incidence, λ)
};

ProbeMap MakeMap(const Material &m, ScatterQuery q, const ProbeResult &r, int size) {
    ProbeMap map;
    map.size = size;
    q.lobes = LobeContinuous;
    const double side = q.wi.z > 0 ? 1 : -1;
    for (int disc = 0; disc < 2; ++disc) {
        std::vector<double> &v = map.value[disc];
        v.assign(std::size_t(size) * size, std::nan(""));
        for (int j = 0; j < size; ++j)
            for (int i = 0; i < size; ++i) {
                const double x = 2 * (i + 0.5) / size - 1, y = 1 - 2 * (j + 0.5) / size;
                const double s2 = x * x + y * y;
                if (s2 >= 1) continue;
                const Vec3 wo(x, y, (disc == 0 ? side : -side) * std::sqrt(1 - s2));
                const double f = r.continuous ? m.Eval(q, wo)[0] * std::abs(wo.z) : 0.0;
                v[std::size_t(j) * size + i] = std::isfinite(f) ? f : 0.0;
            }
    }
    for (const ProbeLobe &l : r.lobes) map.lobes.push_back({l.transmission ? 1 : 0, l.wo.x, l.wo.y, l.efficiency});
    map.sourceX = q.wi.x;
    map.sourceY = q.wi.y;
    return map;
}

// The one place that draws probe's plot (core/image/plot.h's raster colour-bar image): both discs on
// one dB scale (0 dB = the maximum, 40 dB range), light-grey circles at θ = 30° and 60°, near-delta
// lobes as red rings (larger for larger efficiency), the source direction as a white cross.
// Staged in `files`; returns the PlotResult (text drawn or not).
PlotResult WriteProbePlot(OutputFiles &files, const std::string &path, const ProbeMap &map) {
    constexpr double RangeDb = 40;
    const int n = map.size, gap = 24, margin = 12;
    const int w = 2 * n + gap + 2 * margin, h = n + 2 * margin;
    std::vector<double> rgb(std::size_t(w) * h * 3, 1.0);  // white background
    auto blend = [&](int x, int y, const Vec3 &c, double a) {
        if (x < 0 || y < 0 || x >= w || y >= h || !(a > 0)) return;
        double *p = &rgb[(std::size_t(y) * w + x) * 3];
        a = std::min(a, 1.0);
        for (int k = 0; k < 3; ++k) p[k] = (1 - a) * p[k] + a * c[k];
    };
    double peak = 0;
    for (const auto &v : map.value)
        for (double x : v)
            if (std::isfinite(x)) peak = std::max(peak, x);
    auto level = [&](double v) {  // colour-map coordinate: 0 dB at 1, −RangeDb at 0
        return peak > 0 && v > 0 ? Clamp(1 + 10 * std::log10(v / peak) / RangeDb, 0.0, 1.0) : 0.0;
    };
    auto discX = [&](int disc) { return margin + disc * (n + gap); };
    for (int disc = 0; disc < 2; ++disc)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const double v = map.value[disc][std::size_t(j) * n + i];
                if (std::isnan(v)) continue;
                // Without a continuous lobe the discs are neutral grey, not the colour of "≤ −40 dB".
                blend(discX(disc) + i, margin + j, peak > 0 ? ViridisDisplay(level(v)) : Vec3(0.9, 0.9, 0.9), 1);
            }
    // A ring of radius `rad` and width `lw` [pixels] centred at pixel position (cx, cy), anti-aliased.
    auto ring = [&](double cx, double cy, double rad, double lw, const Vec3 &c) {
        const int x0 = int(std::floor(cx - rad - lw)), x1 = int(std::ceil(cx + rad + lw));
        const int y0 = int(std::floor(cy - rad - lw)), y1 = int(std::ceil(cy + rad + lw));
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                const double d = std::hypot(x + 0.5 - cx, y + 0.5 - cy);
                blend(x, y, c, lw / 2 + 0.5 - std::abs(d - rad));
            }
    };
    auto toPixel = [&](int disc, double x, double y) {
        return Vec2(discX(disc) + (x + 1) * n / 2, margin + (1 - y) * n / 2);
    };
    const Vec3 grey(0.75, 0.75, 0.75), red(0.95, 0.1, 0.1), white(1, 1, 1), black(0, 0, 0);
    for (int disc = 0; disc < 2; ++disc) {
        const Vec2 c = toPixel(disc, 0, 0);
        for (double th : {30.0, 60.0}) ring(c.x, c.y, std::sin(th * Pi / 180) * n / 2, 1, grey);
        ring(c.x, c.y, n / 2.0, 1.5, black);  // the horizon
    }
    for (const ProbeMap::Mark &l : map.lobes) {
        const Vec2 p = toPixel(l.disc, l.x, l.y);
        // 4 px for an efficiency of 1e-6 or less, 11 px for 1.
        const double rad = 4 + 7 * Clamp(1 + std::log10(std::max(l.efficiency, 1e-12)) / 6, 0.0, 1.0);
        ring(p.x, p.y, rad + 1.5, 1.5, white);
        ring(p.x, p.y, rad, 2.5, red);
    }
    {
        const Vec2 p = toPixel(0, map.sourceX, map.sourceY);
        for (int k = -7; k <= 7; ++k)
            for (int t = -1; t <= 1; ++t) {
                const Vec3 c = t == 0 ? white : black;
                blend(int(p.x) + k, int(p.y) + k + t, c, 1);
                blend(int(p.x) + k, int(p.y) - k + t, c, 1);
            }
    }
    std::vector<uint8_t> bytes(rgb.size());
    for (std::size_t k = 0; k < rgb.size(); ++k) bytes[k] = uint8_t(std::lround(Clamp(rgb[k], 0.0, 1.0) * 255));
    std::vector<ColourBarTick> ticks;
    for (double db = 0; db <= RangeDb; db += 10) ticks.push_back({1 - db / RangeDb, Num(-db, 3) + " dB"});
    // (The bar title is the only text this raster draws: short enough for the image's width.)
    const std::string scale = peak > 0 ? "Eval*cos(theta_o) in dB, 0 dB = " + Num(peak, 4) + "/sr"
                                       : "no continuous lobe";
    const std::string barTitle = "reflection | transmission: " + scale + "; o: lobes, x: source";
    return WriteImageWithColourBarPng(files, path, bytes, w, h, ViridisDisplay, ticks, barTitle,
                                      map.title + "; " + barTitle);
}

// The scene's named materials, for messages.
std::vector<std::string> MaterialNames(const SceneDesc &desc) {
    std::vector<std::string> names;
    for (const SceneEntity &e : desc.entities)
        if (e.keyword == "Material" && !e.name.empty()) names.push_back(e.name);
    std::sort(names.begin(), names.end());
    return names;
}

}  // namespace

int RunProbe(const CliOptions &o) {
    const CliOptions::ProbeOptions &p = o.probe;
    const bool colour = isatty(2) && !std::getenv("NO_COLOR");
    try {
        // The quantities first: a typo there needs no scene.
        const double theta = ParseQuantity("--theta", p.theta, Dim::Angle(), "30deg");
        const double phi = p.phi.empty() ? 0.0 : ParseQuantity("--phi", p.phi, Dim::Angle(), "45deg");
        const double lambda = ParseQuantity("--lambda", p.lambda, Dim::Length(), "550nm");
        if (theta < 0 || theta > Pi)
            throw ProbeError{"'--theta' must lie in [0deg, 180deg] (from the normal; above 90deg the light comes "
                             "from below); got '" + p.theta + "'"};
        if (std::abs(std::cos(theta)) < 1e-6)
            throw ProbeError{"'--theta' " + p.theta + " is grazing (the light runs along the surface): no "
                             "kernel scatters it; use an angle below or above 90deg"};
        if (!(lambda > 0)) throw ProbeError{"'--lambda' must be positive; got '" + p.lambda + "'"};
        if (!p.plot.empty()) {
            const std::string ext = p.plot.size() >= 4 ? p.plot.substr(p.plot.size() - 4) : "";
            if (ext != ".png" && ext != ".PNG") throw ProbeError{"'--plot' writes a PNG; name it FILE.png, not '" + p.plot + "'"};
        }

        // The scene: parsed and resolved whole, but only the material (and what it refers to) is built,
        // so a scene without lights or a detector (a material library) can be probed.
        Diagnostics diag(o.strict);
        diag.SetPermissive(o.permissive);
        ParseOptions parse;
        parse.defines = o.defines;
        std::optional<SceneDesc> desc = ParseSceneFile(o.scene, parse, diag);
        std::shared_ptr<Material> material;
        std::string type;
        const std::string name = !p.material.empty() && p.material[0] == '@' ? p.material.substr(1) : p.material;
        if (desc && !diag.HasErrors()) {
            const SceneEntity *entity = nullptr;
            for (const SceneEntity &e : desc->entities)
                if (e.name == name) entity = &e;
            if (!entity || entity->keyword != "Material") {
                const std::vector<std::string> names = MaterialNames(*desc);
                const std::string sug = Suggest(name, names);
                std::string msg = entity ? "'" + name + "' in '" + o.scene + "' is a " + entity->keyword +
                                               ", not a Material"
                                         : "no material named '" + name + "' in '" + o.scene + "'";
                if (!sug.empty()) msg += "; did you mean '" + sug + "'?";
                else if (names.empty()) msg += " (it defines no named material)";
                throw ProbeError{msg};
            }
            type = entity->type;
            BuildContext ctx(*desc, diag);
            ParamDict ref;
            ref.Set("material", Value::Ref(name, FileLoc{"<command line>", 0, 0, 1}));
            try {
                material = ctx.GetRef<Material>(ref, "material");
            } catch (const Error &e) {
                diag.Report(e);
            }
        }
        diag.Print(std::cerr, colour);
        if (!material || diag.HasErrors()) {
            if (diag.HasErrors())
                std::cerr << diag.ErrorCount() << " error" << (diag.ErrorCount() == 1 ? "" : "s") << " in '"
                          << o.scene << "'\n";
            return 1;
        }
        if (material->IsFootprintAware())
            throw ProbeError{"material '" + name + "' (" + type + ") is footprint-aware: its response depends on the "
                             "incident generalized ray's footprint on the shape it lies on (theory §9), which a "
                             "plane-wave probe does not have; render a scene with it instead (docs/aperture.md)"};

        // The query: the plane z = 0, first tangent +x (see the file comment).
        SampledWavelengths wl;
        wl.lambda[0] = lambda;
        wl.pdf[0] = 1;
        wl.delta = true;
        ScatterQuery q;
        q.wi = Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
        q.wl = &wl;
        q.etaOutside = 1;
        q.rayOptics = p.rayOptics;
        const Vec2 uv(p.u, p.v);
        q.tex.uv = uv;
        q.tex.p = Vec3(uv.x, uv.y, 0);
        q.tex.dpdu = Vec3(1, 0, 0);
        q.tex.dpdv = Vec3(0, 1, 0);
        q.tex.n = Vec3(0, 0, 1);
        const uint64_t seed = o.seed >= 0 ? uint64_t(o.seed) : 0;
        const ProbeResult result = Measure(*material, q, p.samples, seed);

        const std::string report = ReportText(name, type, o, theta, phi, lambda, uv, seed, result);
        const std::string csv = CsvText(result);
        const bool csvToStdout = p.csv == "-";
        OutputFiles files;
        if (!p.csv.empty() && !csvToStdout) {
            MakeParentDirectory(p.csv);
            files.Stage(p.csv, csv);
        }
        if (!p.plot.empty()) {
            ProbeMap map = MakeMap(*material, q, result, 300);
            map.title = "phasor probe " + name + " (" + type + "), theta = " + DegText(theta) + " deg, phi = " +
                        DegText(phi) + " deg, lambda = " + Num(lambda * 1e9, 6) + " nm";
            MakeParentDirectory(p.plot);
            const PlotResult r = WriteProbePlot(files, p.plot, map);
            if (!r.textDrawn) std::cerr << "warning: " << r.textProblem << "; the plot has no text\n";
        }
        files.Commit();
        (csvToStdout ? std::cerr : std::cout) << report;
        if (csvToStdout) std::cout << csv;
        if (!o.quiet) {
            if (!p.csv.empty() && !csvToStdout) std::cerr << "wrote " << p.csv << "\n";
            if (!p.plot.empty()) std::cerr << "wrote " << p.plot << "\n";
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
