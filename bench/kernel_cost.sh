#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Per-kernel Sample and Eval time of two builds side by side: runs two `bench_kernels` binaries
# (bench/kernel_bench.cpp) alternately, ROUNDS times each (old, new, old, new, …), so that both see
# the same machine load over the run, and prints per kernel × preset the median ns per call of each
# and their ratio. For a change that must not make kernels slower (issue 25: the prepared kernel).
#
#   bench/kernel_cost.sh OLD_BENCH_KERNELS NEW_BENCH_KERNELS [FILTER]
#
# FILTER is a Google Benchmark regex (default: every kernel). Environment: ROUNDS (default 3),
# MIN_TIME (seconds per benchmark and round, default 0.05). Both binaries print a Markdown table
# "| kernel / preset | Sample [ns] | Eval [ns] | …" after Google Benchmark's own; an older binary
# without the "Eval prepared" column is read the same way. "Sample" and "Eval" are what a caller
# pays for one question about a new query (the new build: Prepare, then Sample or Eval); the new
# build's "Eval prepared" (Eval on a kernel prepared once, what light sampling and MIS pay per
# further direction) is shown without a ratio.
set -euo pipefail
if [ $# -lt 2 ]; then
    echo "usage: $0 OLD_BENCH_KERNELS NEW_BENCH_KERNELS [FILTER]" >&2
    exit 2
fi
old=$(realpath "$1")
new=$(realpath "$2")
filter=${3:-.}
rounds=${ROUNDS:-3}
min_time=${MIN_TIME:-0.05}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

for ((r = 0; r < rounds; ++r)); do
    for which in old new; do
        bin=$old; [ $which = new ] && bin=$new
        "$bin" --benchmark_filter="$filter" --benchmark_min_time="$min_time" 2> /dev/null |
            awk -v w=$which -v r=$r '/^\| kernel \/ preset/ { on = 1; next } on && /^\|[^-]/ {
                gsub(/ /, ""); n = split($0, f, "|"); print w, r, f[2], f[3], f[4], (n > 5 ? f[5] : "-") }' >> "$work/rows"
    done
done

# Median over the rounds of each (build, kernel, column); the table in the old binary's row order.
/usr/bin/env python3 - "$work/rows" "$rounds" "$(date -u '+%Y-%m-%d %H:%M UTC')" "$(cut -d' ' -f1-3 /proc/loadavg)" <<'EOF'
import statistics, sys
rows, rounds, when, load = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
data, order = {}, []
for line in open(rows):
    which, r, name, sample, ev, prepared = line.split()
    if name not in order:
        order.append(name)
    d = data.setdefault((which, name), {"sample": [], "eval": [], "prepared": []})
    d["sample"].append(float(sample))
    d["eval"].append(float(ev))
    if prepared != "-":
        d["prepared"].append(float(prepared))
med = lambda v: statistics.median(v) if v else float("nan")
print("| kernel / preset | Sample old [ns] | Sample new [ns] | new/old | Eval old [ns] | Eval new [ns] | new/old | Eval prepared new [ns] |")
print("|---|---:|---:|---:|---:|---:|---:|---:|")
ratios = {"sample": [], "eval": []}
for name in order:
    if ("old", name) not in data or ("new", name) not in data:
        print("| %s | only in the %s build |||||||" % (name, "old" if ("old", name) in data else "new"))
        continue
    o, n = data[("old", name)], data[("new", name)]
    cells = []
    for col in ("sample", "eval"):
        a, b = med(o[col]), med(n[col])
        ratios[col].append(b / a)
        cells += ["%.0f" % a, "%.0f" % b, "%.2f" % (b / a)]
    print("| %s | %s | %.0f |" % (name, " | ".join(cells), med(n["prepared"])))
geo = lambda v: statistics.geometric_mean(v) if v else float("nan")
print("\nGeometric mean of new/old over %d presets: Sample %.2f, Eval %.2f (median of %d alternating rounds each; "
      "%s, load average %s at the end)" % (len(ratios["sample"]), geo(ratios["sample"]), geo(ratios["eval"]), rounds,
                                          when, load))
EOF
