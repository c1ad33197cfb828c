// SPDX-License-Identifier: Apache-2.0
// phasor — `phasor profile` (profile.h). Reads every input first and checks everything (channel,
// row, widths, pixel positions) before writing anything; the CSV and the plot are written all or
// nothing (core/image/output_file.h), so an error leaves no output behind.

#include "app/profile.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "core/image/image_io.h"
#include "core/image/plot.h"

namespace phasor {
namespace {

namespace fs = std::filesystem;

// A problem with one input file: printed as "error: <file>: <reason>".
struct InputError {
    std::string file, reason;
};

struct Input {
    std::string path;
    Image img;
    int row = 0;
    std::vector<double> values;  // the row of the channel
    std::string label;
    bool labelFromMetadata = false;
};

std::string Num(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}

// Optional numeric metadata (stored as a string attribute by the renderer).
std::optional<double> MetadataNumber(const Input &in, const std::string &key) {
    auto it = in.img.metadata.find(key);
    if (it == in.img.metadata.end()) return std::nullopt;
    const std::string &s = it->second;
    char *end = nullptr;
    double v = std::strtod(s.c_str(), &end);
    while (end && *end == ' ') ++end;
    if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v))
        throw InputError{in.path, "metadata " + key + " = '" + s + "' is not a number"};
    return v;
}

// RFC 4180 quoting for a CSV header field.
std::string CsvField(const std::string &s) {
    if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

// The integrator's name from "grt { max_depth = 5, … }".
std::string IntegratorName(const std::string &desc) {
    std::size_t b = desc.find_first_not_of(' ');
    if (b == std::string::npos) return "";
    std::size_t e = desc.find_first_of(" {", b);
    return desc.substr(b, e == std::string::npos ? std::string::npos : e - b);
}

// x axis unit for a plot of positions in metres: a factor and its name.
std::pair<double, std::string> LengthUnit(double maxAbs) {
    if (maxAbs >= 1) return {1, "m"};
    if (maxAbs >= 1e-3) return {1e3, "mm"};
    if (maxAbs >= 1e-6) return {1e6, "um"};
    return {1e9, "nm"};
}

}  // namespace

int RunProfile(const CliOptions &o, const std::vector<const Image *> &preloaded, OutputFiles *into) {
    const CliOptions::ProfileOptions &p = o.profile;
    std::vector<Input> inputs;
    bool havePositions = p.hasX0;
    double x0 = p.x0, pitch = p.pitch;
    try {
        for (const std::string &path : p.inputs) {
            Input in;
            in.path = path;
            const std::size_t index = inputs.size();
            if (index < preloaded.size() && preloaded[index])
                in.img = *preloaded[index];
            else
                in.img = ReadImage(path);  // throws "cannot read '<path>': …"
            const int c = in.img.ChannelIndex(p.channel);
            if (c < 0) {
                std::string names;
                for (const std::string &n : in.img.channels) names += (names.empty() ? "" : " ") + n;
                throw InputError{path, "no channel '" + p.channel + "' (it has: " + names + ")"};
            }
            if (in.img.width <= 0 || in.img.height <= 0) throw InputError{path, "the image is empty"};
            in.row = p.row >= 0 ? p.row : in.img.height / 2;
            if (in.row >= in.img.height)
                throw InputError{path, "row " + std::to_string(in.row) + " is out of range (the image has " +
                                           std::to_string(in.img.height) + " row" +
                                           (in.img.height == 1 ? "" : "s") + ")"};
            if (!inputs.empty() && in.img.width != inputs[0].img.width)
                throw InputError{path, "it is " + std::to_string(in.img.width) + " pixels wide but '" +
                                           inputs[0].path + "' is " + std::to_string(inputs[0].img.width) +
                                           " (profiles must have the same width)"};
            for (int x = 0; x < in.img.width; ++x) in.values.push_back(in.img.At(x, in.row, c));

            // Pixel positions: --x0/--pitch, else the renderer's metadata (all inputs must agree).
            std::optional<double> mx0 = MetadataNumber(in, "phasor:x0_m"),
                                  mp = MetadataNumber(in, "phasor:pitch_m");
            if (!p.hasX0 && mx0 && mp) {
                if (!(*mp > 0))
                    throw InputError{path, "metadata phasor:pitch_m = " + Num(*mp, 9) + " is not positive"};
                auto differs = [](double a, double b) {
                    return std::abs(a - b) > 1e-9 * std::max(std::abs(a), std::abs(b));
                };
                if (havePositions && (differs(x0, *mx0) || differs(pitch, *mp)))
                    throw InputError{
                        path, "its pixel positions (x0 = " + Num(*mx0, 12) + " m, pitch = " + Num(*mp, 12) +
                                  " m) differ from the other images' (x0 = " + Num(x0, 12) +
                                  " m, pitch = " + Num(pitch, 12) + " m); give --x0 and --pitch to override"};
                havePositions = true;
                x0 = *mx0;
                pitch = *mp;
            }

            if (!p.labels.empty()) {  // one per input (checked by the parser)
                in.label = p.labels[inputs.size()];
            } else if (auto it = in.img.metadata.find("phasor:integrator");
                       it != in.img.metadata.end() && !IntegratorName(it->second).empty()) {
                in.label = IntegratorName(it->second);
                in.labelFromMetadata = true;
            } else {
                in.label = fs::path(path).stem().string();
            }
            inputs.push_back(std::move(in));
        }
    } catch (const InputError &e) {
        std::cerr << "error: " << e.file << ": " << e.reason << "\n";
        return 1;
    } catch (const Error &e) {
        std::cerr << "error: " << e.Message() << "\n";
        return 1;
    }
    // Default labels must tell the columns apart: integrator names that repeat (two grt renders)
    // give way to the file stems; stems that still repeat get "#2", "#3", ….
    {
        std::set<std::string> seen, dup;
        for (const Input &in : inputs)
            if (!seen.insert(in.label).second) dup.insert(in.label);
        for (Input &in : inputs)
            if (in.labelFromMetadata && dup.count(in.label)) in.label = fs::path(in.path).stem().string();
        std::set<std::string> used;
        for (Input &in : inputs) {
            std::string base = in.label;
            for (int k = 2; !used.insert(in.label).second; ++k) in.label = base + "#" + std::to_string(k);
        }
    }

    const int width = inputs[0].img.width;
    std::vector<double> x(width);
    for (int i = 0; i < width; ++i) x[i] = havePositions ? x0 + i * pitch : double(i);  // pixel centres
    const bool pair = inputs.size() == 2;
    std::vector<double> diff;
    if (pair)
        for (int i = 0; i < width; ++i) diff.push_back(std::abs(inputs[0].values[i] - inputs[1].values[i]));

    // CSV text.
    std::ostringstream csv;
    csv << (havePositions ? "x_m" : "x_px");
    for (const Input &in : inputs) csv << ',' << CsvField(in.label);
    if (pair) csv << ",abs_diff";
    csv << '\n';
    for (int i = 0; i < width; ++i) {
        csv << (havePositions ? Num(x[i], 12) : std::to_string(i));
        for (const Input &in : inputs) csv << ',' << Num(in.values[i], 9);
        if (pair) csv << ',' << Num(diff[i], 9);
        csv << '\n';
    }
    const bool csvToStdout = p.csv == "-" || (p.csv.empty() && p.plot.empty());

    // Summary for a pair: the largest difference relative to the second image's peak.
    std::string summary;
    if (pair) {
        double maxDiff = -1, peak = -Infinity;
        int at = 0, nonFinite = 0;
        for (int i = 0; i < width; ++i) {
            if (!std::isfinite(diff[i])) {
                ++nonFinite;
                continue;
            }
            if (diff[i] > maxDiff) {
                maxDiff = diff[i];
                at = i;
            }
            if (std::isfinite(inputs[1].values[i])) peak = std::max(peak, inputs[1].values[i]);
        }
        const std::string a = inputs[0].label, b = inputs[1].label;
        std::ostringstream s;
        if (maxDiff < 0) {
            s << "max |" << a << " - " << b << "|: no pixel has two finite values";
        } else {
            s << "max |" << a << " - " << b << "| / max(" << b << ") = "
              << (peak > 0 ? Num(maxDiff / peak, 6) : std::string("undefined (the peak is not positive)"))
              << "  (max |" << a << " - " << b << "| = " << Num(maxDiff, 6) << " at "
              << (havePositions ? "x = " + Num(x[at], 9) + " m" : "pixel " + std::to_string(at)) << ", max("
              << b << ") = " << Num(peak, 6) << ")";
        }
        if (nonFinite > 0) s << "; " << nonFinite << " pixel(s) with NaN/Inf skipped";
        summary = s.str();
    }

    // Plot series: the first input blue and solid, the second green and dashed (Fig. S6), more
    // inputs in further colours; |a − b| black and dotted, optionally magnified.
    std::vector<PlotSeries> series;
    PlotOptions plot;
    if (!p.plot.empty()) {
        const Vec3 palette[] = {{0.10, 0.35, 0.85}, {0.10, 0.62, 0.20}, {0.85, 0.15, 0.15},
                                {0.95, 0.55, 0.05}, {0.55, 0.25, 0.70}, {0.45, 0.45, 0.45}};
        double maxAbsX = 0;
        for (double v : x) maxAbsX = std::max(maxAbsX, std::abs(v));
        auto [scale, unit] = havePositions ? LengthUnit(maxAbsX) : std::pair<double, std::string>{1, "pixel"};
        std::vector<double> xs(width);
        for (int i = 0; i < width; ++i) xs[i] = x[i] * scale;
        for (std::size_t k = 0; k < inputs.size(); ++k) {
            PlotSeries s;
            s.label = inputs[k].label;
            s.x = xs;
            s.y = inputs[k].values;
            s.rgb = palette[k % 6];
            s.style = k == 1 ? PlotSeries::Dashed : PlotSeries::Solid;
            series.push_back(std::move(s));
        }
        if (pair) {
            PlotSeries s;
            s.label = "|" + inputs[0].label + " - " + inputs[1].label + "|" +
                      (p.diffScale != 1 ? " x " + Num(p.diffScale, 6) : "");
            s.x = xs;
            for (double d : diff) s.y.push_back(d * p.diffScale);
            s.rgb = Vec3(0, 0, 0);
            s.style = PlotSeries::Dotted;
            series.push_back(std::move(s));
        }
        // One pixel's extent as a cyan bar, centred on the peak of the last input, just above it.
        const std::vector<double> &ref = inputs.back().values;
        int peakAt = 0;
        double peak = -Infinity, top = -Infinity;
        for (int i = 0; i < width; ++i)
            if (std::isfinite(ref[i]) && ref[i] > peak) {
                peak = ref[i];
                peakAt = i;
            }
        for (const PlotSeries &s : series)
            for (double v : s.y)
                if (std::isfinite(v)) top = std::max(top, v);
        if (std::isfinite(peak) && std::isfinite(top)) {
            const double w = havePositions ? pitch * scale : 1;
            PlotBar bar;
            bar.label = havePositions ? "one pixel (" + Num(w, 4) + " " + unit + ")" : "one pixel";
            bar.x0 = xs[peakAt] - w / 2;
            bar.x1 = xs[peakAt] + w / 2;
            bar.y = top > 0 ? 1.03 * top : top + 0.03 * std::abs(top) + 1e-30;
            plot.bars.push_back(bar);
        }
        // The x axis spans the sensor row: from pixel 0's left edge to the last pixel's right edge.
        const double halfPixel = (havePositions ? pitch * scale : 1) / 2;
        plot.xMin = std::min(xs.front(), xs.back()) - halfPixel;
        plot.xMax = std::max(xs.front(), xs.back()) + halfPixel;
        plot.title =
            !p.title.empty()
                ? p.title
                : p.channel + ", row " + (p.row >= 0 ? std::to_string(p.row) : std::to_string(inputs[0].row));
        plot.xLabel = havePositions ? "x (" + unit + ")" : "x (pixel)";
        plot.yLabel = p.channel;
    }

    // Write the CSV and the plot all or nothing (core/image/output_file.h).
    try {
        OutputFiles own;
        OutputFiles &files = into ? *into : own;
        if (!csvToStdout && !p.csv.empty()) {
            MakeParentDirectory(p.csv);
            files.Stage(p.csv, csv.str());
        }
        if (!p.plot.empty()) {
            MakeParentDirectory(p.plot);
            PlotResult r = WritePlotPng(files, p.plot, series, plot);
            if (!r.textDrawn) std::cerr << "warning: " << r.textProblem << "; the plot has no text\n";
        }
        if (into) return 0;  // the caller commits (and reports) the files
        files.Commit();
    } catch (const Error &e) {
        std::cerr << "error: " << e.Message() << "\n";
        return 1;
    }
    if (csvToStdout) std::cout << csv.str();
    if (!summary.empty()) (csvToStdout ? std::cerr : std::cout) << summary << "\n";
    if (!o.quiet) {
        if (!csvToStdout && !p.csv.empty()) std::cerr << "wrote " << p.csv << "\n";
        if (!p.plot.empty()) std::cerr << "wrote " << p.plot << "\n";
    }
    return 0;
}

}  // namespace phasor
