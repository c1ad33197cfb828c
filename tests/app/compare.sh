#!/usr/bin/env bash
# compare.sh PART PHASOR WRITE_TEST_EXR SOURCE_DIR OUTDIR — `phasor compare` end to end:
#   double_slit  grt vs rs on the paper's double slit: every output, the max-error column equal to
#                the figure the double-slit validation checks (max |grt − rs| / max(rs), computed
#                independently by `phasor profile` from the EXRs written, and within the
#                validation's 2e-3), the same with the rs image as --reference, and the page in
#                headless Chromium: every <img> loads, no error, every link resolves, a screenshot
#   errors       bad input: an unknown integrator (suggestion), a reference of another resolution,
#                an integrator that cannot render the scene (its own error; the others still run
#                and the table says which failed): clear errors, exit status 1
#   modes        equal time (--time), --reference-integrator/--reference-spp, --column, all
#   sigint       Ctrl-C during the second integrator: exit 130, the finished run and the page
#   no_plots     without matplotlib: the CSV instead of each plot, one line saying how to install it;
#                without jinja2 (and matplotlib): no page, results.md and results.json say it all
#   reference    the reference is independent of every graded run: `grt` cut after three scattering events (a
#                deliberately biased integrator) passes against a reference rendered with the graded
#                runs' seed and is caught by compare's own reference (other seeds, 4× the samples);
#                `ray` against it is "not comparable"; the page (Chromium) shows the seed, version,
#                -D values, warnings, the reference's noise floor and the colour error
set -u
part=$1 phasor=$2 mkexr=$3 src=$4 out=$5/compare_$1
rm -rf "$out"; mkdir -p "$out"
ds=$src/scenes/validation/double_slit.wscene
small=$src/tests/app/scenes/small.wscene
bias=$src/tests/app/scenes/compare_bias.wscene
slow=$src/tests/app/scenes/slow.wscene
source "$(dirname "$0")/common.sh"  # fail, run
# field CSV ROW_NAME COLUMN_NAME: a field of results.csv (rows by integrator, columns by header).
field() {
    awk -F, -v row="$2" -v col="$3" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == col) c = i; next }
        $1 == row { print $c }' "$1"
}
is_png() { [[ "$(head -c 4 "$1" 2>/dev/null | od -An -tx1 | tr -d ' ')" == 89504e47 ]]; }
no_temporaries() { if ls -A "$1" | grep -q '^\.'; then fail "temporary files left in $1: $(ls -A "$1" | tr '\n' ' ')"; fi; }

# check_page DIR: opens DIR/index.html in headless Chromium; every image loads, no error event,
# every relative link and image source exists; a screenshot DIR/page.png.
check_page() {
    local dir=$1 chromium
    chromium=$(command -v chromium || command -v chromium-browser) ||
        { fail "chromium is needed to check the page (scripts/install-deps.sh installs it)"; return; }
    local flags=(--headless --no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking
                 --disable-component-update --disable-sync --user-data-dir="$out/chromium-profile")
    # A copy of the page beside it (same relative links) with a script that marks, after the load
    # event, each image that loaded (naturalWidth > 0) and counts error events (a resource that
    # failed, a script error). (No "&" in it: bash substitutes the match for it.)
    local script='<script>let errors = 0; window.addEventListener("error", () => { ++errors; }, true);
window.addEventListener("load", () => { let bad = 0; for (const img of document.images) {
const ok = img.naturalWidth > 0; img.setAttribute("data-loaded", ok ? "yes" : "no"); if (!ok) ++bad; }
document.body.setAttribute("data-check", document.images.length + " images, " + bad + " broken, " + errors + " errors"); });
</script>'
    local page
    page=$(cat "$dir/index.html")
    printf '%s\n' "${page/<\/body>/$script</body>}" >"$dir/.check.html"
    timeout 60 "$chromium" "${flags[@]}" --virtual-time-budget=10000 --dump-dom "file://$dir/.check.html" \
        >"$out/dom.html" 2>"$out/chromium.log"
    rm -f "$dir/.check.html"
    local check images
    check=$(grep -o 'data-check="[^"]*"' "$out/dom.html")
    images=$(grep -o '<img ' "$dir/index.html" | wc -l)
    [[ "$check" == "data-check=\"$images images, 0 broken, 0 errors\"" && $images -ge 5 ]] ||
        fail "page: $check (index.html has $images <img>); chromium: $(tail -3 "$out/chromium.log")"
    # Every relative href/src names a file of the folder (the page works without a server).
    for f in $(grep -o '\(href\|src\)="[^"]*"' "$dir/index.html" | sed 's/.*="\(.*\)"/\1/' | sort -u); do
        [[ "$f" != *:* && -f "$dir/$f" ]] || fail "page links to '$f', which is not a file in $dir"
    done
    timeout 60 "$chromium" "${flags[@]}" --window-size=1400,2000 --screenshot="$out/page.png" \
        "file://$dir/index.html" >/dev/null 2>&1
    is_png "$out/page.png" || fail "no screenshot of the page"
}

case $part in
double_slit)
    dir=$out/ds
    run compare "$ds" --integrators grt,rs -o "$dir"
    [[ $rc -eq 0 ]] || fail "double slit: exit status $rc: $stderr"
    for f in grt.exr grt.png rs.exr rs.png grid.png diff_grt.png results.csv results.md profile.csv profile.png \
        convergence.csv convergence.png index.html; do
        [[ -s "$dir/$f" ]] || fail "double slit: $f not written"
    done
    for f in "$dir"/*.png; do is_png "$f" || fail "$f is not a PNG"; done
    no_temporaries "$dir"
    grep -q '^\[1/2\] grt: 4096 spp in ' <<<"$stderr" || fail "no progress line for grt: $stderr"
    grep -q '^\[2/2\] rs: solved 48 pixels' <<<"$stderr" || fail "no progress line for rs: $stderr"
    # No reference given: rs (deterministic) is the best-converged run, and the table says so.
    [[ $(field "$dir/results.csv" rs role) == reference && $(field "$dir/results.csv" grt role) == compared ]] ||
        fail "rs is not the reference: $(cat "$dir/results.csv")"
    grep -q "reference: rs, deterministic (no sampling noise; no reference was given)" "$dir/results.md" ||
        fail "results.md does not say which run is the reference"
    [[ $(field "$dir/results.csv" grt spp) == 4096 ]] || fail "grt spp: $(cat "$dir/results.csv")"
    # The max-error column is the double-slit validation's figure max |grt − rs| / max(rs)
    # (tests/validation/double_slit_test.cpp, MaxDiffOfPeak), as `phasor profile` computes it from
    # the two EXRs written: equal to the 6 digits profile prints (relative 1e-5), within the 2e-3
    # the validation allows.
    max=$(field "$dir/results.csv" grt max_error)
    run profile "$dir/grt.exr" "$dir/rs.exr" --quiet
    fig=$(sed -n 's/.*max |grt - rs| \/ max(rs) = \([^ ]*\) .*/\1/p' <<<"$stderr")
    awk -v a="$max" -v b="$fig" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(b > 0 && d <= 1e-5 * b && a <= 2e-3) }' ||
        fail "max error '$max' in results.csv, profile says '$fig' (must agree to 1e-5 and be <= 2e-3)"
    echo "double slit: max error $max (profile: $fig)"
    # RMSE from the EXRs (independent of the program): √(mean((grt − rs)²)) over the 48 pixels.
    rmse=$(awk -F, 'NR > 1 { s += ($2 - $3) ^ 2; n++ } END { printf "%.9g", sqrt(s / n) }' "$dir/profile.csv")
    awk -v a="$(field "$dir/results.csv" grt rmse)" -v b="$rmse" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= 1e-6 * b) }' ||
        fail "RMSE $(field "$dir/results.csv" grt rmse), from profile.csv $rmse"

    # The rs image as --reference: the same grt render, the same figure.
    run compare "$ds" --integrators grt --reference "$dir/rs.exr" -o "$out/ref"
    [[ $rc -eq 0 ]] || fail "--reference: exit status $rc: $stderr"
    [[ $(field "$out/ref/results.csv" grt max_error) == "$max" ]] ||
        fail "--reference rs.exr: max error $(field "$out/ref/results.csv" grt max_error), expected $max"
    [[ -s "$out/ref/reference.png" ]] || fail "--reference: no reference.png"
    grep -q "reference: the image '.*rs.exr'" "$out/ref/results.md" || fail "--reference: not named in results.md"
    grep -q "reference noise floor: 0 (deterministic: no sampling noise)" "$out/ref/results.md" ||
        fail "--reference rs.exr: its noise floor is not 0: $(cat "$out/ref/results.md")"

    check_page "$dir"
    ;;
errors)
    # An unknown integrator: a suggestion, nothing rendered, nothing written (not even the folder).
    run compare "$ds" --integrators grt,grtt -o "$out/unknown"
    [[ $rc -eq 1 ]] && grep -q "^error: unknown integrator 'grtt'; did you mean 'grt'?" <<<"$stderr" ||
        fail "unknown integrator: exit status $rc, stderr '$stderr'"
    [[ ! -e "$out/unknown" ]] || fail "unknown integrator: $out/unknown was created"
    # A reference of another resolution.
    "$mkexr" "$out/small.exr" 8 3 0 1 2 3 4 3 2 1 || exit 1
    run compare "$ds" --integrators grt --reference "$out/small.exr" -o "$out/size"
    [[ $rc -eq 1 ]] && grep -q "^error: reference '.*small.exr' is 8x3 pixels but detector 'sensor' renders 48x1$" <<<"$stderr" ||
        fail "reference size: exit status $rc, stderr '$stderr'"
    [[ ! -e "$out/size" ]] || fail "reference size: $out/size was created"
    run compare "$ds" --integrators grt --reference "$out/none.exr" -o "$out/none"
    [[ $rc -eq 1 ]] && grep -q "^error: reference '.*none.exr': cannot read" <<<"$stderr" ||
        fail "missing reference: exit status $rc, stderr '$stderr'"
    run compare "$ds" --integrators grt --spp 4 --time 1
    [[ $rc -eq 1 ]] && grep -q "'--spp' (equal samples) and '--time' (equal time) exclude each other" <<<"$stderr" ||
        fail "--spp with --time: exit status $rc"
    # rs cannot render a camera scene: its own located error; ray and grt still run; exit status 1.
    dir=$out/fail
    run compare "$small" --integrators ray,rs,grt --spp 4 -o "$dir"
    [[ $rc -eq 1 ]] || fail "rs on a camera: exit status $rc, expected 1"
    grep -q "small.wscene:8:1: error: integrator 'rs' needs a virtual_plane detector" <<<"$stderr" ||
        fail "rs on a camera: its error is not reported: $stderr"
    grep -q "^error: rs failed" <<<"$stderr" || fail "rs on a camera: no summary line: $stderr"
    for f in ray.exr ray.png grt.exr grt.png grid.png diff_grt.png results.csv index.html; do
        [[ -s "$dir/$f" ]] || fail "rs on a camera: $f not written"
    done
    [[ ! -e "$dir/rs.exr" ]] || fail "rs on a camera: rs.exr written"
    [[ $(field "$dir/results.csv" rs status) == failed && $(field "$dir/results.csv" grt status) == ok ]] ||
        fail "rs on a camera: results.csv $(cat "$dir/results.csv")"
    grep -q "integrator 'rs' needs a virtual_plane detector" "$dir/results.csv" || fail "the table lacks rs's error"
    grep -q "<h2>Failures</h2>" "$dir/index.html" || fail "the page lacks the failures"
    no_temporaries "$dir"
    ;;
modes)
    # Equal time: each sampling integrator renders for the budget (never stopped before it; the
    # convergence snapshots taken meanwhile extend the deadline and are not counted).
    dir=$out/time
    run compare "$small" --integrators grt,ray --time 0.3 -o "$dir" --quiet
    [[ $rc -eq 0 ]] || fail "--time: exit status $rc: $stderr"
    for n in grt ray; do
        awk -v s="$(field "$dir/results.csv" $n seconds)" -v spp="$(field "$dir/results.csv" $n spp)" \
            'BEGIN { exit !(s >= 0.3 && s < 30 && spp >= 1) }' ||
            fail "--time 0.3: $n took $(field "$dir/results.csv" $n seconds) s for $(field "$dir/results.csv" $n spp) spp"
    done
    grep -q "equal time: 0.3 s per integrator" "$dir/index.html" || fail "--time: the page does not say so"
    # A reference render of its own, and a profile along a column.
    dir=$out/refint
    run compare "$small" --integrators ray --spp 4 --reference-integrator grt --reference-spp 16 --column 16 -o "$dir"
    [[ $rc -eq 0 ]] || fail "--reference-integrator: exit status $rc: $stderr"
    [[ -s "$dir/reference_grt.exr" && -s "$dir/ray.exr" && -s "$dir/profile.png" ]] ||
        fail "--reference-integrator: outputs $(ls "$dir")"
    [[ $(field "$dir/results.csv" "grt (reference)" role) == reference &&
        $(field "$dir/results.csv" "grt (reference)" spp) == 16 && $(field "$dir/results.csv" ray spp) == 4 ]] ||
        fail "--reference-integrator: $(cat "$dir/results.csv")"
    [[ "$(head -1 "$dir/profile.csv")" == "y_px,ray,grt (reference),abs_diff" ]] || fail "--column: $(head -1 "$dir/profile.csv")"
    grep -q "reference: grt at 16 spp: 4 independent renders of 4 spp (--reference-integrator)" "$dir/results.md" ||
        fail "--reference-integrator: results.md $(cat "$dir/results.md")"
    # `all`: every registered integrator, in the registry's order (a new one joins by registering).
    dir=$out/all
    run compare "$ds" --integrators all --spp 16 -o "$dir" --quiet
    registered=$("$phasor" list integrator | sed -n 's/^  \([a-z_0-9]*\) — .*/\1/p' | tr '\n' ' ')
    compared=$(awk -F, 'NR > 1 { printf "%s ", $1 }' "$dir/results.csv")
    [[ $rc -eq 0 && -n "$registered" && "$compared" == "$registered" ]] ||
        fail "--integrators all: exit status $rc, compared '$compared', registered '$registered': $stderr"
    ;;
sigint)
    # Ctrl-C while the second integrator renders (slow: ≥ 15 s per pass): the first one's results
    # and the page are written, the second is marked interrupted, exit status 130.
    dir=$out/stopped
    "$phasor" compare "$slow" --integrators ray,slow --spp 1 --threads 1 -o "$dir" 2>"$out/stderr" &
    pid=$!
    for _ in $(seq 1 300); do grep -q '^\[1/2\] ray: ' "$out/stderr" && break; sleep 0.1; done
    sleep 1
    kill -INT $pid
    wait $pid; rc=$?
    [[ $rc -eq 130 ]] || fail "Ctrl-C: exit status $rc, expected 130: $(cat "$out/stderr")"
    [[ -s "$dir/index.html" && -s "$dir/ray.exr" ]] || fail "Ctrl-C: outputs $(ls "$dir" 2>&1)"
    # (slow is normally interrupted mid-pass; on a machine so loaded that the signal beat its start
    # it is not_run — either way it has no complete result)
    slow_status=$(field "$dir/results.csv" slow status)
    [[ $(field "$dir/results.csv" ray status) == ok && ($slow_status == interrupted || $slow_status == not_run) ]] ||
        fail "Ctrl-C: $(cat "$dir/results.csv")"
    grep -q "stopped (Ctrl-C)" "$dir/index.html" || fail "Ctrl-C: the page does not say the comparison was stopped"
    no_temporaries "$dir"
    ;;
no_plots)
    # A Python without matplotlib (a stand-in package that fails to import shadows it): every plot
    # becomes its CSV, with a one-line warning naming the package; the page (jinja2) links the data,
    # the rest is written and the exit status is 0.
    mkdir -p "$out/blocked/matplotlib"
    echo 'raise ImportError("matplotlib blocked by the test")' >"$out/blocked/matplotlib/__init__.py"
    printf '#!/bin/sh\nPYTHONPATH="%s" exec python3 "$@"\n' "$out/blocked" >"$out/python-without-matplotlib"
    chmod +x "$out/python-without-matplotlib"
    dir=$out/ds
    PHASOR_PYTHON=$out/python-without-matplotlib run compare "$ds" --integrators grt,rs --spp 64 -o "$dir"
    [[ $rc -eq 0 ]] || fail "no matplotlib: exit status $rc: $stderr"
    grep -q "warning: no Python with matplotlib.*(install it with: apt-get install python3-matplotlib)" <<<"$stderr" ||
        fail "no matplotlib: no install hint: $stderr"
    for f in grt.exr grt.csv rs.csv grid.png profile.csv convergence.csv results.csv results.json index.html; do
        [[ -s "$dir/$f" ]] || fail "no matplotlib: $f not written"
    done
    for f in grt.png profile.png convergence.png; do [[ ! -e "$dir/$f" ]] || fail "no matplotlib: $f written"; done
    grep -q 'not drawn: .*apt-get install python3-matplotlib' "$dir/index.html" || fail "no matplotlib: the page does not say"
    no_temporaries "$dir"
    # A Python without site packages (-S): no jinja2 either. No page — one warning saying how to
    # install it — and results.md and results.json carry everything; exit status 0.
    printf '#!/bin/sh\nexec python3 -S "$@"\n' >"$out/python-bare"
    chmod +x "$out/python-bare"
    dir=$out/bare
    PHASOR_PYTHON=$out/python-bare run compare "$ds" --integrators grt,rs --spp 64 -o "$dir"
    [[ $rc -eq 0 ]] || fail "no jinja2: exit status $rc: $stderr"
    grep -q "warning: no Python with jinja2 found .*(install it with: apt-get install python3-jinja2); index.html is not written (results.md and results.json are)" <<<"$stderr" ||
        fail "no jinja2: no install hint: $stderr"
    [[ ! -e "$dir/index.html" && -s "$dir/results.md" && -s "$dir/results.json" ]] || fail "no jinja2: outputs $(ls "$dir")"
    grep -q "wrote $dir/results.md and" <<<"$stderr" || fail "no jinja2: the summary names the page: $stderr"
    no_temporaries "$dir"
    ;;
reference)
    # 1. The failure this guards against: a reference that shares the graded run's random numbers.
    #    `grt` and `biased` (grt cut after four scattering events) draw the same numbers for the same seed, so
    #    their noise cancels in biased − reference and the bias passes the test.
    common=(--spp 64 --seed 7 --sampler independent)
    run render "$bias" --integrator full "${common[@]}" -o "$out/same_seed.exr" --quiet
    [[ $rc -eq 0 ]] || fail "same-seed reference render: exit status $rc: $stderr"
    dir=$out/same_seed
    run compare "$bias" --integrators biased --reference "$out/same_seed.exr" "${common[@]}" -o "$dir" --quiet
    [[ $rc -eq 0 ]] || fail "same-seed reference: exit status $rc: $stderr"
    verdict=$(field "$dir/results.csv" biased verdict)
    [[ $verdict == consistent* ]] || fail "the same-seed reference did not pass the biased integrator (the failure this test demonstrates): '$verdict'"
    grep -q "rendered with seed 7, the seed of the compared runs" <<<"$stderr$(cat "$dir/results.md")" ||
        fail "no warning about the reference's seed: $(cat "$dir/results.md")"
    # 2. compare's own reference: grt (the first wave-optical integrator compared) at 4× the samples,
    #    4 renders with seeds 8–11. It catches the bias and passes grt itself; ray (other physics)
    #    is not comparable. A -D value and a --permissive warning must appear on the page.
    dir=$out/auto
    run compare "$bias" --integrators grt,biased,ray "${common[@]}" -D gain=1 -D nosuch=2 --permissive -o "$dir"
    [[ $rc -eq 0 ]] || fail "automatic reference: exit status $rc: $stderr"
    [[ $(field "$dir/results.csv" "grt (reference)" role) == reference &&
        $(field "$dir/results.csv" "grt (reference)" spp) == 256 ]] ||
        fail "the reference is not grt at 256 spp: $(cat "$dir/results.csv")"
    [[ $(field "$dir/results.csv" biased verdict) == differs* ]] ||
        fail "compare's reference did not catch the biased integrator: $(cat "$dir/results.csv")"
    [[ $(field "$dir/results.csv" grt verdict) == consistent* ]] ||
        fail "grt is not consistent with its own independent reference: $(cat "$dir/results.csv")"
    [[ $(field "$dir/results.csv" ray comparable) == false && $(field "$dir/results.csv" ray verdict) == "not comparable"* ]] ||
        fail "ray against a wave-optical reference is not marked not comparable: $(cat "$dir/results.csv")"
    floor=$(field "$dir/results.csv" "grt (reference)" noise_floor)
    awk -v f="$floor" 'BEGIN { exit !(f > 0) }' || fail "no noise floor: '$floor'"
    awk -v c="$(field "$dir/results.csv" biased rgb_rmse)" 'BEGIN { exit !(c > 0) }' || fail "no RGB RMSE"
    grep -q "seeds (8–11) differ from the compared runs' (7)" "$dir/results.md" ||
        fail "results.md does not say how the reference is independent: $(cat "$dir/results.md")"
    for want in "phasor $("$phasor" --version | cut -d' ' -f2)" "seed: 7" "-D gain=1" "noise floor" "does not override any Define"; do
        grep -qF -- "$want" "$dir/results.md" || fail "results.md lacks '$want'"
    done
    python3 -c "import json, sys; r = json.load(open(sys.argv[1])); assert r['format'] == 'phasor-compare-results' and r['seed'] == 7 and r['reference']['noise_floor'] > 0" \
        "$dir/results.json" || fail "results.json: $(head -c 400 "$dir/results.json")"
    check_page "$dir"
    # What the page shows, as Chromium rendered it.
    for want in "$("$phasor" --version | cut -d' ' -f2)" ">7 (every compared run" "-D gain=1" "noise floor" \
        "RGB RMSE" "does not override any Define" "differs (z =" "not comparable"; do
        grep -qF -- "$want" "$out/dom.html" || fail "the page (as Chromium shows it) lacks '$want'"
    done
    ;;
*) echo "unknown part '$part'"; exit 2 ;;
esac

[[ $failures -eq 0 ]] || { echo "$failures failure(s)"; exit 1; }
echo "compare $part: all checks passed"
