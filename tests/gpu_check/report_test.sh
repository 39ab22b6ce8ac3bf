#!/usr/bin/env bash
# scripts/gpu-check.sh --report on canned results (no GL, no build): every
# suite gets its row with the counts from its gtest log, failures and skips
# are named, saved images and the bench's tables are listed, and the verdict
# follows. Usage: report_test.sh SOURCE_DIR
set -euo pipefail
src=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
r=$tmp/results
fail() { echo "FAIL: $*" >&2; echo "--- report:" >&2; cat "$tmp/report.md" >&2; exit 1; }

# gtest's closing lines, as 1.12 prints them.
gtest_log() {  # PASSED FAILED SKIPPED [FAILED_NAME] [SKIPPED_NAME]
  local ran=$(($1 + $2 + $3))
  echo "[----------] Global test environment tear-down"
  echo "[==========] $ran tests from 3 test suites ran. (1234 ms total)"
  echo "[  PASSED  ] $1 tests."
  if (($3)); then echo "[  SKIPPED ] $3 test, listed below:"; echo "[  SKIPPED ] ${5:-X.Skipped}"; fi
  if (($2)); then echo "[  FAILED  ] $2 test, listed below:"; echo "[  FAILED  ] ${4:-X.Failed}"; echo; echo " $2 FAILED TEST"; fi
}
make_results() {  # BROKEN: 1 = one failing suite, one crashed suite, an image
  rm -rf "$r"
  mkdir -p "$r"
  echo "GL_VENDOR: Canned Vendor" >"$r/machine.txt"
  echo "GL_RENDERER: Canned GPU 9000" >>"$r/machine.txt"
  local names=(render clustered oracle tiled aa stability plugin) i=0 n
  for n in "${names[@]}"; do
    i=$((i + 1))
    echo "$n rgraph_${n}_tests *" >>"$r/suites.list"
    mkdir -p "$r/suites/$n/images"
    gtest_log $((10 + i)) 0 0 >"$r/suites/$n/log.txt"
    echo 0 >"$r/suites/$n/exit"
    echo $i >"$r/suites/$n/seconds"
  done
  if [[ $1 == 1 ]]; then
    gtest_log 40 1 1 TiledDeferred.MatchesFullscreen TiledDeferred.NeedsThing >"$r/suites/tiled/log.txt"
    echo 1 >"$r/suites/tiled/exit"
    : >"$r/suites/tiled/images/tiled-256-lit.png"
    echo "[ RUN      ] Stability.Boom" >"$r/suites/stability/log.txt"
    echo 139 >"$r/suites/stability/exit"
    mkdir -p "$r/frames/images"
    {
      echo "default@learnopengl same "
      echo "deferred-taa@learnopengl over max difference 9 at 3,4 over 57600 pixels compared, 12 over tolerance 1"
      echo "forward@many-lights_64 refused-here error: cannot create the GL context"
      echo "compact@many-lights_64 refused-both error: needs thing"
    } >"$r/frames/list.txt"
    : >"$r/frames/images/deferred-taa@learnopengl.here.png"
    echo 5 >"$r/frames/seconds"
  fi
  mkdir -p "$r/bench"
  printf 'rgraph bench: 42 points, 6 aa rows in 88 s on Canned GPU 9000 (--quick)\n' >"$r/bench/log.txt"
  printf '| method | lights | frame ms |\n| --- | ---: | ---: |\n| tiled | 1024 | 0.25 |\n' >"$r/bench/figures.md"
  {
    echo "axes,method,lights,width,height,median_ms,status"
    echo "lights,tiled,64,640,360,0.5,ok"
    echo "lights;threshold,tiled,256,640,360,0.75,ok"
    echo "lights,clustered,64,640,360,0.4,ok"
    echo "threshold,tiled,1024,640,360,9.9,ok"
    echo "lights,clustered,256,640,360,0,failed"
  } >"$r/bench/results.csv"
  echo 0 >"$r/bench/exit"
  echo 88 >"$r/bench/seconds"
}

make_results 0
bash "$src/scripts/gpu-check.sh" --report "$r" "$tmp/report.md"
for n in render clustered oracle tiled aa stability plugin; do
  grep -q "^| $n | \`rgraph_${n}_tests" "$tmp/report.md" || fail "no row for suite $n"
done
grep -q '^| oracle | .* | 13 | 0 | 0 | 3 s | pass |$' "$tmp/report.md" || fail "oracle's row lacks its counts"
grep -q 'GL_RENDERER: Canned GPU 9000' "$tmp/report.md" || fail "no GL strings"
grep -q '^| tiled | 1024 | 0.25 |$' "$tmp/report.md" || fail "the bench's table is missing"
grep -q '^rgraph bench: 42 points' <(sed 's/^    //' "$tmp/report.md") || fail "the bench's summary is missing"
grep -q '^| method | 64 | 256 |$' "$tmp/report.md" || fail "the frame-time table's light counts are wrong"
grep -q '^| tiled | 0.50 | 0.75 |$' "$tmp/report.md" || fail "tiled's frame times are wrong"
grep -q '^| clustered | 0.40 |  |$' "$tmp/report.md" || fail "clustered's frame times are wrong (a failed point shows)"
grep -q '^GPUCHECK_VERDICT=pass$' "$r/verdict.env" || fail "all passed, verdict not pass"
grep -q '^None\.$' "$tmp/report.md" || fail "no images, yet not 'None.'"

make_results 1
bash "$src/scripts/gpu-check.sh" --report "$r" "$tmp/report.md"
grep -q '^| tiled | .* | 40 | 1 | 1 | 4 s | FAIL (exit 1) |$' "$tmp/report.md" || fail "tiled's failure is not counted"
grep -q '^- TiledDeferred.MatchesFullscreen$' "$tmp/report.md" || fail "the failing test is not named"
grep -q '^- TiledDeferred.NeedsThing$' "$tmp/report.md" || fail "the skipped test is not named"
grep -q '^| stability | .* | no summary (exit 139) |$' "$tmp/report.md" || fail "the crash is not reported"
grep -q '^- tiled: tiled-256-lit.png$' "$tmp/report.md" || fail "the saved image is not listed"
grep -q '^| deferred-taa@learnopengl | over | max difference 9 at 3,4 .*|$' "$tmp/report.md" || fail "the frame over tolerance is not listed"
grep -q '^| forward@many-lights_64 | refused-here | error: cannot create the GL context |$' "$tmp/report.md" ||
  fail "the frame refused here is not listed"
grep -q ' same 1; within 0; over 1; refused-both 1; refused-here 1; only-here 0;$' "$tmp/report.md" || fail "the frame counts are wrong"
grep -q '^- frames: deferred-taa@learnopengl.here.png$' "$tmp/report.md" || fail "the frame's image is not listed"
grep -q '^3 of the checks (suites, frames, bench) did not pass' "$tmp/report.md" || fail "a frame refused here is not a failure"
grep -q '^GPUCHECK_VERDICT=fail$' "$r/verdict.env" || fail "a failure, yet the verdict is not fail"
echo "gpu-check report: ok"
