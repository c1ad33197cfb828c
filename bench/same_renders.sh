#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Renders every validation and showcase scene with two phasor programs and compares the images
# pixel for pixel (idiff, tolerance 0): the check that a refactoring left every render unchanged
# (issue 25's acceptance: bit-identical at the same seed). Each scene is rendered with every
# Integrator it defines (by name) and with its default; `SPP` samples (default 4; the showcase
# scenes 1), `THREADS` threads (default 2). Renders are deterministic for any thread count, so the
# two programs must agree exactly; an integrator that refuses a scene must refuse it in both.
#
#   bench/same_renders.sh OLD/bin/phasor NEW/bin/phasor OUTDIR
#
# Prints one line per render ("same", "DIFFERS", "both refuse") and exits 1 if any render differs.
set -u
old=$1 new=$2 out=$3
spp=${SPP:-4}
threads=${THREADS:-2}
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
status=0
for scene in "$root"/scenes/validation/*.wscene "$root"/scenes/showcase/*.wscene; do
    base=$(basename "$scene" .wscene)
    s=$spp
    case "$scene" in */showcase/*) s=1 ;; esac
    # The scene's own integrators by name, and its default ("").
    names=$(sed -n 's/^Integrator *"[a-z_]*" *"\([A-Za-z0-9_]*\)".*/\1/p' "$scene")
    for name in "" $names; do
        tag=${name:-default}
        args="--spp $s --threads $threads --quiet"
        [ -n "$name" ] && args="$args --integrator $name"
        # shellcheck disable=SC2086
        "$old" render "$scene" $args -o "$out/$base.$tag.old.exr" > "$out/$base.$tag.old.log" 2>&1
        a=$?
        # shellcheck disable=SC2086
        "$new" render "$scene" $args -o "$out/$base.$tag.new.exr" > "$out/$base.$tag.new.log" 2>&1
        b=$?
        if [ $a -ne 0 ] && [ $b -ne 0 ]; then
            echo "both refuse  $base ($tag)"
        elif [ $a -ne 0 ] || [ $b -ne 0 ]; then
            echo "DIFFERS      $base ($tag): exit status $a (old) vs $b (new)"
            status=1
        elif idiff -fail 0 -failpercent 0 -warn 0 -warnpercent 0 "$out/$base.$tag.old.exr" "$out/$base.$tag.new.exr" > "$out/$base.$tag.diff" 2>&1; then
            echo "same         $base ($tag)"
        else
            echo "DIFFERS      $base ($tag): $(grep -m1 -i 'max' "$out/$base.$tag.diff")"
            status=1
        fi
    done
done
exit $status
