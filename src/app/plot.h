// SPDX-License-Identifier: Apache-2.0
// phasor — plots through matplotlib. The program writes the data as CSV and runs the plot module
// shipped with it, python/phasor_plot.py (its docstring lists the commands and their CSV), which
// draws the file at the temporary path of core/image/output_file.h, so a plot appears together
// with the other outputs of a command or not at all.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace phasor {

class OutputFiles;

/// One plot: a command of phasor_plot.py with its data and options — or a page: a command of
/// phasor_report.py (jinja2 templates), which the same machinery runs.
struct PlotRequest {
    std::string module = "phasor_plot.py";  // beside it: phasor_report.py
    std::string command;                     // "profile", "convergence", "disc-map"; "compare"
    std::string data;     // CSV text, passed as --data
    /// Further CSV inputs: option → CSV text (e.g. {"--points", "u,v,label\n…"}).
    std::vector<std::pair<std::string, std::string>> extraData;
    std::vector<std::string> args;  // further options, e.g. {"--title", "double slit"}
};

/// Draws `request` into `path` — SVG or PDF when `path` ends in .svg or .pdf, otherwise PNG —
/// staged in `files` (it appears at files.Commit()). Returns false, staging nothing, when no
/// Python with matplotlib and numpy is found (MatplotlibMissing() says what to install); throws
/// phasor::Error "cannot write 'PATH': reason" when the plot fails (the module's own message, e.g.
/// "File too large").
///
/// The interpreter is $PHASOR_PYTHON when set (only that one), else `python3` from PATH, else
/// /usr/bin/python3 (where Debian's python3-matplotlib installs for): the first that can import
/// matplotlib is used from then on (while $PHASOR_PYTHON stays the same). It runs in its own process group (a Ctrl-C at
/// the terminal stops phasor's render, not a plot being drawn), without writing bytecode.
bool StagePlot(OutputFiles &files, const std::string &path, const PlotRequest &request);
/// Why `module` could not run (no Python with its library: matplotlib for phasor_plot.py,
/// jinja2 for phasor_report.py), with the Debian package that provides it.
std::string ModuleMissing(const std::string &module);

/// A value over projected hemispheres, e.g. a kernel's angular distribution (`phasor probe`): one
/// or more discs, each an n × n grid over [−1, 1]² in (u, v) = (sinθ cosφ, sinθ sinφ), `values[j·n +
/// i]` at the centre of cell (i, j), u growing with i, v with j (j = 0 at v = −1); cells outside
/// the unit disc are not drawn. All discs share one colour scale (0 dB = the largest value of any)
/// and one colour bar. Markers on a disc: 'o' a red ring, 'x' a white cross, `size` in points,
/// with an optional label.
struct DiscMap {
    int n = 0;
    struct Disc {
        std::string name;  // the disc's title: distinct when there are several ("" with one: none)
        std::vector<double> values;
    };
    std::vector<Disc> discs;
    struct Marker {
        int disc = 0;
        double u = 0, v = 0;
        std::string label;
        char symbol = 'o';
        double size = 7;
    };
    std::vector<Marker> markers;
    std::string title;
    std::string valueLabel = "value";  // the colour bar's label
    std::string scale = "db";          // "db" (0 dB = the maximum), "log" or "linear"
    double rangeDb = 40;               // shown below the maximum (db, log)
};
/// The map's data as the plot module reads it: `[disc,]u,v,value` (the `disc` column when a disc
/// has a name). Throws phasor::Error for an inconsistent map (n ≤ 0, no disc, a disc without n²
/// values, several discs without distinct names, a marker on no disc or with another symbol).
std::string DiscMapCsv(const DiscMap &map);
/// Draws `map` (python/phasor_plot.py disc-map) as StagePlot does (false: matplotlib is missing,
/// nothing staged; the caller may stage DiscMapCsv instead). Throws phasor::Error.
bool StageDiscMap(OutputFiles &files, const std::string &path, const DiscMap &map);

/// The plot module: $PHASOR_PLOT_MODULE when set, else phasor_plot.py in $PHASOR_MODULE_DIR when
/// set (the Python package's own directory), else share/phasor/phasor_plot.py beside the
/// directory of the phasor executable (`<prefix>/bin/phasor` → `<prefix>/share/phasor/`; the build
/// tree has the same layout). Empty when that file does not exist. The page module
/// (phasor_report.py, templates/ beside it) is found the same way.
std::string PlotModulePath();

/// One line for the user after StagePlot returned false: what was missing and how to install it.
std::string MatplotlibMissing();

}  // namespace phasor
