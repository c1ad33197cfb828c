#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Where a `ray` integrator's ray goes, in instructions (valgrind's callgrind; independent of the
# machine's load): bench_ray's scene, one single-threaded 4-spp pass, the same rays replayed through
# bare rtcIntersect1 (bench_ray --instructions). Prints a Markdown table: raw Embree's instructions
# per ray, the integrator's, their ratio (the instruction-count counterpart of bench_ray's
# "integrator / raw Embree"), and the integrator's instructions per ray by part of the program.
#
#   bench/ray_cost.sh BENCH_RAY [LEVELS [RES]]     (defaults: 6, 64 — ~1 min)
#
# Instructions are not time: raw Embree's traversal of a large BVH waits on memory more than the
# integrator's shading does, so bench_ray's wall-time ratio is lower than this one.
set -euo pipefail
if [ $# -lt 1 ]; then
    echo "usage: $0 BENCH_RAY [LEVELS [RES]]" >&2
    exit 2
fi
bin=$(realpath "$1")
levels=${2:-6}
res=${3:-64}
root=$(cd "$(dirname "$0")/.." && pwd)
command -v valgrind > /dev/null || { echo "$0: needs valgrind" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# shellcheck source=bench/callgrind_env.sh
. "$root/bench/callgrind_env.sh"
callgrind_preload "$work" "$bin"

# run NAME FUNCTION: callgrind counting only inside FUNCTION (bench_ray's CountedReplay or
# CountedRender); its output in $work/NAME.out, bench_ray's counts in $work/NAME.txt.
run() {
    "${preload[@]}" valgrind --tool=callgrind --callgrind-out-file="$work/$1.out" --collect-atstart=no \
        --toggle-collect="$2" "$bin" --instructions --levels "$levels" --res "$res" > "$work/$1.txt" 2> /dev/null
}
run raw '*CountedReplay(*'
run render '*CountedRender(*'
rays=$(awk '/^replayed_rays/ { print $2 }' "$work/raw.txt")
rendered=$(awk '/^rendered_rays/ { print $2 }' "$work/render.txt")
total() { awk '/^summary:/ { print $2 }' "$work/$1.out"; }
raw=$(total raw)
integrator=$(total render)

echo "## Instructions per ray: the \`ray\` integrator against raw Embree (callgrind)"
echo
echo "bench_ray scene at Catmull-Clark level $levels, ${res}x${res}, one 4-spp pass, 1 thread: $rays rays replayed, $rendered traced by the integrator"
echo
awk -v raw="$raw" -v integ="$integrator" -v rays="$rays" -v rendered="$rendered" 'BEGIN {
    printf "| measurement | instructions per ray |\n|---|---:|\n"
    printf "| raw rtcIntersect1 replay | %.0f |\n", raw / rays
    printf "| `ray` integrator (everything in its render) | %.0f |\n", integ / rendered
    printf "| raw / integrator | **%.1f %%** |\n\n", 100 * (raw / rays) / (integ / rendered)
}'
# The integrator's exclusive instructions by part (function names; the first pattern that matches).
callgrind_annotate --threshold=100 "$work/render.out" 2> /dev/null | awk -v rendered="$rendered" -v integ="$integrator" '
    /^ *[0-9,]+ +\([ 0-9.]+%\) +/ {
        n = $1; gsub(",", "", n); line = $0
        if (line ~ /PROGRAM TOTALS/) next
        # The name of the function without its arguments (a signature names types such as Sampler&).
        fn = line; sub(/^ *[0-9,]+ +\([ 0-9.]+%\) +/, "", fn); sub(/ \[.*$/, "", fn)
        i = index(fn, ":"); if (i > 0) fn = substr(fn, i + 1)
        gsub(/\(anonymous namespace\)::/, "", fn)
        i = index(fn, "("); if (i > 0) fn = substr(fn, 1, i - 1)
        part = "other"
        if (line ~ /libembree3/) part = "Embree (traversal, triangle tests)"
        else if (line ~ /\/math\/|libm\.so/) part = "libm (sin, cos, hypot)"
        else if (fn ~ /Accel::|UserIntersect|UserOccluded|::Intersect$|FtzDaz/) part = "phasor around Embree (query set-up, analytic shapes, double refinement)"
        else if (fn ~ /Interaction$|PointAt|Frame::|SpawnOrigin|ShadowRay|Transform::|::Mesh$/) part = "hit geometry (point, normals, frame, spawn)"
        else if (fn ~ /Sobol|Sampler::(Start|Get)|Scramble|ReverseBits|MixBits|::Hash$/) part = "sampler (Sobol'"'"', Owen scrambling)"
        else if (fn ~ /Light|Emission|MeshShape::Sample$|Transmittance|Mis/) part = "lights (selection, sampling, NEE, MIS)"
        else if (fn ~ /Material|Kernel|Smooth|Diffuse|Conductor|Fresnel|Bare|LayerStack|Lobe/) part = "kernels (prepare, sample, evaluate)"
        else if (fn ~ /Camera|Detector/) part = "camera"
        else if (fn ~ /Film|Spectrum|Wavelength|Cie|SensorResponse|Xyz|Render|tbb|Tile|Scratch|memset|malloc|free|mutex/) part = "film, wavelengths, render loop"
        else if (fn ~ /RayIntegrator|RussianRoulette/) part = "integrator loop"
        sum[part] += n
    }
    END {
        printf "| part of the integrator | instructions per ray | share |\n|---|---:|---:|\n"
        k = 0
        for (p in sum) order[++k] = p
        for (i = 1; i <= k; ++i) for (j = i + 1; j <= k; ++j) if (sum[order[j]] > sum[order[i]]) { t = order[i]; order[i] = order[j]; order[j] = t }
        for (i = 1; i <= k; ++i) printf "| %s | %.0f | %.1f %% |\n", order[i], sum[order[i]] / rendered, 100 * sum[order[i]] / integ
    }'
