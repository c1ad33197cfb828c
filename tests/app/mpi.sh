#!/usr/bin/env bash
# mpi.sh PART PHASOR EXR_EQUAL SOURCE_DIR OUTDIR — phasor on several MPI ranks (docs/distributed.md;
# the Open MPI settings are mpi_env.sh's):
#   images   grt, ray, sample_solve (with Stokes channels) and rs on 2 and 3 ranks: every image
#            equals the one-process image bit for bit (exr_equal: every channel, variance and
#            samples included), and every rank did part of the work (phasor:mpi_work)
#   errors   a scene error: exit status 1 on every rank and the error printed once; a scene only
#            rank 1 cannot read: rank 0 names the rank and the error; an unwritable output: one
#            error; a usage error: one message
#   compare  `phasor compare` of 3 integrators on 2 ranks (whole runs on ranks) and of 2 on 3 ranks
#            (each run's tiles shared): every run's EXR equals the one-process compare's and the
#            table's error columns are the same; equal time (--time) on 2 ranks runs
#   sigterm  SIGTERM to mpirun (which passes it on to the ranks after odls_base_sigkill_timeout)
#            and SIGTERM to the ranks themselves (a batch system): the job stops, says so once, and
#            rank 0 writes the partial image (cancelled, per-pixel sample counts)
set -u
part=$1 phasor=$2 exr_equal=$3 src=$4
out=$5/mpi_$part
rm -rf "$out"; mkdir -p "$out"
source "$(dirname "$0")/common.sh"  # fail
ranks=2
source "$(dirname "$0")/mpi_env.sh"  # the Open MPI settings; signal_job
mpi() { local n=$1; shift; mpirun -q --oversubscribe --allow-run-as-root -n "$n" "$phasor" "$@"; }
meta() { iinfo -v "$1" | sed -n "s/.*phasor:$2: \"\([^\"]*\)\".*/\1/p"; }
val=$src/scenes/validation

case $part in
images)
    # A glass plate at Brewster's angle seen by a 48×48 camera with Stokes output (sample_solve.sh's).
    cat >"$out/plate.wscene" <<'SCENE'
wscene 1
Material "dielectric" "glass" { ior = 1.5 }
Shape "rectangle" "plate" { material = @glass  to_world = scale(10) }
Light "distant" "sun" { direction = [-0.83205 0 -0.5547]  angular_radius = 20 mrad  profile = "gaussian"  spectrum = line(550 nm) }
Detector "perspective" "cam" {
    to_world = lookat(eye = [-0.83205 0 0.5547] m, target = [0 0 0] m, up = [0 0 1])
    fov = 0.8 deg  resolution = [48 48]  response = "radiometric"  stokes = true
}
Integrator "sample_solve" "ss" { max_depth = 1 }
Render { integrator = @ss  spp = 12 }
SCENE
    # name, tiled (every rank must get work), arguments. A tiled render must last well beyond the
    # ranks' start-up skew on an oversubscribed machine and beyond the SlackSeconds (8 ms) of work
    # a helper keeps queued (distributed_mpi.cpp), else a rank that starts late legitimately finds
    # every tile taken: 160 spp make the Cornell box's 45 tiles ~25 ms each (at 20 spp, 3 ms, a
    # third rank on 2 cores got none in CI).
    cases=(
        "grt|1|$val/grt_cornell.wscene --integrator grt --spp 160 -D res=40"
        "ray|1|$val/grt_cornell.wscene --integrator ray --spp 160 -D res=40"
        "sample_solve|1|$out/plate.wscene"
        "rs|0|$val/gaussian_beam_aperture.wscene --integrator rs"
    )
    for c in "${cases[@]}"; do
        IFS='|' read -r name tiled args <<<"$c"
        # shellcheck disable=SC2086
        "$phasor" render $args -o "$out/$name.exr" --quiet || { fail "$name: the one-process render failed"; continue; }
        for n in 2 3; do
            # shellcheck disable=SC2086
            mpi $n render $args -o "$out/$name-$n.exr" --threads 1 --quiet 2>"$out/$name-$n.log" ||
                { cat "$out/$name-$n.log"; fail "$name on $n ranks failed"; continue; }
            d=$("$exr_equal" "$out/$name.exr" "$out/$name-$n.exr") || fail "$name on $n ranks differs: $d"
            work=$(meta "$out/$name-$n.exr" mpi_work)
            [[ $(meta "$out/$name-$n.exr" mpi_ranks) == "$n" && $(tr ',' '\n' <<<"$work" | wc -l) -eq $n ]] ||
                fail "$name on $n ranks: phasor:mpi_work '$work'"
            if [[ $tiled == 1 ]] && tr ',' '\n' <<<"$work" | grep -qx 0; then fail "$name on $n ranks: a rank did nothing ($work)"; fi
            echo "$name on $n ranks: equal (work by rank: $work)"
        done
    done
    for c in S0 S1 S2 S3 DoP; do
        iinfo -v "$out/sample_solve-3.exr" | grep -Eq "channel list:.*\<$c\>" || fail "sample_solve: no $c channel"
    done
    ;;
errors)
    mpi 3 render "$src/tests/app/scenes/misspelt_parameter.wscene" -o "$out/x.exr" 2>"$out/load.log"; rc=$?
    [[ $rc -eq 1 ]] || fail "scene error: exit status $rc, expected 1"
    [[ $(grep -c "error: unknown parameter 'fvo'" "$out/load.log") -eq 1 && $(grep -c "^1 error in" "$out/load.log") -eq 1 ]] ||
        { cat "$out/load.log"; fail "scene error: not printed exactly once"; }
    [[ ! -e "$out/x.exr" ]] || fail "scene error: an image was written"
    # A scene only rank 1 cannot read (as on a node without the file; Open MPI's MPMD syntax gives
    # that rank another path): rank 0 names the rank and its error; nothing is written.
    mpirun -q --oversubscribe --allow-run-as-root -n 1 "$phasor" render "$src/tests/app/scenes/small.wscene" -o "$out/y.exr" \
        : -n 1 "$phasor" render "$out/elsewhere/small.wscene" -o "$out/y.exr" 2>"$out/rank.log"; rc=$?
    [[ $rc -eq 1 && $(grep -c "^error: rank 1: .*elsewhere/small.wscene" "$out/rank.log") -eq 1 ]] ||
        { cat "$out/rank.log"; fail "a rank's own load error: exit status $rc, or not named once"; }
    [[ ! -e "$out/y.exr" ]] || fail "a rank's own load error: an image was written"
    mpi 2 render "$src/tests/app/scenes/small.wscene" -o /proc/phasor-test/x.exr 2>"$out/write.log"; rc=$?
    [[ $rc -eq 1 && $(grep -c "cannot write '/proc/phasor-test/x.exr'" "$out/write.log") -eq 1 ]] ||
        { cat "$out/write.log"; fail "unwritable output: exit status $rc or not one message"; }
    mpi 2 render --bogus 2>"$out/usage.log"; rc=$?
    [[ $rc -eq 1 && $(grep -c "unknown option '--bogus'" "$out/usage.log") -eq 1 ]] || fail "usage error: $rc, $(cat "$out/usage.log")"
    echo "errors: once, exit status 1"
    ;;
compare)
    args=("$val/grt_cornell.wscene" -D res=24 --quiet)
    "$phasor" compare "${args[@]}" --spp 8 --integrators grt,ray,sample_solve -o "$out/one" || fail "one-process compare failed"
    # The table without its time and rate columns (5 and 6).
    errors() { cut -d, -f1-4,7- "$1/results.csv"; }
    for run in "2 grt,ray,sample_solve" "3 grt,ray"; do
        read -r n list <<<"$run"
        mpi "$n" compare "${args[@]}" --spp 8 --integrators "$list" -o "$out/n$n" 2>"$out/n$n.log" ||
            { cat "$out/n$n.log"; fail "compare on $n ranks failed"; continue; }
        for name in ${list//,/ }; do
            d=$("$exr_equal" "$out/one/$name.exr" "$out/n$n/$name.exr") || fail "compare on $n ranks: $name differs: $d"
        done
        [[ -f "$out/n$n/index.html" && -f "$out/n$n/grid.png" ]] || fail "compare on $n ranks: no page or grid"
        echo "compare of $list on $n ranks: every run equal"
    done
    diff <(errors "$out/one") <(errors "$out/n2") >/dev/null || fail "the table's errors differ on 2 ranks"
    mpi 2 compare "${args[@]}" --integrators grt,ray --time 1 -o "$out/timed" 2>"$out/timed.log" ||
        { cat "$out/timed.log"; fail "equal-time compare on 2 ranks failed"; }
    [[ -f "$out/timed/results.csv" ]] || fail "equal-time compare on 2 ranks: no table"
    ;;
sigterm)
    # The slow scene at 768² pixels: its first pass is ≈ 135 s of CPU (≈ 70 s on each of 2 ranks), so
    # a job that waited for the pass would take far longer than STOP_BOUND, seconds from a rank's
    # signal to the job's end (the stop itself takes ~0.1 s; a loaded machine needed 4.8 s once
    # to end two ranks and write the image).
    STOP_BOUND=10
    slow=("$src/tests/app/scenes/slow.wscene" -D res=768)
    # check_partial FILE LOG: the partial image, marked; "stopping" said once.
    check_partial() {
        [[ -f "$1" && -f "${1%.exr}.png" ]] || { cat "$2"; fail "$1: no partial image"; return; }
        [[ $(meta "$1" cancelled) == true ]] || fail "$1: not marked cancelled"
        [[ $(grep -c "^stopping" "$2") -eq 1 ]] || { cat "$2"; fail "$2: 'stopping' not said once"; }
    }
    # started LOG: waits (up to 60 s) until the render is under way: its work estimate, printed just
    # before the first pass (a signal before the handlers are installed would simply kill it).
    started() {
        for _ in $(seq 600); do grep -q "this render would take" "$1" && return; sleep 0.1; done
        fail "$1: the render did not start within 60 s"
    }
    # 1. The ranks signalled themselves (Slurm's scancel and time limit, `kill` of the ranks).
    "${PH[@]}" render "${slow[@]}" -o "$out/ranks.exr" --threads 1 2>"$out/ranks.log" &
    pid=$!
    started "$out/ranks.log"
    sleep 1
    start=$(date +%s%3N)
    signal_job TERM $pid
    wait $pid; rc=$?
    elapsed=$(( $(date +%s%3N) - start ))
    [[ $rc -eq 143 ]] || fail "ranks signalled: exit status $rc, expected 143"
    (( elapsed <= STOP_BOUND * 1000 )) || fail "ranks signalled: the job ended ${elapsed} ms after the signal"
    check_partial "$out/ranks.exr" "$out/ranks.log"
    echo "ranks signalled: stopped ${elapsed} ms after the signal"
    # 2. mpirun signalled (Ctrl-C at the terminal): Open MPI signals the ranks after its kill timeout
    #    and kills them that long after; rank 0 writes the partial image in between (6 s: on a
    #    machine loaded 8-fold, 3 s were once too few to stop and write).
    KILL_TIMEOUT=6
    export OMPI_MCA_odls_base_sigkill_timeout=$KILL_TIMEOUT
    mpirun -q --oversubscribe --allow-run-as-root -n 2 "$phasor" render "${slow[@]}" \
        -o "$out/mpirun.exr" --threads 1 2>"$out/mpirun.log" &
    pid=$!
    started "$out/mpirun.log"
    sleep 1
    start=$(date +%s%3N)
    kill -TERM $pid
    wait $pid
    elapsed=$(( $(date +%s%3N) - start ))
    (( elapsed <= (KILL_TIMEOUT + STOP_BOUND) * 1000 )) || fail "mpirun signalled: the job ended ${elapsed} ms after the signal"
    check_partial "$out/mpirun.exr" "$out/mpirun.log"
    echo "mpirun signalled: ended ${elapsed} ms after the signal (${KILL_TIMEOUT} s of them Open MPI's kill timeout)"
    ;;
*) fail "unknown part '$part'" ;;
esac
exit $((failures > 0))
