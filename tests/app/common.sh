# SPDX-License-Identifier: Apache-2.0
# Sourced by the command-line tests (profile.sh, compare.sh): a failure counter and `run`, which
# runs $phasor in the test's folder $out.
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# run ARGS…: runs phasor ARGS, leaving $rc, $stdout, $stderr.
run() {
    "$phasor" "$@" >"$out/.stdout" 2>"$out/.stderr"; rc=$?
    stdout=$(cat "$out/.stdout"); stderr=$(cat "$out/.stderr")
    rm -f "$out/.stdout" "$out/.stderr"
}
