#!/usr/bin/env bash
# expect.sh EXIT_CODE REGEX [--no-file PATH] -- COMMAND...
# Runs COMMAND; passes if it exits with EXIT_CODE, its stderr matches REGEX (grep -E), and (with
# --no-file) PATH does not exist afterwards. Prints what it saw on failure.
set -u
want=$1 regex=$2; shift 2
nofile=""
if [[ "${1:-}" == --no-file ]]; then nofile=$2; shift 2; fi
[[ "${1:-}" == -- ]] && shift
rm -f "${nofile:-/nonexistent-phasor}" 2>/dev/null
err=$("$@" 2>&1 >/dev/null); got=$?
ok=1
[[ $got -eq $want ]] || { echo "exit status $got, expected $want"; ok=0; }
grep -Eq -- "$regex" <<<"$err" || { echo "stderr does not match /$regex/"; ok=0; }
if [[ -n "$nofile" && -e "$nofile" ]]; then echo "'$nofile' exists but must not"; ok=0; fi
(( ok )) || { echo "--- stderr ---"; echo "$err"; exit 1; }
