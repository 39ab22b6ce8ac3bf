#!/usr/bin/env bash
# An installed rgraph stands alone (issue 30): the install copied to a new
# prefix outside the source and build trees (so any absolute path baked into it
# is wrong), those trees made unreachable (an empty tmpfs mounted over each in a
# private mount namespace: `unshare`, as root or in a user namespace), then,
# against the copy only:
#   1. the installed `rgraph render` renders the default pipeline and scene, and
#      its debug log says its shaders, pipelines and plugins are the copy's;
#   2. it renders deferred-ssao-bloom.json (the copy's plugins and their shaders);
#   3. examples/embed-glfw, unmodified, configured and built against the copy,
#      runs 3 frames under Xvfb and writes its screenshot;
#   4. examples/plugin-template built against the copy: its own unit test passes
#      and the copy's rgraph renders its pipeline with the plugin;
# and no output names a path under the source or build tree.
#   standalone_test.sh PREFIX SOURCE_DIR BINARY_DIR CONFIGURED_PREFIX LIBDIR PNG_PROBE XVFB_RUN
set -uo pipefail
prefix=$1; src=$2; bin=$3; configured=$4; libdir=$5; probe=$6; xvfb=$7
fail() { echo "FAIL: $*" >&2; exit 1; }
cannot() { echo "cannot run: $*" >&2; exit 1; }
[[ -x "$prefix/bin/rgraph" ]] || fail "no installed rgraph in $prefix (fixture rgraph_installed)"

work=$(mktemp -d "${TMPDIR:-/tmp}/rgraph-standalone.XXXXXX") || cannot "mktemp -d failed"
trap 'rm -rf "$work"' EXIT
real_work=$(realpath "$work")
for tree in "$src" "$bin"; do
  t=$(realpath "$tree")
  [[ "$real_work/" != "$t/"* ]] || cannot "the temporary folder $work is inside $tree, which is hidden (set TMPDIR elsewhere)"
done

# The copy, the example sources it builds, and the tools the hidden part runs.
moved="$work/elsewhere/rgraph"
mkdir -p "$moved" "$work/src" "$work/tools" || fail "mkdir in $work"
cp -a "$prefix/." "$moved/" || fail "copying $prefix to $moved"
cp -a "$src/examples/embed-glfw" "$src/examples/plugin-template" "$work/src/" || fail "copying the examples"
cp "$probe" "$work/tools/png_probe" || fail "copying $probe"
cp "$src/tests/embed/standalone_inner.sh" "$work/inner.sh" || fail "copying standalone_inner.sh"

# Deepest first, so that a tree inside another (build/ in the source tree) is
# hidden before its parent hides it. The original install and the prefix it was
# configured for (its share/rgraph and <libdir>/rgraph, where a baked-in path
# would point) are hidden too when they exist.
hide=()
for p in "$prefix" "$bin" "$src" "$configured/share/rgraph" "$configured/$libdir/rgraph"; do
  [[ -d "$p" ]] && hide+=("$(realpath "$p")")
done
mapfile -t hide < <(printf '%s\n' "${hide[@]}" | sort -u | awk '{ print gsub("/", "/") "\t" $0 }' | sort -rn | cut -f2)

# A mount namespace: as root directly, else in a user namespace.
mkdir -p "$work/probe"
ns=()
for args in "--mount" "--user --map-root-user --mount"; do
  # shellcheck disable=SC2086
  if unshare $args sh -c "mount -t tmpfs none '$work/probe'" 2>/dev/null; then read -ra ns <<<"$args"; break; fi
done
[[ ${#ns[@]} -gt 0 ]] || cannot "no private mount namespace (unshare --mount as root, or unshare --user --map-root-user --mount)"

cd "$work" || fail "cd $work"
unset RGRAPH_PLUGIN_PATH RGRAPH_SHADER_DIR RGRAPH_PIPELINE_DIR CMAKE_PREFIX_PATH
export RGRAPH_CACHE_DIR="$work/cache"
unshare "${ns[@]}" bash "$work/inner.sh" "$work" "$moved" "$libdir" "$xvfb" "$src" "$bin" -- "${hide[@]}" 2>&1 |
  tee "$work/all.log"
rc=${PIPESTATUS[0]}
[[ $rc -eq 0 ]] || fail "the stand-alone run exited $rc (its output above)"
# No message may point into the trees: a path there was baked in somewhere.
for tree in "$src" "$bin" "$prefix"; do
  t=$(realpath "$tree")
  if grep -F -- "$t/" "$work/all.log" | grep -vF -- "hidden: $t" >&2; then
    fail "the output names a path under $t (lines above)"
  fi
done
echo "ok: the install copied to $moved works with $(printf '%s ' "${hide[@]}")hidden"
