// SPDX-License-Identifier: Apache-2.0
// phasor — `phasor profile` (profile.h). Reads every input first and checks everything (channel,
// row or column, sizes, pixel positions) before writing anything; the CSV and the plot (drawn by
// matplotlib through app/plot.h) are written all or nothing (core/image/output_file.h), so an
// error leaves no output behind.

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
#include "app/plot.h"
#include "app/render_common.h"
#include "app/text.h"

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
    int line = 0;                // the row (or column) taken
    std::vector<double> values;  // its values of the channel
    std::string label;
    bool labelFromMetadata = false;
};

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

// The integrator's name from "grt { max_depth = 5, … }".
std::string IntegratorName(const std::string &desc) {
    std::size_t b = desc.find_first_not_of(' ');
    if (b == std::string::npos) return "";
    std::size_t e = desc.find_first_of(" {", b);
    return desc.substr(b, e == std::string::npos ? std::string::npos : e - b);
}

}  // namespace

int RunProfile(const CliOptions &o, const std::vector<const Image *> &preloaded, OutputFiles *into,
               std::string *plotData) {
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
            const bool column = p.column >= 0;
            const int lines = column ? in.img.width : in.img.height, length = column ? in.img.height : in.img.width;
            const char *what = column ? "column" : "row";
            in.line = column ? p.column : p.row >= 0 ? p.row : in.img.height / 2;
            if (in.line >= lines)
                throw InputError{path, std::string(what) + " " + std::to_string(in.line) +
                                           " is out of range (the image has " + std::to_string(lines) + " " + what +
                                           (lines == 1 ? "" : "s") + ")"};
            if (!inputs.empty() && length != int(inputs[0].values.size()))
                throw InputError{path, "it is " + std::to_string(length) + " pixels " + (column ? "tall" : "wide") +
                                           " but '" + inputs[0].path + "' is " +
                                           std::to_string(inputs[0].values.size()) + " (profiles must have the same " +
                                           (column ? "height" : "width") + ")"};
            for (int k = 0; k < length; ++k)
                in.values.push_back(column ? in.img.At(in.line, k, c) : in.img.At(k, in.line, c));

            // Pixel positions: --x0/--pitch, else the renderer's metadata (all inputs must agree).
            std::optional<double> mx0 = MetadataNumber(in, "phasor:x0_m"),
                                  mp = MetadataNumber(in, "phasor:pitch_m");
            if (!p.hasX0 && mx0 && mp && p.column < 0) {  // (the metadata gives x positions only)
                if (!(*mp > 0))
                    throw InputError{path, "metadata phasor:pitch_m = " + FormatNumber(*mp, 9) + " is not positive"};
                auto differs = [](double a, double b) {
                    return std::abs(a - b) > 1e-9 * std::max(std::abs(a), std::abs(b));
                };
                if (havePositions && (differs(x0, *mx0) || differs(pitch, *mp)))
                    throw InputError{path, "its pixel positions (x0 = " + FormatNumber(*mx0, 12) +
                                               " m, pitch = " + FormatNumber(*mp, 12) +
                                               " m) differ from the other images' (x0 = " + FormatNumber(x0, 12) +
                                               " m, pitch = " + FormatNumber(pitch, 12) +
                                               " m); give --x0 and --pitch to override"};
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

    const int width = int(inputs[0].values.size());  // the profile's length
    const bool column = p.column >= 0;
    std::vector<double> x(width);
    for (int i = 0; i < width; ++i) x[i] = havePositions ? x0 + i * pitch : double(i);  // pixel centres
    const bool pair = inputs.size() == 2;
    std::vector<double> diff;
    if (pair)
        for (int i = 0; i < width; ++i) diff.push_back(std::abs(inputs[0].values[i] - inputs[1].values[i]));

    // CSV text.
    std::ostringstream csv;
    csv << (havePositions ? "x_m" : column ? "y_px" : "x_px");
    for (const Input &in : inputs) csv << ',' << CsvField(in.label);
    if (pair) csv << ",abs_diff";
    csv << '\n';
    for (int i = 0; i < width; ++i) {
        csv << (havePositions ? FormatNumber(x[i], 12) : std::to_string(i));
        for (const Input &in : inputs) csv << ',' << FormatNumber(in.values[i], 9);
        if (pair) csv << ',' << FormatNumber(diff[i], 9);
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
              << (peak > 0 ? FormatNumber(maxDiff / peak, 6) : std::string("undefined (the peak is not positive)"))
              << "  (max |" << a << " - " << b << "| = " << FormatNumber(maxDiff, 6) << " at "
              << (havePositions ? "x = " + FormatNumber(x[at], 9) + " m" : "pixel " + std::to_string(at)) << ", max("
              << b << ") = " << FormatNumber(peak, 6) << ")";
        }
        if (nonFinite > 0) s << "; " << nonFinite << " pixel(s) with NaN/Inf skipped";
        summary = s.str();
    }

    // The plot (python/phasor_plot.py `profile`, in the style of Fig. S6: the first input blue
    // and solid, the second green and dashed, |a − b| black and dotted, one pixel as a cyan bar).
    PlotRequest plot;
    plot.command = "profile";
    plot.data = csv.str();
    plot.args = {"--title",
                 !p.title.empty() ? p.title
                                  : p.channel + (column ? ", column " : ", row ") + std::to_string(inputs[0].line),
                 "--ylabel", p.channel, "--diff-scale", FormatNumber(p.diffScale, 9)};

    // Write the CSV and the plot all or nothing (core/image/output_file.h). Without matplotlib the
    // plot's data is written instead (to the --csv file, else beside the plot as .csv).
    std::string dataInstead;
    try {
        OutputFiles own;
        OutputFiles &files = into ? *into : own;
        if (!csvToStdout && !p.csv.empty()) {
            MakeParentDirectory(p.csv);
            files.Stage(p.csv, csv.str());
        }
        if (!p.plot.empty()) {
            MakeParentDirectory(p.plot);
            if (!StagePlot(files, p.plot, plot)) {
                dataInstead =
                    !csvToStdout && !p.csv.empty() ? p.csv : fs::path(p.plot).replace_extension(".csv").string();
                if (dataInstead != p.csv) files.Stage(dataInstead, csv.str());
                if (plotData) *plotData = dataInstead;  // the caller tells the user
                else
                    std::cerr << "warning: " << MatplotlibMissing() << "; '" << p.plot
                              << "' not drawn, its data is in '" << dataInstead << "'\n";
            }
        }
        if (into) return 0;  // the caller commits (and reports) the files
        files.Commit();
    } catch (const Error &e) {
        if (into) throw;  // the caller reports it (and discards its other files)
        std::cerr << "error: " << e.Message() << "\n";
        return 1;
    }
    if (csvToStdout) std::cout << csv.str();
    if (!summary.empty()) (csvToStdout ? std::cerr : std::cout) << summary << "\n";
    if (!o.quiet) {
        if (!csvToStdout && !p.csv.empty()) std::cerr << "wrote " << p.csv << "\n";
        if (!p.plot.empty() && dataInstead.empty()) std::cerr << "wrote " << p.plot << "\n";
        if (!dataInstead.empty() && dataInstead != p.csv) std::cerr << "wrote " << dataInstead << "\n";
    }
    return 0;
}

}  // namespace phasor
