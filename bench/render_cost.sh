#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# What a render costs, in instructions, with two phasor binaries side by side: valgrind's callgrind
# counts the instructions of the integrator's per-sample estimates alone (every
# `<Integrator>::EstimatePixel` call of the render loop; the work estimate's pilot samples, whose
# number depends on elapsed time, scene loading and the film excluded), one thread, for
# `grt` and `ray` on the Cornell box (scenes/validation/grt_cornell.wscene) and every showcase
# scene, small. Instruction counts do not depend on the machine's load, so two builds compare
# exactly on a shared machine; the table gives both and their ratio.
#
#   bench/render_cost.sh OLD_PHASOR NEW_PHASOR [SPP]
#
# Environment: SCENES (default: the Cornell box and scenes/showcase/*; paths relative to the
# repository, or absolute), INTEGRATORS (default: "grt ray"). Showcase scenes are rendered at 32×24
# (their `Define res`), the Cornell box at 16².
#
# OLD_ROOT: an older tree whose scenes the old binary renders instead (each scene at the same path
# under OLD_ROOT), for a binary that cannot read the current scenes. Where such a scene is a
# 'wscene 1' file that the new binary refuses only because a light's strength changed meaning in
# 'wscene 2', the new binary renders a copy made 'wscene 2' with `normalize_spectrum = false` on
# each such light (the old meaning, which phasor's own error message proposes), beside links to
# the old tree's assets: both binaries render the same scene.
set -euo pipefail
if [ $# -lt 2 ]; then
    echo "usage: $0 OLD_PHASOR NEW_PHASOR [SPP]" >&2
    exit 2
fi
old=$(realpath "$1")
new=$(realpath "$2")
spp=${3:-2}
root=$(cd "$(dirname "$0")/.." && pwd)
command -v valgrind > /dev/null || { echo "$0: needs valgrind" >&2; exit 2; }
scenes=${SCENES:-"scenes/validation/grt_cornell.wscene $(cd "$root" && ls scenes/showcase/*.wscene | tr '\n' ' ')"}
old_root=${OLD_ROOT:+$(realpath "$OLD_ROOT")}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# shellcheck source=bench/callgrind_env.sh
. "$root/bench/callgrind_env.sh"
callgrind_preload "$work" "$new"

# Instructions of one render's estimates (the "summary:" line of callgrind's output). Collection is
# toggled on entering and leaving each EstimatePixel (toggling on PixelIntegrator::Render, as this
# script first did, counts almost none of today's render loop: 0.6 M instructions for the beetle's
# 768 `ray` samples, which take 21 M); EstimateWork toggles it the other way round, so its pilot
# samples are not counted (its own few instructions per pilot sample are).
count() {
    local bin=$1 scene=$2 integrator=$3 res
    if grep -Eq '^Define res = \[' "$scene"; then res=(-D "res=[32 24]"); else res=(-D "res=16"); fi
    "${preload[@]}" valgrind --tool=callgrind --callgrind-out-file="$work/cg.out" --collect-atstart=no \
        --toggle-collect='phasor::*Integrator::EstimatePixel(*' --toggle-collect='phasor::PixelIntegrator::EstimateWork(*' \
        "$bin" render "$scene" --integrator "$integrator" --spp "$spp" --seed 7 --threads 1 --quiet "${res[@]}" \
        -o "$work/out.exr" > /dev/null 2>&1
    awk '/^summary:/ { print $2 }' "$work/cg.out"
}

# The old tree's scene `rel` as the new binary reads it (see OLD_ROOT above); prints its path.
upgraded() {
    local rel=$1 src="$old_root/$1" base sdir pdir f dst
    # A fresh folder per scene: real folders for the scene's path, links to the old tree's files
    # beside it and to its parent's other entries (assets, includes); nothing in the old tree is
    # written or removed.
    base=$(mktemp -d "$work/upgraded.XXXXXX")
    sdir=$(dirname "$rel") pdir=$(dirname "$(dirname "$rel")")
    mkdir -p "$base/$sdir"
    for f in "$old_root/$pdir"/*; do [ "$f" = "$old_root/$sdir" ] || ln -s "$f" "$base/$pdir/"; done
    for f in "$old_root/$sdir"/*; do [ "$f" = "$src" ] || ln -s "$f" "$base/$sdir/"; done
    dst="$base/$rel"
    { "$new" check "$src" 2>&1 || true; } | /usr/bin/env python3 -c '
import re, sys
src, dst = sys.argv[1], sys.argv[2]
lines = open(src).read().split("\n")
for m in re.finditer(r":(\d+):\d+: error: in a .wscene 1. file the .(\w+). of ", sys.stdin.read()):
    n, name = int(m.group(1)) - 1, m.group(2)
    lines[n] = re.sub(r"\b" + name + r"\s*=", "normalize_spectrum = false  " + name + " =", lines[n], count=1)
text = "\n".join(lines)
text = re.sub(r"(?m)^wscene 1\b", "wscene 2", text, count=1)
open(dst, "w").write(text)' "$src" "$dst"
    "$new" check "$dst" > /dev/null 2>&1 ||
        { echo "$0: the new binary cannot read $rel of the old tree even upgraded" >&2; exit 1; }
    echo "$dst"
}

printf '| scene | integrator | old [Minstr] | new [Minstr] | new/old |\n|---|---|---:|---:|---:|\n'
for scene in $scenes; do
    case $scene in /*) ;; *) scene="$root/$scene" ;; esac
    old_scene=$scene new_scene=$scene
    if [ -n "$old_root" ]; then
        rel=${scene#"$root"/}
        old_scene="$old_root/$rel"
        new_scene=$(upgraded "$rel")
    fi
    for integrator in ${INTEGRATORS:-grt ray}; do
        a=$(count "$old" "$old_scene" "$integrator")
        b=$(count "$new" "$new_scene" "$integrator")
        awk -v s="$(basename "$scene" .wscene)" -v i="$integrator" -v a="$a" -v b="$b" \
            'BEGIN { printf "| %s | %s | %.1f | %.1f | %.3f |\n", s, i, a / 1e6, b / 1e6, b / a }'
    done
done
