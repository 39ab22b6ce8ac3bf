#!/usr/bin/env bash
# Output files of rgraph render, view and bench (issue 25): no output replaces
# an input or another output, write failures exit 1 with the OS's reason and
# leave an earlier file whole, and the shader-check cache's entries are data.
#   outputs.sh CASE RGRAPH PIPELINE OUT_DIR [XVFB_RUN]
# Each CASE prints "CASE ok" when it holds.
set -uo pipefail
case=$1 rgraph=$2 pipeline=$3 out=$4/$1 xvfb=${5:-}
rm -rf "$out" && mkdir -p "$out" || exit 1
export RGRAPH_CACHE_DIR=$out/cache
fail() { echo "FAIL: $*"; exit 1; }
# run WANT_EXIT REGEX ARGS...: rgraph ARGS exits WANT_EXIT with REGEX in its output.
run() {
  local want=$1 regex=$2 got
  shift 2
  msg=$(timeout 120 "$rgraph" "$@" 2>&1); got=$?
  [[ $got -eq $want ]] || fail "rgraph $* exited $got, expected $want: $msg"
  grep -Eq -- "$regex" <<<"$msg" || fail "rgraph $* printed no /$regex/: $msg"
}
small=(--width 32 --height 24)
cp "$pipeline" "$out/p.json"
cp "$out/p.json" "$out/p.orig"
unchanged() { cmp -s "$out/p.json" "$out/p.orig" || fail "$1 changed p.json"; }

case $case in
  same_file)  # an output that is an input or another output: refused before any work, the input unchanged
    run 1 "error: --out '.*p.json' is the pipeline '.*p.json': an output never replaces an input" \
      render "$out/p.json" --out "$out/p.json" "${small[@]}"
    unchanged "--out p.json"
    run 1 "error: --stats '.*p.json' is the pipeline" \
      render "$out/p.json" --out "$out/a.png" --stats "$out/p.json" "${small[@]}"
    unchanged "--stats p.json"
    [[ ! -e "$out/a.png" ]] || fail "a refused render wrote its --out"
    ln -s p.json "$out/link.png" && ln "$out/p.json" "$out/hard.png"
    run 1 "error: --out '.*link.png' is the pipeline" render "$out/p.json" --out "$out/link.png" "${small[@]}"
    run 1 "error: --out '.*hard.png' is the pipeline" render "$out/p.json" --out "$out/hard.png" "${small[@]}"
    unchanged "--out (a link to p.json)"
    echo '{"version": 1}' >"$out/scene.json"
    run 1 "error: --out '.*scene.json' is --scene '.*scene.json'" \
      render "$out/p.json" --scene "$out/scene.json" --out "$out/scene.json" "${small[@]}"
    grep -q '"version": 1' "$out/scene.json" || fail "--out scene.json changed the scene"
    # Two outputs, one file (not there yet: the same resolved path).
    run 1 "error: --stats '.*/\./a.png' is --out '.*a.png': each output needs a file of its own" \
      render "$out/p.json" --out "$out/a.png" --stats "$out/./a.png" "${small[@]}"
    # The viewer: refused before a window opens (no display needed).
    run 1 "error: --status '.*p.json' is the pipeline" view "$out/p.json" --status "$out/p.json"
    unchanged "view --status p.json"
    printf 'screenshot %s\nquit\n' "$out/p.json" >"$out/s.txt"
    run 1 "error: .*s.txt:1: screenshot '.*p.json' is the pipeline" view "$out/p.json" --script "$out/s.txt"
    printf 'screenshot %s\nquit\n' "$out/s.txt" >"$out/s.txt"
    run 1 "error: .*s.txt:1: screenshot '.*s.txt' is --script '.*s.txt'" view "$out/p.json" --script "$out/s.txt"
    unchanged "view screenshot p.json"
    ;;
  shader_file)  # a shader the pipeline compiled (known once it rendered): refused before the write
    here=$(dirname "$0")
    cp -r "$here/shaders" "$out/shaders" && cp "$out/shaders/cli_teal.frag" "$out/teal.orig"
    run 1 "error: --out '.*cli_teal.frag' is the pipeline's file '.*cli_teal.frag'" render "$here/configs/shader-custom.json" \
      --shader-path "$out/shaders" --out "$out/shaders/cli_teal.frag" "${small[@]}"
    cmp -s "$out/shaders/cli_teal.frag" "$out/teal.orig" || fail "--out replaced the shader"
    ;;
  folder)  # an output folder that does not exist or is not writable: refused before rendering
    run 1 "error: --out '.*no-such/a.png': cannot be written: no such folder '.*no-such'" \
      render "$out/p.json" --out "$out/no-such/a.png" "${small[@]}"
    run 1 "error: --stats '$out': cannot be written: is a folder" \
      render "$out/p.json" --out "$out/a.png" --stats "$out" "${small[@]}"
    if [[ $(id -u) -ne 0 ]]; then
      mkdir "$out/ro" && chmod a-w "$out/ro"
      run 1 "error: --out '.*ro/a.png': cannot be written: Permission denied" \
        render "$out/p.json" --out "$out/ro/a.png" "${small[@]}"
    fi
    ;;
  dev_full)  # write failures: exit 1 with the OS's reason, never "wrote"
    run 1 "error: cannot write PNG file /dev/full: No space left on device" render "$out/p.json" --out /dev/full "${small[@]}"
    grep -q "^wrote" <<<"$msg" && fail "'wrote' printed for a failed write: $msg"
    run 1 "error: cannot write stats file /dev/full: No space left on device" \
      render "$out/p.json" --out "$out/a.png" --stats /dev/full "${small[@]}"
    run 0 "wrote .*/dev/null" render "$out/p.json" --out /dev/null --stats /dev/null "${small[@]}"
    ;;
  file_too_large)  # a write that fails half way (here RLIMIT_FSIZE, as a full disk): the earlier file stays whole
    echo "earlier" >"$out/a.png"
    ln -s a.png "$out/link.png"
    (trap '' XFSZ; ulimit -f 1; exec timeout 120 "$rgraph" render "$out/p.json" --out "$out/link.png" --width 256 --height 256) \
      >"$out/log" 2>&1
    got=$?
    [[ $got -eq 1 ]] || fail "exit $got under ulimit -f 1: $(cat "$out/log")"
    grep -q "error: cannot write PNG file .*link.png: File too large" "$out/log" || fail "no reason: $(cat "$out/log")"
    [[ $(cat "$out/a.png") == earlier ]] || fail "the earlier file was changed"
    [[ -L "$out/link.png" ]] || fail "the link was replaced"
    ls -A "$out" | grep -q rgraph-tmp && fail "a temporary file was left: $(ls -A "$out")"
    # Written through the link: the link stays, the file it names is the PNG.
    run 0 "wrote" render "$out/p.json" --out "$out/link.png" "${small[@]}"
    [[ -L "$out/link.png" ]] || fail "the link was replaced by the PNG"
    [[ $(head -c 4 "$out/a.png" | tail -c 3) == PNG ]] || fail "a.png is not the PNG"
    ;;
  view_dev_full)  # the viewer's screenshot and status file: a failed write ends it with exit 1 and the reason
    # Our own auth file: without one, xvfb-run's clean-up can fail (exit 5) when runs overlap.
    x=("$xvfb" -a -f "$out/Xauthority" -e "$out/xvfb-errors.log")
    printf 'screenshot /dev/full\nquit\n' >"$out/s.txt"
    msg=$(timeout 120 "${x[@]}" "$rgraph" view "$out/p.json" --script "$out/s.txt" --width 32 --height 24 2>&1)
    got=$?
    [[ $got -eq 1 ]] || fail "screenshot /dev/full exited $got: $msg"
    grep -q "cannot write PNG file /dev/full: No space left on device" <<<"$msg" || fail "no reason: $msg"
    printf 'wait 2\nquit\n' >"$out/q.txt"  # the first status line comes after the first frame
    msg=$(timeout 120 "${x[@]}" "$rgraph" view "$out/p.json" --script "$out/q.txt" --status /dev/full --width 32 --height 24 2>&1)
    got=$?
    [[ $got -eq 1 ]] || fail "--status /dev/full exited $got: $msg"
    [[ $(grep -c "cannot write the status file /dev/full: No space left on device" <<<"$msg") -eq 1 ]] ||
      fail "not reported exactly once: $msg"
    ;;
  cache_fifo)  # a FIFO at a cache entry's path: render does not block on it, and replaces it
    run 0 "wrote" render "$out/p.json" --out "$out/a.png" "${small[@]}"
    entry=$(ls "$RGRAPH_CACHE_DIR"/shadercheck/*.json) && [[ $(wc -w <<<"$entry") -eq 1 ]] || fail "no one cache entry"
    rm "$entry" && mkfifo "$entry"
    run 0 "wrote" render "$out/p.json" --out "$out/a.png" "${small[@]}"
    [[ -f "$entry" && ! -p "$entry" ]] || fail "the FIFO entry was not replaced by an entry"
    ;;
  cache_crafted)  # an entry is a verdict: messages in one are never printed, any other content is a miss
    run 0 "wrote" render "$out/p.json" --out "$out/a.png" "${small[@]}"
    entry=$(ls "$RGRAPH_CACHE_DIR"/shadercheck/*.json)
    check=$(grep -o '"check":"[0-9a-f]*"' "$entry") || fail "entry without a check: $(cat "$entry")"
    for crafted in "{$check,\"diagnostics\":[[0,7,\"crafted message\",\"\",\"\",\"\",\"x.json\",1,1,\"\"]]}" \
                   "{$check,\"clean\":true,\"diagnostics\":[[0,0,\"crafted message\",\"\",\"\",\"\",\"\",0,0,\"\"]]}" \
                   "{$check,\"clean\":\"crafted message\"}"; do
      printf '%s' "$crafted" >"$entry"
      run 0 "wrote" render "$out/p.json" --out "$out/a.png" "${small[@]}"
      grep -q "crafted message\|error:" <<<"$msg" && fail "replayed from the cache entry $crafted: $msg"
      grep -q crafted "$entry" && fail "the crafted entry was not rewritten: $(cat "$entry")"
    done
    ;;
  *) fail "unknown case $case" ;;
esac
echo "$case ok"
