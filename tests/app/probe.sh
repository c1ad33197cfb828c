#!/usr/bin/env bash
# probe.sh PHASOR SCENE OUTDIR — `phasor probe` against references computed here, independently of
# phasor's code (awk): Fresnel for a dielectric and for a conductor (the real-arithmetic form of the
# complex Fresnel equations), a Lambertian albedo, Saunderson's total reflectance of `plastic` with
# the hemispherical Fresnel integral by Simpson's rule, a grating's orders (Bessel series), the Airy
# formula of a film (complex arithmetic) and the quarter-wave stack's closed form, a rough surface's
# glint and total (F), the weighted sums of a mix, a two-sided sheet. Also: the CSV's exact header and rows, `-`
# for stdout, the texture context (--uv), --ray, the seed, the plot, and errors (exit status 1, a
# message, no output file).
set -u
phasor=$1 scene=$2 out=$3/probe
rm -rf "$out"; mkdir -p "$out"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# run ARGS…: `phasor probe SCENE ARGS…`, leaving $rc, $stdout, $stderr.
run() {
    "$phasor" probe "$scene" "$@" >"$out/.stdout" 2>"$out/.stderr"; rc=$?
    stdout=$(cat "$out/.stdout"); stderr=$(cat "$out/.stderr")
    rm -f "$out/.stdout" "$out/.stderr"
}
# field CSV ROW COL: one field of the CSV text in $stdout (ROW 1 = the header).
field() { awk -F, -v r="$1" -v c="$2" 'NR == r { print $c }' <<<"$stdout"; }
# near WHAT GOT EXPECTED TOL
near() {
    awk -v g="$2" -v e="$3" -v t="$4" 'BEGIN { d = g - e; if (d < 0) d = -d; exit !(g != "" && d <= t) }' ||
        fail "$1: got '$2', expected $3 ± $4"
}
awkmath='
function fresnel(mu, eta,   s2, ct, rs, rp) {   # unpolarised, dielectric, eta = n_t/n_i (Hecht 4.6)
    s2 = (1 - mu * mu) / (eta * eta); if (s2 >= 1) return 1
    ct = sqrt(1 - s2); rs = (mu - eta * ct) / (mu + eta * ct); rp = (eta * mu - ct) / (eta * mu + ct)
    return (rs * rs + rp * rp) / 2
}
function conductor(mu, n, k,   s2, t0, ab, a, rs, rp) {  # from vacuum onto n + ik, real arithmetic
    s2 = 1 - mu * mu; t0 = n * n - k * k - s2; ab = sqrt(t0 * t0 + 4 * n * n * k * k); a = sqrt((ab + t0) / 2)
    rs = (ab + mu * mu - 2 * a * mu) / (ab + mu * mu + 2 * a * mu)
    rp = rs * (mu * mu * ab + s2 * s2 - 2 * a * mu * s2) / (mu * mu * ab + s2 * s2 + 2 * a * mu * s2)
    return (rs + rp) / 2
}
function diffusefresnel(eta,   n, h, i, t, mu, muc, s) {  # 2∫F(μ)μdμ, Simpson in t, μ = μc + (1 − μc)t²
    muc = eta < 1 ? sqrt(1 - eta * eta) : 0; n = 20000; h = 1 / n; s = 0
    for (i = 0; i <= n; i++) {
        t = i * h; mu = muc + (1 - muc) * t * t
        s += (i == 0 || i == n ? 1 : (i % 2 ? 4 : 2)) * fresnel(mu, eta) * mu * 2 * (1 - muc) * t
    }
    return muc * muc + 2 * s * h / 3
}
function atan2pi(y, x) { return atan2(y, x) }
# Complex arithmetic on (re, im) pairs; results in the globals _r, _i.
function cset(a, b) { _r = a; _i = b }
function cmul(ar, ai, br, bi) { cset(ar * br - ai * bi, ar * bi + ai * br) }
function cdiv(ar, ai, br, bi,   d) { d = br * br + bi * bi; cset((ar * br + ai * bi) / d, (ai * br - ar * bi) / d) }
function csqrt(ar, ai,   m) { m = sqrt(ar * ar + ai * ai); cset(sqrt((m + ar) / 2), (ai < 0 ? -1 : 1) * sqrt((m - ar) / 2)) }
# cosθ in a medium n = nr + i·ni for the invariant s = n₀sinθ₀, on the branch whose wave decays
# into the medium (Im(n·cosθ) ≥ 0, the time convention of e^{+iδ}); in _r, _i.
function ccos(s, nr, ni,   ar, ai) {
    cdiv(s, 0, nr, ni); cmul(_r, _i, _r, _i); csqrt(1 - _r, -_i); ar = _r; ai = _i
    cmul(nr, ni, ar, ai); if (_i < 0) { ar = -ar; ai = -ai }
    cset(ar, ai)
}
# Airy reflectance (Born & Wolf §7.6.1), unpolarised, of one film n1 (thickness d [m]) between air
# and n2, light from air at θ0 [rad], vacuum wavelength l [m]: r = (r01 + r12 e)/(1 + r01 r12 e),
# e = exp(2i·k0·n1·d·cosθ1), per polarisation (s: q = n cosθ; p: the same with cosθ/n).
function airy(th, l, n1r, n1i, d, n2r, n2i,   s, c0r, c1r, c1i, c2r, c2i, p, q0r, q0i, q1r, q1i, q2r, q2i, ar, ai, br, bi, er, ei, nr, ni, R) {
    s = sin(th); c0r = cos(th)
    ccos(s, n1r, n1i); c1r = _r; c1i = _i
    ccos(s, n2r, n2i); c2r = _r; c2i = _i
    cmul(n1r, n1i, c1r, c1i); cmul(_r, _i, 0, 4 * atan2(0, -1) * d / l); cset(exp(_r) * cos(_i), exp(_r) * sin(_i)); er = _r; ei = _i
    R = 0
    for (p = 0; p < 2; p++) {
        if (p == 0) { q0r = c0r; q0i = 0; cmul(n1r, n1i, c1r, c1i); q1r = _r; q1i = _i; cmul(n2r, n2i, c2r, c2i); q2r = _r; q2i = _i }
        else { q0r = c0r; q0i = 0; cdiv(c1r, c1i, n1r, n1i); q1r = _r; q1i = _i; cdiv(c2r, c2i, n2r, n2i); q2r = _r; q2i = _i }
        cdiv(q0r - q1r, q0i - q1i, q0r + q1r, q0i + q1i); ar = _r; ai = _i   # r01
        cdiv(q1r - q2r, q1i - q2i, q1r + q2r, q1i + q2i); br = _r; bi = _i   # r12
        cmul(br, bi, er, ei); nr = ar + _r; ni = ai + _i                      # r01 + r12 e
        cmul(ar, ai, _r, _i); cdiv(nr, ni, 1 + _r, _i)                       # / (1 + r01 r12 e)
        R += (_r * _r + _i * _i) / 2
    }
    return R
}
function besselj(n, x,   s, t, k) {  # J_n(x), n ≥ 0, power series (DLMF 10.2.2), exact to ~1e-15 for x < 10
    t = 1; for (k = 1; k <= n; k++) t *= x / 2 / k
    s = 0; for (k = 0; k < 60; k++) { s += t; t *= -(x / 2) * (x / 2) / ((k + 1) * (k + 1 + n)) }
    return s
}
BEGIN { pi = atan2(0, -1); deg = pi / 180 }'
calc() { awk "$awkmath"' BEGIN { printf "%.15g\n", '"$1"' }'; }

# 1. Dielectric 1.5 at normal incidence: R = 0.04, T = 0.96 as power (the listed transmission weight
#    0.96/1.5² is a radiance throughput); the CSV exactly.
run --material glass --theta 0deg --lambda 550nm --csv "$out/glass0.csv" --quiet
[[ $rc -eq 0 ]] || fail "glass 0deg: exit status $rc: $stderr"
expected=$'kind,order,theta_o,phi_o,value,stderr\nR,,,,0.04,0\nT,,,,0.96,0\nlobe,0,0,0,0.04,0\nlobe,1,3.14159265358979,0,0.96,0'
[[ "$(cat "$out/glass0.csv")" == "$expected" ]] || fail "glass0.csv is '$(cat "$out/glass0.csv")'"
grep -q "R = 0.04" <<<"$stdout" && grep -q "transmission" <<<"$stdout" || fail "glass 0deg report: '$stdout'"

# 2. Dielectric at oblique incidence, two indices: R = Fresnel, T = 1 − R, the lobes' angles from
#    the law of reflection and Snell's law (φ_o = φ + 180°). `--csv -`: the CSV alone on stdout.
for case in "1.5 60 0" "1.33 35 120" "2.42 75 -40"; do
    read -r n th ph <<<"$case"
    run --material glass --theta "${th}deg" --phi "${ph}deg" --lambda 633nm --csv - -D "n_glass=$n"
    [[ $rc -eq 0 ]] || { fail "glass $case: exit status $rc: $stderr"; continue; }
    [[ "$(field 1 0)" == "kind,order,theta_o,phi_o,value,stderr" ]] || fail "glass $case: header '$(field 1 0)'"
    [[ $(wc -l <<<"$stdout") -eq 5 ]] || fail "glass $case: stdout is not the CSV alone: '$stdout'"
    grep -q "R = " <<<"$stderr" || fail "glass $case: the report is not on stderr"
    R=$(calc "fresnel(cos($th * deg), $n)")
    near "glass $case R" "$(field 2 5)" "$R" 1e-10
    near "glass $case T" "$(field 3 5)" "$(calc "1 - $R")" 1e-10
    [[ "$(field 2 6),$(field 3 6)" == "0,0" ]] || fail "glass $case: stderr of exact sums not 0"
    phio=$(calc "atan2(sin(($ph + 180) * deg), cos(($ph + 180) * deg))")
    [[ "$(field 4 1),$(field 4 2)" == "lobe,0" && "$(field 5 1),$(field 5 2)" == "lobe,1" ]] ||
        fail "glass $case: lobe rows '$stdout'"
    near "glass $case reflected theta" "$(field 4 3)" "$(calc "$th * deg")" 1e-12
    near "glass $case reflected phi" "$(field 4 4)" "$phio" 1e-12
    near "glass $case refracted theta" "$(field 5 3)" "$(calc "pi - atan2(sin($th * deg) / $n, sqrt(1 - (sin($th * deg) / $n)^2))")" 1e-12
    near "glass $case refracted phi" "$(field 5 4)" "$phio" 1e-12
    near "glass $case lobe sum" "$(calc "$(field 4 5) + $(field 5 5)")" 1 1e-12
done

# 3. Conductor n + ik = 0.2 + 3.4i, and 1.8 + 0.4i: R at 45° and 80° (real-arithmetic Fresnel), no T.
for case in "0.2 3.4 45 30" "1.8 0.4 80 -90"; do
    read -r n k th ph <<<"$case"
    run --material metal --theta "${th}deg" --phi "${ph}deg" --lambda 500nm --csv - -D "n_metal=$n+${k}i"
    [[ $rc -eq 0 ]] || { fail "metal $case: exit status $rc: $stderr"; continue; }
    near "metal $case R" "$(field 2 5)" "$(calc "conductor(cos($th * deg), $n, $k)")" 1e-10
    [[ "$(field 3 5)" == 0 && $(wc -l <<<"$stdout") -eq 4 ]] || fail "metal $case: T or lobes: '$stdout'"
    near "metal $case lobe phi" "$(field 4 4)" "$(calc "atan2(sin(($ph + 180) * deg), cos(($ph + 180) * deg))")" 1e-12
done

# 4. Lambertian: R = albedo exactly (the cosine-sampled weight is constant: standard error 0), T = 0;
#    a textured albedo follows --uv (checkerboard of scale 2: 0.1 at (0.1, 0.1), 0.9 at (0.6, 0.1)).
run --material matte --theta 20deg --lambda 450nm --csv - -D albedo=0.37
[[ "$(field 2 0)" == "R,,,,0.37,0" && "$(field 3 0)" == "T,,,,0,0" && $(wc -l <<<"$stdout") -eq 3 ]] ||
    fail "matte: '$stdout' $stderr"
for uv in "0.1 0.1 0.1" "0.6 0.1 0.9"; do
    read -r u v want <<<"$uv"
    run --material checked --theta 10deg --lambda 500nm --uv "$u" "$v" --csv -
    [[ "$(field 2 5)" == "$want" ]] || fail "checked at uv ($u, $v): R = '$(field 2 5)', expected $want"
done

# 5. plastic: Saunderson's total reflectance F + (1 − F)ρ(1 − F̄in)/(1 − ρF̄in) by Monte Carlo, within
#    4 standard errors (+ 1e-6 for the reference's Simpson error); 1 for a white base.
for case in "0.5 1.5 30" "1 1.5 70" "0.8 1.33 0"; do
    read -r rho n th <<<"$case"
    run --material paint --theta "${th}deg" --lambda 550nm --csv - -D "albedo=$rho" -D "n_glass=$n"
    [[ $rc -eq 0 ]] || { fail "paint $case: exit status $rc: $stderr"; continue; }
    ref=$(calc "fresnel(cos($th * deg), $n) + (1 - fresnel(cos($th * deg), $n)) * $rho * (1 - diffusefresnel(1 / $n)) / (1 - $rho * diffusefresnel(1 / $n))")
    se=$(field 2 6)
    awk -v s="$se" 'BEGIN { exit !(s > 0 && s < 0.01) }' || fail "paint $case: standard error '$se'"
    near "paint $case R" "$(field 2 5)" "$ref" "$(calc "4 * $se + 1e-6")"
    near "paint $case specular lobe" "$(field 4 5)" "$(calc "fresnel(cos($th * deg), $n)")" 1e-12
done
# The seed: the same seed gives the same digits, another seed other digits (of the same value).
run --material paint --theta 30deg --lambda 550nm --csv - --seed 7; a=$stdout
run --material paint --theta 30deg --lambda 550nm --csv - --seed 7; [[ "$stdout" == "$a" ]] || fail "seed 7 twice differs"
run --material paint --theta 30deg --lambda 550nm --csv - --seed 8; [[ "$stdout" != "$a" ]] || fail "seeds 7 and 8 agree"
# --ray: a smooth interface is the same in the ray-optics limit.
run --material glass --theta 40deg --lambda 550nm --csv - --ray; a=$stdout
run --material glass --theta 40deg --lambda 550nm --csv -
[[ "$stdout" == "$a" ]] || fail "--ray changed a smooth dielectric"

# 5b. grating on the metal (ĝ = +x), light from θ in the x–z plane: order j leaves at
#    sinθ_o = |sinθ − jλ/Λ| with J_j(m)²·R/Σ_prop J², m = 2πh·cosθ/λ (D6, renormalised), R = F.
for case in "20 550 0.1" "0 633 0.15" "45 450 0.08"; do
    read -r th lam h <<<"$case"
    run --material lines --theta "${th}deg" --lambda "${lam}nm" --csv - -D "height=${h}um"
    [[ $rc -eq 0 ]] || { fail "grating $case: exit status $rc: $stderr"; continue; }
    R=$(calc "conductor(cos($th * deg), 0.2, 3.4)")
    near "grating $case R" "$(field 2 5)" "$R" 1e-10
    rows=$(wc -l <<<"$stdout")
    for ((r = 4; r <= rows; r++)); do
        j=$(field "$r" 2)
        ref=$(awk "$awkmath"' BEGIN { th = '"$th"' * deg; l = '"$lam"'e-9; L = 2e-6; m = 2 * pi * '"$h"'e-6 * cos(th) / l
            for (k = -20; k <= 20; k++) if ((sin(th) - k * l / L) ^ 2 < 1) S += besselj(k < 0 ? -k : k, m) ^ 2
            jj = '"$j"'; e = besselj(jj < 0 ? -jj : jj, m) ^ 2 * '"$R"' / S
            so = sin(th) - jj * l / L; if (so < 0) so = -so
            printf "%.15g %.15g\n", e, atan2(so, sqrt(1 - so * so)) }')
        read -r eff theta <<<"$ref"
        near "grating $case order $j efficiency" "$(field "$r" 5)" "$eff" "$(calc "1e-9 * $eff + 1e-15")"
        near "grating $case order $j theta_o" "$(field "$r" 3)" "$theta" 1e-9
        # Classical mount: every order in the plane of incidence and ĝ (φ measured from ĝ).
        near "grating $case order $j sin(phi_o)" "$(calc "sin($(field "$r" 4))")" 0 1e-9
    done
    [[ $rows -ge 6 ]] || fail "grating $case: too few orders: '$stdout'"
    # φ is measured from the grating vector: turning the grooves leaves the report unchanged.
    a=$stdout
    run --material lines --theta "${th}deg" --lambda "${lam}nm" --csv - -D "height=${h}um" -D "groove_angle=37deg"
    paste -d, <(cut -d, -f1-4 <<<"$a") <(cut -d, -f1-4 <<<"$stdout") | awk -F, 'NR > 3 {
            d = $4 - $8; while (d > 3.14159265358979) d -= 6.28318530717959; while (d < -3.14159265358979) d += 6.28318530717959
            if ($2 != $6 || ($3 - $7) ^ 2 > 1e-24 || d ^ 2 > 1e-18) bad = 1 } END { exit bad }' ||
        fail "grating $case: the directions depend on the groove angle: $stdout"
    # In the classical mount every order leaves at φ = 0 or π exactly (φ within (−π, π]): turning
    # the answer back from the kernel's frame leaves no round-off (no −π, no 3.5e-15 for 0).
    for g in -90deg 37deg 180deg; do
        run --material lines --theta "${th}deg" --lambda "${lam}nm" --csv - -D "height=${h}um" -D "groove_angle=$g"
        bad=$(awk -F, 'NR > 3 && $4 != "0" && $4 != "3.14159265358979"' <<<"$stdout")
        [[ -z "$bad" ]] || fail "grating $case, grooves at $g: phi_o not exactly 0 or pi: $bad"
        run --material lines --theta "${th}deg" --lambda "${lam}nm" -D "height=${h}um" -D "groove_angle=$g"
        bad=$(awk '$1 == "reflection" || $1 == "transmission" { if ($4 == "-180" || $4 ~ /e-/) print }' <<<"$stdout")
        [[ -z "$bad" ]] || fail "grating $case, grooves at $g: the table shows -180 deg or round-off for phi_o: $bad"
    done
done

# 5c. Layer stacks, against the Airy formula written above (complex arithmetic, both polarisations)
#    and the closed form of a quarter-wave stack. A lossless 250 nm MgF₂-like film (1.38) on glass
#    (1.52) at two angles and wavelengths: R = Airy, T = 1 − R (the kernel's T is its own transmission
#    lobe). An absorbing Cu₂O-like film (2.95 + 0.13i, 150 nm) on a Cu-like substrate (1.02 + 2.58i):
#    R = Airy, T = 0. The lossless film as the coating of the metal (0.2 + 3.4i): R = Airy.
for case in "30 550" "65 420"; do
    read -r th lam <<<"$case"
    run --material film --theta "${th}deg" --lambda "${lam}nm" --csv -
    [[ $rc -eq 0 ]] || { fail "film $case: exit status $rc: $stderr"; continue; }
    R=$(calc "airy($th * deg, ${lam}e-9, 1.38, 0, 250e-9, 1.52, 0)")
    near "film $case R" "$(field 2 5)" "$R" 1e-10
    near "film $case T" "$(field 3 5)" "$(calc "1 - $R")" 1e-10
    near "film $case reflected lobe" "$(field 4 5)" "$R" 1e-10
done
for th in 10 55; do
    run --material film --theta "${th}deg" --lambda 550nm --csv - -D film_n=2.95+0.13i -D film_d=150nm -D substrate_n=1.02+2.58i
    [[ $rc -eq 0 ]] || { fail "Cu2O on Cu $th: exit status $rc: $stderr"; continue; }
    near "Cu2O on Cu $th R" "$(field 2 5)" "$(calc "airy($th * deg, 550e-9, 2.95, 0.13, 150e-9, 1.02, 2.58)")" 1e-10
    [[ "$(field 3 5)" == 0 && $(wc -l <<<"$stdout") -eq 4 ]] || fail "Cu2O on Cu $th: T or lobes: '$stdout'"
done
for th in 0 40; do
    run --material coated_metal --theta "${th}deg" --lambda 600nm --csv -
    near "coated metal $th R" "$(field 2 5)" "$(calc "airy($th * deg, 600e-9, 1.38, 0, 250e-9, 0.2, 3.4)")" 1e-10
    [[ "$(field 3 5)" == 0 ]] || fail "coated metal $th: T = '$(field 3 5)'"
done
# A quarter-wave stack (N pairs of n_hi, n_lo, each λ0/4n thick) on n_s at normal incidence and λ0:
# the admittance Y = (n_hi/n_lo)^{2N}·n_s, R = ((1 − Y)/(1 + Y))², T = 1 − R.
for case in "4 600 2.3 1.38" "7 500 1.8 1.45"; do
    read -r N l0 nh nl <<<"$case"
    run --material mirror --theta 0deg --lambda "${l0}nm" --csv - -D "pairs=$N" -D "lambda0=${l0}nm" -D "n_hi=$nh" -D "n_lo=$nl"
    [[ $rc -eq 0 ]] || { fail "quarter-wave $case: exit status $rc: $stderr"; continue; }
    R=$(calc "(1 - ($nh / $nl)^(2 * $N) * 1.52)^2 / (1 + ($nh / $nl)^(2 * $N) * 1.52)^2")
    near "quarter-wave $case R" "$(field 2 5)" "$R" 1e-10
    near "quarter-wave $case T" "$(field 3 5)" "$(calc "1 - $R")" 1e-10
done

# 5d. harvey_shack: the light from (θ, φ) is reflected with exactly F (D7, per incident direction):
#    the glint α_spec·F with α_spec = exp(−(4πσ_h·cosθ/λ)²) (a listed lobe, exact), the halo
#    (1 − α_spec)·F by Monte Carlo (R within 4 standard errors of F). On the metal, a narrow and a
#    wide halo; on the glass from inside beyond the critical angle (total internal reflection, F = 1)
#    and from outside at normal incidence (F = 0.04). No transmission (reflection only).
for case in "rough 30 0.1 metal" "rough 60 0.3 metal" "rough 20 0.02 metal" "rough_glass 130 0.1 glass" "rough_glass 0 0.2 glass"; do
    read -r mat th ar sub <<<"$case"
    run --material "$mat" --theta "${th}deg" --phi 25deg --lambda 550nm --csv - -D "alpha_r=$ar"
    [[ $rc -eq 0 ]] || { fail "$mat $case: exit status $rc: $stderr"; continue; }
    if [[ $sub == metal ]]; then F=$(calc "conductor(cos($th * deg), 0.2, 3.4)")
    elif ((th > 90)); then F=$(calc "fresnel(-cos($th * deg), 1 / 1.5)")
    else F=$(calc "fresnel(cos($th * deg), 1.5)"); fi
    n=$( ((th > 90)) && echo 1.5 || echo 1)
    spec=$(calc "exp(-(4 * pi * $n * 40e-9 * (cos($th * deg) < 0 ? -cos($th * deg) : cos($th * deg)) / 550e-9)^2) * $F")
    se=$(field 2 6)
    awk -v s="$se" 'BEGIN { exit !(s > 0 && s < 0.01) }' || fail "$mat $case: standard error '$se'"
    near "$mat $case R = F" "$(field 2 5)" "$F" "$(calc "4 * $se")"
    near "$mat $case glint" "$(field 4 5)" "$spec" "$(calc "1e-10 * $spec + 1e-15")"
    near "$mat $case glint theta" "$(field 4 3)" "$(calc "$th * deg")" 1e-12
    [[ "$(field 3 5),$(field 3 6)" == "0,0" && $(wc -l <<<"$stdout") -eq 4 ]] || fail "$mat $case: T or lobes: '$stdout'"
done

# 5e. mix of glass and metal (weight w: the metal's share): R = (1 − w)·F_glass + w·F_metal,
#    T = (1 − w)·(1 − F_glass); lobes 0 (glass reflection), 1 (metal), 2 (glass refraction).
for case in "0.3 30" "0.8 70"; do
    read -r w th <<<"$case"
    run --material blend --theta "${th}deg" --lambda 550nm --csv - -D "weight=$w"
    [[ $rc -eq 0 ]] || { fail "blend $case: exit status $rc: $stderr"; continue; }
    Fg=$(calc "fresnel(cos($th * deg), 1.5)") Fm=$(calc "conductor(cos($th * deg), 0.2, 3.4)")
    near "blend $case R" "$(field 2 5)" "$(calc "(1 - $w) * $Fg + $w * $Fm")" 1e-10
    near "blend $case T" "$(field 3 5)" "$(calc "(1 - $w) * (1 - $Fg)")" 1e-10
    # The order column names each child's own lobe (glass: 0 reflected, 1 refracted; metal: 0),
    # never the mix's renumbered ids (0, 1, 2).
    [[ "$(field 4 2),$(field 5 2),$(field 6 2)" == "a: 0,b: 0,a: 1" ]] || fail "blend $case: lobe names '$stdout'"
    near "blend $case lobe 0" "$(field 4 5)" "$(calc "(1 - $w) * $Fg")" 1e-10
    near "blend $case lobe 1" "$(field 5 5)" "$(calc "$w * $Fm")" 1e-10
    near "blend $case lobe 2" "$(field 6 5)" "$(calc "(1 - $w) * (1 - $Fg)")" 1e-10
done

# 5f. two_sided with the metal in front and the Lambertian at the back: from below (θ > 90°) the
#    albedo exactly (standard error 0) and no lobe; from above the metal's Fresnel R.
run --material sheet --theta 140deg --phi 60deg --lambda 550nm --csv - -D albedo=0.42
[[ "$(field 2 0)" == "R,,,,0.42,0" && "$(field 3 0)" == "T,,,,0,0" && $(wc -l <<<"$stdout") -eq 3 ]] ||
    fail "sheet from below: '$stdout' $stderr"
run --material sheet --theta 40deg --lambda 550nm --csv - -D albedo=0.42
near "sheet from above R" "$(field 2 5)" "$(calc "conductor(cos(40 * deg), 0.2, 3.4)")" 1e-10
[[ $(wc -l <<<"$stdout") -eq 4 ]] || fail "sheet from above: '$stdout'"

# 6. The plot: a PNG, not empty, written together with the CSV (a kernel normalised per query and
#    one per incident direction, whose map is the light from the source into each direction).
for mat in paint rough; do
    run --material $mat --theta 45deg --phi 30deg --lambda 550nm --csv "$out/$mat.csv" --plot "$out/sub/$mat.png" --quiet
    [[ $rc -eq 0 && -s "$out/$mat.csv" ]] || fail "plot run $mat: exit status $rc: $stderr"
    [[ "$(head -c 4 "$out/sub/$mat.png" | od -An -tx1 | tr -d ' ')" == 89504e47 ]] || fail "$mat.png is not a PNG"
    [[ $(stat -c %s "$out/sub/$mat.png") -gt 10000 ]] || fail "$mat.png is suspiciously small"
    grep -aq "Software.Matplotlib version" "$out/sub/$mat.png" || fail "$mat.png was not drawn by matplotlib"
done
# Without matplotlib (a Python without site packages): the map's data instead, and how to install it.
printf '#!/bin/sh\nexec python3 -S "$@"\n' >"$out/nompl"
chmod +x "$out/nompl"
PHASOR_PYTHON=$out/nompl run --material paint --theta 45deg --lambda 550nm --plot "$out/nompl.png" --quiet
[[ $rc -eq 0 && ! -e "$out/nompl.png" && "$(head -1 "$out/nompl.map.csv")" == "disc,u,v,value" ]] &&
    grep -q "apt-get install python3-matplotlib" <<<"$stderr" || fail "no matplotlib: exit status $rc, $stderr"
[[ $(grep -c '^transmission,' "$out/nompl.map.csv") -eq 90000 ]] || fail "no matplotlib: the map's data is incomplete"

# 7. Errors: exit status 1, the message, and no output file (not even a temporary one).
check_error() {  # check_error REGEX ARGS…
    local regex=$1; shift
    run "$@" --csv "$out/err.csv" --plot "$out/err.png"
    [[ $rc -eq 1 ]] || fail "$*: exit status $rc, expected 1"
    grep -Eq -- "$regex" <<<"$stderr" || fail "$*: stderr '$stderr' does not match /$regex/"
    [[ ! -e "$out/err.csv" && ! -e "$out/err.png" ]] || fail "$*: an output file was written"
    if ls -A "$out" | grep -q tmp; then fail "$*: temporary file left: $(ls -A "$out")"; fi
}
check_error "^error: no material named 'glas' in '.*probe.wscene'; did you mean 'glass'\?" \
    --material glas --theta 0deg --lambda 550nm
check_error "^error: 'checks' .* is a Texture, not a Material; did you mean 'checked'\?" \
    --material checks --theta 0deg --lambda 550nm
check_error "^error: material 'slit' \(aperture\) is footprint-aware" --material slit --theta 0deg --lambda 550nm
check_error "^error: '--lambda' expects a length such as 550nm; got '550', a number without a unit" \
    --material glass --theta 0deg --lambda 550
check_error "^error: '--lambda' .*got '550nmm' \(unknown unit 'nmm'; did you mean 'nm'\?\)" \
    --material glass --theta 0deg --lambda 550nmm
check_error "^error: '--theta' expects an angle such as 30deg; got '1um', a length" \
    --material glass --theta 1um --lambda 550nm
check_error "^error: '--theta' 90deg is grazing" --material glass --theta 90deg --lambda 550nm
check_error "^error: '--theta' must lie in \[0deg, 180deg\]" --material glass --theta -5deg --lambda 550nm
check_error "^error: '--lambda' must be positive" --material glass --theta 0deg --lambda -1nm
check_error "error: '-D n_glas' does not override any Define in the scene; did you mean 'n_glass'\?" \
    --material glass --theta 0deg --lambda 550nm -D n_glas=2
check_error "probe.wscene:[0-9]+:[0-9]+: error: .*ior" --material glass --theta 0deg --lambda 550nm -D n_glass=-1
# An unwritable plot: the CSV (staged first) must not appear either.
run --material glass --theta 0deg --lambda 550nm --csv "$out/err.csv" --plot /proc/phasor-test/err.png
[[ $rc -eq 1 ]] && grep -q "^error: cannot write '/proc/phasor-test/err.png'" <<<"$stderr" ||
    fail "unwritable plot: exit status $rc, stderr '$stderr'"
[[ ! -e "$out/err.csv" ]] || fail "unwritable plot: the CSV was written"
# Usage errors (the command line alone).
"$phasor" probe "$scene" --theta 0deg --lambda 550nm >/dev/null 2>"$out/.e"; rc=$?
[[ $rc -eq 1 ]] && grep -q "^error: 'probe' needs --material" "$out/.e" || fail "missing --material: $rc $(cat "$out/.e")"
"$phasor" probe "$scene" --material glass --theta 0deg --lambda 550nm --uv 0.5 >/dev/null 2>"$out/.e"; rc=$?
[[ $rc -eq 1 ]] && grep -q "^error: '--uv' needs two numbers" "$out/.e" || fail "--uv with one number: $rc $(cat "$out/.e")"
rm -f "$out/.e"

# A wavelength far outside the optical range: the answer, with a warning that gives the range.
run --material glass --theta 0deg --lambda 1e-20m
[[ $rc -eq 0 ]] && grep -q "^warning: '--lambda' 1e-20m is far outside the optical range phasor's kernels model (100 nm – 1 mm)" <<<"$stderr" ||
    fail "--lambda 1e-20m: exit status $rc, no warning with the range: $stderr"
run --material glass --theta 0deg --lambda 550nm
grep -q "warning" <<<"$stderr" && fail "--lambda 550nm warns: $stderr"

# A run of hours announces itself as `render` does: 1e11 samples of a continuous lobe give the work
# estimate (a warning naming the fix) within 20 s; the run is then stopped.
"$phasor" probe "$scene" --material paint --theta 30deg --lambda 550nm --samples 1e11 >/dev/null 2>"$out/long.log" &
pid=$!
announced=0
for _ in $(seq 200); do
    if grep -q "^warning: this probe would take about .*1e+11 samples.*lower --samples" "$out/long.log"; then
        announced=1
        break
    fi
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
done
kill "$pid" 2>/dev/null; wait "$pid" 2>/dev/null
(( announced )) || fail "--samples 1e11: no work estimate within 20 s: $(cat "$out/long.log")"

[[ $failures -eq 0 ]] || { echo "$failures failure(s)"; exit 1; }
echo "probe: all checks passed"
