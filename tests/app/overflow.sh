#!/usr/bin/env bash
# overflow.sh PHASOR SCENES OUTDIR — values the float EXR cannot hold never reach it (issue 10 §2).
#  * Light strengths and reference irradiances beyond the physically meaningful range (whose
#    products would overflow) are load errors at the parameter, naming the range; no output.
#  * In-range parameters whose pixels still exceed float (3.4e38) give counted invalid samples, a
#    warning and an image with no Inf (and no NaN) pixel.
set -eu
phasor=$1 scenes=$2 out=$3/overflow
rm -rf "$out"
mkdir -p "$out"
fail() { echo "$*"; exit 1; }
command -v oiiotool >/dev/null || fail "oiiotool (openimageio-tools) is needed for the pixel statistics"

# rejected NAME PATTERN — `render NAME.wscene` exits 1 with PATTERN on stderr and writes nothing.
rejected() {
    local code msg
    set +e; msg=$("$phasor" render "$scenes/$1.wscene" -o "$out/$1.exr" 2>&1 >/dev/null); code=$?; set -e
    [[ $code -eq 1 ]] || fail "$1: exit status $code, expected 1: $msg"
    grep -Eq "$2" <<<"$msg" || fail "$1: stderr does not match '$2': $msg"
    [[ ! -e "$out/$1.exr" && ! -e "$out/$1.png" ]] || fail "$1: an image was written"
}
rejected overflow_radiance "overflow_radiance.wscene:6:43: error: 'radiance' is out of range: 1e\+40 W/m\^2/sr \(must be .*≤ 1e\+30 W/m\^2/sr\)"
rejected overflow_reference "overflow_reference.wscene:6:28: error: 'reference_irradiance' is out of range: 1e-300 W/m\^2 \(must be ≥ 1e-30 W/m\^2"
rejected overflow_power "overflow_power.wscene:3:[0-9]+: error: 'power' is out of range: 1e\+300 W \(must be .*≤ 1e\+30 W\)"

# Pixels of 1e20 / 1e-30 = 1e50: exit 0 with a warning; every sample counted, no Inf written.
set +e; msg=$("$phasor" render "$scenes/overflow_at_render.wscene" -o "$out/r.exr" 2>&1 >/dev/null); code=$?; set -e
[[ $code -eq 0 ]] || fail "overflow_at_render: exit status $code: $msg"
grep -q "warning: 20 samples were NaN, negative or beyond the float range" <<<"$msg" || fail "no warning: $msg"
iinfo -v "$out/r.exr" | grep -q 'phasor:invalid_samples: "20"' || fail "invalid_samples is not 20: $(iinfo -v "$out/r.exr")"
stats=$(oiiotool --stats "$out/r.exr")
grep -q "InfCount: 0 0 0 0 0" <<<"$stats" && grep -q "NanCount: 0 0 0 0 0" <<<"$stats" || fail "non-finite pixels: $stats"
echo ok
