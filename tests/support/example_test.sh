# Sourced by the tests of the examples built against the installed rgraph
# (tests/embed/embed_test.sh, tests/editor/editor_test.sh) once they have set
# $case_ (the case), $build (the example's build folder) and $xvfb (xvfb-run):
# the environment cleared of rgraph's overrides, an empty output folder
# $out = $build/out-$case_, and what every case uses:
#   fail MESSAGE...           FAIL: MESSAGE and what Xvfb said on stderr, exit 1
#   require_example PATH      fail unless the example was built (PATH executable)
#   run_x COMMAND...          COMMAND under its own X server
#   expect REGEX COMMAND...   COMMAND exits 1 (not a signal) printing REGEX
unset RGRAPH_PLUGIN_PATH RGRAPH_SHADER_DIR RGRAPH_PIPELINE_DIR
out="$build/out-$case_"; rm -rf "$out"; mkdir -p "$out"
fail() {
  echo "FAIL: $*" >&2
  [[ -s "$out/xvfb-errors.log" ]] && { echo "Xvfb said:" >&2; cat "$out/xvfb-errors.log" >&2; }
  exit 1
}
require_example() { [[ -x "$1" ]] || fail "the example did not build: no $1"; }
# Our own auth file: without one, xvfb-run makes a temporary folder and its
# clean-up can fail (exit 5) after the command, hiding the command's status.
run_x() { "$xvfb" -a -f "$out/Xauthority" -e "$out/xvfb-errors.log" -s '-screen 0 1024x768x24' "$@"; }
expect() {
  local regex=$1; shift
  local msg; msg=$("$@" 2>&1); local rc=$?
  echo "$ $*"; echo "$msg"
  [[ $rc -eq 1 ]] || fail "exit $rc, expected 1: $*"
  grep -Eq -- "$regex" <<<"$msg" || fail "output does not match /$regex/: $*"
}
