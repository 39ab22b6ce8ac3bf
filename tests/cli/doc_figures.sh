#!/usr/bin/env bash
# The figures README.md, the pipeline descriptions and docs/writing-a-pass.md
# state about memory are what `rgraph plan` computes (docs/performance.md's
# figures are checked by tests/bench_cli/doc_figures_test.cpp).
# Usage: doc_figures.sh RGRAPH SOURCE_DIR
set -u
rgraph=$1 src=$2
fail=0
check() {  # what stated computed
  if [ "$2" != "$3" ]; then
    echo "FAIL: $1: the text says $2, the code gives $3" >&2
    fail=1
  else
    echo "ok: $1: $2"
  fi
}
num() { tr -d ','; }

# deferred-compact: "N bytes of colour targets + M of depth" (README) and
# "(N bytes of colour targets per pixel plus M of depth)" (its description).
plan=$("$rgraph" plan "$src/pipelines/deferred-compact.json" --scene learnopengl) || { echo "FAIL: plan" >&2; exit 1; }
total=$(sed -n 's/^G-buffer bytes per pixel: \([0-9]*\) before.*/\1/p' <<<"$plan")
readme=$(grep -o '[0-9]* bytes of colour targets + [0-9]* of depth' "$src/README.md")
[ -n "$readme" ] || { echo "FAIL: README.md no longer states deferred-compact's bytes per pixel" >&2; exit 1; }
# "+ N of optional targets": the emissive and reflectance targets the file
# declares (the plan's "before"; adaptation removes them where not needed).
optional() { grep -o '+ [0-9]* of optional targets' "$1" | awk '{print $2}'; }
check "README.md deferred-compact bytes per pixel" "$(awk '{print $1 + $7}' <<<"$readme")" "$((total - $(optional "$src/README.md")))"
desc=$(grep -o '[0-9]* bytes of colour targets per pixel plus [0-9]* of depth' "$src/pipelines/deferred-compact.json")
[ -n "$desc" ] || { echo "FAIL: deferred-compact.json's description no longer states its bytes per pixel" >&2; exit 1; }
check "deferred-compact.json description bytes per pixel" "$(awk '{print $1 + $9}' <<<"$desc")" \
  "$((total - $(optional "$src/pipelines/deferred-compact.json")))"
check "deferred-compact depth bytes (depth32f)" "$(awk '{print $7}' <<<"$readme")" 4

# docs/writing-a-pass.md: naive and allocated bytes of deferred-ssao-bloom at 1920x1080.
json=$("$rgraph" plan "$src/pipelines/deferred-ssao-bloom.json" --width 1920 --height 1080 --json) ||
  { echo "FAIL: plan deferred-ssao-bloom" >&2; exit 1; }
naive=$(grep -o '"naive_bytes": [0-9]*' <<<"$json" | grep -o '[0-9]*$')
alloc=$(grep -o '"allocated_bytes": [0-9]*' <<<"$json" | grep -o '[0-9]*$')
text=$(tr '\n' ' ' <"$src/docs/writing-a-pass.md" | grep -o 'reports [0-9,]* naive bytes and *[0-9,]* allocated ([0-9]*%)')
[ -n "$text" ] || { echo "FAIL: docs/writing-a-pass.md no longer states the plan's bytes" >&2; exit 1; }
check "writing-a-pass.md naive bytes" "$(awk '{print $2}' <<<"$text" | num)" "$naive"
check "writing-a-pass.md allocated bytes" "$(awk '{print $6}' <<<"$text" | num)" "$alloc"
check "writing-a-pass.md allocated share" "$(awk '{print $8}' <<<"$text" | tr -d '()%')" "$(((alloc * 100 + naive / 2) / naive))"
peak=$(grep -o '"peak_live_bytes": [0-9]*' <<<"$json" | grep -o '[0-9]*$')
text=$(tr '\n' ' ' <"$src/docs/writing-a-pass.md" | grep -o 'its peak live bytes, [0-9,]* at the lighting pass')
[ -n "$text" ] || { echo "FAIL: docs/writing-a-pass.md no longer states the plan's peak live bytes" >&2; exit 1; }
check "writing-a-pass.md peak live bytes" "$(awk '{print $5}' <<<"$text" | num)" "$peak"

# deferred-ssao-bloom.json's description: "allocates N bytes in M textures" at 1920x1080.
desc=$(grep -o 'allocates [0-9,]* bytes in [0-9]* textures' "$src/pipelines/deferred-ssao-bloom.json")
[ -n "$desc" ] || { echo "FAIL: deferred-ssao-bloom.json's description no longer states its bytes" >&2; exit 1; }
check "deferred-ssao-bloom.json description allocated bytes" "$(awk '{print $2}' <<<"$desc" | num)" "$alloc"
textures=$("$rgraph" plan "$src/pipelines/deferred-ssao-bloom.json" --width 1920 --height 1080 |
  sed -n 's/.* in \([0-9]*\) physical textures;.*/\1/p')
check "deferred-ssao-bloom.json description textures" "$(awk '{print $5}' <<<"$desc")" "$textures"
exit $fail
