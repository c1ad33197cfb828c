// SPDX-License-Identifier: Apache-2.0
// phasor — the results of `phasor compare` (compare_report.h): error metrics, the reference, and
// every output file. Images go through the image module (EXR, the display PNG of `render`, sheets
// drawn by OpenImageIO), plots through matplotlib (app/plot.h), the page is plain HTML with
// relative links (no script, no server).

#include "app/compare_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

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
constexpr double NaN = std::numeric_limits<double>::quiet_NaN();

// A number for the table; "" when there is none.
std::string Num(double v, int digits) { return std::isfinite(v) ? FormatNumber(v, digits) : ""; }
// A number for people: 3 significant digits, "—" when there is none.
std::string Short(double v) { return std::isfinite(v) ? Num(v, 3) : "—"; }

std::string Html(const std::string &s) {
    std::string out;
    for (char ch : s) {
        switch (ch) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += ch;
        }
    }
    return out;
}

// The smallest 1, 2 or 5 × 10^k not below x > 0.
double NiceCeil(double x) {
    const double e = std::pow(10.0, std::floor(std::log10(x)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * e >= x * (1 - 1e-12)) return m * e;
    return 10 * e;
}

bool Sampling(const CompareRun &r) { return !r.deterministic; }
long long Pixels(const CompareRun &r) { return r.image ? (long long)r.image->width * r.image->height : 0; }

// One row of the table, as text.
struct TableRow {
    std::string name, role, status, statusText, spp, seconds, rate, rmse, relMse, maxError, error;
};

TableRow RowOf(const CompareRun &r) {
    TableRow t;
    t.name = r.name;
    t.role = r.isReference ? "reference" : "compared";
    t.error = r.error;
    switch (r.status) {
        case CompareRun::Status::Done:
            t.status = "ok";
            break;
        case CompareRun::Status::Interrupted:
            t.status = "interrupted";
            break;
        case CompareRun::Status::Failed:
            t.status = "failed";
            break;
        case CompareRun::Status::NotRun:
            t.status = "not_run";
            break;
    }
    t.statusText = r.status == CompareRun::Status::Failed        ? "failed: " + r.error
                   : r.status == CompareRun::Status::NotRun      ? "not run (stopped)"
                   : r.status == CompareRun::Status::Interrupted ? "interrupted (Ctrl-C)"
                   : r.isReference                               ? "reference"
                                                                 : "ok";
    if (!r.warnings.empty() && r.status != CompareRun::Status::Failed) t.statusText += " — warning: " + r.warnings[0];
    if (r.status == CompareRun::Status::Done || r.status == CompareRun::Status::Interrupted) {
        t.seconds = Num(r.seconds, 4);
        if (!r.deterministic && r.image) {
            t.spp = std::to_string(r.sppReached);
            if (r.seconds > 0) t.rate = Num(double(r.sppReached) * Pixels(r) / r.seconds, 4);
        }
    }
    if (r.metrics) {
        t.rmse = Num(r.metrics->rmse, 9);
        t.relMse = Num(r.metrics->relMse, 9);
        t.maxError = Num(r.metrics->maxError, 9);
    }
    return t;
}

std::string Dash(const std::string &s, const char *none = "—") { return s.empty() ? none : s; }
std::string ShortField(const std::string &s, const char *none = "—") {
    return s.empty() ? none : Short(std::stod(s));
}

const char *MetricsNote =
    "Errors of the `intensity` channel against the reference, over the pixels: RMSE = √mean((I − R)²); "
    "relative MSE = mean((I − R)² / (R² + 0.01·mean(R)²)); max error = max |I − R| / max(R).";

std::string MarkdownTable(const std::vector<CompareRun> &runs, const CompareReference &ref, const CompareReport &rep) {
    std::ostringstream md;
    md << "# phasor compare: " << fs::path(rep.scene).filename().string() << "\n\n";
    md << "`" << rep.command << "`\n\n";
    md << "Mode: " << rep.mode << ". Reference: " << ref.description << ".";
    if (rep.stopped) md << " The comparison was stopped (Ctrl-C) before every integrator had finished.";
    md << "\n\n" << MetricsNote << "\n\n";
    md << "| integrator | status | spp | time (s) | samples/s | RMSE | relative MSE | max error |\n";
    md << "|---|---|---:|---:|---:|---:|---:|---:|\n";
    for (const CompareRun &r : runs) {
        const TableRow t = RowOf(r);
        std::string status = t.statusText;
        std::replace(status.begin(), status.end(), '|', '/');
        md << "| " << t.name << " | " << status << " | " << Dash(t.spp) << " | " << ShortField(t.seconds) << " | "
           << ShortField(t.rate) << " | " << ShortField(t.rmse) << " | " << ShortField(t.relMse) << " | "
           << ShortField(t.maxError) << " |\n";
    }
    return md.str();
}

std::string CsvTable(const std::vector<CompareRun> &runs) {
    std::ostringstream csv;
    csv << "integrator,role,status,spp,seconds,samples_per_second,rmse,rel_mse,max_error,error\n";
    for (const CompareRun &r : runs) {
        const TableRow t = RowOf(r);
        csv << CsvField(t.name) << ',' << t.role << ',' << t.status << ',' << t.spp << ',' << t.seconds << ',' << t.rate
            << ',' << t.rmse << ',' << t.relMse << ',' << t.maxError << ',' << CsvField(t.error) << '\n';
    }
    return csv.str();
}

// The label of a run's tile: "grt — 4096 spp, 0.52 s".
std::string TileLabel(const CompareRun &r, const char *separator = "\n") {
    std::string s = r.name + (r.isReference ? " (reference)" : "") + separator;
    if (r.deterministic)
        s += "deterministic, ";
    else
        s += std::to_string(r.sppReached) + " spp, ";
    return s + FormatSeconds(r.seconds) + (r.status == CompareRun::Status::Interrupted ? ", interrupted" : "");
}

Rgb8Image Tone(const Image &img, bool radiometric, double zeroDb) {
    return radiometric ? ToFalseColourDb(img, "intensity", 40, zeroDb) : ToDisplay(img);
}

void Warn(const SheetResult &r, const std::string &path) {
    if (!r.textDrawn) std::fprintf(stderr, "warning: %s; '%s' has no text\n", r.textProblem.c_str(), path.c_str());
}

// What the page shows for one file: an image, or a link to the data drawn instead.
struct Shown {
    std::string file;  // relative to the output directory ("" = nothing)
    bool image = true;
};

}  // namespace

CompareMetrics ErrorMetrics(const std::vector<double> &image, const std::vector<double> &reference) {
    CompareMetrics m;
    if (image.size() != reference.size() || image.empty()) return m;
    double sumSq = 0, sumRef = 0, peak = -Infinity, maxAbs = 0;
    long long n = 0;
    for (std::size_t i = 0; i < image.size(); ++i) {
        if (!std::isfinite(image[i]) || !std::isfinite(reference[i])) {
            ++m.skipped;
            continue;
        }
        const double d = image[i] - reference[i];
        sumSq += d * d;
        sumRef += reference[i];
        peak = std::max(peak, reference[i]);
        maxAbs = std::max(maxAbs, std::abs(d));
        ++n;
    }
    if (n == 0) return m;
    m.rmse = std::sqrt(sumSq / n);
    const double mean = sumRef / n, eps = 0.01 * mean * mean;
    if (eps > 0) {
        double rel = 0;
        for (std::size_t i = 0; i < image.size(); ++i)
            if (std::isfinite(image[i]) && std::isfinite(reference[i])) {
                const double d = image[i] - reference[i];
                rel += d * d / (reference[i] * reference[i] + eps);
            }
        m.relMse = rel / n;
    }
    if (peak > 0) m.maxError = maxAbs / peak;
    return m;
}

void ChooseReference(std::vector<CompareRun> &runs, CompareReference &ref) {
    // Complete runs first: an interrupted one may have pixels without samples (and no variance).
    const bool anyDone = std::any_of(
        runs.begin(), runs.end(), [](const CompareRun &r) { return r.image && r.status == CompareRun::Status::Done; });
    CompareRun *best = nullptr;
    double bestNoise = Infinity;
    for (CompareRun &r : runs) {
        if (!r.image || (anyDone && r.status != CompareRun::Status::Done)) continue;
        double noise = Infinity;
        if (r.deterministic) {
            noise = r.status == CompareRun::Status::Done ? -1 : Infinity;  // a complete exact solution first
        } else if (!r.variance.empty() && r.sppReached >= 2) {             // (one sample has no variance estimate)
            double var = 0, sq = 0;
            for (std::size_t i = 0; i < r.variance.size(); ++i)
                if (std::isfinite(r.variance[i]) && std::isfinite(r.intensity[i])) {
                    var += r.variance[i];
                    sq += r.intensity[i] * r.intensity[i];
                }
            noise = sq > 0 ? var / sq : Infinity;
        }
        if (!best || noise < bestNoise) {
            best = &r;
            bestNoise = noise;
        }
    }
    if (!best) return;
    best->isReference = true;
    ref.image = &*best->image;
    ref.name = best->name;
    ref.description = best->name + ", the best-converged run (no reference was given): ";
    if (best->deterministic)
        ref.description += "deterministic, no sampling noise";
    else if (std::isfinite(bestNoise))
        ref.description +=
            "the least estimated noise, relative variance " + Short(bestNoise) + " from its variance channel";
    else
        ref.description += "no run has a noise estimate";
}

void ComputeErrors(std::vector<CompareRun> &runs, CompareReference &ref) {
    for (CompareRun &r : runs)
        if (r.isReferenceRun && r.image && !ref.image) {
            r.isReference = true;
            ref.image = &*r.image;
            ref.name = r.name;
            ref.description =
                r.name + " at " +
                (r.deterministic ? std::string("its own accuracy") : std::to_string(r.sppReached) + " spp") +
                " (--reference-integrator)";
        }
    if (!ref.image) {  // no reference given, or the reference run failed: the best-converged run
        ChooseReference(runs, ref);
        if (!ref.image) return;
        if (std::any_of(runs.begin(), runs.end(), [](const CompareRun &r) { return r.isReferenceRun; }))
            ref.description += " (the reference integrator did not finish)";
    }
    ref.values = ChannelValues(*ref.image, "intensity");
    ref.peak = FiniteMax(ref.values);
    for (CompareRun &r : runs) {
        if (!r.image || r.isReference) continue;
        r.metrics = ErrorMetrics(r.intensity, ref.values);
        for (CompareSnapshot &s : r.snapshots)
            if (!s.metrics) {
                s.metrics = ErrorMetrics(std::vector<double>(s.intensity.begin(), s.intensity.end()), ref.values);
                s.intensity = {};
            }
    }
}

std::string FormatSeconds(double s) {
    char buf[32];
    if (s < 60)
        std::snprintf(buf, sizeof buf, "%.3g s", s);
    else
        return FormatDuration(s);
    return buf;
}

void PrintSummary(std::ostream &os, const std::vector<CompareRun> &runs) {
    char line[256];
    std::snprintf(line, sizeof line, "  %-14s %-12s %8s %9s %10s %10s %10s\n", "integrator", "status", "spp", "time(s)",
                  "RMSE", "rel.MSE", "max err");
    os << line;
    for (const CompareRun &r : runs) {
        const TableRow t = RowOf(r);
        std::snprintf(line, sizeof line, "  %-14s %-12s %8s %9s %10s %10s %10s\n", t.name.c_str(),
                      (r.isReference && t.status == "ok" ? std::string("reference") : t.status).c_str(),
                      Dash(t.spp, "-").c_str(), ShortField(t.seconds, "-").c_str(), ShortField(t.rmse, "-").c_str(),
                      ShortField(t.relMse, "-").c_str(), ShortField(t.maxError, "-").c_str());
        os << line;
    }
}

std::vector<std::string> StageCompareOutputs(OutputFiles &files, std::vector<CompareRun> &runs,
                                             const CompareReference &ref, const Image *refImage,
                                             const CompareReport &rep) {
    std::vector<std::string> written;
    const fs::path dir(rep.dir);
    auto path = [&](const std::string &name) { return (dir / name).string(); };
    auto add = [&](const std::string &name) { written.push_back(name); };
    const std::string sceneName = fs::path(rep.scene).filename().string();
    const double zeroDb = ref.peak;  // one dB scale for every sensor image: 0 dB = the reference's peak

    // Each run: its EXR and the PNG `render` would write (with the shared dB scale).
    std::vector<Shown> shown(runs.size());
    for (std::size_t k = 0; k < runs.size(); ++k) {
        const CompareRun &r = runs[k];
        if (!r.image) continue;
        WriteExr(files, path(r.file + ".exr"), *r.image);
        add(r.file + ".exr");
        const std::string staged = StageDisplayPng(files, path(r.file + ".png"), *r.image, rep.radiometric, r.name,
                                                   sceneName + ": " + r.name, zeroDb);
        shown[k] = {fs::path(staged).filename().string(), fs::path(staged).extension() == ".png"};
        add(shown[k].file);
    }
    Shown refShown;
    if (refImage) {
        const std::string staged = StageDisplayPng(files, path("reference.png"), *refImage, rep.radiometric,
                                                   "reference", sceneName + ": reference", zeroDb);
        refShown = {fs::path(staged).filename().string(), fs::path(staged).extension() == ".png"};
        add(refShown.file);
    }

    // The grid: the reference image (if given), then every run, labelled; one colour bar for
    // sensor images.
    std::vector<SheetTile> tiles;
    if (refImage) tiles.push_back({Tone(*refImage, rep.radiometric, zeroDb), "reference\n" + ref.description});
    for (const CompareRun &r : runs)
        if (r.image) tiles.push_back({Tone(*r.image, rep.radiometric, zeroDb), TileLabel(r)});
    ColourBar dbBar = DecibelBar(40, "intensity, 0 dB = " + Short(zeroDb));
    Warn(StageSheetPng(files, path("grid.png"), tiles, rep.radiometric ? &dbBar : nullptr,
                       "phasor compare: " + sceneName),
         path("grid.png"));
    add("grid.png");

    // Signed differences (I − R) / max(R), one symmetric scale for all: the largest 99.5th
    // percentile of |I − R| / max(R) over the runs, rounded up to 1, 2 or 5 × 10^k.
    const double norm = ref.peak > 0 ? ref.peak : 1;
    double limit = 0;
    std::vector<std::vector<double>> diffs(runs.size());
    for (std::size_t k = 0; k < runs.size(); ++k) {
        const CompareRun &r = runs[k];
        if (!r.image || r.isReference || ref.values.empty()) continue;
        std::vector<double> abs;
        for (std::size_t i = 0; i < r.intensity.size(); ++i) {
            const double d = (r.intensity[i] - ref.values[i]) / norm;
            diffs[k].push_back(std::isfinite(d) ? d : NaN);
            if (std::isfinite(d)) abs.push_back(std::abs(d));
        }
        if (abs.empty()) continue;
        const std::size_t at = std::min(abs.size() - 1, std::size_t(std::ceil(0.995 * (abs.size() - 1))));
        std::nth_element(abs.begin(), abs.begin() + std::ptrdiff_t(at), abs.end());
        limit = std::max(limit, abs[at]);
    }
    limit = limit > 0 ? NiceCeil(limit) : 1e-6;
    ColourBar diffBar;
    diffBar.map = ColourMap::Diverging;
    diffBar.title = ref.peak > 0 ? "(I - R) / max(R)" : "I - R";
    for (double f : {-1.0, -0.5, 0.0, 0.5, 1.0}) {
        char label[32];
        std::snprintf(label, sizeof label, f == 0 ? "0" : "%+.3g", f * limit);
        diffBar.ticks.push_back({(f + 1) / 2, label});
    }
    std::vector<Shown> diffShown(runs.size());
    for (std::size_t k = 0; k < runs.size(); ++k) {
        if (diffs[k].empty()) continue;
        const CompareRun &r = runs[k];
        const std::string name = "diff_" + r.file + ".png";
        const Rgb8Image img =
            MapColours(diffs[k], r.image->width, r.image->height, ColourMap::Diverging, -limit, limit);
        Warn(StageSheetPng(files, path(name), {SheetTile{img, r.name + " - reference"}}, &diffBar,
                           "(" + r.name + " - reference) / max(reference), clipped at +-" + Num(limit, 3)),
             path(name));
        diffShown[k] = {name, true};
        add(name);
    }

    // Results.
    files.Stage(path("results.csv"), CsvTable(runs));
    files.Stage(path("results.md"), MarkdownTable(runs, ref, rep));
    add("results.csv");
    add("results.md");

    // A profile along a row or a column (a one-row image: its row), every run with the reference
    // last (so that two images give |run − reference| and the pixel bar sits on the reference).
    Shown profileShown;
    const int row = rep.column < 0 && rep.row < 0 && rep.height == 1 ? 0 : rep.row;
    if (row >= 0 || rep.column >= 0) {
        if (row >= rep.height || rep.column >= rep.width)
            throw Error(row >= 0 ? "--row " + std::to_string(row) + " is out of range (the image has " +
                                       std::to_string(rep.height) + " rows)"
                                 : "--column " + std::to_string(rep.column) + " is out of range (the image has " +
                                       std::to_string(rep.width) + " columns)");
        CliOptions po;
        po.quiet = true;
        auto &p = po.profile;
        std::vector<const Image *> images;
        for (const CompareRun &r : runs)
            if (r.image && !r.isReference) {
                p.inputs.push_back(path(r.file + ".exr"));
                p.labels.push_back(r.name);
                images.push_back(&*r.image);
            }
        for (const CompareRun &r : runs)
            if (r.image && r.isReference) {
                p.inputs.push_back(path(r.file + ".exr"));
                p.labels.push_back(r.name);
                images.push_back(&*r.image);
            }
        if (refImage) {
            p.inputs.push_back(path("reference.exr"));
            p.labels.push_back("reference");
            images.push_back(refImage);
        }
        p.row = row;
        p.column = rep.column;
        p.csv = path("profile.csv");
        p.plot = path("profile.png");
        p.title = sceneName + ": intensity, " +
                  (row >= 0 ? "row " + std::to_string(row) : "column " + std::to_string(rep.column));
        std::string data;
        if (RunProfile(po, images, &files, &data) != 0) throw Error("cannot draw the profile");
        add("profile.csv");
        if (data.empty()) {
            add("profile.png");
            profileShown = {"profile.png", true};
        } else {
            profileShown = {"profile.csv", false};
        }
    }

    // Convergence: the error of each sampling run against the reference after 1, 2, 4, … spp.
    Shown convergenceShown;
    std::ostringstream conv;
    conv << "run,spp,seconds,rmse,rel_mse,max_error\n";
    int curves = 0;
    for (const CompareRun &r : runs) {
        if (!Sampling(r) || r.isReference || r.snapshots.size() < 2) continue;
        ++curves;
        for (const CompareSnapshot &s : r.snapshots) {
            const CompareMetrics m = s.metrics.value_or(CompareMetrics{});
            conv << CsvField(r.name) << ',' << s.spp << ',' << Num(s.seconds, 6) << ',' << Num(m.rmse, 6) << ','
                 << Num(m.relMse, 6) << ',' << Num(m.maxError, 6) << '\n';
        }
    }
    if (curves > 0) {
        files.Stage(path("convergence.csv"), conv.str());
        add("convergence.csv");
        PlotRequest plot;
        plot.command = "convergence";
        plot.data = conv.str();
        plot.args = {"--title", sceneName + ": error of intensity against the reference (" + ref.name + ")"};
        if (StagePlot(files, path("convergence.png"), plot)) {
            add("convergence.png");
            convergenceShown = {"convergence.png", true};
        } else {
            convergenceShown = {"convergence.csv", false};
        }
    }

    // Without matplotlib: one warning for every plot not drawn.
    std::vector<std::string> notDrawn;
    for (const Shown &x : shown)
        if (!x.file.empty() && !x.image) notDrawn.push_back(x.file);
    for (const Shown *x : {&refShown, &profileShown, &convergenceShown})
        if (!x->file.empty() && !x->image) notDrawn.push_back(x->file);
    if (!notDrawn.empty()) {
        std::string list;
        for (const std::string &f : notDrawn) list += (list.empty() ? "" : ", ") + f;
        std::fprintf(stderr, "warning: %s; the plots are not drawn, their data is in %s\n",
                     MatplotlibMissing().c_str(), list.c_str());
    }

    // The page.
    std::ostringstream h;
    // A figure; matplotlib's plots (`plot`) are shown at a fixed width, images at their size.
    // Small renders are shown enlarged by the grid's whole factor.
    Rgb8Image probe;
    probe.width = rep.width;
    probe.height = rep.height;
    const int enlarged = rep.width * SheetScale({SheetTile{probe, ""}});
    auto figure = [&](const Shown &s, const std::string &caption, const std::string &extraLink, bool plot = false,
                      int width = 0) {
        if (s.file.empty()) return;
        h << (plot ? "<figure class=\"plot\">" : "<figure>");
        if (s.image)
            h << "<a href=\"" << Html(s.file) << "\"><img src=\"" << Html(s.file) << "\" alt=\"" << Html(caption)
              << "\"" << (width > 0 ? " width=\"" + std::to_string(width) + "\"" : "") << "></a>";
        else
            h << "<p class=\"missing\">not drawn: " << Html(MatplotlibMissing()) << "; data: <a href=\"" << Html(s.file)
              << "\">" << Html(s.file) << "</a></p>";
        h << "<figcaption>" << Html(caption) << extraLink << "</figcaption></figure>\n";
    };
    h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      << "<title>phasor compare: " << Html(sceneName) << "</title>\n"
      << "<style>\n"
         "body { font-family: sans-serif; margin: 1.5em; color: #222; }\n"
         "table { border-collapse: collapse; margin: 0.5em 0; }\n"
         "th, td { border: 1px solid #bbb; padding: 3px 9px; text-align: right; }\n"
         "th { background: #eee; } td.name, td.status { text-align: left; }\n"
         "tr.reference td { background: #f4f8ff; } tr.failed td { color: #a00; }\n"
         "figure { display: inline-block; vertical-align: top; margin: 0 1.2em 1.2em 0; }\n"
         "figure img { max-width: 100%; border: 1px solid #ddd; }\n"
         "figure:not(.plot) img { image-rendering: pixelated; }\n"
         "figure.plot img { width: 640px; }\n"
         "figcaption { font-size: 90%; color: #444; }\n"
         "code { background: #f3f3f3; padding: 1px 4px; } .missing { color: #a00; } .note { color: #555; }\n"
         "</style>\n</head>\n<body>\n";
    h << "<h1>phasor compare: " << Html(sceneName) << "</h1>\n";
    h << "<p><code>" << Html(rep.command) << "</code></p>\n";
    h << "<p>" << Html(rep.mode) << "; detector <code>" << Html(rep.detector) << "</code>, " << rep.width << "×"
      << rep.height << " pixels, " << (rep.radiometric ? "radiometric (false colour in dB)" : "camera (OCIO display)")
      << ".<br>Reference: " << Html(ref.description) << ".</p>\n";
    if (rep.stopped)
        h << "<p class=\"missing\">The comparison was stopped (Ctrl-C) before every integrator had finished; "
             "what finished is shown.</p>\n";
    h << "<h2>Results</h2>\n<table>\n<tr><th>integrator</th><th>status</th><th>spp</th><th>time (s)</th>"
         "<th>samples/s</th><th>RMSE</th><th>relative MSE</th><th>max error</th></tr>\n";
    for (std::size_t k = 0; k < runs.size(); ++k) {
        const CompareRun &r = runs[k];
        const TableRow t = RowOf(r);
        const char *cls = r.status == CompareRun::Status::Failed ? " class=\"failed\""
                          : r.isReference                        ? " class=\"reference\""
                                                                 : "";
        h << "<tr" << cls << "><td class=\"name\">";
        if (r.image)
            h << "<a href=\"" << Html(r.file) << ".exr\">" << Html(r.name) << "</a>";
        else
            h << Html(r.name);
        h << "</td><td class=\"status\">" << Html(t.statusText) << "</td><td>" << Dash(t.spp) << "</td><td>"
          << ShortField(t.seconds) << "</td><td>" << ShortField(t.rate) << "</td><td>" << ShortField(t.rmse)
          << "</td><td>" << ShortField(t.relMse) << "</td><td>" << ShortField(t.maxError) << "</td></tr>\n";
    }
    std::string note = MetricsNote;
    note.erase(std::remove(note.begin(), note.end(), '`'), note.end());
    h << "</table>\n<p class=\"note\">" << Html(note)
      << " Full precision: <a href=\"results.csv\">results.csv</a>, <a href=\"results.md\">results.md</a>.</p>\n";
    h << "<h2>Side by side</h2>\n";
    figure({"grid.png", true},
           rep.radiometric ? "intensity in dB, one scale for all (0 dB = the reference's peak, " + Short(zeroDb) + ")"
                           : "through the OpenColorIO display transform",
           "");
    h << "<h2>Each integrator</h2>\n";
    const bool plots = rep.height == 1;  // a one-row image is shown as a line plot
    // (a radiometric render's PNG carries its colour bar: shown at its own size)
    const int width = plots || rep.radiometric ? 0 : enlarged;
    if (refImage) figure(refShown, "reference: " + ref.description, "", plots, width);
    for (std::size_t k = 0; k < runs.size(); ++k)
        if (runs[k].image)
            figure(shown[k], TileLabel(runs[k], ": "),
                   " (<a href=\"" + Html(runs[k].file) + ".exr\">" + Html(runs[k].file) + ".exr</a>)", plots, width);
    if (std::any_of(diffShown.begin(), diffShown.end(), [](const Shown &s) { return !s.file.empty(); })) {
        h << "<h2>Difference from the reference</h2>\n<p class=\"note\">(I − R) / max(R), blue below and red above "
             "the reference; one scale for all, clipped at ±"
          << Html(Num(limit, 3)) << ".</p>\n";
        for (std::size_t k = 0; k < runs.size(); ++k) figure(diffShown[k], runs[k].name + " − reference", "");
    }
    if (!profileShown.file.empty()) {
        h << "<h2>Profile</h2>\n";
        figure(profileShown, row >= 0 ? "row " + std::to_string(row) : "column " + std::to_string(rep.column),
               " (<a href=\"profile.csv\">profile.csv</a>)", true);
    }
    if (!convergenceShown.file.empty()) {
        h << "<h2>Convergence</h2>\n";
        figure(convergenceShown, "error against the reference as the samples accumulate (the render loop's passes)",
               " (<a href=\"convergence.csv\">convergence.csv</a>)");
    }
    if (std::any_of(runs.begin(), runs.end(), [](const CompareRun &r) { return !r.warnings.empty(); })) {
        h << "<h2>Warnings at load</h2>\n<ul>\n";
        for (const CompareRun &r : runs)
            for (const std::string &w : r.warnings)
                h << "<li class=\"warning\"><code>" << Html(r.name) << "</code>: " << Html(w) << "</li>\n";
        h << "</ul>\n";
    }
    bool anyFailed = false;
    for (const CompareRun &r : runs) anyFailed |= r.status == CompareRun::Status::Failed;
    if (anyFailed) {
        h << "<h2>Failures</h2>\n<ul>\n";
        for (const CompareRun &r : runs)
            if (r.status == CompareRun::Status::Failed)
                h << "<li><code>" << Html(r.name) << "</code>: " << Html(r.error) << "</li>\n";
        h << "</ul>\n";
    }
    h << "</body>\n</html>\n";
    files.Stage(path("index.html"), h.str());
    add("index.html");
    return written;
}

}  // namespace phasor
