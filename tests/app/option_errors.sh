#!/usr/bin/env bash
# option_errors.sh PHASOR SCENE OUTDIR — every command-line mistake is one line, "error: …",
# ending in where to look ("see 'phasor … --help'"), exit status 1, and never the whole usage
# text; the wording of each says what the option takes.
set -u
phasor=$1 scene=$2 out=$3/option_errors
rm -rf "$out"; mkdir -p "$out"
source "$(dirname "$0")/common.sh"  # fail, run

# check REGEX ARGS…: phasor ARGS fails with exactly one line on stderr matching REGEX and the hint.
check() {
    local regex=$1; shift
    run "$@"
    local lines
    lines=$(printf '%s\n' "$stderr" | grep -c .)
    [[ $rc -eq 1 ]] || fail "phasor $*: exit status $rc, expected 1"
    [[ $lines -eq 1 ]] || fail "phasor $*: $lines lines on stderr, expected one: $stderr"
    grep -qi "usage:" <<<"$stderr" && fail "phasor $*: the usage text was printed: $stderr"
    grep -Eq -- "^error: $regex" <<<"$stderr" || fail "phasor $*: stderr does not match /^error: $regex/: $stderr"
    grep -Eq -- "see 'phasor( [a-z]+)? --help'" <<<"$stderr" || fail "phasor $*: no 'see … --help' hint: $stderr"
    [[ -z "$stdout" ]] || fail "phasor $*: wrote to stdout: $stdout"
}

check "'--spp' expects a whole number ≥ 1; got '0'" render "$scene" --spp 0
check "'--spp' expects a whole number ≥ 1; got 'many'" render "$scene" --spp many
check "'--threads' expects a whole number ≥ 0" render "$scene" --threads -2
check "'--seed' expects a whole number ≥ 0" render "$scene" --seed -1
check "'--samples' expects a whole number ≥ 1; got '0'" probe "$scene" --material m --theta 0deg --lambda 1um --samples 0
check "'--uv' expects two finite numbers; got '5 nan'" probe "$scene" --material m --theta 0deg --lambda 1um --uv 5 nan
check "'--integrators' names 'grt' twice" compare "$scene" --integrators grt,grt
check "'--time' expects a positive number of seconds; got '-1'" compare "$scene" --integrators grt --time -1
check "unknown option '--bogus'" render "$scene" --bogus
check "'--spp' \(equal samples\) and '--time' \(equal time\) exclude each other" compare "$scene" --integrators grt --spp 4 --time 1
check "unknown command 'rendr'; did you mean 'render'\?" rendr "$scene"
check "'render' expects exactly one scene file" render
check "'-D' expects name=value; got 'x'" render "$scene" -D x

# A file that cannot be written is named once: "error: cannot write 'FILE': reason" (not prefixed
# with the file as a location).
for target in /proc/phasor-test/x.exr /proc/phasor-test/cmp/index.html; do
    if [[ $target == *.exr ]]; then run render "$scene" -o "$target"
    else run compare "$scene" --integrators ray --spp 1 -o "$(dirname "$target")"; fi
    named=$(grep -o "$target" <<<"$stderr" | wc -l)
    [[ $rc -eq 1 && $named -eq 1 && "$stderr" == "error: cannot write '$target': "* ]] ||
        fail "writing $target: exit status $rc, the file named $named times: $stderr"
done

# Without any argument: the usage text (that is what was asked for), exit status 1.
run
[[ $rc -eq 1 && "${stderr,,}" == *"usage: phasor"* ]] || fail "phasor without arguments: exit status $rc, stderr $stderr"
# --help: the usage text on stdout, exit status 0.
run --help
[[ $rc -eq 0 && "${stdout,,}" == *"usage: phasor"* && -z "$stderr" ]] || fail "phasor --help: exit status $rc"
# A command's own help: its options, from the same declaration that parses them.
run render --help
[[ $rc -eq 0 && "$stdout" == *"--spp N"* && "$stdout" == *"--integrator NAME"* ]] || fail "phasor render --help: $stdout"

[[ $failures -eq 0 ]] || { echo "$failures failures"; exit 1; }
echo "all option errors are one line with a hint"
