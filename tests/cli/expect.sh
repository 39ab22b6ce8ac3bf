#!/usr/bin/env bash
# Runs a command and checks its exit code and output.
#   expect.sh EXIT_CODE REGEX [--stdout-file F] -- COMMAND ARGS...
# REGEX (extended grep) must match the combined stdout+stderr; "" skips it.
set -uo pipefail
want_exit=$1; want_regex=$2; shift 2
[[ "$1" == "--" ]] && shift
out=$("$@" 2>&1); got_exit=$?
printf '%s\n' "$out"
if [[ $got_exit -ne $want_exit ]]; then
  echo "FAIL: exit code $got_exit, expected $want_exit" >&2; exit 1
fi
if [[ -n "$want_regex" ]] && ! grep -Eq -- "$want_regex" <<<"$out"; then
  echo "FAIL: output does not match /$want_regex/" >&2; exit 1
fi
echo "ok"
