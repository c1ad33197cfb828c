#!/usr/bin/env bash
# rs_report.sh PHASOR DOUBLE_SLIT OUTDIR — `rs` takes no samples: it reports what it solved, never
# an spp ("rendered 1 spp" used to stand beside "phasor:spp_requested 4096"), and its EXR metadata
# carries its own counts instead of spp, seed and sampler.
set -eu
phasor=$1 scene=$2 out=$3/rs_report.exr
fail() { echo "$*"; exit 1; }
rm -f "$out"
msg=$("$phasor" render "$scene" --integrator rs -o "$out" 2>&1 >/dev/null)
grep -Eq "^rs solved 48 pixels \(48x1, 2d\) from [0-9]+ field points in " <<<"$msg" || fail "no rs summary: $msg"
! grep -q "spp" <<<"$msg" || fail "rs reported an spp: $msg"
meta=$(iinfo -v "$out")
grep -Eq 'phasor:rs_field_points: "[1-9][0-9]*"' <<<"$meta" || fail "no phasor:rs_field_points: $meta"
grep -q 'phasor:rs_mode: "2d"' <<<"$meta" || fail "no phasor:rs_mode: $meta"
! grep -Eq 'phasor:(spp_|seed|sampler|samples_per_pixel)' <<<"$meta" || fail "sampling metadata on an rs image: $meta"
echo ok
