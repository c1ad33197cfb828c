#!/usr/bin/env bash
# Renders the showcase scenes (scenes/showcase) with `phasor compare` and puts the images of
# docs/gallery.md in docs/gallery/: <scene>.png (the grt render at the scene's defaults) and
# <scene>_compare.png (compare's labelled grid of every integrator); for bornite also
# bornite_bare.png, the scene without its tarnish film.
#
#   scripts/make_gallery.sh [BUILD_DIR]            (make gallery)
#   INTEGRATORS=grt,ray scripts/make_gallery.sh                   another set of integrators
#   SCENES="cd beetle" scripts/make_gallery.sh                    some scenes only
#   REUSE=1 scripts/make_gallery.sh                               reuse out/<scene>_compare/
#
# The compare folders stay in out/<scene>_compare/ (EXRs, diffs, table, index.html). For the
# repository the grid is scaled to at most 960 pixels wide and a PNG that would exceed 300 KB is
# reduced to a 256-colour palette (Floyd–Steinberg dither), with Pillow if a Python with it is
# found (Debian: python3-pil); otherwise the PNGs are copied as they are.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
INTEGRATORS=${INTEGRATORS:-grt,ray,sample_solve}
SCENES=${SCENES:-"bornite boa beetle cd soap_bubble"}
mkdir -p docs/gallery out

python=""
for p in python3 /usr/bin/python3; do
  if command -v "$p" > /dev/null && "$p" -c "import PIL" 2> /dev/null; then python=$p; break; fi
done
[[ -n "$python" ]] || echo "make_gallery: no Python with Pillow (apt-get install python3-pil): PNGs copied unreduced" >&2

# reduce SRC DST MAX_WIDTH
reduce() {
  if [[ -z "$python" ]]; then cp "$1" "$2"; return; fi
  "$python" - "$1" "$2" "$3" << 'EOF'
import io, sys
from PIL import Image
src, dst, width = sys.argv[1], sys.argv[2], int(sys.argv[3])
im = Image.open(src).convert("RGB")
if im.width > width:
    im = im.resize((width, round(im.height * width / im.width)), Image.Resampling.LANCZOS)
out = io.BytesIO()
im.save(out, "PNG", optimize=True)
if out.tell() > 300_000:  # noisy renders: a 256-colour palette keeps them small
    out = io.BytesIO()
    im.quantize(colors=256, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.FLOYDSTEINBERG).save(
        out, "PNG", optimize=True)
open(dst, "wb").write(out.getvalue())
EOF
}

for s in $SCENES; do
  dir=out/${s}_compare
  if [[ "${REUSE:-0}" != 1 || ! -f $dir/grid.png ]]; then
    echo "== $s"
    "$BUILD/bin/phasor" compare "scenes/showcase/$s.wscene" --integrators "$INTEGRATORS" -o "$dir"
  fi
  reduce "$dir/grt.png" "docs/gallery/$s.png" 640
  reduce "$dir/grid.png" "docs/gallery/${s}_compare.png" 960
  if [[ $s == bornite ]]; then
    # bornite's honest reference: the scene without its tarnish film (docs/gallery.md)
    if [[ "${REUSE:-0}" != 1 || ! -f out/bornite_bare.png ]]; then
      "$BUILD/bin/phasor" render scenes/showcase/bornite.wscene -D tarnish=false -o out/bornite_bare.exr
    fi
    reduce out/bornite_bare.png docs/gallery/bornite_bare.png 640
  fi
done
ls -l docs/gallery
