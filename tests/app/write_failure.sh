#!/usr/bin/env bash
# write_failure.sh PHASOR SCENE OUTDIR — an output that cannot be written completely is an error
# naming the file ("cannot write 'FILE': reason"), exit status 1, and leaves no partial output:
# neither the file, nor its companions (a render's EXR and PNG, profile's CSV and plot), nor a
# temporary; a file of that name from an earlier run stays as it was.
#
# A file-size limit (`ulimit -f`, RLIMIT_FSIZE) makes write(2) fail with EFBIG exactly where a full
# disk makes it fail with ENOSPC; SIGXFSZ is ignored (inherited through exec) so that the program
# sees the failed write rather than being killed — as the unchecked PNG writer once did not, and
# reported a truncated plot as written.
set -eu
phasor=$1 scene=$2 out=$3/write_failure
rm -rf "$out"
mkdir -p "$out"
fail() { echo "$*"; exit 1; }

# limited KB ARGS… — runs phasor ARGS with files limited to KB KiB; sets $code and $msg (stderr).
limited() {
    local kb=$1
    shift
    set +e
    msg=$( (ulimit -f "$kb"; trap '' XFSZ; exec "$phasor" "$@") 2>&1 >/dev/null)
    code=$?
    set -e
}
# expect_error PATTERN — exit status 1 and stderr matching PATTERN (extended regex).
expect_error() {
    [[ $code -eq 1 ]] || fail "exit status $code, expected 1; stderr: $msg"
    grep -Eq "$1" <<<"$msg" || fail "stderr does not match '$1': $msg"
}
# listing: the directory's files, temporaries included.
listing() { ls -A "$out" | tr '\n' ' '; }

# A render whose EXR (3.6 KB) does not fit in 2 KiB: no EXR, no PNG (the PNG would fit), and the
# EXR of an earlier run is untouched.
echo "earlier run" >"$out/r.exr"
limited 2 render "$scene" -o "$out/r.exr" --spp 2 --quiet
expect_error "^error: cannot write '$out/r.exr': File too large$"
[[ "$(listing)" == "r.exr " ]] || fail "render left: $(listing)"
[[ "$(cat "$out/r.exr")" == "earlier run" ]] || fail "the earlier r.exr was changed"
rm "$out/r.exr"

# The same render without a limit, as the input of `profile`.
"$phasor" render "$scene" -o "$out/good.exr" --spp 2 --quiet

# profile: the CSV (≈ 1 KB) fits in 4 KiB, the plot (≈ 30 KB) does not: neither is written.
limited 4 profile "$out/good.exr" --csv "$out/p.csv" --plot "$out/p.png"
expect_error "^error: cannot write '$out/p.png': File too large$"
[[ "$(listing)" == "good.exr good.png " ]] || fail "profile left: $(listing)"

# profile's CSV on standard output, redirected to a file that cannot grow.
set +e
msg=$( (ulimit -f 0; trap '' XFSZ; exec "$phasor" profile "$out/good.exr" >"$out/stdout.csv") 2>&1)
code=$?
set -e
expect_error "^error: cannot write to standard output: File too large$"
rm -f "$out/stdout.csv"

# Standard output on a full device.
if [[ -w /dev/full ]]; then
    set +e
    msg=$("$phasor" format "$scene" 2>&1 >/dev/full)
    code=$?
    set -e
    expect_error "^error: cannot write to standard output: No space left on device$"
fi

[[ "$(listing)" == "good.exr good.png " ]] || fail "left behind: $(listing)"
echo ok
