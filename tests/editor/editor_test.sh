#!/usr/bin/env bash
# The editor example (examples/editor), built against the INSTALLED rgraph, run
# in a GLFW window under Xvfb with the scripted session levels/workshop-edits.txt:
#   editor_test.sh CASE PREFIX EXAMPLE_BUILD EXAMPLE_SOURCE PNG_COMPARE OVERLAY_CHECK XVFB_RUN
# CASE:
#   matches_render  with the pipeline as is (--no-tint), rgraph's frame after the
#                   edits equals the installed `rgraph render --scene` of the scene
#                   file the editor wrote (same pipeline, size; its camera) within
#                   1/255; and differs from the unedited level's (the edits show);
#                   with --no-overlay the window is that frame exactly
#   own_pass        with its own pass type (registered in-process), rgraph's frame
#                   equals that same render times the tint 1,0.9,0.8 within 1/255,
#                   and differs from it untinted: the pass ran
#   overlay_depth   the grid and gizmo are depth-tested against rgraph's depth: over
#                   the crate, the lines behind it show the crate and the gizmo's arm
#                   in front of it shows (runs with the crate shown and hidden)
#   animation       levels/skin.json (SimpleSkin) at `time 0.5` played at 4 fps for
#                   3 frames equals `rgraph render --time 0.5 --fps 4 --frames 3` of
#                   its state within 1/255, and differs from the rest pose
#   pick            a click on a model selects it a frame or two later (printed),
#                   a click on the background selects nothing
#   errors          argument, script and level mistakes (no window needed) and
#   edit_errors     pipeline and edit mistakes (under X): "error: ..." naming the
#                   place, exit 1, never a signal
set -uo pipefail
case_=$1; prefix=$2; build=$3; source=$4; compare=$5; overlay_check=$6; xvfb=$7
editor="$build/rgraph_editor"
source "$(dirname "${BASH_SOURCE[0]}")/../support/example_test.sh"  # $out, fail, run_x, expect
require_example "$editor"

W=160; H=90
script="$source/levels/workshop-edits.txt"
frames=6  # the script's last step is at frame 5

# Runs the editor's session (more options after); writes $out/$1-*.
edit() {
  local name=$1; shift
  run_x "$editor" --size ${W}x$H --frames $frames --script "$script" --rgraph-out "$out/$name-rgraph.png" \
    --screenshot "$out/$name-window.png" --save-state "$out/$name-state.json" "$@" >"$out/$name.log" 2>&1
  local rc=$?
  cat "$out/$name.log"
  [[ $rc -eq 0 ]] || fail "the editor exited $rc"
}
render() {  # render SCENE OUT [OPTION...]: the installed rgraph, default pipeline, same size
  local scene=$1 png=$2; shift 2
  "$prefix/bin/rgraph" render --scene "$scene" --width $W --height $H --out "$png" "$@" >"$out/render.log" 2>&1 ||
    { cat "$out/render.log"; fail "rgraph render --scene $scene $*: exit $?"; }
}

case "$case_" in
matches_render)
  edit plain --no-tint --no-overlay
  # Without the overlay the window shows rgraph's frame as it is (Renderer::render(0)).
  "$compare" "$out/plain-window.png" "$out/plain-rgraph.png" 0 ||
    fail "with --no-overlay the window differs from rgraph's frame"
  render "$out/plain-state.json" "$out/reference.png"
  "$compare" "$out/plain-rgraph.png" "$out/reference.png" 1 ||
    fail "the editor's frame differs from rgraph render of its state by more than 1/255"
  # Control: the edits changed the picture, so the comparison above can fail.
  render "$source/levels/workshop.json" "$out/unedited.png"
  "$compare" "$out/plain-rgraph.png" "$out/unedited.png" 1
  rc=$?; [[ $rc -eq 2 ]] || fail "the edited frame should differ from the unedited level's (compare exit $rc)"
  echo "ok: after the scripted edits the editor's frame matches rgraph render --scene of its state" ;;
own_pass)
  edit tinted
  render "$out/tinted-state.json" "$out/reference.png"
  "$compare" "$out/tinted-rgraph.png" "$out/reference.png" 1 --scale 1,0.9,0.8 ||
    fail "the editor's frame is not rgraph render's times its tint 1,0.9,0.8"
  "$compare" "$out/tinted-rgraph.png" "$out/reference.png" 1
  rc=$?; [[ $rc -eq 2 ]] || fail "the editor's frame should differ from the untinted render: its pass did not run (compare exit $rc)"
  echo "ok: the editor's own pass type ran: its frame is rgraph render's times the tint" ;;
overlay_depth)
  # Model 5 (the crate's duplicate) is selected at the end: its gizmo's Z arm
  # leaves the crate towards the camera, the grid passes behind it.
  edit shown
  edit hidden --do "5 hide 5"
  "$overlay_check" "$out/shown-window.png" "$out/shown-rgraph.png" "$out/hidden-window.png" "$out/hidden-rgraph.png" ||
    fail "the overlay is not depth-tested against rgraph's depth (see the counts above)"
  echo "ok: the overlay hides behind the crate and shows in front of it" ;;
animation)
  run_x "$editor" --level "$source/levels/skin.json" --size ${W}x$H --frames 3 --no-tint --no-overlay \
    --do "0 time 0.5" --play 4 --rgraph-out "$out/anim-rgraph.png" --save-state "$out/anim-state.json" \
    >"$out/anim.log" 2>&1 || { cat "$out/anim.log"; fail "the editor exited $?"; }
  render "$out/anim-state.json" "$out/reference.png" --time 0.5 --fps 4 --frames 3
  "$compare" "$out/anim-rgraph.png" "$out/reference.png" 1 ||
    fail "the editor's skinned frame at 1.0 s differs from rgraph render --time 0.5 --fps 4 --frames 3"
  render "$out/anim-state.json" "$out/rest.png"
  "$compare" "$out/anim-rgraph.png" "$out/rest.png" 1
  rc=$?; [[ $rc -eq 2 ]] || fail "the played frame should differ from the rest pose (compare exit $rc)"
  echo "ok: the editor plays the skinned model as rgraph render --time does" ;;
pick)
  run_x "$editor" --size ${W}x$H --frames 4 --no-overlay --do "0 click 80 45" >"$out/pick.log" 2>&1 ||
    { cat "$out/pick.log"; fail "the editor exited $?"; }
  cat "$out/pick.log"
  grep -q "^selected model 1$" "$out/pick.log" || fail "a click at 80,45 did not select model 1"
  run_x "$editor" --size ${W}x$H --frames 4 --no-overlay --do "0 click 2 2" >"$out/pick-bg.log" 2>&1 ||
    { cat "$out/pick-bg.log"; fail "the editor exited $?"; }
  cat "$out/pick-bg.log"
  grep -q "^selected nothing$" "$out/pick-bg.log" || fail "a click on the background selected something"
  echo "ok: a click selects the model under it, the background nothing" ;;
errors)  # mistakes found before a window opens (arguments, scripts, levels)
  printf '0 select 1\n\n# a comment\n2 mvoe 1 0 0 0\n' >"$out/typo.txt"
  expect "^error: $out/typo.txt:4: unknown command 'mvoe'" "$editor" --script "$out/typo.txt"
  expect "^error: --do '1 move 1 0 0': 'move' takes 4 numbers, got 3" "$editor" --do "1 move 1 0 0"
  expect "^error: --do '1 move 1 x 0 0': 'x' is not a number" "$editor" --do "1 move 1 x 0 0"
  expect "^error: --do '9 hide 1': frame 9 is never drawn \(--frames 2\)" "$editor" --frames 2 --do "9 hide 1"
  expect "^error: --screenshot, --rgraph-out and --save-state need --frames" "$editor" --screenshot "$out/x.png"
  expect "^error: unknown argument '--bogus'" "$editor" --bogus
  expect "^error: --size must be WxH" "$editor" --size 160
  expect "^error: cannot read $out/no-such-script.txt" "$editor" --script "$out/no-such-script.txt"
  expect "^error: .*no-such-level.json" "$editor" --level "$out/no-such-level.json" --frames 1
  printf '{\n  "models": [\n    {"shape": "cube",}\n  ]\n}\n' >"$out/broken.json"
  expect "^error: .*broken.json:3:[0-9]+" "$editor" --level "$out/broken.json" --frames 1
  expect "^error: the editor edits scene files \(.json\)" "$editor" --level "$out/model.gltf" --frames 1
  expect "^error: cannot start GLFW" env -u DISPLAY -u WAYLAND_DISPLAY "$editor" --frames 1
  echo "ok: every failure prints error: and exits 1" ;;
edit_errors)  # mistakes found with the pipeline built or at a step: all under one X server
  run_x bash "$0" edit_errors_under_x "${@:2}" || fail "a case above failed"
  echo "ok: every failure prints error: and exits 1" ;;
edit_errors_under_x)
  expect "^error: cannot read $out/no-such-pipeline.json" "$editor" --pipeline "$out/no-such-pipeline.json" --frames 1
  printf '{\n  "version": 1,\n  "resources": {\n    "a": { "format": "rgba8" }\n' >"$out/broken-pipeline.json"
  expect "broken-pipeline.json:[0-9]+:[0-9]+" "$editor" --pipeline "$out/broken-pipeline.json" --frames 1
  printf '{"version": 1, "resources": {"output": {"format": "rgba8"}}, "passes": [], "output": "output"}\n' >"$out/unwritten.json"
  expect "^error: .*unwritten.json: no pass of the pipeline writes its output 'output'" "$editor" --pipeline "$out/unwritten.json" --frames 1
  expect "^error: --do '0 move 7 0 0 0': no model 7 \(the level has 5\)" "$editor" --frames 1 --do "0 move 7 0 0 0"
  expect "^error: --do '0 hide 3': model 3 was removed" "$editor" --frames 1 --do "0 remove 3" --do "0 hide 3"
  expect "^error: --do '0 scale 1 0': .*instance" "$editor" --frames 1 --do "0 scale 1 0"
  expect "^error: --do '0 click 500 45': .*pixel \\(500, 45\\)" "$editor" --size 160x90 --frames 1 --do "0 click 500 45" ;;
*) fail "unknown case $case_" ;;
esac
