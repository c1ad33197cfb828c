#!/usr/bin/env bash
# work_estimate.sh PHASOR SCENE OUTDIR NAME FIX [RENDER ARGS...] — a render far beyond the usual
# (the double slit at a picometre wavelength: minutes with grt, days with rs) must announce itself
# within 20 s with a warning containing FIX; the render is then stopped.
set -u
phasor=$1 scene=$2 out=$3 name=$4 fix=$5
shift 5
log="$out/$name.log"
rm -f "$log"
"$phasor" render "$scene" "$@" -o "$out/$name.exr" 2>"$log" &
pid=$!
for _ in $(seq 200); do
  if grep -q "warning: this render would take about .*far beyond the usual: .*$fix" "$log"; then
    kill "$pid" 2>/dev/null; wait "$pid" 2>/dev/null
    exit 0
  fi
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.1
done
kill "$pid" 2>/dev/null; wait "$pid" 2>/dev/null
echo "no work-estimate warning within 20 s:"; cat "$log"
exit 1
