#!/usr/bin/env bash
# The part of standalone_test.sh that runs in its private mount namespace:
#   standalone_inner.sh WORK MOVED_PREFIX LIBDIR XVFB_RUN SOURCE_DIR BINARY_DIR -- HIDDEN...
# Hides every HIDDEN folder under an empty tmpfs, checks the source and build
# trees are unreachable, then runs the copied install's checks (standalone_test.sh
# lists them). Runs from a copy in WORK: the source tree is gone once hidden.
set -uo pipefail
work=$1; moved=$2; libdir=$3; xvfb=$4; src=$5; bin=$6; shift 6
[[ "${1:-}" == "--" ]] && shift
fail() { echo "FAIL: $*" >&2; exit 1; }
cd "$work" || fail "cd $work"

for dir in "$@"; do
  mount -t tmpfs -o size=1m,mode=0555 rgraph-hidden "$dir" || fail "cannot hide $dir"
  echo "hidden: $dir"
done
[[ ! -e "$src/CMakeLists.txt" && ! -e "$src/shaders" ]] || fail "the source tree $src is still reachable"
[[ ! -e "$bin/CMakeCache.txt" ]] || fail "the build tree $bin is still reachable"

probe="$work/tools/png_probe"
took() { echo "($((SECONDS - t0)) s)"; t0=$SECONDS; }  # each step's cost, for CI's time budget
t0=$SECONDS
rgraph="$moved/bin/rgraph"
size_is() {  # size_is PNG W H
  local got; got=$("$probe" "$1" | head -n 1) || fail "png_probe $1: $got"
  [[ "$got" == "$2 $3" ]] || fail "$1 is $got, expected $2 $3"
}

# 1. The default pipeline and scene, with rgraph's own folders logged.
log=$("$rgraph" --log-level debug render --width 64 --height 48 --out "$work/default.png" 2>&1); rc=$?
[[ $rc -eq 0 ]] || { echo "$log"; fail "$rgraph render (default pipeline and scene): exit $rc"; }
size_is "$work/default.png" 64 48
line=$(grep -o "rgraph's own files .*" <<<"$log" | head -n 1)
echo "$line"
want="rgraph's own files (an install, relative to $moved/$libdir/librgraph.so): shaders $moved/share/rgraph/shaders,"
want+=" pipelines $moved/share/rgraph/pipelines, plugins $moved/$libdir/rgraph/plugins"
[[ "$line" == "$want" ]] || fail "rgraph's own folders are not the copy's: expected '$want'"
echo "ok: rgraph render (default pipeline and scene) from the copy $(took)"

# 2. A pipeline with plugins: the copy's plugin folder and the plugins' shaders.
"$rgraph" render "$moved/share/rgraph/pipelines/deferred-ssao-bloom.json" --width 64 --height 48 \
  --out "$work/bloom.png" || fail "$rgraph render deferred-ssao-bloom.json: exit $?"
size_is "$work/bloom.png" 64 48
echo "ok: rgraph render deferred-ssao-bloom.json (plugins) from the copy $(took)"

# 3. The embedding example, unmodified, built against the copy.
cmake -S "$work/src/embed-glfw" -B "$work/build-embed" -DCMAKE_PREFIX_PATH="$moved" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  >"$work/embed-configure.log" 2>&1 || { cat "$work/embed-configure.log"; fail "configuring examples/embed-glfw"; }
cmake --build "$work/build-embed" -j2 >"$work/embed-build.log" 2>&1 ||
  { cat "$work/embed-build.log"; fail "building examples/embed-glfw"; }
"$xvfb" -a -f "$work/Xauthority" -e "$work/xvfb-errors.log" -s '-screen 0 640x480x24' \
  "$work/build-embed/embed_glfw" --size 128x96 --frames 3 --screenshot "$work/embed.png"
rc=$?
[[ $rc -eq 0 ]] || { cat "$work/xvfb-errors.log" 2>/dev/null; fail "examples/embed-glfw against the copy: exit $rc"; }
size_is "$work/embed.png" 128 96
echo "ok: examples/embed-glfw built against the copy renders $(took)"

# 4. The plugin template built against the copy: its unit test, and a render.
cmake -S "$work/src/plugin-template" -B "$work/build-template" -DCMAKE_PREFIX_PATH="$moved" \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >"$work/template-configure.log" 2>&1 ||
  { cat "$work/template-configure.log"; fail "configuring examples/plugin-template"; }
cmake --build "$work/build-template" -j2 >"$work/template-build.log" 2>&1 ||
  { cat "$work/template-build.log"; fail "building examples/plugin-template"; }
ctest --test-dir "$work/build-template" --output-on-failure --no-tests=error ||
  fail "the template's unit test against the copy"
"$rgraph" render "$work/src/plugin-template/vignette.json" --plugin-path "$work/build-template/lib/rgraph/plugins" \
  --width 96 --height 64 --out "$work/template.png" || fail "rendering the template's pipeline: exit $?"
size_is "$work/template.png" 96 64
echo "ok: examples/plugin-template built against the copy: unit test and render $(took)"
