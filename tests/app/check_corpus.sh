#!/usr/bin/env bash
# check_corpus.sh PHASOR DIR — runs `phasor check` on every malformed scene in DIR
# (tests/parser/diagnostics): each must exit with status 1 (never a crash or a signal) and print
# its first annotated error as "file:L:C: error: …text…".
set -u
phasor=$1 dir=$2
fail=0 n=0
for f in "$dir"/*.wscene; do
  n=$((n + 1))
  args=()
  grep -q '^# strict' "$f" && args+=(--strict)
  while read -r def; do args+=(-D "$def"); done < <(sed -n 's/^# define: //p' "$f")
  err=$("$phasor" check "$f" "${args[@]}" 2>&1 >/dev/null); code=$?
  if [[ $code -ne 1 ]]; then echo "$f: exit status $code (expected 1)"; echo "$err" | head -5; fail=1; continue; fi
  first=$(grep -m1 '^# expect: error' "$f" | sed 's/^# expect: error //')
  if [[ "$first" == "<command line>:"* ]]; then
    rest=${first#<command line>:}; pos="<command line>:${rest%% *}"; text=${rest#* }
  else
    pos=${first%% *} text=${first#* }
  fi
  case "$pos" in
    *:*:*) where="$pos" ;;                        # FILE:L:C (or <command line>:L:C)
    *) where="$(basename "$f"):$pos" ;;
  esac
  if ! grep -qF -- "$where: error: " <<<"$err" || ! grep -qF -- "$text" <<<"$err"; then
    echo "$f: expected '$where: error: …$text…'"; echo "$err" | head -8; fail=1
  fi
done
echo "$n malformed scenes checked through phasor check"
exit $fail
