#!/usr/bin/env bash
# scripts/gpu-check.sh --from on a fake pack (no GL, no build: the programs
# are shell scripts that print gtest's closing lines). Each fake test reads a
# file through the source path compiled into it, as the real ones do, and
# through ../shared/assets: the check must point that path at the unpacked
# copy, run the programs through it, and leave it as it was, whichever way it
# takes:
#   the path is free          -> a symbolic link, removed afterwards;
#   the path is a real folder -> a bind mount in a mount namespace (root);
#   no namespace (forced)     -> the folder moved aside and back.
# Then a failing suite: exit 1, its image and its failure in the report.
# Usage: run_test.sh SOURCE_DIR
set -euo pipefail
src=$1
[[ "$(id -u)" == 0 ]] || { echo "cannot run: the namespace and move-aside cases need root" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
root=$tmp/root/checkout   # the "compiled-in" source path
fail() { echo "FAIL: $*" >&2; [[ -f "$tmp/out/report.md" ]] && cat "$tmp/out/report.md" >&2; exit 1; }

stage=$tmp/stage
mkdir -p "$stage/src/tests" "$stage/src/build/bin" "$stage/shared/assets" "$stage/lib" "$stage/lib-base" "$tmp/pack" \
  "$stage/src/pipelines/examples" "$stage/frames"
echo '{}' >"$stage/src/pipelines/fake.json"
# The reference frames llvmpipe "rendered" (what the fake rgraph writes).
for scene in learnopengl many-lights_64; do echo "frame pipelines/fake.json" >"$stage/frames/fake@$scene.png"; done
echo unpacked >"$stage/src/tests/marker.txt"
echo asset >"$stage/shared/assets/a.txt"
: >"$stage/packages.txt"
printf "GPUCHECK_SOURCE_ROOT=%s\nGPUCHECK_BUILD_REL=build\nGPUCHECK_COMMIT=fake\nGPUCHECK_PACKED_AT='now'\n" "$root" \
  >"$stage/manifest.env"
# shellcheck source=../../scripts/gpu-check/common.sh
source "$src/scripts/gpu-check/common.sh"  # the suites' programs, one list
for prog in $(suite_programs); do
  cat >"$stage/src/build/bin/$prog" <<FAKE
#!/usr/bin/env bash
ok=1
[[ "\$(cat '$root/tests/marker.txt')" == unpacked ]] || ok=0
[[ "\$(cat '$root/../shared/assets/a.txt')" == asset ]] || ok=0
[[ "\$LD_LIBRARY_PATH" == */lib* ]] || ok=0
[[ "\$0" == '$root'/build/bin/* ]] || ok=0  # run through the source path (plugins: /proc/self/exe)
[[ "$prog" == rgraph_tiled_tests && -n "\${FAKE_FAIL:-}" ]] && ok=0
echo "[==========] 3 tests from 1 test suite ran. (1 ms total)"
if ((ok)); then echo "[  PASSED  ] 3 tests."; exit 0; fi
mkdir -p "\$RGRAPH_TEST_OUTPUT" && : >"\$RGRAPH_TEST_OUTPUT/fake-diff.png"
echo "[  PASSED  ] 2 tests."
echo "[  FAILED  ] 1 test, listed below:"
echo "[  FAILED  ] Fake.SeesTheUnpackedTree"
exit 1
FAKE
done
cat >"$stage/src/build/bin/rgraph_png_compare" <<'FAKE'
#!/usr/bin/env bash
echo "max difference 7 at 1,2 over 57600 pixels compared, 3 over tolerance $3"
exit 2
FAKE
cat >"$stage/src/build/bin/rgraph" <<'FAKE'
#!/usr/bin/env bash
[[ "$1" == render && -n "${FAKE_FRAME_DIFF:-}" ]] && echo changed >"${@: -1}" && exit 0
[[ "$1" == render && "$2" != --* ]] && echo "frame $2" >"${@: -1}" && exit 0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --stats) printf '{\n  "context": {\n    "egl_device": 0,\n    "platform": "egl-device",\n    "renderer": "Fake GPU",\n    "vendor": "Fake Vendor",\n    "version": "4.6 fake"\n  },\n  "frames": 1\n}\n' >"$2"; shift ;;
    --out) out=$2; shift ;;
    bench) bench=1 ;;
  esac
  shift
done
if [[ -n "${bench:-}" ]]; then
  printf '| method | ms |\n| --- | ---: |\n| fake | 1.5 |\n' >"$out/figures.md"
  echo "rgraph bench: 1 points, 0 aa rows in 0 s on Fake GPU (--quick)"
fi
FAKE
chmod +x "$stage/src/build/bin/"*
tar -C "$stage" -czf "$tmp/pack/rgraph-gpucheck.tar.gz" .

check() {  # CASE [VAR=VALUE...]: a run that must pass
  local name=$1
  shift
  rm -rf "$tmp/out"
  env "$@" bash "$src/scripts/gpu-check.sh" --from "$tmp/pack" --out "$tmp/out" --jobs 2 \
    >"$tmp/log" 2>&1 || fail "$name: exit $? ($(tail -n 3 "$tmp/log"))"
  [[ $(grep -c '| pass |$' "$tmp/out/report.md") == "${#GPUCHECK_SUITES[@]}" ]] ||
    fail "$name: not ${#GPUCHECK_SUITES[@]} passing suites"
  grep -q 'GL_VENDOR: Fake Vendor' "$tmp/out/report.md" || fail "$name: GL_VENDOR not read from --stats JSON"
  grep -q '^| fake | 1.5 |$' "$tmp/out/report.md" || fail "$name: no bench table"
  [[ -n "${FAKE_FRAME_DIFF:-}" ]] || grep -q ' same 2; within 0; over 0;' "$tmp/out/report.md" ||
    fail "$name: the reference frames are not the same"
  tar -tzf "$tmp/out/details.tar.gz" >"$tmp/list" && grep -q 'suites/tiled/log.txt' "$tmp/list" || fail "$name: details.tar.gz lacks the logs"
}

check "free path"
[[ ! -e "$root" && ! -L "$root" ]] || fail "free path: the link was left behind"

mkdir -p "$root/tests"
echo real >"$root/tests/marker.txt"
check "existing folder"
[[ "$(cat "$root/tests/marker.txt")" == real ]] || fail "existing folder: the checkout changed"

grep -q 'mount namespace' "$tmp/log" || fail "existing folder: no mount namespace"

check "move aside" GPUCHECK_NO_NAMESPACE=1
grep -q 'moving .* aside' "$tmp/log" || fail "move aside: the fallback did not run"
[[ -d "$root" && ! -L "$root" && "$(cat "$root/tests/marker.txt")" == real ]] || fail "move aside: the folder was not put back"
[[ ! -e "$root.gpucheck-aside" ]] || fail "move aside: the aside copy is left"

rm -rf "$tmp/out"
if FAKE_FAIL=1 bash "$src/scripts/gpu-check.sh" --from "$tmp/pack" --out "$tmp/out" >"$tmp/log" 2>&1; then
  fail "a failing suite, yet exit 0"
fi
grep -q '^| tiled | .* | 2 | 1 | 0 | .* | FAIL (exit 1) |$' "$tmp/out/report.md" || fail "tiled's failure is not in its row"
grep -q '^- tiled: fake-diff.png$' "$tmp/out/report.md" || fail "the saved image is not listed"
tar -tzf "$tmp/out/details.tar.gz" >"$tmp/list" && grep -q 'suites/tiled/images/fake-diff.png' "$tmp/list" || fail "the image is not in details.tar.gz"
# A frame that differs from llvmpipe's: listed with both images; not a failure
# (a GPU's frames differ from llvmpipe's in the last bits).
FAKE_FRAME_DIFF=1 check "frame differs"
grep -q '^| fake@learnopengl | over | max difference 7 at 1,2 ' "$tmp/out/report.md" || fail "the differing frame is not listed"
grep -q '^- frames: fake@learnopengl.llvmpipe.png$' "$tmp/out/report.md" || fail "llvmpipe's frame is not listed"
grep -q '^- frames: fake@learnopengl.here.png$' "$tmp/out/report.md" || fail "this machine's frame is not listed"
echo "gpu-check run: ok"
