// SPDX-License-Identifier: Apache-2.0
// phasor — the outputs of `phasor compare` (compare_report.h), staged in named steps: each run's
// images, the grid, the differences, the profile and convergence plots, the tables (CSV,
// Markdown) and results.json, from which python/phasor_report.py renders index.html through a
// jinja2 template. Images go through the image module (EXR, the display PNG of `render`, sheets
// drawn by OpenImageIO), plots through matplotlib (app/plot.h).

#include "app/compare_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "app/plot.h"
#include "app/profile.h"
#include "app/render_common.h"
#include "app/text.h"
#include "core/diagnostics.h"
#include "core/image/image_io.h"
#include "core/image/sheet.h"

namespace phasor {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;
constexpr double NaN = std::numeric_limits<double>::quiet_NaN();

// A number for the CSV (full precision); "" when there is none.
std::string Num(double v, int digits) { return std::isfinite(v) ? FormatNumber(v, digits) : ""; }
// A number for people: 3 significant digits, "—" when there is none.
std::string Short(double v) { return std::isfinite(v) ? FormatNumber(v, 3) : "—"; }
// A number for JSON: null when there is none.
Json JsonNumber(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

// The smallest 1, 2 or 5 × 10^k not below x > 0.
double NiceCeil(double x) {
    const double e = std::pow(10.0, std::floor(std::log10(x)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * e >= x * (1 - 1e-12)) return m * e;
    return 10 * e;
}

std::string Dash(const std::string &s) { return s.empty() ? "—" : s; }
// How tables and the page name a run: the reference render as "grt (reference)", so that it is
// told apart from a compared run of the same integrator.
std::string Label(const CompareRun &r) { return r.isReferenceRun ? r.name + " (reference)" : r.name; }

long long Pixels(const CompareRun &r) { return r.image ? (long long)r.image->width * r.image->height : 0; }
bool Rendered(const CompareRun &r) {
    return r.status == CompareRun::Status::Done || r.status == CompareRun::Status::Interrupted;
}

const char *StatusName(CompareRun::Status s) {
    switch (s) {
        case CompareRun::Status::Done: return "ok";
        case CompareRun::Status::Interrupted: return "interrupted";
        case CompareRun::Status::Failed: return "failed";
        case CompareRun::Status::NotRun: return "not_run";
    }
    return "";
}

std::string StatusText(const CompareRun &r) {
    switch (r.status) {
        case CompareRun::Status::Failed: return "failed: " + r.error;
        case CompareRun::Status::NotRun: return "not run (stopped)";
        case CompareRun::Status::Interrupted: return "interrupted (stopped)";
        case CompareRun::Status::Done: return r.isReference ? "reference" : "ok";
    }
    return "";
}

double SamplesPerSecond(const CompareRun &r) {
    return !r.deterministic && r.image && r.seconds > 0 ? double(r.sppReached) * Pixels(r) / r.seconds : NaN;
}

// The last column: what the comparison with the reference says about the run, and its class on
// the page (consistent, differs, other).
std::pair<std::string, std::string> Verdict(const CompareRun &r, const CompareReference &ref) {
    if (r.isReference) return {"reference", "other"};
    if (!r.metrics) return {"", "other"};
    if (!r.comparable) {
        const bool refWave = ref.waveOptical.value_or(true);
        return {fmt::format("not comparable: {} optics against a {}-optical reference (the difference includes "
                            "what the other physics shows)",
                            r.waveOptical ? "wave" : "ray", refWave ? "wave" : "ray"),
                "other"};
    }
    if (!r.test || !r.test->tested) {
        const char *why = ref.variance.empty() ? "the reference has no noise estimate"
                          : r.deterministic    ? "no noise on either side"
                                               : "the run has no variance estimate (one sample)";
        return {fmt::format("not tested: {}", why), "other"};
    }
    if (r.test->consistent) return {fmt::format("consistent (z = {:.2f})", r.test->z), "consistent"};
    return {std::isfinite(r.test->z) ? fmt::format("differs (z = {:.3g})", r.test->z)
                                     : std::string("differs (noiseless and unequal)"),
            "differs"};
}

// The label of a run's tile: "grt — 4096 spp, 0.52 s".
std::string TileLabel(const CompareRun &r, const char *separator = "\n") {
    std::string s = Label(r) + (r.isReference && !r.isReferenceRun ? " (reference)" : "") + separator;
    s += r.deterministic ? std::string("deterministic, ") : std::to_string(r.sppReached) + " spp, ";
    return s + FormatSeconds(r.seconds) + (r.status == CompareRun::Status::Interrupted ? ", interrupted" : "");
}

void WarnNoText(const SheetResult &r, const std::string &path) {
    if (!r.textDrawn) fmt::print(stderr, "warning: {}; '{}' has no text\n", r.textProblem, path);
}

// What the page shows for one file: an image, or a link to the data drawn instead.
struct Shown {
    std::string file;  // relative to the output directory ("" = nothing)
    bool image = true;
};

// The output directory and the names staged so far.
struct Staging {
    OutputFiles &files;
    std::string dir;
    std::vector<std::string> written;
    std::string Path(const std::string &name) const { return (fs::path(dir) / name).string(); }
    void Add(const std::string &name) { written.push_back(name); }
};

// What every step shares: the runs, the reference, the report and how images are shown.
struct Context {
    std::vector<CompareRun> &runs;
    const CompareReference &ref;
    const Image *refImage;
    const CompareReport &rep;
    std::string sceneName;
    double zeroDb;  // one dB scale for every sensor image: 0 dB = the reference's peak
};

Rgb8Image Tone(const Context &c, const Image &img) {
    if (c.rep.radiometric) return ToFalseColourDb(img, "intensity", 40, c.zeroDb);
    DisplayOptions display;
    display.exposure = c.rep.exposureStops;
    return ToDisplay(img, display);
}

// ---- 1. Each run's EXR and the PNG `render` would write (one dB scale, one exposure) -------------
struct RunImages {
    std::vector<Shown> runs;
    Shown reference;  // a given reference image
};
RunImages StageRunImages(Staging &st, const Context &c) {
    RunImages out;
    out.runs.resize(c.runs.size());
    auto stage = [&](const Image &img, const std::string &png, const std::string &label) {
        const std::string staged = StageDisplayPng(st.files, st.Path(png), img, c.rep.radiometric, label,
                                                   c.sceneName + ": " + label, c.zeroDb, c.rep.exposureStops);
        const Shown s{fs::path(staged).filename().string(), fs::path(staged).extension() == ".png"};
        st.Add(s.file);
        return s;
    };
    for (std::size_t k = 0; k < c.runs.size(); ++k) {
        const CompareRun &r = c.runs[k];
        if (!r.image) continue;
        WriteExr(st.files, st.Path(r.file + ".exr"), *r.image);
        st.Add(r.file + ".exr");
        out.runs[k] = stage(*r.image, r.file + ".png", Label(r));
    }
    if (c.refImage) out.reference = stage(*c.refImage, "reference.png", "reference");
    return out;
}

// ---- 2. The grid: the reference image (if given), then every run, labelled ---------------------
void StageGrid(Staging &st, const Context &c) {
    std::vector<SheetTile> tiles;
    if (c.refImage) tiles.push_back({Tone(c, *c.refImage), "reference\n" + c.ref.description});
    for (const CompareRun &r : c.runs)
        if (r.image) tiles.push_back({Tone(c, *r.image), TileLabel(r)});
    ColourBar dbBar = DecibelBar(40, "intensity, 0 dB = " + Short(c.zeroDb));
    WarnNoText(StageSheetPng(st.files, st.Path("grid.png"), tiles, c.rep.radiometric ? &dbBar : nullptr,
                             "phasor compare: " + c.sceneName),
               st.Path("grid.png"));
    st.Add("grid.png");
}

// ---- 3. Signed differences (I − R) / max(R), one symmetric scale for all -------------------------
// The scale: the largest 99.5th percentile of |I − R| / max(R) over the runs, rounded up to 1, 2 or
// 5 × 10^k.
struct Differences {
    std::vector<Shown> runs;
    double limit = 0;
};
Differences StageDifferences(Staging &st, const Context &c) {
    Differences out;
    out.runs.resize(c.runs.size());
    const double norm = c.ref.peak > 0 ? c.ref.peak : 1;
    std::vector<std::vector<double>> diffs(c.runs.size());
    for (std::size_t k = 0; k < c.runs.size(); ++k) {
        const CompareRun &r = c.runs[k];
        if (!r.image || r.isReference || c.ref.values.empty()) continue;
        std::vector<double> abs;
        for (std::size_t i = 0; i < r.intensity.size(); ++i) {
            const double d = (r.intensity[i] - c.ref.values[i]) / norm;
            diffs[k].push_back(std::isfinite(d) ? d : NaN);
            if (std::isfinite(d)) abs.push_back(std::abs(d));
        }
        if (abs.empty()) continue;
        const std::size_t at = std::min(abs.size() - 1, std::size_t(std::ceil(0.995 * double(abs.size() - 1))));
        std::nth_element(abs.begin(), abs.begin() + std::ptrdiff_t(at), abs.end());
        out.limit = std::max(out.limit, abs[at]);
    }
    out.limit = out.limit > 0 ? NiceCeil(out.limit) : 1e-6;
    ColourBar bar;
    bar.map = ColourMap::Diverging;
    bar.title = c.ref.peak > 0 ? "(I - R) / max(R)" : "I - R";
    for (double f : {-1.0, -0.5, 0.0, 0.5, 1.0})
        bar.ticks.push_back({(f + 1) / 2, f == 0 ? std::string("0") : fmt::format("{:+.3g}", f * out.limit)});
    for (std::size_t k = 0; k < c.runs.size(); ++k) {
        if (diffs[k].empty()) continue;
        const CompareRun &r = c.runs[k];
        const std::string name = "diff_" + r.file + ".png";
        const Rgb8Image img =
            MapColours(diffs[k], r.image->width, r.image->height, ColourMap::Diverging, -out.limit, out.limit);
        WarnNoText(StageSheetPng(st.files, st.Path(name), {SheetTile{img, r.name + " - reference"}}, &bar,
                                 "(" + r.name + " - reference) / max(reference), clipped at +-" + Num(out.limit, 3)),
                   st.Path(name));
        out.runs[k] = {name, true};
        st.Add(name);
    }
    return out;
}

// ---- 4. A profile along a row or a column (a one-row image: its row) ---------------------------
// Every run with the reference last, so that two images give |run − reference| and the pixel bar
// sits on the reference.
Shown StageProfile(Staging &st, const Context &c, int row) {
    const CompareReport &rep = c.rep;
    if (row < 0 && rep.column < 0) return {};
    if (row >= rep.height || rep.column >= rep.width)
        throw Error(row >= 0 ? fmt::format("--row {} is out of range (the image has {} rows)", row, rep.height)
                             : fmt::format("--column {} is out of range (the image has {} columns)", rep.column,
                                           rep.width));
    CliOptions po;
    po.quiet = true;
    auto &p = po.profile;
    std::vector<const Image *> images;
    for (int referenceLast = 0; referenceLast < 2; ++referenceLast)
        for (const CompareRun &r : c.runs)
            if (r.image && r.isReference == bool(referenceLast)) {
                p.inputs.push_back(st.Path(r.file + ".exr"));
                p.labels.push_back(Label(r));
                images.push_back(&*r.image);
            }
    if (c.refImage) {
        p.inputs.push_back(st.Path("reference.exr"));
        p.labels.push_back("reference");
        images.push_back(c.refImage);
    }
    p.row = row;
    p.column = rep.column;
    p.csv = st.Path("profile.csv");
    p.plot = st.Path("profile.png");
    p.title = c.sceneName + ": intensity, " +
              (row >= 0 ? "row " + std::to_string(row) : "column " + std::to_string(rep.column));
    std::string data;
    if (RunProfile(po, images, &st.files, &data) != 0) throw Error("cannot draw the profile");
    st.Add("profile.csv");
    if (!data.empty()) return {"profile.csv", false};
    st.Add("profile.png");
    return {"profile.png", true};
}

// ---- 5. Convergence: each sampling run's error against the reference after 1, 3, 7, … spp -------
Shown StageConvergence(Staging &st, const Context &c) {
    if (c.ref.values.empty()) return {};  // no reference, no errors
    std::string csv = "run,spp,seconds,rmse,rel_mse,max_error\n";
    int curves = 0;
    for (const CompareRun &r : c.runs) {
        if (r.deterministic || r.isReference || r.snapshots.size() < 2) continue;
        ++curves;
        for (const CompareSnapshot &s : r.snapshots) {
            const CompareMetrics m = s.metrics.value_or(CompareMetrics{});
            csv += fmt::format("{},{},{},{},{},{}\n", CsvField(r.name), s.spp, Num(s.seconds, 6), Num(m.rmse, 6),
                               Num(m.relMse, 6), Num(m.maxError, 6));
        }
    }
    if (curves == 0) return {};
    st.files.Stage(st.Path("convergence.csv"), csv);
    st.Add("convergence.csv");
    PlotRequest plot;
    plot.command = "convergence";
    plot.data = csv;
    plot.args = {"--title", c.sceneName + ": error of intensity against the reference (" + c.ref.name + ")"};
    if (!StagePlot(st.files, st.Path("convergence.png"), plot)) return {"convergence.csv", false};
    st.Add("convergence.png");
    return {"convergence.png", true};
}

// ---- 6. The tables: CSV (full precision) and Markdown ------------------------------------------
const char *MetricsNote =
    "Errors of the `intensity` channel against the reference, over the pixels: RMSE = √mean((I − R)²); "
    "relative MSE = mean((I − R)² / (R² + 0.01·mean(R)²)); max error = max |I − R| / max(R); RGB RMSE = "
    "√mean((I − R)²) over the R, G, B channels (the colour error of cameras). The last column tests whether the "
    "run and the reference can have the same expectation, given both images' noise (block χ², z > 3.09: "
    "differs; docs/compare.md).";

}  // namespace

std::string CompareCsv(const std::vector<CompareRun> &runs, const CompareReference &ref) {
    std::string csv =
        "integrator,role,status,spp,seconds,samples_per_second,rmse,rel_mse,max_error,rgb_rmse,noise_floor,"
        "comparable,chi2,dof,z,verdict,error\n";
    for (const CompareRun &r : runs) {
        const bool rendered = Rendered(r);
        const CompareMetrics m = r.metrics.value_or(CompareMetrics{});
        const bool tested = r.test && r.test->tested;
        csv += fmt::format(
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", CsvField(Label(r)),
            r.isReference ? "reference" : "compared", StatusName(r.status),
            rendered && !r.deterministic && r.image ? std::to_string(r.sppReached) : "",
            rendered ? Num(r.seconds, 4) : "", Num(SamplesPerSecond(r), 4), Num(m.rmse, 9), Num(m.relMse, 9),
            Num(m.maxError, 9), Num(m.rgbRmse, 9), r.isReference ? Num(ref.noiseFloor, 9) : "",
            r.metrics ? (r.comparable ? "true" : "false") : "", tested ? Num(r.test->chi2, 9) : "",
            tested ? std::to_string(r.test->dof) : "", tested ? Num(r.test->z, 6) : "",
            CsvField(Verdict(r, ref).first), CsvField(r.error));
    }
    return csv;
}

namespace {

std::string MarkdownTable(const Context &c) {
    const CompareReport &rep = c.rep;
    std::string md = fmt::format("# phasor compare: {}\n\n`{}`\n\n", c.sceneName, rep.command);
    md += fmt::format("- phasor {}\n- mode: {}\n- seed: {} (every compared run), sampler {}\n", rep.version,
                      rep.modeText, rep.seed, rep.sampler);
    std::string defines;
    for (const auto &[k, v] : rep.defines) defines += (defines.empty() ? "" : ", ") + fmt::format("`-D {}={}`", k, v);
    md += "- defines: " + (defines.empty() ? std::string("none (the scene's values)") : defines) + "\n";
    if (c.ref.kind == CompareReference::Kind::None) {
        md += "- reference: none — " + c.ref.description + "\n";
    } else {
        md += fmt::format("- reference: {}\n- independence: {}\n- reference noise floor: {} ({})\n", c.ref.description,
                          c.ref.independence, Short(c.ref.noiseFloor), c.ref.noiseSource);
        for (const std::string &w : c.ref.warnings) md += "- warning (reference): " + w + "\n";
    }
    if (!rep.stopped.empty())
        md += "\nThe comparison was stopped (" + rep.stopped + ") before every integrator had finished.\n";
    md += std::string("\n") + MetricsNote + "\n\n";
    md += "| integrator | status | spp | time (s) | samples/s | RMSE | relative MSE | max error | RGB RMSE | against the "
          "reference |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---|\n";
    auto cell = [](std::string s) {
        std::replace(s.begin(), s.end(), '|', '/');
        return s;
    };
    for (const CompareRun &r : c.runs) {
        const CompareMetrics m = r.metrics.value_or(CompareMetrics{});
        const std::string rmse = r.isReference ? Short(c.ref.noiseFloor) + " (noise floor)" : Short(m.rmse);
        md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", cell(Label(r)), cell(StatusText(r)),
                          Rendered(r) && !r.deterministic && r.image ? std::to_string(r.sppReached) : "—",
                          Rendered(r) ? Short(r.seconds) : "—", Short(SamplesPerSecond(r)), rmse, Short(m.relMse),
                          Short(m.maxError), Short(m.rgbRmse), cell(Dash(Verdict(r, c.ref).first)));
    }
    std::string warnings;
    for (const std::string &w : rep.sceneWarnings) warnings += "- scene: " + w + "\n";
    for (const CompareRun &r : c.runs)
        for (const std::string &w : r.warnings) warnings += "- " + Label(r) + ": " + w + "\n";
    md += "\n## Warnings\n\n" + (warnings.empty() ? std::string("None.\n") : warnings);
    return md;
}

// ---- 7. results.json and the page rendered from it ---------------------------------------------
struct Figures {
    RunImages images;
    Differences diffs;
    Shown profile, convergence;
    int profileRow = -1;
};

Json ResultsJson(const Context &c, const Figures &f) {
    const CompareReport &rep = c.rep;
    const CompareReference &ref = c.ref;
    Json j;
    j["format"] = "phasor-compare-results";
    j["format_version"] = 1;
    j["phasor_version"] = rep.version;
    j["command"] = rep.command;
    j["scene"] = rep.scene;
    j["scene_name"] = c.sceneName;
    j["mode"] = {{"kind", rep.modeKind},
                 {"text", rep.modeText},
                 {"spp", rep.modeKind == "spp" ? Json(rep.spp) : Json(nullptr)},
                 {"seconds", rep.modeKind == "time" ? Json(rep.seconds) : Json(nullptr)}};
    j["seed"] = rep.seed;
    j["sampler"] = rep.sampler;
    j["defines"] = Json::array();
    for (const auto &[k, v] : rep.defines) j["defines"].push_back({{"name", k}, {"value", v}});
    j["detector"] = {{"name", rep.detector},      {"width", rep.width},
                     {"height", rep.height},      {"radiometric", rep.radiometric},
                     {"exposure_stops", rep.exposureStops}, {"auto_exposure", rep.autoExposure}};
    j["reference"] = {{"kind", ref.kind == CompareReference::Kind::Image ? "image"
                               : ref.kind == CompareReference::Kind::Run ? "run"
                                                                         : "none"},
                      {"name", ref.name},
                      {"description", ref.description},
                      {"independence", ref.independence},
                      {"noise_floor", JsonNumber(ref.noiseFloor)},
                      {"noise_source", ref.noiseSource},
                      {"optics", ref.waveOptical ? Json(*ref.waveOptical ? "wave" : "ray") : Json(nullptr)},
                      {"warnings", ref.warnings}};
    j["metrics_note"] = [] {
        std::string note = MetricsNote;
        note.erase(std::remove(note.begin(), note.end(), '`'), note.end());
        return note;
    }();
    j["runs"] = Json::array();
    for (std::size_t k = 0; k < c.runs.size(); ++k) {
        const CompareRun &r = c.runs[k];
        const auto [verdict, verdictClass] = Verdict(r, ref);
        Json run = {{"name", Label(r)},
                    {"integrator", r.name},
                    {"role", r.isReference ? "reference" : "compared"},
                    {"status", StatusName(r.status)},
                    {"status_text", StatusText(r)},
                    {"error", r.error},
                    {"optics", r.waveOptical ? "wave" : "ray"},
                    {"deterministic", r.deterministic},
                    {"work", r.work},
                    {"spp", Rendered(r) && !r.deterministic && r.image ? Json(r.sppReached) : Json(nullptr)},
                    {"seeds", r.deterministic ? std::vector<unsigned long long>{} : r.seeds},
                    {"seconds", Rendered(r) ? JsonNumber(r.seconds) : Json(nullptr)},
                    {"samples_per_second", JsonNumber(SamplesPerSecond(r))},
                    {"tile_label", TileLabel(r, ": ")}};
        if (r.metrics)
            run["metrics"] = {{"rmse", JsonNumber(r.metrics->rmse)},
                              {"rel_mse", JsonNumber(r.metrics->relMse)},
                              {"max_error", JsonNumber(r.metrics->maxError)},
                              {"rgb_rmse", JsonNumber(r.metrics->rgbRmse)}};
        else
            run["metrics"] = nullptr;
        if (!verdict.empty()) {
            run["verdict"] = {{"text", verdict}, {"class", verdictClass}, {"comparable", r.comparable}};
            if (r.test && r.test->tested)
                run["verdict"].update({{"chi2", JsonNumber(r.test->chi2)},
                                       {"dof", r.test->dof},
                                       {"z", JsonNumber(r.test->z)},
                                       {"consistent", r.test->consistent}});
        } else {
            run["verdict"] = nullptr;
        }
        run["warnings"] = r.warnings;
        run["messages"] = r.messages;
        const Shown &png = f.images.runs[k];
        run["files"] = {{"exr", r.image ? Json(r.file + ".exr") : Json(nullptr)},
                        {"png", png.file.empty() ? Json(nullptr) : Json(png.file)},
                        {"png_is_image", png.image},
                        {"diff", f.diffs.runs[k].file.empty() ? Json(nullptr) : Json(f.diffs.runs[k].file)}};
        j["runs"].push_back(std::move(run));
    }
    j["scene_warnings"] = rep.sceneWarnings;
    // Small renders are shown enlarged by the grid's whole factor (a radiometric render's PNG
    // carries its colour bar, a one-row image is a line plot: both at their own size).
    Rgb8Image probe;
    probe.width = rep.width;
    probe.height = rep.height;
    const bool oneRow = rep.height == 1;
    auto shownJson = [](const Shown &s) {
        return s.file.empty() ? Json(nullptr) : Json{{"file", s.file}, {"image", s.image}};
    };
    j["figures"] = {
        {"grid", "grid.png"},
        {"grid_caption", rep.radiometric ? "intensity in dB, one scale for all (0 dB = the reference's peak, " +
                                               Short(c.zeroDb) + ")"
                                         : fmt::format("through the OpenColorIO display transform, one exposure for "
                                                       "all ({:.3g} stops)",
                                                       rep.exposureStops)},
        {"one_row", oneRow},
        {"display_width", oneRow || rep.radiometric ? 0 : rep.width * SheetScale({SheetTile{probe, ""}})},
        {"reference_png", shownJson(f.images.reference)},
        {"diff_limit", f.diffs.limit},
        {"profile", f.profile.file.empty()
                        ? Json(nullptr)
                        : Json{{"file", f.profile.file},
                               {"image", f.profile.image},
                               {"caption", f.profileRow >= 0 ? "row " + std::to_string(f.profileRow)
                                                             : "column " + std::to_string(rep.column)}}},
        {"convergence", shownJson(f.convergence)}};
    j["missing_plots"] = MatplotlibMissing();
    j["stopped"] = rep.stopped.empty() ? Json(nullptr) : Json(rep.stopped);
    return j;
}

// Plots not drawn (matplotlib missing): one warning naming their data files.
void WarnPlotsNotDrawn(const Figures &f) {
    std::vector<std::string> notDrawn;
    for (const Shown &x : f.images.runs)
        if (!x.file.empty() && !x.image) notDrawn.push_back(x.file);
    for (const Shown *x : {&f.images.reference, &f.profile, &f.convergence})
        if (!x->file.empty() && !x->image) notDrawn.push_back(x->file);
    if (!notDrawn.empty())
        fmt::print(stderr, "warning: {}; the plots are not drawn, their data is in {}\n", MatplotlibMissing(),
                   fmt::join(notDrawn, ", "));
}

}  // namespace

std::vector<std::string> StageCompareOutputs(OutputFiles &files, std::vector<CompareRun> &runs,
                                             const CompareReference &ref, const Image *refImage,
                                             const CompareReport &report) {
    Staging st{files, report.dir, {}};
    const Context c{runs, ref, refImage, report, fs::path(report.scene).filename().string(), ref.peak};
    Figures f;
    f.images = StageRunImages(st, c);
    StageGrid(st, c);
    f.diffs = StageDifferences(st, c);
    f.profileRow = report.column < 0 && report.row < 0 && report.height == 1 ? 0 : report.row;
    f.profile = StageProfile(st, c, f.profileRow);
    f.convergence = StageConvergence(st, c);
    WarnPlotsNotDrawn(f);

    files.Stage(st.Path("results.csv"), CompareCsv(c.runs, c.ref));
    files.Stage(st.Path("results.md"), MarkdownTable(c));
    const std::string json = ResultsJson(c, f).dump(2) + "\n";
    files.Stage(st.Path("results.json"), json);
    for (const char *name : {"results.csv", "results.md", "results.json"}) st.Add(name);

    PlotRequest page;
    page.module = "phasor_report.py";
    page.command = "compare";
    page.data = json;
    if (StagePlot(files, st.Path("index.html"), page))
        st.Add("index.html");
    else
        fmt::print(stderr, "warning: {}; index.html is not written (results.md and results.json are)\n",
                   ModuleMissing("phasor_report.py"));
    return st.written;
}

void PrintSummary(std::ostream &os, const std::vector<CompareRun> &runs, const CompareReference &ref) {
    os << fmt::format("{:<16} {:<12} {:>8} {:>9} {:>11} {:>11} {:>11}  {}\n", "integrator", "status", "spp",
                      "time", "RMSE", "max error", "RGB RMSE", "against the reference");
    for (const CompareRun &r : runs) {
        const CompareMetrics m = r.metrics.value_or(CompareMetrics{});
        std::string status = StatusName(r.status);
        if (r.isReference) status = "reference";
        os << fmt::format("{:<16} {:<12} {:>8} {:>9} {:>11} {:>11} {:>11}  {}\n", Label(r), status,
                          Rendered(r) && !r.deterministic && r.image ? std::to_string(r.sppReached) : "—",
                          Rendered(r) ? FormatSeconds(r.seconds) : "—",
                          r.isReference ? Short(ref.noiseFloor) + "*" : Short(m.rmse), Short(m.maxError),
                          Short(m.rgbRmse), Verdict(r, ref).first);
    }
    if (std::isfinite(ref.noiseFloor)) os << "* the reference's noise floor (" << ref.noiseSource << ")\n";
}

std::string FormatSeconds(double s) {
    if (!std::isfinite(s)) return "—";
    if (s < 60) return FormatNumber(s, 3) + " s";
    return fmt::format("{}m{:02d}s", int(s) / 60, int(s) % 60);
}

}  // namespace phasor
