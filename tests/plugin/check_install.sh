#!/usr/bin/env bash
# Checks what `cmake --install` put under a prefix: check_install.sh PREFIX LIBDIR
set -uo pipefail
prefix=$1; libdir=$2
fail=0
need() { if [[ ! -e "$prefix/$1" ]]; then echo "FAIL: missing $prefix/$1" >&2; fail=1; else echo "ok: $1"; fi; }
need bin/rgraph
need "$libdir/librgraph.so"
need "$libdir/rgraph/plugins/librgraph_bloom.so"
need "$libdir/rgraph/plugins/librgraph_ssao.so"
need "$libdir/cmake/rgraph/rgraphConfig.cmake"
need "$libdir/cmake/rgraph/rgraphConfigVersion.cmake"
need "$libdir/cmake/rgraph/rgraphTargets.cmake"
need "$libdir/cmake/rgraph/rgraphPlugin.cmake"
need include/rgraph/plugin.h
need include/rgraph/pass.h
need include/rgraph/testing.h
need include/rgraph/pipeline_check.h
need include/rgraph/gl/shader_library.h
need include/rgraph/gl/fullscreen.h
need include/rgraph/passes/gbuffer_layout.h
need include/rgraph/passes/lighting_options.h
need share/rgraph/shaders/fullscreen.vert
need share/rgraph/shaders/include/frame.glsl
need share/rgraph/pipelines/default.json
need share/rgraph/pipelines/deferred-ssao-bloom.json
need share/rgraph/plugins/bloom/bloom_blur.frag
need share/rgraph/plugins/bloom/bloom_chain.glsl
need share/rgraph/plugins/ssao/ssao.frag
# The installed executable runs on its own (RUNPATH to its library) and finds
# its default pipeline and the installed plugins (not the build tree's).
unset RGRAPH_PLUGIN_PATH RGRAPH_SHADER_DIR RGRAPH_PIPELINE_DIR
out=$("$prefix/bin/rgraph" passes --plugin bloom --plugin ssao 2>&1); rc=$?
if [[ $rc -ne 0 ]]; then echo "FAIL: installed rgraph passes --plugin bloom: exit $rc: $out" >&2; fail=1; fi
for t in bloom_bright bloom_blur bloom_composite ssao ssao_blur ssao_upsample; do
  if ! grep -Eq "^$t  \\($prefix/$libdir/rgraph/plugins/librgraph_(bloom|ssao)\\.so\\)" <<<"$out"; then
    echo "FAIL: '$t' not listed with its installed origin:" >&2; echo "$out" | grep -E "^(bloom|ssao)" >&2; fail=1
  fi
done
out=$("$prefix/bin/rgraph" validate "$prefix/share/rgraph/pipelines/deferred-ssao-bloom.json" 2>&1); rc=$?
if [[ $rc -ne 0 ]]; then echo "FAIL: installed rgraph validate deferred-ssao-bloom.json: exit $rc: $out" >&2; fail=1; fi
# Rendering it needs the installed plugins' shaders (share/rgraph/plugins/<name>/).
png=$(mktemp --suffix=.png)
out=$("$prefix/bin/rgraph" render "$prefix/share/rgraph/pipelines/deferred-ssao-bloom.json" --width 64 --height 48 \
      --out "$png" 2>&1); rc=$?
if [[ $rc -ne 0 || ! -s "$png" ]]; then echo "FAIL: installed rgraph render deferred-ssao-bloom.json: exit $rc: $out" >&2; fail=1; fi
rm -f "$png"
# The installed rgraph searches for plugins only in its own prefix (issue 16):
# no folder of the build tree it was built in is baked in. Its debug log names
# the search path; with no --plugin-path and no RGRAPH_PLUGIN_PATH that is
# exactly <prefix>/<libdir>/rgraph/plugins (the build tree's rgraph finds its
# own plugins the same way: tests/plugin/plugin_cli_test.cpp).
want=$(realpath -m "$prefix/$libdir/rgraph/plugins")
out=$("$prefix/bin/rgraph" --log-level debug validate "$prefix/share/rgraph/pipelines/deferred-ssao-bloom.json" 2>&1); rc=$?
if [[ $rc -ne 0 ]]; then echo "FAIL: installed rgraph --log-level debug validate: exit $rc: $out" >&2; fail=1; fi
search=$(grep -o "plugin 'ssao': search path .*" <<<"$out" | head -1)
if [[ "$search" != "plugin 'ssao': search path $want" ]]; then
  echo "FAIL: the installed rgraph's plugin search path is not only its prefix's folder ($want):" >&2
  echo "${search:-(no search path logged)}" >&2; fail=1
else
  echo "ok: plugin search path is $want alone"
fi
# A plugin that is nowhere in the prefix is not found, and the folders the
# error lists are that one folder.
out=$("$prefix/bin/rgraph" passes --plugin no_such_plugin 2>&1); rc=$?
if [[ $rc -ne 1 || "$out" != *"no_such_plugin.so in $want; add a folder"* ]]; then
  echo "FAIL: installed rgraph passes --plugin no_such_plugin (exit $rc) should search $want alone: $out" >&2; fail=1
fi
# `rgraph render` with no pipeline finds share/rgraph/pipelines/default.json.
png=$(mktemp --suffix=.png)
out=$("$prefix/bin/rgraph" render --width 64 --height 48 --out "$png" 2>&1); rc=$?
if [[ $rc -ne 0 || ! -s "$png" ]]; then echo "FAIL: installed rgraph render (default pipeline): exit $rc: $out" >&2; fail=1; fi
rm -f "$png"
[[ $fail -eq 0 ]] && echo "install layout ok"
exit $fail
