#!/usr/bin/env bash
# sweep.sh PHASOR EXR_EQUAL SOURCE_DIR OUTDIR [MPI_RANKS] — `render --sweep` (docs/distributed.md),
# on one process or on MPI_RANKS ranks (mpi_env.sh):
#  1. two --sweep options (2 × 2 values): one EXR and PNG per combination, named OUT-A=a-B=b.exr, each
#     equal bit for bit to the render of that combination with -D (under MPI: 4 renders, more than
#     the ranks, so whole renders go to the ranks);
#  2. one --sweep of 2 values (under MPI: no more renders than ranks, so each render's tiles are
#     shared), each equal to its separate render;
#  3. (one process only) bad sweeps: a value that does not load, two values that give one file
#     name, a name given by -D too, --checkpoint with --sweep, a malformed --sweep: exit status 1,
#     a clear error, nothing written.
set -u
phasor=$1 exr_equal=$2 src=$3 ranks=${5:-1}
out=$4/sweep_n$ranks
rm -rf "$out"; mkdir -p "$out"
scene=$src/scenes/validation/grt_cornell.wscene
source "$(dirname "$0")/common.sh"  # fail, run
source "$(dirname "$0")/mpi_env.sh"  # PH
common=(--spp 6)

# check_render SUFFIX DEFINES…: out/c-SUFFIX.exr (and .png) equals a separate render with DEFINES.
check_render() {
    local suffix=$1; shift
    local defines=() d
    for d in "$@"; do defines+=(-D "$d"); done
    [[ -f "$out/c-$suffix.exr" && -f "$out/c-$suffix.png" ]] || { fail "no c-$suffix.exr/.png: $(ls "$out")"; return; }
    "$phasor" render "$scene" "${common[@]}" "${defines[@]}" -o "$out/ref-$suffix.exr" --quiet || fail "reference $suffix failed"
    local diff
    diff=$("$exr_equal" "$out/ref-$suffix.exr" "$out/c-$suffix.exr") || fail "c-$suffix.exr differs from its own render: $diff"
}

# 1. -------------------------------------------------------------------------------------------
"${PH[@]}" render "$scene" "${common[@]}" -D res=20 --sweep lamp_radiance=2W/m^2/sr,4W/m^2/sr --sweep quality=1,2 \
    -o "$out/c.exr" 2>"$out/sweep1.log" || { cat "$out/sweep1.log"; fail "1: the sweep failed"; }
check_render "lamp_radiance=2W_m_2_sr-quality=1" res=20 "lamp_radiance=2W/m^2/sr" quality=1
check_render "lamp_radiance=2W_m_2_sr-quality=2" res=20 "lamp_radiance=2W/m^2/sr" quality=2
check_render "lamp_radiance=4W_m_2_sr-quality=1" res=20 "lamp_radiance=4W/m^2/sr" quality=1
check_render "lamp_radiance=4W_m_2_sr-quality=2" res=20 "lamp_radiance=4W/m^2/sr" quality=2
[[ $(ls "$out"/c-*.exr | wc -l) -eq 4 ]] || fail "1: expected 4 EXRs: $(ls "$out")"
if [[ $ranks -gt 1 ]]; then  # whole renders, and not all on rank 0
    grep -q "sweep: 4 renders of .*, whole renders shared over $ranks ranks" "$out/sweep1.log" || fail "1: not whole renders"
    others=$(for f in "$out"/c-*.exr; do iinfo -v "$f" | sed -n 's/.*phasor:mpi_rank: "\([0-9]*\)".*/\1/p'; done | grep -vc '^0$')
    [[ $others -ge 1 ]] || fail "1: rank 0 rendered every image"
fi
echo "1: 2 x 2 sweep, each render equal to its own"

# 2. -------------------------------------------------------------------------------------------
rm -f "$out"/c-*
"${PH[@]}" render "$scene" "${common[@]}" --sweep "res=12,20" -o "$out/c.exr" 2>"$out/sweep2.log" ||
    { cat "$out/sweep2.log"; fail "2: the sweep failed"; }
check_render "res=12" res=12
check_render "res=20" res=20
if [[ $ranks -gt 1 ]]; then
    grep -q "sweep: 2 renders of .*, each render's tiles shared over $ranks ranks" "$out/sweep2.log" || fail "2: not shared tiles"
fi
echo "2: 2-value sweep, each render equal to its own"

[[ $ranks -gt 1 ]] && exit $((failures > 0))

# 3. -------------------------------------------------------------------------------------------
refused() {  # refused REGEX ARGS…
    local regex=$1; shift
    rm -rf "$out/bad"; mkdir -p "$out/bad"
    run render "$scene" "${common[@]}" "$@" -o "$out/bad/c.exr"
    [[ $rc -eq 1 ]] || fail "3: '$*': exit status $rc, expected 1"
    grep -Eq -- "$regex" <<<"$stderr" || fail "3: '$*': stderr does not match /$regex/: $stderr"
    [[ -z "$(ls -A "$out/bad")" ]] || fail "3: '$*' wrote $(ls -A "$out/bad")"
}
refused "error: the sweep's render \[2/2\] res=-4: does not load; nothing rendered" --sweep res=8,-4
refused "renders \[1/2\] quality=4\*1: and \[2/2\] quality=4/1: would both write '.*c-quality=4_1.exr'" \
    --sweep "quality=4*1,4/1"
refused "'quality' is given both by -D and by --sweep" -D quality=2 --sweep quality=1,3
refused "'--sweep' renders several images; '--checkpoint' is for one render" --sweep quality=1,3 --checkpoint 10
refused "'--sweep' expects NAME=value1,value2" --sweep quality=1,,3
refused "'--sweep' names 'quality' twice" --sweep quality=1 --sweep quality=2
echo "3: bad sweeps refused"
exit $((failures > 0))
