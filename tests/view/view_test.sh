#!/usr/bin/env bash
# `rgraph view` in a GLFW window under Xvfb, driven by --script:
#   view_test.sh CASE RGRAPH PNG_COMPARE XVFB_RUN SOURCE_DIR OUT_DIR
# CASE:
#   matches_render  a scripted screenshot (UI off) equals `rgraph render --camera` of the same pose within
#                   1/255, and differs from the scene's own camera (so the comparison can fail)
#   reload_pipeline a copy of a pipeline edited valid -> broken JSON -> broken graph -> valid while the viewer
#                   runs: status lines ok, error (FILE:LINE:COL), error, ok; the viewer exits 0 at `quit`
#   reload_shader   a copy of tonemap.frag (--shader-path) broken then fixed: error naming it with its line, then ok
#   reload_leak     50 reloads (valid and broken alternating): the last ok line's gl_objects equals the first's
#   threshold_leak  100 distinct light_volumes thresholds (script params): gl_objects stays at its steady count
#   resize          `resize 200 150` then a screenshot: the PNG is 200x150
#   param_then_file a script `param`, then edits of the file: still watched (reload ok, then error), and the
#                   file's change replaces the in-memory edit (the frame equals rgraph render of the file)
#   param_errors    a value out of range, 1e999, a value nested 100,000 deep: status errors naming the script
#                   line and (for the renderer's) the param's line in the pipeline file; no crash, exit 0
#   resize_budget   `resize 16384 16384` over --max-memory: one error line with both figures, the screenshot
#                   after it has the last good size, the script goes on to quit (exit 0)
#   render_refused  a fixed-size pipeline the device refuses at the window's size: reported once, the last
#                   good frame (not black) stays in the window
#   shader_override a --shader-path override of tonemap.frag deleted (built-in used), then created broken and
#                   fixed: error naming the override, then ok
#   inspect_layers  at 960x540 with the panels on, `inspect shadowAtlas L` (deferred-pbr-shadows, the shadows
#                   scene): the inspector's image (right half, below its pickers) differs between layers 0
#                   and 6, the whole screenshot of layer 0 twice does not (the image is on screen and shows
#                   the layer asked for); the Shadows tab is in front (the plan tab's times change each frame)
#   pick            `pick 80 60` selects the object at the centre (printed with material and transform),
#                   `pick 2 2` the background (nothing), `pick 500 10` is an error naming the script line
#   script_errors   an unknown command, a bad number, a missing script, a folder: FILE:LINE error, exit 1, no window
set -uo pipefail
case_=$1; rgraph=$2; compare=$3; xvfb=$4; src=$5; out=$6/view-$1
unset RGRAPH_PLUGIN_PATH RGRAPH_SHADER_DIR RGRAPH_PIPELINE_DIR
rm -rf "$out"; mkdir -p "$out"
viewer=
fail() {
  echo "FAIL: $*" >&2
  # A viewer left running would write into the next run's files: its script quits once "done" exists.
  # (param_then_file's waits for "shoot" first.)
  [[ -n "$viewer" ]] && { touch "$out/shoot" "$out/done"; wait "$viewer"; }
  for f in "$out/xvfb-errors.log" "$out/view.log" "$out/status.jsonl"; do
    [[ -s "$f" ]] && { echo "--- $f:" >&2; cat "$f" >&2; }
  done
  exit 1
}
# Our own auth file: without one, xvfb-run's temporary folder clean-up can fail
# (exit 5) after the command and hide its status (as tests/embed/embed_test.sh).
run_x() { "$xvfb" -a -f "$out/Xauthority" -e "$out/xvfb-errors.log" -s '-screen 0 1280x1024x24' "$@"; }
png_size() { python3 -c "import struct,sys; d=open(sys.argv[1],'rb').read(24); print(*struct.unpack('>II', d[16:24]))" "$1"; }

# Waits (up to 60 s) until the status file has N lines; the viewer polls files every 250 ms.
wait_lines() {
  local n=$1
  for _ in $(seq 600); do
    [[ -f "$out/status.jsonl" && $(wc -l <"$out/status.jsonl") -ge $n ]] && return 0
    kill -0 "$viewer" 2>/dev/null || fail "the viewer exited while waiting for status line $n"
    sleep 0.1
  done
  fail "no status line $n within 60 s"
}
# Replaces a file in one step (a half-written file is never read) with a new modification time.
put() { cat >"$1.tmp" && mv "$1.tmp" "$1"; }
# The viewer in the background until the test creates $out/done; sets $viewer.
start_viewer() {
  printf 'waitfile %s\nquit\n' "$out/done" >"$out/script.txt"
  run_x "$rgraph" view "$@" --width 160 --height 120 --script "$out/script.txt" --status "$out/status.jsonl" \
    >"$out/view.log" 2>&1 &
  viewer=$!
  wait_lines 1
}
stop_viewer() {
  touch "$out/done"
  wait "$viewer"; local rc=$?
  [[ $rc -eq 0 ]] || fail "the viewer exited $rc (expected 0 at quit)"
}
line() { sed -n "${1}p" "$out/status.jsonl"; }
expect_line() {  # N REGEX
  local l; l=$(line "$1")
  [[ "$l" =~ $2 ]] || fail "status line $1 is '$l', expected /$2/"
}

case "$case_" in
matches_render)
  cam="1.5,2.5,5.5,0,0.5,0"
  printf 'camera %s\nwait 2\nscreenshot %s\nquit\n' "${cam//,/ }" "$out/view.png" >"$out/script.txt"
  run_x "$rgraph" view --width 256 --height 192 --script "$out/script.txt" >"$out/view.log" 2>&1 ||
    fail "rgraph view exited $?"
  [[ "$(png_size "$out/view.png")" == "256 192" ]] || fail "screenshot size $(png_size "$out/view.png")"
  "$rgraph" render --camera "$cam" --width 256 --height 192 --out "$out/render.png" || fail "rgraph render: exit $?"
  "$compare" "$out/view.png" "$out/render.png" 1 || fail "the viewer's screenshot differs from rgraph render's"
  "$rgraph" render --width 256 --height 192 --out "$out/unmoved.png" || fail "rgraph render: exit $?"
  "$compare" "$out/view.png" "$out/unmoved.png" 1; rc=$?
  [[ $rc -eq 2 ]] || fail "the screenshot should differ from the scene camera's image (compare exit $rc)"
  echo "ok: view's screenshot matches rgraph render --camera $cam within 1/255" ;;
param)
  # The script's `param` edits a pass parameter live (as the panel does): the
  # frame equals rgraph render of the pipeline with that value written in.
  p="$out/pipeline.json"; cp "$src/pipelines/default.json" "$p"
  printf 'param tonemap gamma 2.2\nwait 2\nscreenshot %s\nquit\n' "$out/view.png" >"$out/script.txt"
  run_x "$rgraph" view "$p" --width 160 --height 120 --script "$out/script.txt" --status "$out/status.jsonl" \
    >"$out/view.log" 2>&1 || fail "rgraph view exited $?"
  grep -q '"event":"param".*"result":"ok"' "$out/status.jsonl" || fail "no param ok line in the status file"
  sed 's/"gamma": 1.0/"gamma": 2.2/' "$src/pipelines/default.json" >"$out/gamma.json"
  "$rgraph" render "$out/gamma.json" --width 160 --height 120 --out "$out/render.png" || fail "rgraph render: exit $?"
  "$compare" "$out/view.png" "$out/render.png" 1 || fail "the edited frame differs from rgraph render of the edit"
  "$rgraph" render "$p" --width 160 --height 120 --out "$out/unedited.png" || fail "rgraph render: exit $?"
  "$compare" "$out/view.png" "$out/unedited.png" 1; rc=$?
  [[ $rc -eq 2 ]] || fail "the edit should change the frame (compare exit $rc)"
  cmp -s "$p" "$src/pipelines/default.json" || fail "a live edit must not write the file (only Save does)"
  echo "ok: param tonemap gamma 2.2 applied live, equals rgraph render of the edited pipeline" ;;
reload_scene)
  # The scene file edited while the viewer runs: valid (ambient raised), broken, valid again.
  sc="$out/scene.json"; cp "$src/scenes/learnopengl.json" "$sc"
  start_viewer --scene "$sc"
  expect_line 1 '"event":"load".*"result":"ok"'
  python3 -c "import json,sys; d=json.load(open(sys.argv[1])); d['ambient']=0.4; json.dump(d, sys.stdout)" "$sc" |
    put "$sc"; wait_lines 2
  expect_line 2 '"event":"reload".*"result":"ok"'
  { cat "$src/scenes/learnopengl.json"; echo '}'; } | put "$sc"; wait_lines 3
  expect_line 3 '"diagnostics":\["[^"]*scene\.json:[0-9]+:[0-9]+: error: invalid JSON'
  expect_line 3 '"result":"error"'
  cp "$src/scenes/learnopengl.json" "$sc.tmp" && mv "$sc.tmp" "$sc"; wait_lines 4
  expect_line 4 '"event":"reload".*"result":"ok"'
  stop_viewer
  echo "ok: scene file ok, error, ok; exit 0 at quit" ;;
reload_pipeline)
  p="$out/pipeline.json"; cp "$src/pipelines/default.json" "$p"
  start_viewer "$p"
  expect_line 1 '"event":"load".*"result":"ok"'
  sed 's/"gamma": 1.0/"gamma": 1.2/' "$src/pipelines/default.json" | put "$p"; wait_lines 2
  expect_line 2 '"event":"reload".*"result":"ok"'
  { cat "$src/pipelines/default.json"; echo '}'; } | put "$p"; wait_lines 3
  expect_line 3 '"diagnostics":\[".*pipeline\.json:[0-9]+:[0-9]+: error'
  expect_line 3 '"result":"error"'
  sed 's/"inputs": { "hdr": "hdr_forward" }/"inputs": { "hdr": "no_such_resource" }/' "$src/pipelines/default.json" |
    put "$p"; wait_lines 4
  expect_line 4 '"diagnostics":\[".*pipeline\.json:[0-9]+:[0-9]+: error: /passes/5/inputs/hdr: .*no_such_resource'
  expect_line 4 '"result":"error"'
  cp "$src/pipelines/default.json" "$p.tmp" && mv "$p.tmp" "$p"; wait_lines 5
  expect_line 5 '"event":"reload".*"result":"ok"'
  stop_viewer
  echo "ok: ok, error (JSON), error (graph), ok; exit 0 at quit" ;;
reload_shader)
  mkdir -p "$out/shaders"; cp -r "$src/shaders/." "$out/shaders/"
  f="$out/shaders/tonemap.frag"
  start_viewer --shader-path "$out/shaders"
  { cat "$src/shaders/tonemap.frag"; echo 'this is not glsl;'; } | put "$f"; wait_lines 2
  # glslang reports a line, no column: FILE:LINE: error.
  expect_line 2 '"diagnostics":\[".*shaders/tonemap\.frag:[0-9]+: error: pass .tonemap.'
  expect_line 2 '"result":"error"'
  cp "$src/shaders/tonemap.frag" "$f.tmp" && mv "$f.tmp" "$f"; wait_lines 3
  expect_line 3 '"event":"reload".*"result":"ok"'
  stop_viewer
  echo "ok: a broken shader is reported with FILE:LINE and survived" ;;
reload_leak)
  p="$out/pipeline.json"; cp "$src/pipelines/default.json" "$p"
  start_viewer "$p"
  for i in $(seq 1 50); do
    if ((i % 2)); then
      sed "s/\"gamma\": 1.0/\"gamma\": 1.$i/" "$src/pipelines/default.json" | put "$p"
    else
      { cat "$src/pipelines/default.json"; echo '}'; } | put "$p"
    fi
    wait_lines $((i + 1))
  done
  stop_viewer
  oks=$(grep '"result":"ok"' "$out/status.jsonl" | grep -o '"gl_objects":[0-9]*' | cut -d: -f2)
  [[ $(grep -c '"result":"error"' "$out/status.jsonl") -eq 25 ]] || fail "expected 25 error lines"
  first=$(sed -n 2p <<<"$oks"); last=$(tail -n 1 <<<"$oks")  # line 1 is the load; 2 the first reload
  [[ -n "$first" && "$first" == "$last" ]] || fail "gl_objects went from $first to $last over 50 reloads"
  echo "ok: gl_objects $first after the first reload and $last after the last" ;;
threshold_leak)
  # 100 distinct light_volumes thresholds from a script, a frame each (a slider drag): the per-threshold light
  # buffers are bounded, so gl_objects after the 10th edit equals gl_objects after the 100th.
  p="$out/pipeline.json"; cp "$src/pipelines/default.json" "$p"
  for i in $(seq 1 100); do printf 'param light_volumes threshold 0.%04d\nwait 1\n' $((100 + i)); done >"$out/script.txt"
  echo quit >>"$out/script.txt"
  run_x "$rgraph" view "$p" --width 96 --height 64 --script "$out/script.txt" --status "$out/status.jsonl" \
    >"$out/view.log" 2>&1 || fail "rgraph view exited $?"
  counts=$(grep '"event":"param".*"result":"ok"' "$out/status.jsonl" | grep -o '"gl_objects":[0-9]*' | cut -d: -f2)
  [[ $(wc -l <<<"$counts") -eq 100 ]] || fail "expected 100 param ok lines"
  tenth=$(sed -n 10p <<<"$counts"); last=$(tail -n 1 <<<"$counts")
  [[ -n "$tenth" && "$tenth" == "$last" ]] || fail "gl_objects went from $tenth to $last over 90 threshold edits"
  echo "ok: gl_objects $tenth after the 10th threshold and $last after the 100th" ;;
param_then_file)
  p="$out/pipeline.json"; cp "$src/pipelines/default.json" "$p"
  printf 'param tonemap gamma 2.2\nwaitfile %s\nscreenshot %s\nwaitfile %s\nquit\n' "$out/shoot" "$out/view.png" \
    "$out/done" >"$out/script.txt"
  run_x "$rgraph" view "$p" --width 160 --height 120 --script "$out/script.txt" --status "$out/status.jsonl" \
    >"$out/view.log" 2>&1 &
  viewer=$!
  wait_lines 2
  expect_line 1 '"event":"param".*"result":"ok"'
  expect_line 2 '"event":"load".*"result":"ok"'
  sed 's/"gamma": 1.0/"gamma": 1.2/' "$src/pipelines/default.json" | put "$p"; wait_lines 3
  expect_line 3 '"event":"reload".*"result":"ok"'
  touch "$out/shoot"
  for _ in $(seq 600); do [[ -f "$out/view.png" ]] && break; sleep 0.1; done
  { cat "$src/pipelines/default.json"; echo '}'; } | put "$p"; wait_lines 4
  expect_line 4 '"diagnostics":\[".*pipeline\.json:[0-9]+:[0-9]+: error'
  stop_viewer
  sed 's/"gamma": 1.0/"gamma": 1.2/' "$src/pipelines/default.json" >"$out/file.json"
  "$rgraph" render "$out/file.json" --width 160 --height 120 --out "$out/render.png" || fail "rgraph render: exit $?"
  "$compare" "$out/view.png" "$out/render.png" 1 || fail "the frame after the file's edit is not the file's pipeline"
  echo "ok: after a param edit the file is still watched: ok, error; its edit replaced the param's" ;;
param_errors)
  p="$out/pipeline.json"; cp "$src/pipelines/default.json" "$p"
  { echo 'param tonemap gamma 9.0'; echo 'param tonemap gamma 1e999'
    python3 -c "print('param tonemap gamma ' + '[' * 100000 + ']' * 100000)"; echo 'wait 1'; echo quit; } >"$out/script.txt"
  run_x "$rgraph" view "$p" --width 160 --height 120 --script "$out/script.txt" --status "$out/status.jsonl" \
    >"$out/view.log" 2>&1 || fail "rgraph view exited $?"
  gamma=$(grep -n '"gamma": 1.0' "$p" | cut -d: -f1)  # the line the param is on in the file
  expect_line 1 "script\.txt:1: error: param tonemap gamma: [^\"]*pipeline\.json:$gamma:[0-9]+: /passes/[0-9]+/params/gamma: "
  expect_line 2 "script\.txt:2: error: param tonemap gamma: the value '1e999' is not JSON.*number overflow"
  expect_line 3 'script\.txt:3: error: param tonemap gamma: .*nested deeper than'
  expect_line 4 '"event":"load".*"result":"ok"'
  echo "ok: param errors name the script line and the param's line ($gamma) in the file" ;;
resize_budget)
  printf 'wait 1\nresize 16384 16384\nwait 2\nscreenshot %s\nquit\n' "$out/shot.png" >"$out/script.txt"
  run_x "$rgraph" view --width 160 --height 120 --max-memory 64MB --script "$out/script.txt" \
    --status "$out/status.jsonl" >"$out/view.log" 2>&1 || fail "rgraph view exited $?"
  [[ $(grep -c '"result":"error"' "$out/status.jsonl") -eq 1 ]] || fail "expected exactly one error line"
  grep -qE '16384x16384 needs [0-9]+ bytes.*more than the 67108864 bytes.*--max-memory.*"event":"render"' \
    "$out/status.jsonl" || fail "no render error with both figures"
  [[ "$(png_size "$out/shot.png")" == "160 120" ]] || fail "screenshot size $(png_size "$out/shot.png"), expected 160 120"
  "$rgraph" render --width 160 --height 120 --out "$out/render.png" || fail "rgraph render: exit $?"
  "$compare" "$out/shot.png" "$out/render.png" 1 || fail "the screenshot is not the last good frame"
  echo "ok: a size over --max-memory refused once, the last good size and frame kept" ;;
render_refused)
  # hdr fixed at 128x128: at any other size its passes' attachments differ, a graph the executor refuses.
  p="$out/fixed.json"
  sed 's/"hdr":          { "format": "rgba16f", "size": "output"/"hdr":          { "format": "rgba16f", "size": [128, 128]/' \
    "$src/pipelines/default.json" >"$p"
  grep -q '"size": \[128, 128\]' "$p" || fail "the fixed-size pipeline was not made"
  printf 'wait 2\nresize 64 64\nwait 5\nscreenshot %s\nquit\n' "$out/shot.png" >"$out/script.txt"
  run_x "$rgraph" view "$p" --width 128 --height 128 --script "$out/script.txt" --status "$out/status.jsonl" \
    >"$out/view.log" 2>&1 || fail "rgraph view exited $?"
  [[ $(grep -c '"result":"error"' "$out/status.jsonl") -eq 1 ]] || fail "expected one error line, not one a frame"
  expect_line 2 'all attachments of a pass must have the same size.*"event":"render".*"result":"error"'
  expect_line 3 '"event":"render".*"result":"ok"'
  [[ "$(png_size "$out/shot.png")" == "128 128" ]] || fail "screenshot size $(png_size "$out/shot.png"), expected 128 128"
  "$rgraph" render "$p" --width 128 --height 128 --out "$out/render.png" || fail "rgraph render: exit $?"
  "$compare" "$out/shot.png" "$out/render.png" 1 || fail "the window does not show the last good frame"
  echo "ok: a refused frame reported once, the last good frame and size kept" ;;
shader_override)
  mkdir -p "$out/shaders"; f="$out/shaders/tonemap.frag"
  cp "$src/shaders/tonemap.frag" "$f"
  start_viewer --shader-path "$out/shaders"
  rm "$f"; wait_lines 2
  expect_line 2 '"event":"reload".*"result":"ok"'
  { cat "$src/shaders/tonemap.frag"; echo 'this is not glsl;'; } | put "$f"; wait_lines 3
  expect_line 3 '"diagnostics":\[".*shaders/tonemap\.frag:[0-9]+: error: '
  cp "$src/shaders/tonemap.frag" "$f.tmp" && mv "$f.tmp" "$f"; wait_lines 4
  expect_line 4 '"event":"reload".*"result":"ok"'
  stop_viewer
  echo "ok: an override deleted, recreated broken, then fixed: ok, error, ok" ;;
resize)
  printf 'wait 1\nresize 200 150\nwait 3\nscreenshot %s\nquit\n' "$out/small.png" >"$out/script.txt"
  run_x "$rgraph" view --width 320 --height 240 --script "$out/script.txt" >"$out/view.log" 2>&1 ||
    fail "rgraph view exited $?"
  [[ "$(png_size "$out/small.png")" == "200 150" ]] || fail "screenshot size $(png_size "$out/small.png"), expected 200 150"
  "$rgraph" render --width 200 --height 150 --out "$out/render.png" || fail "rgraph render: exit $?"
  "$compare" "$out/small.png" "$out/render.png" 1 || fail "the resized frame differs from rgraph render at 200x150"
  echo "ok: resized to 200x150" ;;
inspect_layers)
  printf '%s\n' 'param shadows size 256' 'panel shadows' 'inspect shadowAtlas 0' 'ui on' 'wait 3' \
    "screenshot $out/layer0.png" 'inspect shadowAtlas 6' 'wait 3' "screenshot $out/layer6.png" \
    'inspect shadowAtlas 0' 'wait 3' "screenshot $out/layer0-again.png" 'quit' >"$out/script.txt"
  run_x "$rgraph" view "$src/pipelines/deferred-pbr-shadows.json" --scene "$src/scenes/shadows.json" \
    --width 960 --height 540 --script "$out/script.txt" >"$out/view.log" 2>&1 || fail "rgraph view exited $?"
  grep -q "error:" "$out/view.log" && fail "the viewer reported an error"
  "$compare" "$out/layer0.png" "$out/layer0-again.png" 1 || fail "layer 0 shown twice differs (the UI is not steady)"
  # Only the inspector's image (right half, below its pickers at 960x540): the layer's label above it differs
  # whichever layer is copied.
  "$compare" "$out/layer0.png" "$out/layer6.png" 1 --region 480,175,480,185; rc=$?
  [[ $rc -eq 2 ]] || fail "layers 0 and 6 look the same in the inspector's image (compare exit $rc)"
  echo "ok: two atlas layers shown differ, one layer twice does not" ;;
pick)
  # `pick X Y` (as a click) selects the object under window pixel X Y (top-left origin), printed a frame or
  # two later with its material and transform; the background selects nothing; a pixel outside the window
  # is an error line naming the script line, and the script goes on.
  printf 'pick 80 60\nwait 4\npick 2 2\nwait 4\npick 500 10\nwait 2\nquit\n' >"$out/script.txt"
  run_x "$rgraph" view --width 160 --height 120 --script "$out/script.txt" --status "$out/status.jsonl" \
    >"$out/view.log" 2>&1 || fail "rgraph view exited $?"
  grep -Eq "^rgraph view: picked \(80, 60\) in frame [0-9]+: instance [0-9]+ 'object4', triangle [0-9]+$" \
    "$out/view.log" || fail "no selection of object4 (the overview's middle cube) at (80, 60)"
  grep -Eq "^rgraph view: material [0-9]+ '[^']*': base colour [-0-9.e ]+, metallic [-0-9.e]+, roughness" \
    "$out/view.log" || fail "no material line"
  grep -Eq "^rgraph view: translation [-0-9.e]+ [-0-9.e]+ [-0-9.e]+$" "$out/view.log" || fail "no transform line"
  grep -Eq "^rgraph view: picked \(2, 2\) in frame [0-9]+: nothing$" "$out/view.log" ||
    fail "the background at (2, 2) should select nothing"
  grep -q '"diagnostics":\[".*script.txt:5: error: Renderer::requestPick: pixel (500, 10) is outside.*"event":"pick".*"result":"error"' \
    "$out/status.jsonl" || fail "no error line for the pick outside the window"
  echo "ok: pick selects object4 at the centre, nothing in the corner, an error outside" ;;
script_errors)
  check() {  # SCRIPT-TEXT EXPECTED-REGEX
    printf '%b' "$1" >"$out/bad.txt"
    # No DISPLAY: a script error must be reported before any window is opened.
    env -u DISPLAY "$rgraph" view --script "$out/bad.txt" >"$out/view.log" 2>&1; local rc=$?
    [[ $rc -eq 1 ]] || fail "script '$1': exit $rc, expected 1"
    grep -qE "$2" "$out/view.log" || fail "script '$1': expected /$2/ in: $(cat "$out/view.log")"
  }
  check 'wait 1\nfly away\n' "bad\.txt:2: error: unknown command 'fly'"
  check '# a comment\n\ncamera 1 2 x 4 5 6\n' "bad\.txt:3: error: 'camera': 'x' is not a number"
  check 'wait 2.5\n' "bad\.txt:1: error: 'wait' needs whole numbers"
  check 'resize 100\n' "bad\.txt:1: error: 'resize' expects W H"
  env -u DISPLAY "$rgraph" view --script "$out/missing.txt" >"$out/view.log" 2>&1; rc=$?
  [[ $rc -eq 1 ]] && grep -q "missing.txt: error: cannot read" "$out/view.log" || fail "a missing script: exit $rc"
  # A folder read as an empty script would never quit: refused before any window, with the reason.
  mkdir -p "$out/folder"
  env -u DISPLAY "$rgraph" view --script "$out/folder" >"$out/view.log" 2>&1; rc=$?
  [[ $rc -eq 1 ]] && grep -q "folder: error: cannot read the script file (it is a folder)" "$out/view.log" ||
    fail "a folder as the script: exit $rc: $(cat "$out/view.log")"
  echo "ok: script errors exit 1 with FILE:LINE" ;;
*) fail "unknown case $case_" ;;
esac
