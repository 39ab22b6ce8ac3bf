#!/usr/bin/env bash
# The embedding example (examples/embed-glfw), built against the INSTALLED rgraph,
# run in a GLFW window under Xvfb:
#   embed_test.sh CASE PREFIX EXAMPLE_BUILD PNG_PROBE PNG_COMPARE XVFB_RUN
# CASE:
#   matches_render  its screenshot equals `rgraph render --camera <its last camera>`
#                   within 1/255 where rgraph's image shows (frame and inset excluded),
#                   and differs from rgraph render's default (unmoved) camera there
#   own_drawing     the example's own drawing is on top: the orange frame, and the
#                   G-buffer inset is not rgraph's output image
#   resize          --resize-to 200x150 half-way: the last frame is 200x150 and
#                   matches rgraph render at that size
#   import_mismatch --import-mismatch: exit 1, one error naming the resource and both sizes
#   errors          a missing pipeline, a broken pipeline, a bad argument, no display:
#                   "error: ..." and exit 1, never a signal
set -uo pipefail
case_=$1; prefix=$2; build=$3; probe=$4; compare=$5; xvfb=$6
example="$build/embed_glfw"
source "$(dirname "${BASH_SOURCE[0]}")/../support/example_test.sh"  # $out, fail, run_x, expect
require_example "$example"

# The picture's layout for W x H (examples/embed-glfw/main.cpp: kBorder, the inset):
# frame 8 px; inset W/4 x H/4 in the lower right, inside the frame. Top-down y here.
layout() {
  W=$1; H=$2; B=8; IW=$((W / 4)); IH=$((H / 4))
  region="$B,$B,$((W - 2 * B)),$((H - 2 * B))"
  inset="$((W - B - IW)),$((H - B - IH)),$IW,$IH"
}
layout 256 192
frames=12

# Runs the example for $frames frames at W x H (more options after); sets
# $camera from --print-camera.
shoot() {
  local log="$out/example.log"
  run_x "$example" --size ${W}x$H --frames $frames --screenshot "$out/example.png" --print-camera "$@" >"$log" 2>&1
  local rc=$?
  cat "$log"
  [[ $rc -eq 0 ]] || fail "the example exited $rc"
  camera=$(grep -E '^-?[0-9.e+-]+(,-?[0-9.e+-]+){5,6}$' "$log" | tail -n 1)
  [[ -n "$camera" ]] || fail "no camera line in the example's output"
  [[ -s "$out/example.png" ]] || fail "no screenshot $out/example.png"
}

# The example's screenshot against `rgraph render --camera $camera` at W x H:
# within 1/255 where rgraph's image shows.
matches() {
  "$prefix/bin/rgraph" render --camera "$camera" --width $W --height $H --out "$out/rgraph.png" ||
    fail "rgraph render --camera $camera: exit $?"
  "$compare" "$out/example.png" "$out/rgraph.png" 1 --region "$region" --exclude "$inset"
  local rc=$?
  [[ $rc -eq 0 ]] || fail "the example's image differs from rgraph render's by more than 1/255 (exit $rc)"
}

case "$case_" in
matches_render)
  shoot
  matches
  # Control: the camera matters (the example moved it), so the comparison above can fail.
  "$prefix/bin/rgraph" render --width $W --height $H --out "$out/unmoved.png" || fail "rgraph render: exit $?"
  "$compare" "$out/example.png" "$out/unmoved.png" 1 --region "$region" --exclude "$inset"
  rc=$?; [[ $rc -eq 2 ]] || fail "the example's image should differ from the unmoved camera's (compare exit $rc)"
  echo "ok: the example matches rgraph render --camera $camera within 1/255" ;;
own_drawing)
  shoot
  probe_out=$("$probe" "$out/example.png" 0 0 $((W - 1)) $((H / 2)) $((W / 2)) $((H - 3))) || fail "probe: $probe_out"
  echo "$probe_out"
  mapfile -t px <<<"$probe_out"
  [[ "${px[0]}" == "$W $H" ]] || fail "screenshot size ${px[0]}, expected $W $H"
  for i in 1 2 3; do
    [[ "${px[$i]}" =~ ^255\ 12[78]\ 0\  ]] || fail "frame pixel $i is '${px[$i]}', expected orange (255 127/128 0)"
  done
  "$prefix/bin/rgraph" render --camera "$camera" --width $W --height $H --out "$out/rgraph.png" ||
    fail "rgraph render --camera $camera: exit $?"
  "$compare" "$out/example.png" "$out/rgraph.png" 8 --region "$inset"
  rc=$?; [[ $rc -eq 2 ]] || fail "the inset shows rgraph's output image, not the G-buffer normals (compare exit $rc)"
  echo "ok: the orange frame and the G-buffer inset are the example's own drawing" ;;
resize)
  # The window resized half-way: setSize, a new texture of the new size imported.
  shoot --resize-to 200x150
  layout 200 150
  size=$("$probe" "$out/example.png") || fail "probe: $size"
  [[ "$size" == "200 150" ]] || fail "the last frame is $size, expected 200 150 after --resize-to 200x150"
  matches
  echo "ok: after a resize to 200x150 the example still matches rgraph render --camera $camera" ;;
import_mismatch)
  msg=$(run_x "$example" --size ${W}x$H --frames 1 --import-mismatch 2>&1); rc=$?
  echo "$msg"
  [[ $rc -eq 1 ]] || fail "--import-mismatch exit $rc, expected 1"
  [[ $(grep -c '^error: ' <<<"$msg") -eq 1 ]] || fail "expected exactly one 'error: ' line"
  grep -Eq "^error: .*'?output'?" <<<"$msg" || fail "the error does not name the resource 'output'"
  grep -q "${W}x$H" <<<"$msg" || fail "the error does not give the declared size ${W}x$H"
  grep -q "$((W / 2))x$((H / 2))" <<<"$msg" || fail "the error does not give the texture's size $((W / 2))x$((H / 2))"
  echo "ok: a mismatched import is refused naming the resource and both sizes" ;;
errors)
  expect "^error: .*$out/missing.json" run_x "$example" --pipeline "$out/missing.json" --frames 1
  printf '{\n  "version": 1,\n  "resources": {\n    "a": { "format": "rgba8" }\n' >"$out/broken.json"
  expect "broken.json:[0-9]+:[0-9]+" run_x "$example" --pipeline "$out/broken.json" --frames 1
  expect "^error: .*no-such-scene" run_x "$example" --scene "$out/no-such-scene.gltf" --frames 1
  expect "^error: --size must be WxH" "$example" --size 256
  expect "^error: unknown argument '--bogus'" "$example" --bogus
  expect "^error: --screenshot needs --frames" "$example" --screenshot "$out/x.png"
  expect "^error: --resize-to needs --frames" "$example" --resize-to 100x100
  expect "^error: cannot start GLFW" env -u DISPLAY -u WAYLAND_DISPLAY "$example" --frames 1
  echo "ok: every failure prints error: and exits 1" ;;
*) fail "unknown case $case_" ;;
esac
