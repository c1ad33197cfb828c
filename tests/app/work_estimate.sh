#!/usr/bin/env bash
# work_estimate.sh PHASOR SCENE OUTDIR — a render far beyond the usual (the double slit at a 1 pm
# wavelength: many minutes) must announce itself within 20 s; the render is then stopped.
set -u
phasor=$1 scene=$2 out=$3
log="$out/work_estimate.log"
rm -f "$log"
"$phasor" render "$scene" -D lambda=1pm -o "$out/work_estimate.exr" 2>"$log" &
pid=$!
for _ in $(seq 200); do
  if grep -q 'warning: this render would take about .*far beyond the usual: lower the spp' "$log"; then
    kill "$pid" 2>/dev/null; wait "$pid" 2>/dev/null
    exit 0
  fi
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.1
done
kill "$pid" 2>/dev/null; wait "$pid" 2>/dev/null
echo "no work-estimate warning within 20 s:"; cat "$log"
exit 1
