#!/usr/bin/env bash
# Renders every glTF sample in ../shared/assets/gltf (one folder per model: its
# .glb, else its .gltf) through one pipeline, and keeps what each run said on
# stderr (the loader's warnings, one per ignored feature per file).
#
#   scripts/gltf-samples.sh BUILD_DIR OUT_DIR [--pipeline P] [--size WxH] [--sheet PNG] [--expect FILE]
#
# OUT_DIR gets NAME.png and NAME.warnings (the stderr lines that say "warning"
# or "ignored", with the file's folder cut off) for each sample. --sheet lays
# the renders beside each sample's screenshot into a contact sheet
# (rgraph_contact_sheet; docs/images/gltf_contact_sheet.png is made so).
# --expect compares the warnings with FILE (lines "NAME: warning text", sorted)
# and prints the difference. Exit 1 when a render fails or the warnings differ.
set -uo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: gltf-samples.sh BUILD_DIR OUT_DIR [options]}
out=${2:?usage: gltf-samples.sh BUILD_DIR OUT_DIR [options]}
shift 2
pipeline=pipelines/deferred-pbr.json size=320x180 sheet="" expect="" extra=()
while (($#)); do
  case $1 in
    --pipeline) pipeline=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --sheet) sheet=$2; shift 2 ;;
    --expect) expect=$2; shift 2 ;;
    --) shift; extra=("$@"); break ;;
    *) echo "gltf-samples.sh: unknown option '$1'" >&2; exit 1 ;;
  esac
done
assets=${RGRAPH_ASSETS_DIR:-../shared/assets}/gltf
[[ -d $assets ]] || { echo "gltf-samples.sh: no samples at $assets" >&2; exit 1; }
mkdir -p "$out"
bad=0 rows=()
for dir in "$assets"/*/; do
  name=$(basename "$dir")
  model=$(ls "$dir"*.glb 2>/dev/null | head -1)
  [[ -n $model ]] || model=$(ls "$dir"*.gltf 2>/dev/null | head -1)
  [[ -n $model ]] || continue
  if "$build/bin/rgraph" render "$pipeline" --scene "$model" --width "${size%x*}" --height "${size#*x}" \
      --out "$out/$name.png" "${extra[@]}" >/dev/null 2>"$out/$name.stderr"; then
    :
  else
    echo "FAILED ($?): $name" >&2
    cat "$out/$name.stderr" >&2
    bad=1
  fi
  # Warnings without the log's time stamps and level tags, and without the
  # sample's folder (the text names the file).
  grep -iE "warn|ignored" "$out/$name.stderr" | sed -E 's/^\[[^]]*\] *//; s/^\[[^]]*\] *//; s#[^ ]*/##g' |
    sed "s/^/$name: /" >"$out/$name.warnings"
  shot=$(ls "$dir"screenshot.* 2>/dev/null | head -1)
  rows+=(--row "$name" "$out/$name.png" "${shot:-$dir/screenshot.png}")
done
cat "$out"/*.warnings | sort >"$out/warnings.txt"
if [[ -n $expect ]] && ! diff -u "$expect" "$out/warnings.txt"; then
  echo "gltf-samples.sh: the samples' warnings differ from $expect (above: - expected, + got)" >&2
  bad=1
fi
if [[ -n $sheet ]]; then
  "$build/bin/rgraph_contact_sheet" "$sheet" --cell "${size%x*}" "${size#*x}" \
    --columns "rgraph $(basename "$pipeline" .json)" "the sample's screenshot" "${rows[@]}" || bad=1
fi
exit $bad
