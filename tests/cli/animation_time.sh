#!/usr/bin/env bash
# `render --time T` poses glTF animations: SimpleSkin at 1 s differs from its
# rest pose (the skin bends); `--frames 3 --fps 4 --time 0.5` writes its last
# frame, at 0.5 + 2/4 = 1 s: the same image as `--time 1`.
#   animation_time.sh RGRAPH PNG_COMPARE SCENE OUT_DIR
set -euo pipefail
rgraph=$1 compare=$2 scene=$3 out=$4
mkdir -p "$out"
render() { "$rgraph" render --scene "$scene" --width 64 --height 48 --out "$out/$1.png" "${@:2}" >/dev/null; }
render rest
render posed --time 1
render played --time 0.5 --frames 3 --fps 4
if "$compare" "$out/rest.png" "$out/posed.png" 8; then
  echo "FAIL: --time 1 drew the rest pose (within 8/255)"
  exit 1
fi
"$compare" "$out/posed.png" "$out/played.png" 0 || { echo "FAIL: --frames 3 --fps 4 --time 0.5 is not --time 1"; exit 1; }
echo "animation time ok"
