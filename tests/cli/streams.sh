#!/usr/bin/env bash
# Runs a command and checks what it prints on each stream separately.
#   streams.sh EXIT_CODE STDOUT_REGEX STDERR_REGEX STDOUT_ABSENT_REGEX -- COMMAND ARGS...
# Each regex (extended grep) must match its stream; STDOUT_ABSENT_REGEX must
# match no line of stdout (log lines belong on stderr); "" skips a check.
set -uo pipefail
want_exit=$1; want_out=$2; want_err=$3; absent_out=$4; shift 4
[[ "$1" == "--" ]] && shift
errfile=$(mktemp); trap 'rm -f "$errfile"' EXIT
out=$("$@" 2>"$errfile"); got_exit=$?
err=$(cat "$errfile")
printf -- '--- stdout\n%s\n--- stderr\n%s\n' "$out" "$err"
fail() { echo "FAIL: $1" >&2; exit 1; }
[[ $got_exit -eq $want_exit ]] || fail "exit code $got_exit, expected $want_exit"
[[ -z "$want_out" ]] || grep -Eq -- "$want_out" <<<"$out" || fail "stdout does not match /$want_out/"
[[ -z "$want_err" ]] || grep -Eq -- "$want_err" <<<"$err" || fail "stderr does not match /$want_err/"
[[ -z "$absent_out" ]] || ! grep -Eq -- "$absent_out" <<<"$out" || fail "stdout matches /$absent_out/"
echo "ok"
