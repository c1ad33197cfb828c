#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""phasor_plot — every plot phasor draws, through matplotlib.

The phasor program (src/app/plot.cpp) writes the data as CSV and runs

    python3 phasor_plot.py COMMAND --data FILE.csv --out FILE [--format png|svg|pdf] [options]

Commands (each reads CSV only; none reads images):

  profile      line plot of image rows/columns (`phasor profile`, a one-row render, `compare
               --row/--column`). CSV: first column x_m (metres), x_px or y_px (pixels), then one
               column per series, optionally abs_diff (drawn dotted, magnified by --diff-scale).
  convergence  error against samples per pixel and against time, one curve per run (`compare`).
               CSV: run,spp,seconds,rmse[,...]
  accuracy-map the accuracy map (tests/accuracy, docs/accuracy.md): one heat map per family of
               approximations, a cell per (row, column + integrator), coloured by error/tolerance on a
               log scale centred on 1 (green within tolerance, red beyond; failing cells crossed).
               CSV: family,row,column,integrator,value,reference,error,tolerance.
  disc-map     a value over the projected hemisphere (sinθcosφ, sinθsinφ) on the unit disc — one
               disc per name in an optional first column `disc` (e.g. reflection, transmission),
               all on one colour scale (dB/log/linear) with a colour bar — and markers (`phasor
               probe`). CSV: [disc,]u,v,value on a regular grid per disc; --points CSV:
               [disc,]u,v,label[,marker[,size]] (marker o: a red ring, x: a white cross; size in
               points).

Exit status: 0 drawn; 1 an error (one line "error: reason" on stderr; for a file that cannot be
written the reason is the system's, e.g. "File too large"); 2 bad arguments; 3 matplotlib or
numpy is not installed for this interpreter (the caller may try another one).
"""

import argparse
import csv
import math
import os
import sys

MISSING_LIBRARY = 3

try:
    import numpy as np
    import matplotlib

    matplotlib.use("Agg")  # no display; must precede pyplot
    import matplotlib.pyplot as plt
    from matplotlib import colors as mcolors
    from matplotlib import patheffects
except ImportError as e:  # the caller tells the user how to install it
    print(f"error: {e.name or 'matplotlib'} is not installed for {sys.executable}", file=sys.stderr)
    sys.exit(MISSING_LIBRARY)


class PlotError(Exception):
    """An error about the input, reported as one line."""


# The colours of the paper's Fig. S6 (first series blue and solid, second green and dashed), then
# more series in further colours.
PALETTE = ["#1a59d9", "#1a9e33", "#d92626", "#f28c0d", "#8c40b3", "#737373"]


def read_csv(path):
    """Header and rows (lists of strings) of a CSV file."""
    try:
        with open(path, newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        raise PlotError(f"cannot read '{path}': {e.strerror}")
    if not rows:
        raise PlotError(f"'{path}' is empty")
    return rows[0], rows[1:]


def number(text, path, line):
    try:
        v = float(text)
    except ValueError:
        raise PlotError(f"{path}:{line}: '{text}' is not a number")
    return v if math.isfinite(v) else math.nan  # NaN/Inf break a line instead of stretching the axes


def numeric_columns(path, header, rows, first=0):
    """Columns first.. of rows as float arrays (NaN for non-finite values)."""
    cols = [[] for _ in header[first:]]
    for i, row in enumerate(rows):
        if len(row) != len(header):
            raise PlotError(f"{path}:{i + 2}: {len(row)} fields, the header has {len(header)}")
        for k, text in enumerate(row[first:]):
            cols[k].append(number(text, path, i + 2))
    return [np.array(c, dtype=float) for c in cols]


def length_unit(max_abs):
    """A display unit for lengths in metres: (factor, name)."""
    if max_abs >= 1:
        return 1.0, "m"
    if max_abs >= 1e-3:
        return 1e3, "mm"
    if max_abs >= 1e-6:
        return 1e6, "µm"
    return 1e9, "nm"


def save(fig, args):
    fmt = args.format or os.path.splitext(args.out)[1].lstrip(".").lower() or "png"
    if fmt not in ("png", "svg", "pdf"):
        fmt = "png"
    metadata = {"Title": args.title} if args.title and fmt in ("png", "pdf") else None
    fig.savefig(args.out, format=fmt, metadata=metadata)
    plt.close(fig)


# ---- profile ------------------------------------------------------------------------------------


def figure_profile(args):
    header, rows = read_csv(args.data)
    if len(header) < 2:
        raise PlotError(f"'{args.data}' has no data column (header: {','.join(header)})")
    if not rows:
        raise PlotError(f"'{args.data}' has no rows")
    x, *cols = numeric_columns(args.data, header, rows)
    names = header[1:]
    kind = header[0]
    if kind == "x_m":
        scale, unit = length_unit(np.nanmax(np.abs(x)) if np.isfinite(x).any() else 1.0)
        xlabel = f"x ({unit})"
    elif kind in ("x_px", "y_px"):
        scale, unit = 1.0, "pixel"
        xlabel = f"{kind[0]} (pixel)"
    else:
        raise PlotError(f"'{args.data}': the first column must be x_m, x_px or y_px, not '{kind}'")
    xs = x * scale
    # One pixel: the spacing of the samples (pixel centres).
    pitch = abs(xs[1] - xs[0]) if len(xs) > 1 and np.isfinite(xs[:2]).all() else 1.0

    fig, ax = plt.subplots(figsize=(args.width / 100, args.height / 100), dpi=100)
    series = [(n, c) for n, c in zip(names, cols) if n != "abs_diff"]
    top = -math.inf
    for k, (name, y) in enumerate(series):
        ax.plot(xs, y, color=PALETTE[k % len(PALETTE)], linestyle="--" if k == 1 else "-", linewidth=1.8,
                label=name, zorder=3 + k)
        if np.isfinite(y).any():
            top = max(top, np.nanmax(y))
    if "abs_diff" in names:
        d = cols[names.index("abs_diff")] * args.diff_scale
        a, b = (series[0][0], series[1][0]) if len(series) >= 2 else ("a", "b")
        label = f"|{a} - {b}|" + (f" × {args.diff_scale:g}" if args.diff_scale != 1 else "")
        ax.plot(xs, d, color="black", linestyle=":", linewidth=1.8, label=label, zorder=10)
        if np.isfinite(d).any():
            top = max(top, np.nanmax(d))
    # One pixel's extent as a cyan bar, centred on the peak of the last series, just above the data.
    last = series[-1][1] if series else None
    if last is not None and np.isfinite(last).any() and math.isfinite(top):
        i = int(np.nanargmax(last))
        y = 1.03 * top if top > 0 else top + 0.03 * abs(top) + 1e-30
        width_text = f"{pitch:.4g} {unit}" if unit != "pixel" else ""
        ax.plot([xs[i] - pitch / 2, xs[i] + pitch / 2], [y, y], color="#00bfe6", linewidth=5,
                solid_capstyle="butt", label=f"one pixel ({width_text})" if width_text else "one pixel",
                zorder=11)
    finite = xs[np.isfinite(xs)]
    if len(finite):
        ax.set_xlim(finite.min() - pitch / 2, finite.max() + pitch / 2)
    lo, hi = ax.get_ylim()
    if lo > 0:  # intensities: the axis starts at zero
        ax.set_ylim(0, hi)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(args.ylabel)
    ax.set_title(args.title)
    ax.grid(True, color="#e0e0e0", linewidth=0.8)
    ax.legend(loc="best", framealpha=0.9)
    fig.tight_layout()
    return fig


# ---- convergence --------------------------------------------------------------------------------


def figure_convergence(args):
    header, rows = read_csv(args.data)
    need = ["run", "spp", "seconds", args.metric]
    for n in need:
        if n not in header:
            raise PlotError(f"'{args.data}' has no column '{n}' (header: {','.join(header)})")
    runs = {}
    for i, row in enumerate(rows):
        if len(row) != len(header):
            raise PlotError(f"{args.data}:{i + 2}: {len(row)} fields, the header has {len(header)}")
        rec = dict(zip(header, row))
        runs.setdefault(rec["run"], []).append(
            tuple(number(rec[n], args.data, i + 2) for n in ("spp", "seconds", args.metric)))
    if not runs:
        raise PlotError(f"'{args.data}' has no rows")
    fig, axes = plt.subplots(1, 2, figsize=(args.width / 100, args.height / 100), dpi=100)
    ylabel = {"rmse": "RMSE", "rel_mse": "relative MSE", "max_error": "max error (of the peak)"}.get(
        args.metric, args.metric)
    for k, (name, pts) in enumerate(runs.items()):
        pts = [p for p in pts if p[0] > 0 and p[1] > 0 and p[2] > 0 and all(map(math.isfinite, p))]
        if not pts:
            continue
        spp, sec, err = (np.array(v) for v in zip(*pts))
        colour = PALETTE[k % len(PALETTE)]
        axes[0].plot(spp, err, "o-", color=colour, label=name, markersize=3.5)
        axes[1].plot(sec, err, "o-", color=colour, label=name, markersize=3.5)
        if k == 0 and len(spp) > 1:  # the Monte Carlo rate through the first run's first point
            slope = -1.0 if args.metric in ("rel_mse",) else -0.5
            guide = err[0] * (spp / spp[0]) ** slope
            axes[0].plot(spp, guide, color="#999999", linestyle="--", linewidth=1,
                         label="∝ 1/spp" if slope == -1 else "∝ 1/√spp")
    for ax, xl in zip(axes, ("samples per pixel", "render time (s)")):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(xl)
        ax.set_ylabel(ylabel)
        ax.grid(True, which="both", color="#e6e6e6", linewidth=0.6)
        if ax.lines:
            ax.legend(loc="best", framealpha=0.9)
    fig.suptitle(args.title)
    fig.tight_layout()
    return fig


# ---- disc map -----------------------------------------------------------------------------------


def disc_grids(path):
    """{disc name: (grid, extent)} in order of appearance from a CSV [disc,]u,v,value on regular grids."""
    header, rows = read_csv(path)
    named = header[:1] == ["disc"]
    cols = header[1:4] if named else header[:3]
    if cols != ["u", "v", "value"]:
        raise PlotError(f"'{path}': the header must be [disc,]u,v,value (got {','.join(header)})")
    groups = {}
    for i, row in enumerate(rows):
        if len(row) != len(header):
            raise PlotError(f"{path}:{i + 2}: {len(row)} fields, the header has {len(header)}")
        name = row[0] if named else ""
        rest = row[1:4] if named else row[:3]
        groups.setdefault(name, []).append([number(t, path, i + 2) for t in rest])
    if not groups:
        raise PlotError(f"'{path}' has no rows")
    grids = {}
    for name, pts in groups.items():
        u, v, val = (np.array(c) for c in zip(*pts))
        us, vs = np.unique(u), np.unique(v)
        if len(us) * len(vs) != len(u):
            raise PlotError(f"'{path}': the points{' of ' + name if name else ''} do not form a regular grid "
                            f"({len(us)} u values × {len(vs)} v values for {len(u)} points)")
        grid = np.full((len(vs), len(us)), np.nan)
        grid[np.searchsorted(vs, v), np.searchsorted(us, u)] = val
        U, V = np.meshgrid(us, vs)
        grid[U * U + V * V > 1 + 1e-12] = np.nan  # outside the projected hemisphere
        du = (us[1] - us[0]) if len(us) > 1 else 1.0
        dv = (vs[1] - vs[0]) if len(vs) > 1 else 1.0
        grids[name] = (grid, [us[0] - du / 2, us[-1] + du / 2, vs[0] - dv / 2, vs[-1] + dv / 2])
    return grids


def disc_points(path, discs):
    """Markers from a CSV [disc,]u,v,label[,marker[,size]]: (disc, u, v, label, marker, size)."""
    header, rows = read_csv(path)
    named = header[:1] == ["disc"]
    rest = header[1:] if named else header
    if rest[:3] != ["u", "v", "label"] or any(h not in ("marker", "size") for h in rest[3:]):
        raise PlotError(f"'{path}': the header must be [disc,]u,v,label[,marker[,size]] (got {','.join(header)})")
    points = []
    for i, row in enumerate(rows):
        if len(row) != len(header):
            raise PlotError(f"{path}:{i + 2}: {len(row)} fields, the header has {len(header)}")
        rec = dict(zip(rest, row[1:] if named else row))
        disc = row[0] if named else next(iter(discs))
        if disc not in discs:
            raise PlotError(f"{path}:{i + 2}: no disc '{disc}' in the data")
        marker = rec.get("marker") or "o"
        if marker not in ("o", "x"):
            raise PlotError(f"{path}:{i + 2}: marker '{marker}' is neither o (a ring) nor x (a cross)")
        size = number(rec["size"], path, i + 2) if rec.get("size") else 7.0
        points.append((disc, number(rec["u"], path, i + 2), number(rec["v"], path, i + 2), rec["label"], marker,
                       size))
    return points


def figure_disc_map(args):
    grids = disc_grids(args.data)
    values = np.concatenate([g.ravel() for g, _ in grids.values()])
    finite = values[np.isfinite(values)]
    peak = finite.max() if len(finite) else 0.0
    cmap = matplotlib.colormaps["viridis"].copy()
    cmap.set_bad("white")
    empty = not peak > 0 and args.scale != "linear"  # nothing to show on a dB or log scale

    def shown_of(grid):
        if empty:
            return grid
        if args.scale == "db":
            with np.errstate(divide="ignore", invalid="ignore"):
                db = np.where(grid > 0, 10 * np.log10(grid / peak), -np.inf)
            return np.where(np.isnan(grid), np.nan, np.maximum(db, -args.db_range))
        if args.scale == "log":
            return np.where(np.isnan(grid), np.nan, np.maximum(grid, lo))
        return grid

    if args.scale == "db":
        norm = mcolors.Normalize(vmin=-args.db_range, vmax=0)
        bar_label = f"{args.value_label} (dB, 0 dB = {peak:.4g})"
    elif args.scale == "log":
        positive = finite[finite > 0]
        lo = max(positive.min(), peak * 10 ** (-args.db_range / 10)) if len(positive) else 1e-30
        norm = mcolors.LogNorm(vmin=lo, vmax=max(peak, lo * 10))
        bar_label = args.value_label
    else:
        norm = mcolors.Normalize(vmin=min(0.0, finite.min()) if len(finite) else 0, vmax=peak if peak > 0 else 1)
        bar_label = args.value_label
    if empty:
        bar_label = f"{args.value_label}: zero everywhere"

    k = len(grids)
    width = args.width or 80 + 420 * k + 130
    fig, axes = plt.subplots(1, k, figsize=(width / 100, args.height / 100), dpi=100, squeeze=False)
    axes = list(axes[0])
    t = np.linspace(0, 2 * np.pi, 361)
    for ax, (name, (grid, extent)) in zip(axes, grids.items()):
        if empty:  # a neutral disc, not the colour of "−40 dB"
            ax.imshow(np.ma.masked_invalid(np.where(np.isnan(grid), np.nan, 0.0)), origin="lower", extent=extent,
                      cmap=mcolors.ListedColormap(["#e6e6e6"]), interpolation="nearest")
        else:
            ax.imshow(np.ma.masked_invalid(shown_of(grid)), origin="lower", extent=extent, cmap=cmap, norm=norm,
                      interpolation="nearest")
        ax.plot(np.cos(t), np.sin(t), color="black", linewidth=1.2)  # the horizon
        for deg in (30, 60):  # rings of constant θ
            r = math.sin(math.radians(deg))
            ax.plot(r * np.cos(t), r * np.sin(t), color="#888888", linewidth=0.7, linestyle=":")
            ax.text(r * math.cos(math.radians(45)), r * math.sin(math.radians(45)), f"θ = {deg}°", color="black",
                    fontsize=8, path_effects=[patheffects.withStroke(linewidth=2, foreground="white")])
        ax.set_xlim(-1.05, 1.05)
        ax.set_ylim(-1.05, 1.05)
        ax.set_aspect("equal")
        ax.set_xlabel("sinθ cosφ")
        if ax is axes[0]:
            ax.set_ylabel("sinθ sinφ")
        if name:
            ax.set_title(name)
    if args.points:
        where = dict(zip(grids, axes))
        placed = []  # (disc, u, v) of the labels drawn so far
        for disc, pu, pv, label, marker, size in disc_points(args.points, grids):
            ax = where[disc]
            if marker == "o":  # a red ring with a white halo
                ax.plot([pu], [pv], marker="o", markersize=size, markerfacecolor="none", markeredgecolor="white",
                        markeredgewidth=3.5, zorder=5)
                ax.plot([pu], [pv], marker="o", markersize=size, markerfacecolor="none", markeredgecolor="#e62020",
                        markeredgewidth=1.8, zorder=6)
            else:  # a white cross with a black outline
                ax.plot([pu], [pv], marker="x", markersize=size, color="black", markeredgewidth=3.5, zorder=5)
                ax.plot([pu], [pv], marker="x", markersize=size, color="white", markeredgewidth=1.5, zorder=6)
            if label:
                # Labels of markers that (nearly) coincide — two lobes leaving in one direction — are
                # stacked downwards instead of printed over each other.
                stack = sum(1 for d, u, v in placed if d == disc and math.hypot(u - pu, v - pv) < 0.05)
                placed.append((disc, pu, pv))
                ax.annotate(label, (pu, pv), textcoords="offset points",
                            xytext=(size / 2 + 3, size / 2 + 1 - 11 * stack),
                            color="#a00000" if marker == "o" else "black", fontsize=8, zorder=7,
                            path_effects=[patheffects.withStroke(linewidth=2, foreground="white")])
    fig.suptitle(args.title)
    if empty:  # no scale to show
        fig.text(0.5, 0.03, bar_label, ha="center")
    else:
        bar = fig.colorbar(matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap), ax=axes, fraction=0.046 / k,
                           pad=0.04 / k)
        bar.set_label(bar_label)
    return fig


def figure_accuracy_map(args):
    header, rows = read_csv(args.data)
    need = ["family", "row", "column", "integrator", "error", "tolerance"]
    missing = [c for c in need if c not in header]
    if missing:
        raise PlotError(f"'{args.data}': missing column(s) {', '.join(missing)}")
    col = {name: header.index(name) for name in need}
    families = {}  # family → (row labels, column labels, {(row, column): ratio}) in order of appearance
    for line, r in enumerate(rows, start=2):
        fam = r[col["family"]]
        rlabels, clabels, cells = families.setdefault(fam, ([], [], {}))
        rl, cl = r[col["row"]], r[col["column"]] + " | " + r[col["integrator"]]
        if rl not in rlabels:
            rlabels.append(rl)
        if cl not in clabels:
            clabels.append(cl)
        err = number(r[col["error"]], args.data, line)
        tol = number(r[col["tolerance"]], args.data, line)
        cells[(rl, cl)] = err / tol if tol > 0 else math.inf
    if not families:
        raise PlotError(f"'{args.data}': no cells")
    cmap = matplotlib.colormaps["RdYlGn_r"].copy()
    cmap.set_bad("#dddddd")
    norm = mcolors.LogNorm(vmin=1e-3, vmax=1e3)  # centred on error = tolerance
    # Each panel: its rows plus room for the column labels below it (they are long).
    longest = max(len(c) for f in families.values() for c in f[1])
    heights = [0.14 * len(f[0]) + 0.45 + 0.055 * longest for f in families.values()]
    widest = max(len(f[1]) for f in families.values())
    width = args.width or int(max(900, 300 + 13 * widest))
    fig, axes = plt.subplots(len(families), 1, figsize=(width / 100, sum(heights) + 0.8), dpi=100, squeeze=False,
                             gridspec_kw={"height_ratios": heights}, layout="constrained")
    for ax, (fam, (rlabels, clabels, cells)) in zip(axes[:, 0], families.items()):
        grid = np.full((len(rlabels), len(clabels)), np.nan)
        for (rl, cl), v in cells.items():
            grid[rlabels.index(rl), clabels.index(cl)] = max(v, 1e-3)
        ax.imshow(np.ma.masked_invalid(grid), cmap=cmap, norm=norm, aspect="auto", interpolation="nearest")
        bad = np.argwhere(np.nan_to_num(grid) > 1)
        for i, j in bad:
            ax.plot([j], [i], marker="x", color="black", markersize=5, markeredgewidth=1.2)
        ax.set_yticks(range(len(rlabels)))
        ax.set_yticklabels(rlabels, fontsize=6)
        ax.set_xticks(range(len(clabels)))
        ax.set_xticklabels(clabels, fontsize=5, rotation=90)
        failed = len(bad)
        ax.set_title(f"{fam}: {len(cells)} cells, {failed} beyond tolerance", fontsize=9)
    fig.suptitle(args.title)
    bar = fig.colorbar(matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap), ax=list(axes[:, 0]), fraction=0.02, pad=0.01,
                       aspect=40)
    bar.set_label("error / tolerance")
    return fig


# ---- command line -------------------------------------------------------------------------------


def parse_args(argv):
    """The command line: a namespace whose .figure(args) draws the plot (tests call it directly)."""
    parser = argparse.ArgumentParser(prog="phasor_plot.py", description="phasor's plots (matplotlib).")
    sub = parser.add_subparsers(dest="command", required=True)

    def common(p, width, height):
        p.add_argument("--data", required=True, help="input CSV")
        p.add_argument("--out", required=True, help="output file")
        p.add_argument("--format", choices=["png", "svg", "pdf"], help="default: from --out's extension")
        p.add_argument("--title", default="")
        p.add_argument("--width", type=int, default=width, help="pixels")
        p.add_argument("--height", type=int, default=height, help="pixels")

    p = sub.add_parser("profile", help="line plot of image rows or columns")
    common(p, 1000, 600)
    p.add_argument("--ylabel", default="intensity")
    p.add_argument("--diff-scale", type=float, default=1.0, help="magnification of abs_diff")
    p.set_defaults(figure=figure_profile)

    p = sub.add_parser("convergence", help="error against spp and time")
    common(p, 1200, 500)
    p.add_argument("--metric", default="rmse", help="the CSV column to plot (rmse, rel_mse, max_error)")
    p.set_defaults(figure=figure_convergence)

    p = sub.add_parser("accuracy-map", help="the accuracy map: error/tolerance per cell, one heat map per family")
    common(p, 0, 600)  # width 0: from the number of columns; the height follows the rows
    p.set_defaults(figure=figure_accuracy_map)

    p = sub.add_parser("disc-map", help="a value over the projected hemisphere (one disc per 'disc' name)")
    common(p, 0, 520)  # width 0: from the number of discs
    p.add_argument("--points", help="CSV u,v,label of markers")
    p.add_argument("--scale", choices=["db", "log", "linear"], default="db")
    p.add_argument("--db-range", type=float, default=40.0, help="dB shown below the maximum (db, log)")
    p.add_argument("--value-label", default="value")
    p.set_defaults(figure=figure_disc_map)

    args = parser.parse_args(argv)
    if not ((16 <= args.width or args.width == 0) and args.width <= 16384 and 16 <= args.height <= 16384):
        parser.error("--width and --height must be within 16..16384 pixels")
    return args


def main(argv):
    args = parse_args(argv)
    try:
        save(args.figure(args), args)
    except PlotError as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    except OSError as e:  # a failed write (full disk, file-size limit): the system's reason
        print(f"error: {e.strerror or e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
