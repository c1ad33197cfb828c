#!/usr/bin/env bash
# profile.sh PHASOR WRITE_TEST_EXR SCENE OUTDIR — `phasor profile`: CSV columns and values, pixel
# positions from metadata or --x0/--pitch, rows and columns, labels, the |a − b| summary, the plot
# (matplotlib; its data instead when matplotlib is missing); errors give exit status 1, a message
# naming the file and no output file (not even a temporary one).
set -u
phasor=$1 mkexr=$2 scene=$3 out=$4/profile
rm -rf "$out"; mkdir -p "$out"
source "$(dirname "$0")/common.sh"  # fail, run
expect_line() {  # expect_line FILE N TEXT: line N of FILE is exactly TEXT
    local got; got=$(sed -n "$2p" "$1")
    [[ "$got" == "$3" ]] || fail "$1 line $2 is '$got', expected '$3'"
}
no_outputs() {  # no_outputs FILE…: none of them (nor any temporary file) exists
    for f in "$@"; do [[ ! -e "$f" ]] || fail "'$f' exists but must not"; done
    if ls -A "$out" | grep -q tmp; then fail "temporary file left: $(ls -A "$out")"; fi
}

# Two 8×3 "renders" of the same sensor: pixel centres at x = -3.5 µm … 3.5 µm, pitch 1 µm.
meta=(--meta phasor:x0_m=-3.5e-06 --meta phasor:pitch_m=1e-06)
"$mkexr" "$out/a.exr" 8 3 "${meta[@]}" --meta "phasor:integrator=grt { max_depth = 4 }" \
    0 1 2 3 4 3 2 1 || exit 1
"$mkexr" "$out/b.exr" 8 3 "${meta[@]}" --meta "phasor:integrator=rs { samples = 64 }" \
    0 1.5 2 2.5 4 3 2 0.5 || exit 1
"$mkexr" "$out/plain.exr" 8 3 0 1 2 3 4 3 2 1 || exit 1
"$mkexr" "$out/narrow.exr" 5 3 0 1 2 3 4 || exit 1

# 1. A pair: header, values of the middle row, |a − b|, the summary, the plot.
run profile "$out/a.exr" "$out/b.exr" --csv "$out/pair.csv" --plot "$out/pair.png" --diff-scale 10 --quiet
[[ $rc -eq 0 ]] || fail "pair: exit status $rc: $stderr"
expect_line "$out/pair.csv" 1 "x_m,grt,rs,abs_diff"
expect_line "$out/pair.csv" 2 "-3.5e-06,0,0,0"
expect_line "$out/pair.csv" 3 "-2.5e-06,1,1.5,0.5"
expect_line "$out/pair.csv" 5 "-5e-07,3,2.5,0.5"
expect_line "$out/pair.csv" 9 "3.5e-06,1,0.5,0.5"
[[ $(wc -l <"$out/pair.csv") -eq 9 ]] || fail "pair.csv has $(wc -l <"$out/pair.csv") lines, expected 9"
# max |a − b| = 0.5 (first at pixel 1, x = -2.5 µm), max(b) = 4 → 0.125.
grep -q "max |grt - rs| / max(rs) = 0.125 .*at x = -2.5e-06 m" <<<"$stdout" ||
    fail "pair: summary on stdout is '$stdout'"
[[ "$(head -c 4 "$out/pair.png" | od -An -tx1 | tr -d ' ')" == 89504e47 ]] || fail "pair.png is not a PNG"
# PNG IHDR: width and height (big-endian) at bytes 16..23.
[[ "$(od -An -tu1 -j16 -N8 "$out/pair.png" | tr -s ' ')" == " 0 0 3 232 0 0 2 88" ]] ||
    fail "pair.png is not 1000×600"

# The plot is matplotlib's (its PNG names it as the software that wrote it).
grep -aq "Software.Matplotlib version" "$out/pair.png" || fail "pair.png was not drawn by matplotlib"
# SVG and PDF by the plot's name.
run profile "$out/a.exr" "$out/b.exr" --plot "$out/pair.svg" --quiet
[[ $rc -eq 0 && "$(head -c 5 "$out/pair.svg")" == "<?xml" ]] || fail "pair.svg: exit status $rc: $stderr"

# 2. --row, --label, and the CSV on stdout (no --csv and no --plot); the summary goes to stderr.
run profile "$out/a.exr" "$out/b.exr" --row 0 --label A --label B
[[ $rc -eq 0 ]] || fail "row 0: exit status $rc: $stderr"
[[ "$(sed -n 1p <<<"$stdout")" == "x_m,A,B,abs_diff" ]] || fail "row 0: header in '$stdout'"
[[ "$(sed -n 2p <<<"$stdout")" == "-3.5e-06,1000,1000,0" ]] || fail "row 0: first line in '$stdout'"
grep -q "max |A - B| / max(B) = 0 " <<<"$stderr" || fail "row 0: summary on stderr is '$stderr'"

# 3. No metadata: pixel indices, or --x0/--pitch; labels from the file stem.
run profile "$out/plain.exr"
[[ $rc -eq 0 && "$(sed -n 1p <<<"$stdout")" == "x_px,plain" && "$(sed -n 6p <<<"$stdout")" == "4,4" ]] ||
    fail "plain: exit status $rc, output '$stdout' $stderr"
run profile "$out/plain.exr" --x0 -0.002 --pitch 0.0005 --csv -
[[ $rc -eq 0 && "$(sed -n 1p <<<"$stdout")" == "x_m,plain" && "$(sed -n 9p <<<"$stdout")" == "0.0015,1" ]] ||
    fail "--x0/--pitch: exit status $rc, output '$stdout' $stderr"

# 3b. --column: the values down a column (y in pixels); the middle row of these images is row 1.
run profile "$out/a.exr" "$out/b.exr" --column 2 --csv - --quiet
[[ $rc -eq 0 && "$(sed -n 1p <<<"$stdout")" == "y_px,grt,rs,abs_diff" && "$(sed -n 2p <<<"$stdout")" == "0,1000,1000,0" &&
    "$(sed -n 3p <<<"$stdout")" == "1,2,2,0" && "$(sed -n 4p <<<"$stdout")" == "2,1002,1002,0" ]] ||
    fail "--column: exit status $rc, output '$stdout' $stderr"

# 3c. Without matplotlib (a Python without site packages): the plot's data instead, in one line
# saying how to install it, exit status 0.
printf '#!/bin/sh\nexec python3 -S "$@"\n' >"$out/nompl"
chmod +x "$out/nompl"
PHASOR_PYTHON=$out/nompl run profile "$out/a.exr" "$out/b.exr" --plot "$out/nompl.png"
[[ $rc -eq 0 && ! -e "$out/nompl.png" && -s "$out/nompl.csv" ]] || fail "no matplotlib: exit status $rc, $(ls "$out")"
[[ $(grep -c . <<<"$stderr") -eq 2 ]] &&
    grep -q "^warning: .*apt-get install python3-matplotlib.*'$out/nompl.png' not drawn, its data is in '$out/nompl.csv'$" <<<"$stderr" ||
    fail "no matplotlib: stderr '$stderr'"
rm -f "$out/nompl.csv" "$out/nompl"

# 4. Errors: exit status 1, the file and the reason, and no output at all.
check_error() {  # check_error REGEX ARGS…
    local regex=$1; shift
    run profile "$@" --csv "$out/err.csv" --plot "$out/err.png"
    [[ $rc -eq 1 ]] || fail "$*: exit status $rc, expected 1"
    grep -Eq -- "$regex" <<<"$stderr" || fail "$*: stderr '$stderr' does not match /$regex/"
    no_outputs "$out/err.csv" "$out/err.png"
}
check_error "^error: cannot read '.*/missing\.exr'" "$out/a.exr" "$out/missing.exr"
check_error "^error: .*/narrow\.exr: it is 5 pixels wide but .*a\.exr' is 8" "$out/a.exr" "$out/narrow.exr"
check_error "^error: .*/a\.exr: no channel 'irradiance' \(it has: R G B intensity variance\)" \
    "$out/a.exr" --channel irradiance
check_error "^error: .*/a\.exr: row 3 is out of range \(the image has 3 rows\)" "$out/a.exr" --row 3
check_error "^error: .*'--x0' and '--pitch' go together" "$out/a.exr" --x0 0
check_error "^error: .*a\.exr: column 8 is out of range \(the image has 8 columns\)" "$out/a.exr" --column 8
check_error "^error: '--row' and '--column' exclude each other" "$out/a.exr" --row 1 --column 1
# An unwritable plot: the CSV (written first, to a temporary file) must not appear either.
run profile "$out/a.exr" "$out/b.exr" --csv "$out/err.csv" --plot /proc/phasor-test/err.png
[[ $rc -eq 1 ]] && grep -q "^error: cannot write '/proc/phasor-test/err.png'" <<<"$stderr" ||
    fail "unwritable plot: exit status $rc, stderr '$stderr'"
no_outputs "$out/err.csv"

# 5. Real renders of a one-row virtual_plane: both are grt, so the labels fall back to the stems.
"$phasor" render "$scene" -o "$out/tilt0.exr" --spp 2 --quiet -D theta=0deg &&
    "$phasor" render "$scene" -o "$out/tilt30.exr" --spp 2 --quiet -D theta=30deg || fail "render failed"
run profile "$out/tilt0.exr" "$out/tilt30.exr" --csv "$out/tilt.csv" --plot "$out/tilt.png" --quiet
[[ $rc -eq 0 ]] || fail "renders: exit status $rc: $stderr"
expect_line "$out/tilt.csv" 1 "x_m,tilt0,tilt30,abs_diff"
[[ -s "$out/tilt.png" ]] || fail "tilt.png not written"
# The plane wave fills the sensor: every pixel reads cosθ·(1 − e^{−β²k²}), so a/b = 1/cos 30°.
awk -F, 'NR > 1 { r = $2 / $3; if (r < 1.1547 || r > 1.1548) bad = 1 } END { exit bad }' "$out/tilt.csv" ||
    fail "tilt.csv: ratio tilt0/tilt30 is not 1/cos 30°: $(cat "$out/tilt.csv")"

[[ $failures -eq 0 ]] || { echo "$failures failure(s)"; exit 1; }
echo "profile: all checks passed"
