#!/usr/bin/env bash
# install_test.sh BUILD PYTHON SITE OUT — `cmake --install` puts the package into the interpreter's
# site directory SITE (here under DESTDIR=OUT): the installed package imports, renders, and writes
# its display PNG and a comparison's page (through the plot and page modules it ships) without the
# build tree on PYTHONPATH.
set -eu
build=$1 python=$2 site=$3 out=$4
rm -rf "$out"
DESTDIR="$out" cmake --install "$build" > "$out.log" 2>&1 || { cat "$out.log"; exit 1; }
pkg="$out$site/phasor"
[[ -f "$pkg/__init__.py" && -f "$pkg/phasor_plot.py" && -f "$pkg/phasor_report.py" && -f "$pkg/templates/compare.html.j2" ]] || { echo "package not installed in $pkg"; ls -R "$out" | head -40; exit 1; }
ls "$pkg"/_phasor*.so > /dev/null || { echo "no extension module in $pkg"; exit 1; }
cd "$out"
PYTHONPATH="$out$site" PYTHONDONTWRITEBYTECODE=1 "$python" - "$pkg" <<'PY'
import sys, phasor
assert phasor.__file__.startswith(sys.argv[1]), phasor.__file__
scene = phasor.load_string('wscene 2\nShape "sphere" { radius = 1 m }\nLight "point" { position = [0 3 0] m  intensity = 1 W/sr }\n'
                           'Detector "virtual_plane" { extent = [4 4] m  resolution = [8 1]  to_world = translate([0 0 3] m) }\n')
image = scene.render(spp=1, progress=False)
assert image._repr_png_()[:4] == b"\x89PNG"  # a one-row image: the line plot, through the shipped plot module
c = phasor.compare(scene, ["grt", "ray"], spp=1, reference="none", progress=False)
written = c.write_report("report")  # the page, through the shipped page module and its template
assert any(w.endswith("index.html") for w in written), written
print("installed package ok:", phasor.__file__)
PY
