#!/usr/bin/env bash
# sigint.sh PHASOR SCENE SLOW_SCENE DOUBLE_SLIT OUTDIR — a stop signal during a render: Ctrl-C
# (SIGINT) or SIGTERM (`timeout`, batch schedulers).
#  1. SIGINT on SCENE after some passes: exit status 130, the partial image with the spp reached.
#  2. SIGINT during SLOW_SCENE's long first pass (≥ 15 s of CPU, more under load): it stops within
#     STOP_BOUND seconds of the signal (the pass is not waited for), says it is stopping, exits
#     130 and writes the partial image with each pixel's sample count.
#  3. SIGTERM (as `timeout` or a batch scheduler sends it), the same render: exit status 143, the same partial image.
#  4. SIGINT during a long `rs` render: exit status 130 within the bound, a message, no image
#     (rs's pixels need the whole field integral; docs/rs.md).
set -eu
phasor=$1 scene=$2 slow=$3 doubleslit=$4 outdir=$5
STOP_BOUND=5  # seconds from the signal to the exit (image written), generous for a loaded machine:
              # the fix stops in ~0.3 s, the pass it must not wait for is ≥ 15 s of CPU
command -v iinfo >/dev/null || { echo "iinfo (openimageio-tools) is needed to read the EXR metadata"; exit 1; }
now_ms() { date +%s%3N; }
fail() { echo "$*"; exit 1; }

# wait_cpu PID SECONDS: until the process has used SECONDS of its own CPU time (utime + stime,
# /proc/PID/stat) — load-independent, where a fixed sleep would signal a loaded machine's render
# before it got anywhere; at most 120 s of wall time, or until it exits.
cpu_seconds() { awk -v hz="$(getconf CLK_TCK)" '{ sub(/^.*\) /, ""); print ($12 + $13) / hz }' "/proc/$1/stat" 2>/dev/null || echo 0; }
wait_cpu() {
    for _ in $(seq 1200); do
        awk -v c="$(cpu_seconds "$1")" -v s="$2" 'BEGIN { exit !(c >= s) }' && return
        kill -0 "$1" 2>/dev/null || return
        sleep 0.1
    done
}

# meta FILE KEY: the value of the EXR string attribute phasor:KEY.
meta() { iinfo -v "$1" | sed -n "s/.*phasor:$2: \"\([^\"]*\)\".*/\1/p"; }

# 1. -------------------------------------------------------------------------------------------
out=$outdir/sigint.exr
rm -f "$out" "${out%.exr}.png"
"$phasor" render "$scene" -o "$out" --spp 100000 --quiet --threads 1 &
pid=$!
wait_cpu $pid 3  # past start-up (OIIO plug-ins, scene build, the work estimate), into the render
kill -INT $pid
set +e; wait $pid; code=$?; set -e
[[ $code -eq 130 ]] || fail "1: exit status $code, expected 130"
[[ -f "$out" && -f "${out%.exr}.png" ]] || fail "1: partial image not written"
[[ $(meta "$out" cancelled) == true ]] || fail "1: no cancelled flag"
reached=$(meta "$out" spp_reached)
[[ -n "$reached" && "$reached" -ge 1 && "$reached" -lt 100000 ]] || fail "1: bad spp_reached '$reached'"
echo "1: SIGINT stopped after $reached spp"

# run_stopped SIGNAL CPU_SECONDS EXPECTED_STATUS LOG ARGS… — runs phasor ARGS, sends SIGNAL once it
# has used CPU_SECONDS of CPU (as `timeout` or a batch scheduler would, but after work, not wall
# time); checks the exit status and the time from the signal to the exit.
run_stopped() {
    local sig=$1 cpu=$2 expected=$3 log=$4
    shift 4
    local start code elapsed pid
    "$phasor" "$@" 2>"$log" &
    pid=$!
    wait_cpu $pid "$cpu"
    start=$(now_ms)
    kill -s "$sig" $pid
    set +e; wait $pid; code=$?; set -e
    elapsed=$(( $(now_ms) - start ))
    [[ $code -eq $expected ]] || { cat "$log"; fail "$sig: exit status $code, expected $expected"; }
    (( elapsed <= STOP_BOUND * 1000 )) || fail "$sig: stopped ${elapsed} ms after the signal (bound ${STOP_BOUND} s)"
    echo "$sig: stopped ${elapsed} ms after the signal"
}

# check_partial FILE — cancelled, fewer spp than requested, a per-pixel sample count.
check_partial() {
    [[ -f "$1" && -f "${1%.exr}.png" ]] || fail "partial image $1 not written"
    [[ $(meta "$1" cancelled) == true ]] || fail "$1: no cancelled flag"
    local reached max
    reached=$(meta "$1" spp_reached) max=$(meta "$1" spp_max)
    [[ -n "$reached" && -n "$max" && "$reached" -le "$max" && "$max" -lt 64 ]] || fail "$1: spp_reached '$reached', spp_max '$max'"
    if [[ "$reached" != "$max" ]]; then
        iinfo -v "$1" | grep -q "channel list:.*samples" || fail "$1: pixels differ in spp but no 'samples' channel"
    fi
}

# 2. -------------------------------------------------------------------------------------------
out=$outdir/sigint_slow.exr
rm -f "$out" "${out%.exr}.png"
run_stopped INT 3 130 "$outdir/sigint_slow.log" render "$slow" -o "$out" --threads 1
grep -q "stopping" "$outdir/sigint_slow.log" || { cat "$outdir/sigint_slow.log"; fail "INT: no 'stopping' message"; }
check_partial "$out"

# 3. -------------------------------------------------------------------------------------------
out=$outdir/sigterm.exr
rm -f "$out" "${out%.exr}.png"
run_stopped TERM 3 143 "$outdir/sigterm.log" render "$slow" -o "$out" --threads 1 --quiet
check_partial "$out"

# 4. -------------------------------------------------------------------------------------------
out=$outdir/sigint_rs.exr
rm -f "$out" "${out%.exr}.png"
run_stopped INT 3 130 "$outdir/sigint_rs.log" render "$doubleslit" --integrator rs -D length=1000um \
    -D lambda=0.1um -o "$out" --threads 1
grep -q "interrupted: rs stopped after [0-9]* of [0-9]* steps.*no image written" "$outdir/sigint_rs.log" ||
    { cat "$outdir/sigint_rs.log"; fail "rs: no 'interrupted' message"; }
[[ ! -e "$out" && ! -e "${out%.exr}.png" ]] || fail "rs: an image was written"
[[ -z "$(ls -A "$outdir" | grep '\.tmp-')" ]] || fail "temporary files left in $outdir"
echo ok
