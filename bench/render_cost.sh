#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# What a render costs, in instructions, with two phasor binaries side by side: valgrind's callgrind
# counts the instructions of the render loop alone (PixelIntegrator::Render without its work
# estimate, whose sample count depends on elapsed time; scene loading excluded), one thread, for
# `grt` and `ray` on the Cornell box (scenes/validation/grt_cornell.wscene) and every showcase
# scene, small. Instruction counts do not depend on the machine's load, so two builds compare
# exactly on a shared machine; the table gives both and their ratio.
#
#   bench/render_cost.sh OLD_PHASOR NEW_PHASOR [SPP]
#
# Environment: SCENES (default: the Cornell box and scenes/showcase/*), INTEGRATORS (default:
# "grt ray"). Showcase scenes are rendered at 32×24 (their `Define res`), the Cornell box at 16².
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
scenes=${SCENES:-"$root/scenes/validation/grt_cornell.wscene $(ls "$root"/scenes/showcase/*.wscene | tr '\n' ' ')"}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Valgrind 3.19 stops at an instruction of libhwy's timer probe (an OpenImageIO dependency, run
# when the library loads): a stub of that one function, preloaded, lets the program start.
preload=()
if ldd "$new" | grep -q libhwy; then
    printf '#include <cstdint>\nnamespace hwy { namespace platform { uint64_t TimerResolution() { return 1; } } }\n' \
        > "$work/hwy_stub.cpp"
    c++ -O2 -shared -fPIC "$work/hwy_stub.cpp" -o "$work/libhwy_stub.so"
    preload=(env LD_PRELOAD="$work/libhwy_stub.so")
fi

# Instructions of the render loop of one render (the "summary:" line of callgrind's output).
count() {
    local bin=$1 scene=$2 integrator=$3 res
    if grep -Eq '^Define res = \[' "$scene"; then res=(-D "res=[32 24]"); else res=(-D "res=16"); fi
    "${preload[@]}" valgrind --tool=callgrind --callgrind-out-file="$work/cg.out" --collect-atstart=no \
        --toggle-collect='phasor::PixelIntegrator::Render(*' --toggle-collect='phasor::PixelIntegrator::EstimateWork(*' \
        "$bin" render "$scene" --integrator "$integrator" --spp "$spp" --seed 7 --threads 1 --quiet "${res[@]}" \
        -o "$work/out.exr" > /dev/null 2>&1
    awk '/^summary:/ { print $2 }' "$work/cg.out"
}

printf '| scene | integrator | old [Minstr] | new [Minstr] | new/old |\n|---|---|---:|---:|---:|\n'
for scene in $scenes; do
    for integrator in ${INTEGRATORS:-grt ray}; do
        a=$(count "$old" "$scene" "$integrator")
        b=$(count "$new" "$scene" "$integrator")
        awk -v s="$(basename "$scene" .wscene)" -v i="$integrator" -v a="$a" -v b="$b" \
            'BEGIN { printf "| %s | %s | %.1f | %.1f | %.3f |\n", s, i, a / 1e6, b / 1e6, b / a }'
    done
done
