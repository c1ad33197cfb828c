#!/usr/bin/env bash
# sigint.sh PHASOR SCENE OUTDIR — Ctrl-C during a render stops cleanly and writes the partial image
# with the spp reached in the EXR metadata.
set -eu
phasor=$1 scene=$2 out=$3/sigint.exr
rm -f "$out" "${out%.exr}.png"
"$phasor" render "$scene" -o "$out" --spp 100000 --quiet --threads 1 &
pid=$!
sleep 5   # past start-up (OIIO plug-in loading, scene build), well into the render
kill -INT $pid
set +e; wait $pid; code=$?; set -e
[[ $code -eq 130 ]] || { echo "exit status $code, expected 130"; exit 1; }
[[ -f "$out" && -f "${out%.exr}.png" ]] || { echo "partial image not written"; exit 1; }
command -v iinfo >/dev/null || { echo "iinfo (openimageio-tools) is needed to read the EXR metadata"; exit 1; }
meta=$(iinfo -v "$out")
grep -q 'phasor:cancelled: "true"' <<<"$meta" || { echo "no cancelled flag"; echo "$meta"; exit 1; }
reached=$(sed -n 's/.*phasor:spp_reached: "\([0-9]*\)".*/\1/p' <<<"$meta")
[[ -n "$reached" && "$reached" -ge 1 && "$reached" -lt 100000 ]] || { echo "bad spp_reached '$reached'"; exit 1; }
echo "stopped after $reached spp"
