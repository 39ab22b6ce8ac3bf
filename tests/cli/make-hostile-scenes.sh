#!/usr/bin/env bash
# Writes scenes too big to commit into OUTDIR, for the command-line tests:
#   deep-chain.gltf    a triangle under a chain of 20,000 nodes (each the only child of the one before)
#   deep-nesting.gltf  a triangle whose "extras" nest 100,000 arrays deep
#   deep-nesting.json  a scene file with the same nesting under an unknown key
set -euo pipefail
out=${1:?usage: make-hostile-scenes.sh OUTDIR}
mkdir -p "$out"

# One triangle: 3 float positions (0,0,0) (1,0,0) (0,1,0), uint16 indices 0 1 2, 2 bytes padding.
rest='"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],
"buffers":[{"byteLength":44,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA="}]}'

nest() { head -c "$1" /dev/zero | tr '\0' '['; head -c "$1" /dev/zero | tr '\0' ']'; }

{
  printf '{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[\n'
  for ((i = 1; i < 20000; i++)); do printf '{"translation":[0.0001,0,0],"children":[%d]},\n' "$i"; done
  printf '{"mesh":0}],\n%s\n' "$rest"
} >"$out/deep-chain.gltf"

{
  printf '{"asset":{"version":"2.0"},"extras":'
  nest 100000
  printf ',"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],\n%s\n' "$rest"
} >"$out/deep-nesting.gltf"

{
  printf '{"notes":'
  nest 100000
  printf ',"models":[{"shape":"cube"}]}\n'
} >"$out/deep-nesting.json"
echo "wrote $out/deep-chain.gltf, deep-nesting.gltf, deep-nesting.json"
