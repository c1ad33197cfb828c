#!/usr/bin/env bash
# work_estimate_calibration.sh PHASOR SOURCE_DIR OUTDIR — the work estimate of each sampling
# integrator (the pilot of PixelIntegrator::EstimateWork, recorded as phasor:work_estimate_seconds)
# predicts the render's time: on one thread, the estimate is the render's CPU time, which this
# script measures (the process's user + system time, less nothing: loading and the pilot itself are
# part of the error) — load-independent, as the estimate is taken in the pilot thread's CPU time.
# Each integrator on the soap bubble (the film under three soft sources: its estimate was 2.1×
# the render before the pilot covered the whole image) and on a Cornell box; every ratio
# estimate / measured must lie within [0.5, 2].
set -u
phasor=$1 src=$2 out=$3/work_estimate_calibration
rm -rf "$out"; mkdir -p "$out"
source "$(dirname "$0")/common.sh"  # fail

# measure NAME SCENE INTEGRATOR ARGS…: prints "estimate measured".
measure() {
    local name=$1 scene=$2 integrator=$3; shift 3
    local times TIMEFORMAT='%U %S'  # bash's `time`: the child's user and system CPU seconds
    times=$( { time "$phasor" render "$scene" --integrator "$integrator" --threads 1 --quiet \
        -o "$out/$name.exr" "$@" >/dev/null 2>&1; } 2>&1 | tail -1)
    local estimate
    estimate=$(iinfo -v "$out/$name.exr" | sed -n 's/.*phasor:work_estimate_seconds: "\(.*\)"/\1/p')
    awk -v e="$estimate" -v t="$times" 'BEGIN { split(t, c, " "); printf "%s %.4g\n", e, c[1] + c[2] }'
}

for integrator in grt ray sample_solve; do
    for name in bubble cornell; do
        case $name in  # each scene with its arguments, one word each
            bubble) args=("$src/scenes/showcase/soap_bubble.wscene" -D "res=[48 48]" -D spp=96) ;;
            cornell) args=("$src/scenes/validation/grt_cornell.wscene" -D res=40 --spp 96) ;;
        esac
        read -r estimate measured <<<"$(measure "${name}_$integrator" "${args[0]}" "$integrator" "${args[@]:1}")"
        ratio=$(awk -v e="$estimate" -v m="$measured" 'BEGIN { printf "%.3f", (m > 0 ? e / m : 0) }')
        echo "$name $integrator: estimate $estimate s, measured $measured s of CPU, ratio $ratio"
        awk -v r="$ratio" 'BEGIN { exit !(r >= 0.5 && r <= 2) }' ||
            fail "$name with $integrator: the estimate ($estimate s) is $ratio × the render's CPU time ($measured s)"
    done
done

[[ $failures -eq 0 ]] || { echo "$failures failure(s)"; exit 1; }
echo "work estimates within a factor 2 of the CPU time"
