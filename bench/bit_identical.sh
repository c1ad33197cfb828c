#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Are two phasor binaries' renders bit-identical? Renders every validation and showcase scene
# (scenes/validation/*.wscene, scenes/showcase/*.wscene) small, with the same seed and spp, with
# each of `grt`, `sample_solve` and `ray`, by both binaries, and compares the EXRs pixel for pixel,
# every channel (OpenImageIO's idiff with zero tolerance). For a refactoring that must not change
# a single sample (issue 25: the prepared kernel, the estimator in named steps).
#
#   bench/bit_identical.sh OLD_PHASOR NEW_PHASOR [OUT_DIR]
#
# Environment: SPP (default 4), SEED (default 7), THREADS (default 2; renders are deterministic
# for any thread count). Scenes with `Define res` are rendered at 48×36 (or 16 for a scalar res).
# A pair that both binaries refuse (an integrator a scene's detector cannot serve) is reported as
# refused, not compared; a pair that only one of them refuses is a difference. Exit status 0 if
# every rendered pair is identical, 1 otherwise.
set -u
if [ $# -lt 2 ]; then
    echo "usage: $0 OLD_PHASOR NEW_PHASOR [OUT_DIR]" >&2
    exit 2
fi
old=$(realpath "$1")
new=$(realpath "$2")
root=$(cd "$(dirname "$0")/.." && pwd)
out=${3:-$(mktemp -d)}
spp=${SPP:-4}
seed=${SEED:-7}
threads=${THREADS:-2}
command -v idiff > /dev/null || { echo "$0: needs idiff (Debian: openimageio-tools)" >&2; exit 2; }
mkdir -p "$out/old" "$out/new"

identical=0 different=0 refused=0
for scene in "$root"/scenes/validation/*.wscene "$root"/scenes/showcase/*.wscene; do
    name=$(basename "$scene" .wscene)
    defines=()
    if grep -Eq '^Define res = \[' "$scene"; then defines=(-D "res=[48 36]")
    elif grep -Eq '^Define res = [0-9]' "$scene"; then defines=(-D "res=16"); fi
    for integrator in grt sample_solve ray; do
        args=(render "$scene" --integrator "$integrator" --spp "$spp" --seed "$seed" --threads "$threads" --quiet
              "${defines[@]}")
        a="$out/old/$name.$integrator.exr" b="$out/new/$name.$integrator.exr"
        "$old" "${args[@]}" -o "$a" > "$out/old/$name.$integrator.log" 2>&1
        ra=$?
        "$new" "${args[@]}" -o "$b" > "$out/new/$name.$integrator.log" 2>&1
        rb=$?
        if [ $ra -ne 0 ] && [ $rb -ne 0 ]; then
            printf '%-28s %-13s refused by both (exit %d)\n' "$name" "$integrator" $ra
            refused=$((refused + 1))
        elif [ $ra -ne 0 ] || [ $rb -ne 0 ]; then
            printf '%-28s %-13s DIFFERENT: exit %d (old) vs %d (new)\n' "$name" "$integrator" $ra $rb
            different=$((different + 1))
        elif idiff -fail 0 -failpercent 0 -warn 0 -warnpercent 0 "$a" "$b" > "$out/$name.$integrator.idiff" 2>&1; then
            printf '%-28s %-13s identical\n' "$name" "$integrator"
            identical=$((identical + 1))
        else
            printf '%-28s %-13s DIFFERENT (%s)\n' "$name" "$integrator" "$(grep -m1 -i 'max error' "$out/$name.$integrator.idiff")"
            different=$((different + 1))
        fi
    done
done
echo "bit_identical: $identical identical, $different different, $refused refused by both ($spp spp, seed $seed; renders in $out)"
[ $different -eq 0 ]
