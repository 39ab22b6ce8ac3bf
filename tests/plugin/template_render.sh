#!/usr/bin/env bash
# Renders with the INSTALLED rgraph and the out-of-tree template plugin:
#   template_render.sh PREFIX TEMPLATE_BUILD PNG_PROBE SOURCE_DIR
# 1. the template's own pipeline (scene + vignette) renders, exit 0, image written;
# 2. a flat grey image through the vignette: the corners come out darker than the centre.
set -uo pipefail
prefix=$1; build=$2; probe=$3; src=$4
unset RGRAPH_PLUGIN_PATH RGRAPH_SHADER_DIR RGRAPH_PIPELINE_DIR
plugins="$build/lib/rgraph/plugins"
out="$build/out"; mkdir -p "$out"
fail() { echo "FAIL: $*" >&2; exit 1; }

[[ -f "$plugins/librgraph_vignette.so" ]] || fail "the template did not build $plugins/librgraph_vignette.so"
"$prefix/bin/rgraph" render "$src/examples/plugin-template/vignette.json" --plugin-path "$plugins" \
  --width 96 --height 64 --out "$out/template.png" || fail "rendering the template pipeline: exit $?"
[[ -s "$out/template.png" ]] || fail "no image $out/template.png"

"$prefix/bin/rgraph" render "$src/tests/plugin/configs/vignette-flat.json" --plugin-path "$plugins" \
  --width 64 --height 64 --out "$out/flat.png" || fail "rendering vignette-flat.json: exit $?"
probe_out=$("$probe" "$out/flat.png" 32 32 0 0 63 0 0 63 63 63) || fail "probe: $probe_out"
echo "$probe_out"
mapfile -t lines <<<"$probe_out"
[[ "${lines[0]}" == "64 64" ]] || fail "image size ${lines[0]}, expected 64 64"
centre=$(cut -d' ' -f1 <<<"${lines[1]}")
for i in 2 3 4 5; do
  corner=$(cut -d' ' -f1 <<<"${lines[$i]}")
  (( corner + 40 < centre )) || fail "corner red $corner is not clearly darker than the centre's $centre"
done
echo "ok: vignette darkens the corners (centre $centre)"
