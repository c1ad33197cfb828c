// SPDX-License-Identifier: Apache-2.0
// The accuracy map (issue 20 §3; docs/accuracy.md): every wave-optical approximation `grt` and
// `sample_solve` make, swept over a grid of its parameters against an independent reference, each
// cell with its tolerance. Shared by the ctest (tests/accuracy/accuracy_map_test.cpp, a grid small
// enough for `make test`) and the larger grid of bench/accuracy_map_bench.cpp.
//
// Families and their references (all written here or in tests/support, none shared with src/):
//   * films    a flat film (free-standing or on glass) under a `distant` disc, Gaussian or plane wave,
//              read by a one-pixel sensor in its reflected or transmitted beam
//              (scenes/validation/film_source.wscene) — vs the transfer matrix of tests/support/tmm.h
//              averaged over the source's profile (R; T·cosθ_i/cosθ_t in a refracted beam);
//   * stacks   a 10-pair chitin reflector (a beetle) the same way;
//   * gratings a sinusoidal grating's orders under a plane wave and a disc — vs the thin-phase
//              efficiency J_j(k·h·cosθ)²·F/Σ_prop J² (D6) and the grating equation, with the
//              order's irradiance transfer cosθ_i/cosθ_j;
//   * beams    a Gaussian beam on a sensor plane (Σ pixels·pitch² = P) and reflected by a thick film
//              (Σ = P·∫R|A|²d²k, the beam's spectrum |A|² of variance 1/(k·w0)² per axis);
//   * apertures `grt` against `rs` (docs/rs.md) on the validation scenes, in the cells that pass
//              today (the table ApertureCases; the fine pixels of issue 20 §1 are being fixed
//              separately: add their cells there when they pass).
// A cell's error is relative to its reference (films, stacks, gratings, beams) or to the row's
// peak (apertures); it fails beyond its tolerance.
#pragma once

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "core/render/lobe_average.h"
#include "support/tmm.h"
#include "validation/render_row.h"

namespace phasor::test {

struct AccuracyCell {
    std::string family, row, column, integrator;
    double value = 0, reference = 0, error = 0, tolerance = 0;
    bool Passes() const { return error <= tolerance; }
};

struct AccuracyMap {
    std::vector<AccuracyCell> cells;
    void Add(AccuracyCell c) { cells.push_back(std::move(c)); }
    int Failures() const {
        int n = 0;
        for (const AccuracyCell &c : cells) n += !c.Passes();
        return n;
    }
    /// family,row,column,integrator,value,reference,error,tolerance — the input of phasor_plot.py's
    /// accuracy-map command.
    void WriteCsv(const std::string &path) const {
        std::ofstream f(path);
        f << "family,row,column,integrator,value,reference,error,tolerance\n";
        for (const AccuracyCell &c : cells) {
            char line[512];
            std::snprintf(line, sizeof line, "%s,%s,%s,%s,%.9g,%.9g,%.6g,%.6g\n", c.family.c_str(), c.row.c_str(),
                          c.column.c_str(), c.integrator.c_str(), c.value, c.reference, c.error, c.tolerance);
            f << line;
        }
    }
};

/// Draws the map's CSV as a heat map PNG with python/phasor_plot.py (accuracy-map): 0 drawn, 3 no
/// matplotlib, other: the module's failure.
inline int DrawAccuracyMap(const std::string &csv, const std::string &png, const std::string &title) {
    const std::string cmd = "/usr/bin/python3 -B " + std::string(PHASOR_SOURCE_DIR) +
                            "/python/phasor_plot.py accuracy-map --data '" + csv + "' --out '" + png + "' --title '" +
                            title + "'";
    const int rc = std::system(cmd.c_str());
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

inline std::string Fmt(const char *f, double a) {
    char b[64];
    std::snprintf(b, sizeof b, f, a);
    return b;
}

// ---- films -------------------------------------------------------------------------------------------

/// One film cell: scenes/validation/film_source.wscene's Defines.
struct FilmCase {
    double thickness = 10e-6, thetaDeg = 45, radiusDeg = 2;
    std::string source = "disc";  // disc | gaussian | plane_wave
    double nSub = 1;               // 1: free-standing; 1.5: on glass
    bool transmission = false;
    double sigma = 2e-6;           // the pixel's σ
    double acceptanceDeg = 20;     // the sensor's acceptance (90 for pixels of σ ≲ λ, whose spectrum is wide)
    double lambda = 600e-9, nFilm = 1.33;

    DefineList Defines() const {
        return {{"source", "\"" + source + "\""},
                {"side", transmission ? "\"transmission\"" : "\"reflection\""},
                {"lambda", Fmt("%.6g nm", lambda * 1e9)},
                {"theta", Fmt("%.9g deg", thetaDeg)},
                {"radius", Fmt("%.9g deg", radiusDeg)},
                {"thickness", Fmt("%.9g nm", thickness * 1e9)},
                {"film_ior", Fmt("%.9g", nFilm)},
                {"n_sub", Fmt("%.9g", nSub)},
                {"sigma", Fmt("%.9g nm", sigma * 1e9)},
                {"acceptance", Fmt("%.9g deg", acceptanceDeg)}};
    }
    /// The sensor's reading per plane wave: R, or T·cosθ_i/cosθ_t in the substrate.
    double PerWave(const Vec3 &toLight) const {
        const double s = std::min(1.0, std::hypot(toLight.x, toLight.y));
        const TmmRT rt = Tmm(lambda, 1.0, s, {{Cplx(nFilm, 0), thickness}}, Cplx(nSub, 0));
        if (!transmission) return rt.R();
        return rt.T() * std::sqrt(1 - s * s) / std::sqrt(1 - Sqr(s / nSub));
    }
    /// The reference: PerWave averaged over the source's profile (its irradiance measure), by polar
    /// quadrature sized for the film's fringes (4 harmonics of the round-trip phase).
    double Reference() const {
        const double theta = Radians(thetaDeg), alpha = Radians(radiusDeg);
        const Vec3 axis(std::sin(theta), 0, std::cos(theta));
        if (source == "plane_wave") return PerWave(axis);
        const bool gaussian = source == "gaussian";
        const double reach = gaussian ? 3.5 * alpha : alpha;
        auto phase = [&](double sn) { return 2 * (2 * Pi / lambda) * thickness * std::sqrt(nFilm * nFilm - sn * sn); };
        const PolarResolution res = PolarResolution::For(
            4 * std::abs(phase(std::sin(std::max(0.0, theta - reach))) - phase(std::sin(std::min(1.5, theta + reach)))) + 8);
        auto f = [&](const Vec3 &w) { return PerWave(w); };
        return gaussian ? GaussianAverage(axis, alpha * alpha / 4, f, res.panels, res.angles)
                        : DiscAverage(axis, std::sin(alpha), f, res.panels, res.angles);
    }
    /// The scale below which an error is not taken relative to the reference: sup PerWave over the
    /// film's fringe — the largest value over the source's directions in the plane of incidence (±2
    /// radii) and over one fringe of thickness at the central direction. lobe_average.h's rules
    /// meet LobeAverageTolerance = 1e-4 of that sup per axis (an average: 3e-4): at a dark fringe
    /// (R ≈ 1e-10 for 30 µm at normal incidence) 1 % of the reference is below any stated bound.
    double FringePeak() const {
        const double theta = Radians(thetaDeg), reach = 2 * Radians(source == "plane_wave" ? 0 : radiusDeg);
        double m = 0;
        for (int i = 0; i <= 400; ++i) {
            const double t = theta - reach + 2 * reach * i / 400;
            m = std::max(m, PerWave(Vec3(std::sin(t), 0, std::cos(t))));
        }
        const Vec3 axis(std::sin(theta), 0, std::cos(theta));
        const double cosF = std::sqrt(1 - Sqr(std::sin(theta) / nFilm)), period = lambda / (2 * nFilm * cosF);
        FilmCase c = *this;
        for (int i = 0; i <= 200; ++i) {
            c.thickness = thickness + period * i / 200;
            m = std::max(m, c.PerWave(axis));
        }
        return m;
    }
    std::string Row() const { return Fmt("d %g um", thickness * 1e6) + Fmt(" / %g deg", thetaDeg); }
    std::string Column() const {
        return source + (source == "plane_wave" ? "" : Fmt(" %g deg", radiusDeg)) + (nSub == 1 ? " free" : " glass") +
               (transmission ? " T" : " R") + (sigma != 2e-6 ? Fmt(" px %g um", sigma * 1e6) : "");
    }
};

/// The one pixel of a render of film_source.wscene (closed forms: one sample is the exact value).
inline double RenderFilm(const FilmCase &c, const std::string &integrator) {
    auto scene = BuildValidation(ValidationScene("film_source.wscene"), c.Defines(), integrator);
    if (!scene) return -1;
    const Image img = RenderImage(*scene, 1);
    return img.At(0, 0, img.ChannelIndex("intensity"));
}

/// The film's error: a cell passes when |value − reference| is within `tolerance` of the reference
/// or within LobeAverageTolerance = 1e-4 of the fringe's peak (a third of lobe_average.h's bound; at a
/// dark fringe, R ≈ 1e-10 for 30 µm at normal incidence, 1 % of R is 1e-12: no bound resolves it).
inline void AddFilmCells(AccuracyMap &map, const std::vector<FilmCase> &cases, const std::vector<std::string> &integrators,
                         double tolerance, const std::string &family = "films") {
    for (const FilmCase &c : cases) {
        const double ref = c.Reference(), scale = std::max(ref, LobeAverageTolerance / tolerance * c.FringePeak());
        for (const std::string &integrator : integrators) {
            const double v = RenderFilm(c, integrator);
            map.Add({family, c.Row(), c.Column(), integrator, v, ref, std::abs(v - ref) / scale, tolerance});
        }
    }
}

/// The film grid of issue 20's acceptance: thicknesses × incidences × sources × radii × substrates ×
/// sides (plane waves once per thickness, incidence, substrate and side).
inline std::vector<FilmCase> FilmGrid(const std::vector<double> &thicknesses, const std::vector<double> &angles,
                                      const std::vector<double> &radii) {
    std::vector<FilmCase> out;
    for (double d : thicknesses)
        for (double theta : angles)
            for (double nSub : {1.0, 1.5})
                for (bool t : {false, true}) {
                    FilmCase c;
                    c.thickness = d;
                    c.thetaDeg = theta;
                    c.nSub = nSub;
                    c.transmission = t;
                    c.source = "plane_wave";
                    out.push_back(c);
                    for (const char *source : {"disc", "gaussian"})
                        for (double r : radii) {
                            c.source = source;
                            c.radiusDeg = r;
                            out.push_back(c);
                        }
                }
    return out;
}

// ---- stacks ------------------------------------------------------------------------------------------

/// A leaf beetle's reflector (film_source.wscene with coating = "stack"): 10 pairs of 1.55/1.70
/// (85/78 nm) on a 1.56 base, in reflection.
struct StackCase {
    double lambda = 530e-9, thetaDeg = 30, radiusDeg = 5;
    std::string source = "disc";
    DefineList Defines() const {
        return {{"coating", "\"stack\""},          {"source", "\"" + source + "\""},
                {"lambda", Fmt("%.6g nm", lambda * 1e9)}, {"theta", Fmt("%.9g deg", thetaDeg)},
                {"radius", Fmt("%.9g deg", radiusDeg)},   {"n_sub", "1.56"}};
    }
    double Reference() const {
        std::vector<TmmLayer> layers;
        for (int k = 0; k < 10; ++k) {
            layers.push_back({1.55, 85e-9});
            layers.push_back({1.70, 78e-9});
        }
        const double theta = Radians(thetaDeg), alpha = Radians(radiusDeg);
        const Vec3 axis(std::sin(theta), 0, std::cos(theta));
        auto f = [&](const Vec3 &w) { return Tmm(lambda, 1.0, std::min(1.0, std::hypot(w.x, w.y)), layers, 1.56).R(); };
        if (source == "plane_wave") return f(axis);
        return source == "gaussian" ? GaussianAverage(axis, alpha * alpha / 4, f, 16, 192)
                                    : DiscAverage(axis, std::sin(alpha), f, 16, 192);
    }
};

inline void AddStackCells(AccuracyMap &map, const std::vector<StackCase> &cases, const std::vector<std::string> &integrators,
                          double tolerance) {
    for (const StackCase &c : cases) {
        const double ref = c.Reference();
        for (const std::string &integrator : integrators) {
            auto scene = BuildValidation(ValidationScene("film_source.wscene"), c.Defines(), integrator);
            if (!scene) continue;
            const Image img = RenderImage(*scene, 1);
            const double v = img.At(0, 0, img.ChannelIndex("intensity"));
            map.Add({"stacks", Fmt("%g nm", c.lambda * 1e9) + Fmt(" / %g deg", c.thetaDeg),
                     c.source + (c.source == "plane_wave" ? "" : Fmt(" %g deg", c.radiusDeg)), integrator, v, ref,
                     std::abs(v - ref) / ref, tolerance});
        }
    }
}

// ---- gratings ----------------------------------------------------------------------------------------

/// One order of scenes/validation/grating_order.wscene.
struct GratingCase {
    double heightOverLambda = 0.1, thetaDeg = 20, radiusDeg = 2;
    int order = 1;
    std::string source = "plane_wave";
    double lambda = 550e-9, period = 2e-6;
    Cplx metal = Cplx(0.4, 3.0);
    int maxOrder = 10;

    bool Propagates() const { return std::abs(std::sin(Radians(thetaDeg)) + order * lambda / period) < 0.97; }
    DefineList Defines() const {
        return {{"source", "\"" + source + "\""}, {"lambda", Fmt("%.6g nm", lambda * 1e9)},
                {"theta", Fmt("%.9g deg", thetaDeg)}, {"radius", Fmt("%.9g deg", radiusDeg)},
                {"period", Fmt("%.9g nm", period * 1e9)}, {"height", Fmt("%.9g nm", heightOverLambda * lambda * 1e9)},
                {"order", std::to_string(order)}};
    }
    /// The thin-phase efficiency of the order for light arriving from `toLight` (D6), times the
    /// irradiance transfer cosθ_i/cosθ_j; 0 where the order is evanescent.
    double PerWave(const Vec3 &toLight) const {
        const double cosI = toLight.z, k = 2 * Pi / lambda, shift = lambda / period;
        const Vec2 t(-toLight.x, -toLight.y);  // tangential direction of travel
        auto cosOut = [&](int j) {
            const double sx = t.x + j * shift, s2 = sx * sx + t.y * t.y;
            return s2 < 1 ? std::sqrt(1 - s2) : -1.0;
        };
        const double m = k * heightOverLambda * lambda * cosI;
        double sum = 0;
        for (int j = -maxOrder; j <= maxOrder; ++j)
            if (cosOut(j) > 0) sum += Sqr(std::cyl_bessel_j(std::abs(j), m));
        const double cj = cosOut(order);
        if (!(cj > 0) || !(sum > 0)) return 0;
        const double F = Tmm(lambda, 1.0, std::hypot(toLight.x, toLight.y), {}, metal).R();
        return Sqr(std::cyl_bessel_j(std::abs(order), m)) * F / sum * cosI / cj;
    }
    double Reference() const {
        // The light travels towards +x and down: it arrives from (−sinθ, 0, cosθ).
        const double theta = Radians(thetaDeg), alpha = Radians(radiusDeg);
        const Vec3 axis(-std::sin(theta), 0, std::cos(theta));
        if (source == "plane_wave") return PerWave(axis);
        // The order's cut-off may cross the disc (a kink): a dense grid.
        return DiscAverage(axis, std::sin(alpha), [&](const Vec3 &w) { return PerWave(w); }, 64, 512);
    }
};

inline void AddGratingCells(AccuracyMap &map, const std::vector<GratingCase> &cases,
                            const std::vector<std::string> &integrators, double tolerance) {
    for (const GratingCase &c : cases) {
        if (!c.Propagates()) continue;
        const double ref = c.Reference();
        for (const std::string &integrator : integrators) {
            auto scene = BuildValidation(ValidationScene("grating_order.wscene"), c.Defines(), integrator);
            if (!scene) continue;
            const Image img = RenderImage(*scene, 1);
            const double v = img.At(0, 0, img.ChannelIndex("intensity"));
            map.Add({"gratings", Fmt("h/lambda %g", c.heightOverLambda) + Fmt(" / %g deg", c.thetaDeg),
                     Fmt("order %+g ", c.order) + c.source + (c.source == "plane_wave" ? "" : Fmt(" %g deg", c.radiusDeg)),
                     integrator, v, ref, std::abs(v - ref) / ref, tolerance});
        }
    }
}

// ---- beams -------------------------------------------------------------------------------------------

/// scenes/validation/film_beam.wscene: the power a sensor plane collects from a Gaussian beam
/// reflected by (or through) a film, Σ pixels·pitch² [W] for P = 1 W, against ∫R|A|²d²k.
struct BeamCase {
    double thickness = 20e-6, thetaDeg = 45, waistBefore = 0, w0 = 20e-6, lambda = 632.8e-9, nSub = 1;
    bool transmission = false;
    int pixels = 41;
    double pitch = 4e-6;
    DefineList Defines() const {
        return {{"thickness", Fmt("%.9g nm", thickness * 1e9)},
                {"theta", Fmt("%.9g deg", thetaDeg)},
                {"waist_before", Fmt("%.9g um", waistBefore * 1e6)},
                {"w0", Fmt("%.9g nm", w0 * 1e9)},
                {"side", transmission ? "\"transmission\"" : "\"reflection\""},
                {"pixels", std::to_string(pixels)},
                {"pitch", Fmt("%.9g nm", pitch * 1e9)},
                {"n_sub", Fmt("%.9g", nSub)}};
    }
    /// R (or T) averaged over the beam's angular spectrum: per axis a Gaussian of variance 1/(k·w0)²
    /// in the direction cosines about its axis.
    double Reference() const {
        const double theta = Radians(thetaDeg), k = 2 * Pi / lambda;
        const Vec3 axis(std::sin(theta), 0, std::cos(theta));
        return GaussianAverage(
            axis, 1 / Sqr(k * w0),
            [&](const Vec3 &w) {
                const double sn = std::min(1.0, std::hypot(w.x, w.y));
                const TmmRT rt = Tmm(lambda, 1.0, sn, {{Cplx(1.33, 0), thickness}}, Cplx(nSub, 0));
                return transmission ? rt.T() * std::sqrt(1 - sn * sn) / std::sqrt(1 - Sqr(sn / nSub)) : rt.R();
            },
            96, 512);
    }
    /// The collected power from a render.
    double Collected(const std::string &integrator) const {
        auto scene = BuildValidation(ValidationScene("film_beam.wscene"), Defines(), integrator);
        if (!scene) return -1;
        const Image img = RenderImage(*scene, 1);
        const int c = img.ChannelIndex("intensity");
        double sum = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) sum += img.At(x, y, c);
        return sum * pitch * pitch;  // irradiance over 1 W/m² × pixel area [m²] = W
    }
};

// ---- apertures ----------------------------------------------------------------------------------------

/// grt against rs on a validation scene's row (MaxDiffOfPeak): the cells that pass today. Add a
/// case here to map it (the fine pixels behind apertures of issue 20 §1 belong here once fixed).
struct ApertureCase {
    std::string name, scene;
    DefineList defines;
    double tolerance = 2e-3;  // of the row's peak (docs/generalized_rays.md §8)
};
inline std::vector<ApertureCase> ApertureCases() {
    return {
        {"double slit d 100 um", "double_slit.wscene", {{"d", "100um"}}},
        {"double slit d 400 um tilt 3 deg", "double_slit.wscene", {{"d", "400um"}, {"tilt", "3deg"}, {"width", "2400um"}}},
        {"laser w0 40 um through a disc", "gaussian_beam_aperture.wscene", {{"w0", "40um"}}},
    };
}

inline void AddApertureCells(AccuracyMap &map, const std::vector<ApertureCase> &cases) {
    for (const ApertureCase &c : cases) {
        const Row grt = RenderRow(ValidationScene(c.scene), c.defines, "grt"), rs = RenderRow(ValidationScene(c.scene), c.defines, "rs");
        const double e = grt.v.empty() || rs.v.empty() ? 1.0 : MaxDiffOfPeak(grt, rs);
        map.Add({"apertures", c.name, "grt vs rs", "grt", grt.v.empty() ? 0 : grt.Peak(), rs.v.empty() ? 0 : rs.Peak(), e,
                 c.tolerance});
    }
}

}  // namespace phasor::test
