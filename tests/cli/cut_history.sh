#!/usr/bin/env bash
# `render --cut K` restarts the history before frame K: with TAA, a cut before
# the last frame shows that frame alone (differs from the accumulated image),
# and a cut before frame 0 changes nothing (the first frame has no history).
#   cut_history.sh RGRAPH PNG_COMPARE PIPELINE OUT_DIR
set -euo pipefail
rgraph=$1 compare=$2 pipeline=$3 out=$4
mkdir -p "$out"
render() { "$rgraph" render "$pipeline" --frames 6 --width 64 --height 48 --out "$out/$1.png" "${@:2}" >/dev/null; }
render none
render cut0 --cut 0
render cut5 --cut 5
"$compare" "$out/none.png" "$out/cut0.png" 0 || { echo "FAIL: --cut 0 changed the image"; exit 1; }
if "$compare" "$out/none.png" "$out/cut5.png" 8; then
  echo "FAIL: --cut 5 left the image as without a cut (within 8/255): the history was not restarted"
  exit 1
fi
echo "cut history ok"
