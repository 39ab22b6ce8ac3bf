#!/usr/bin/env bash
# Renders every shipped pipeline (pipelines/*.json and pipelines/examples/*.json)
# on several scenes into OUT_DIR, one PNG each, for byte-for-byte comparison
# across a refactoring that must not change images:
#
#   scripts/render-shipped.sh build /tmp/before      # on the old commit
#   scripts/render-shipped.sh build /tmp/after       # on the new one
#   scripts/render-shipped.sh --compare /tmp/before /tmp/after
#
# Pipelines or scenes a pipeline refuses are recorded as such (the refusal
# message must not change either). Exit 1 on a compare mismatch.
set -uo pipefail
cd "$(dirname "$0")/.."
if [[ ${1:-} == --compare ]]; then
  a=$2 b=$3 bad=0
  for f in "$a"/*; do
    n=$(basename "$f")
    if ! cmp -s "$f" "$b/$n"; then echo "differs: $n"; bad=1; fi
  done
  for f in "$b"/*; do [[ -e "$a/$(basename "$f")" ]] || { echo "only in $b: $(basename "$f")"; bad=1; }; done
  [[ $bad == 0 ]] && echo "identical: $(ls "$a" | wc -l) files"
  exit $bad
fi
build=${1:?usage: render-shipped.sh BUILD_DIR OUT_DIR}
out=${2:?usage: render-shipped.sh BUILD_DIR OUT_DIR}
rgraph="$build/bin/rgraph"
assets=../shared/assets/gltf
mkdir -p "$out"
scenes=(learnopengl learnopengl:overview many-lights:64 "$assets/BoxTextured/BoxTextured.glb" "$assets/Suzanne/Suzanne.gltf"
  "$assets/AlphaBlendModeTest/AlphaBlendModeTest.glb"
  "$assets/NormalTangentMirrorTest/NormalTangentMirrorTest.glb" "$assets/MetalRoughSpheresNoTextures/MetalRoughSpheresNoTextures.glb")
for p in pipelines/*.json pipelines/examples/*.json; do
  for s in "${scenes[@]}"; do
    [[ $s == */* && ! -e $s ]] && continue
    name="$(basename "$p" .json)@$(basename "$s" | tr ':' '_')"
    if ! "$rgraph" render "$p" --scene "$s" --width 320 --height 180 --out "$out/$name.png" >/dev/null 2>"$out/$name.err"; then
      mv "$out/$name.err" "$out/$name.refused"
    else
      rm -f "$out/$name.err"
    fi
  done
done
echo "rendered $(ls "$out"/*.png 2>/dev/null | wc -l) images, $(ls "$out"/*.refused 2>/dev/null | wc -l) refusals into $out"
