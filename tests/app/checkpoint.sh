#!/usr/bin/env bash
# checkpoint.sh PHASOR EXR_EQUAL SOURCE_DIR OUTDIR [MPI_RANKS] — checkpoints and resume
# (docs/distributed.md), on one process, or with MPI_RANKS > 1 under mpirun (mpi_env.sh):
#  1. a render stopped by SIGTERM after its first checkpoint, then `--resume`d, equals the
#     uninterrupted render bit for bit (every channel, exr_equal); the checkpoint was written on the
#     stop, and again at the end;
#  2. a finished render's checkpoint resumed to a larger --spp equals a fresh render at that spp;
#  3. a process killed (SIGKILL) while it writes a checkpoint (PHASOR_TEST_CHECKPOINT_PAUSE holds
#     it between writing the temporary and the rename) leaves the previous checkpoint intact, and
#     resuming that one still gives the uninterrupted image;
#  4. (one process only) a truncated, corrupted, foreign (seed, sampler, integrator, resolution,
#     scene) or non-checkpoint file, a --spp below what is done, and rs with --checkpoint are refused
#     with a clear error, exit status 1 and no output.
set -u
phasor=$1 exr_equal=$2 src=$3 ranks=${5:-1}
out=$4/checkpoint_n$ranks
rm -rf "$out"; mkdir -p "$out"
scene=$src/tests/app/scenes/resume.wscene
source "$(dirname "$0")/common.sh"  # fail, run
source "$(dirname "$0")/mpi_env.sh"  # PH: phasor on $ranks ranks; signal_job
meta() { iinfo -v "$1" | sed -n "s/.*phasor:$2: \"\([^\"]*\)\".*/\1/p"; }
same() { local d; d=$("$exr_equal" "$1" "$2") || fail "$3: $1 and $2 differ: $d"; }

# start_stopped LOG OUT.exr ARGS…: renders in the background with a checkpoint every 0.2 s and
# sends SIGTERM (to every rank under MPI) once the first checkpoint exists; waits; sets $code.
start_stopped() {
    local log=$1 exr=$2; shift 2
    rm -f "$exr" "${exr%.exr}.png" "${exr%.exr}.ckpt"
    "${PH[@]}" render "$scene" -o "$exr" --checkpoint 0.2 "$@" 2>"$log" &
    local pid=$! i
    for i in $(seq 600); do [[ -f "${exr%.exr}.ckpt" ]] && break; sleep 0.05; done
    signal_job TERM $pid
    wait $pid; code=$?
}

# The uninterrupted render (one process), the reference of every resume.
"$phasor" render "$scene" -o "$out/full.exr" --quiet || fail "the reference render failed"

# 1. -------------------------------------------------------------------------------------------
start_stopped "$out/stopped.log" "$out/part.exr"
[[ $code -eq 143 ]] || { cat "$out/stopped.log"; fail "1: exit status $code, expected 143"; }
[[ -f "$out/part.ckpt" && -f "$out/part.exr" ]] || { cat "$out/stopped.log"; fail "1: no checkpoint or partial image"; }
[[ $(meta "$out/part.exr" cancelled) == true ]] || fail "1: the render was not stopped part-way (too fast?)"
reached=$(meta "$out/part.exr" spp_reached)
cp "$out/part.ckpt" "$out/stopped.ckpt"
"${PH[@]}" render --resume "$out/part.ckpt" --quiet 2>"$out/resume.log" || { cat "$out/resume.log"; fail "1: resume failed"; }
same "$out/full.exr" "$out/part.exr" "1: stopped at $reached spp and resumed"
[[ $(meta "$out/part.exr" cancelled) == false && $(meta "$out/part.exr" spp_reached) == 64 ]] || fail "1: resumed image incomplete"
cmp -s "$out/part.ckpt" "$out/stopped.ckpt" && fail "1: the finished render did not write its checkpoint"
if [[ $ranks -gt 1 ]]; then  # the same checkpoint resumed by one process
    cp "$out/stopped.ckpt" "$out/alone.ckpt"
    "$phasor" render --resume "$out/alone.ckpt" -o "$out/alone.exr" --quiet || fail "1: resume on one process failed"
    same "$out/full.exr" "$out/alone.exr" "1: a $ranks-rank checkpoint resumed by one process"
fi
echo "1: stopped at $reached spp, resumed: bit for bit"

# 2. -------------------------------------------------------------------------------------------
"$phasor" render "$scene" --spp 80 -o "$out/full80.exr" --quiet || fail "2: reference at 80 spp failed"
"${PH[@]}" render --resume "$out/part.ckpt" --spp 80 -o "$out/more.exr" --quiet 2>"$out/more.log" ||
    { cat "$out/more.log"; fail "2: resume to 80 spp failed"; }
same "$out/full80.exr" "$out/more.exr" "2: resumed from 64 to 80 spp"
echo "2: 64 then 80 spp equals 80 spp"

# 3. -------------------------------------------------------------------------------------------
rm -f "$out/killed".*
PHASOR_TEST_CHECKPOINT_PAUSE=60 "${PH[@]}" render "$scene" -o "$out/killed.exr" --checkpoint 0.2 2>"$out/killed.log" &
pid=$!
for i in $(seq 1200); do grep -q "paused before replacing" "$out/killed.log" && break; sleep 0.05; done
grep -q "paused before replacing" "$out/killed.log" || { cat "$out/killed.log"; fail "3: the writer never paused"; }
cp "$out/killed.ckpt" "$out/before.ckpt"
signal_job KILL $pid
wait $pid 2>/dev/null
cmp -s "$out/killed.ckpt" "$out/before.ckpt" || fail "3: the checkpoint changed under a killed write"
# The killed writer's temporary (never read; docs/distributed.md) shows the kill came mid-write.
ls -A "$out" | grep -q '^\.killed\.ckpt\.tmp-' || fail "3: no temporary: the process was not killed while writing"
rm -f "$out"/.killed.ckpt.tmp-*
"${PH[@]}" render --resume "$out/killed.ckpt" --quiet 2>"$out/killed_resume.log" ||
    { cat "$out/killed_resume.log"; fail "3: the surviving checkpoint does not resume"; }
same "$out/full.exr" "$out/killed.exr" "3: resumed from the checkpoint that survived the kill"
echo "3: a kill during a checkpoint write left the previous one intact"

[[ $ranks -gt 1 ]] && exit $((failures > 0))

# 4. -------------------------------------------------------------------------------------------
refused() {  # refused REGEX ARGS…: exit 1, the message, no output written
    local regex=$1; shift
    rm -f "$out/refused.exr" "$out/refused.png"
    run render "$@" -o "$out/refused.exr"
    [[ $rc -eq 1 ]] || fail "4: '$*': exit status $rc, expected 1"
    grep -Eq -- "$regex" <<<"$stderr" || fail "4: '$*': stderr does not match /$regex/: $stderr"
    [[ ! -e "$out/refused.exr" && ! -e "$out/refused.png" ]] || fail "4: '$*' wrote an image"
}
size=$(stat -c %s "$out/stopped.ckpt")
head -c $((size / 2)) "$out/stopped.ckpt" >"$out/truncated.ckpt"
refused "checkpoint '.*truncated.ckpt': truncated \([0-9]+ of $size bytes\)" --resume "$out/truncated.ckpt"
head -c 20 "$out/stopped.ckpt" >"$out/short.ckpt"
refused "truncated" --resume "$out/short.ckpt"
cp "$out/stopped.ckpt" "$out/corrupt.ckpt"
printf '\xff\x00\xff' | dd of="$out/corrupt.ckpt" bs=1 seek=$((size * 2 / 3)) conv=notrunc status=none
refused "checkpoint '.*corrupt.ckpt': corrupt \(its checksum does not match" --resume "$out/corrupt.ckpt"
refused "not a phasor checkpoint" --resume "$out/full.exr"
refused "checkpoint '.*nothing.ckpt': no such file" --resume "$out/nothing.ckpt"
refused "does not continue this render: its seed is 0, this render's is 4" --resume "$out/stopped.ckpt" --seed 4
refused "its sampler is sobol, this render's is independent" --resume "$out/stopped.ckpt" --sampler independent
refused "its integrator is grt .*, this render's is ray" --resume "$out/stopped.ckpt" --integrator ray
refused "its resolution is 32x32, this render's is 24x24" --resume "$out/stopped.ckpt" -D res=24
sed 's/reflectance = 0.5/reflectance = 0.6/' "$scene" >"$out/other.wscene"
refused "it was made from another scene" "$out/other.wscene" --resume "$out/stopped.ckpt"
refused "has 64 samples in some pixels; --spp 2 cannot continue it" --resume "$out/part.ckpt" --spp 2
refused "rs takes no samples" "$src/scenes/validation/double_slit.wscene" --integrator rs --checkpoint 5
ls -A "$out" | grep -q '^\.' && fail "temporary files left in $out: $(ls -A "$out" | grep '^\.')"
echo "4: bad checkpoints refused"
exit $((failures > 0))
