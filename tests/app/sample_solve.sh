#!/usr/bin/env bash
# sample_solve.sh PHASOR OUTDIR — `sample_solve` through the program: Stokes output (EXR channels,
# the DoP PNG beside, `phasor profile` of a Stokes channel), a polariser, the error when another
# integrator is asked for them, and `phasor compare` of grt, sample_solve and ray on one scene.
set -u
phasor=$1 out=$2/sample_solve
rm -rf "$out"; mkdir -p "$out"
source "$(dirname "$0")/common.sh"  # fail, run

# A glass plate at Brewster's angle under a 20 mrad sun, seen by a 4×4 camera on the reflection:
# s-polarised light along the image x axis, S1/S0 ≈ 1.
cat >"$out/plate.wscene" <<'SCENE'
wscene 1
Define pol = 0 deg
Define stokes = true
Define with_pol = false
Material "dielectric" "glass" { ior = 1.5 }
Shape "rectangle" "plate" { material = @glass  to_world = scale(10) }
Light "distant" "sun" { direction = [-0.83205 0 -0.5547]  angular_radius = 20 mrad  profile = "gaussian"  spectrum = line(550 nm) }
Detector "perspective" "cam" {
    to_world = lookat(eye = [-0.83205 0 0.5547] m, target = [0 0 0] m, up = [0 0 1])
    fov = 0.2 deg  resolution = [4 4]  response = "radiometric"  stokes = $stokes
}
Detector "perspective" "cam_pol" {
    to_world = lookat(eye = [-0.83205 0 0.5547] m, target = [0 0 0] m, up = [0 0 1])
    fov = 0.2 deg  resolution = [4 4]  response = "radiometric"  polarizer = $pol
}
Integrator "sample_solve" "ss" { max_depth = 1 }
Integrator "grt" "gr" { max_depth = 1 }
Integrator "ray" "classic" { max_depth = 1 }
Render { detector = select($with_pol, @cam_pol, @cam)  integrator = @ss  spp = 4 }
SCENE

# 1. Stokes output: the channels, the DoP PNG beside, a message naming both.
run render "$out/plate.wscene" -o "$out/plate.exr"
[[ $rc -eq 0 ]] || fail "render: exit status $rc: $stderr"
grep -q "wrote .*plate.exr, .*plate.png and .*plate.dop.png" <<<"$stderr" || fail "render message: $stderr"
[[ "$(head -c 4 "$out/plate.dop.png" | od -An -tx1 | tr -d ' ')" == 89504e47 ]] || fail "plate.dop.png is not a PNG"
# 2. `profile` reads the Stokes channels: S1 = S0 (fully s-polarised along image x) and DoP ≈ 1.
run profile "$out/plate.exr" --channel S1 --csv "$out/s1.csv" --quiet
[[ $rc -eq 0 ]] || fail "profile S1: exit status $rc: $stderr"
run profile "$out/plate.exr" --channel S0 --csv "$out/s0.csv" --quiet
run profile "$out/plate.exr" --channel DoP --csv "$out/dop.csv" --quiet
[[ $rc -eq 0 ]] || fail "profile DoP: exit status $rc: $stderr"
awk -F, 'NR > 1 && ($2 < 0.999 || $2 > 1.000001) { bad = 1 } END { exit bad }' "$out/dop.csv" ||
    fail "DoP is not ≈ 1: $(cat "$out/dop.csv")"
paste -d, "$out/s0.csv" "$out/s1.csv" | awk -F, 'NR > 1 && ($2 <= 0 || ($4 / $2) < 0.999) { bad = 1 } END { exit bad }' ||
    fail "S1/S0 is not ≈ 1: $(paste -d, "$out/s0.csv" "$out/s1.csv")"
# 3. A polariser across the polarisation (90°) passes almost nothing, along it (0°) all of S0.
run render "$out/plate.wscene" -D with_pol=true -D pol=90deg -D stokes=false -o "$out/crossed.exr" --quiet
[[ $rc -eq 0 ]] || fail "crossed: exit status $rc: $stderr"
[[ ! -e "$out/crossed.dop.png" ]] || fail "a DoP PNG without stokes = true"
run profile "$out/crossed.exr" --csv "$out/crossed.csv" --quiet
paste -d, "$out/s0.csv" "$out/crossed.csv" | awk -F, 'NR > 1 && $4 > 1e-3 * $2 { bad = 1 } END { exit bad }' ||
    fail "the crossed polariser passes too much: $(paste -d, "$out/s0.csv" "$out/crossed.csv")"
# 4. grt and ray cannot honour them: an error at the parameter, exit status 1, no output.
run render "$out/plate.wscene" --integrator grt -o "$out/grt.exr"
[[ $rc -eq 1 ]] || fail "grt with stokes: exit status $rc"
grep -q "plate.wscene:10:[0-9]*: error: detector 'cam' asks for Stokes output, but integrator 'gr' carries no polarisation" <<<"$stderr" ||
    fail "grt with stokes: $stderr"
[[ ! -e "$out/grt.exr" ]] || fail "grt.exr written after an error"
run render "$out/plate.wscene" --integrator ray -D with_pol=true -D stokes=false -o "$out/ray.exr"
[[ $rc -eq 1 ]] || fail "ray with a polariser: exit status $rc"
grep -q "plate.wscene:14:[0-9]*: error: detector 'cam_pol' asks for a polarizer" <<<"$stderr" || fail "ray with a polariser: $stderr"
# 5. `compare` renders grt, sample_solve and ray side by side (no polarisation asked for).
run compare "$out/plate.wscene" -D stokes=false --integrators grt,sample_solve,ray --spp 4 -o "$out/cmp" --quiet
[[ $rc -eq 0 ]] || fail "compare: exit status $rc: $stderr"
for i in grt sample_solve ray; do
    grep -q "^$i," "$out/cmp/results.csv" || fail "compare: no row for $i in results.csv"
done

[[ $failures -eq 0 ]] || { echo "$failures failure(s)"; exit 1; }
echo "ok"
