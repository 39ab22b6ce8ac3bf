# shellcheck shell=bash disable=SC2034
# The report of scripts/gpu-check.sh (sourced). Reads a results folder:
#   manifest.env, packages.txt, machine.txt (GL strings: run.sh's gl_strings)
#   suites.list                 NAME PROGRAM FILTER per line, in order
#   suites/NAME/{log.txt,exit,seconds,images/*.png}
#   frames/{list.txt,seconds,images/*.png}    (the reference frames; optional)
#   bench/{log.txt,exit,seconds,figures.md}   (absent with --no-bench)
# and writes markdown, plus RESULTS/verdict.env (GPUCHECK_VERDICT=pass|fail).

# "PASSED FAILED SKIPPED RAN" from a gtest log's closing lines; RAN is empty
# when the program never printed them (a crash, a timeout).
gtest_counts() {  # LOG
  awk '
    /^\[==========\] [0-9]+ tests? from .* ran\./ { ran = $2 }
    /^\[  PASSED  \] [0-9]+ test/ { passed = $4 }
    /^\[  SKIPPED \] [0-9]+ test/ { skipped = $4 }
    /^\[  FAILED  \] [0-9]+ test/ { failed = $4 }
    END { printf "%d %d %d %s\n", passed, failed, skipped, ran }' "$1"
}

# The names gtest lists after "N tests, listed below:" for KIND (FAILED, SKIPPED).
gtest_listed() {  # LOG KIND
  awk -v kind="$2" '
    $0 ~ "^\\[  " kind " *\\] [0-9]+ tests?, listed below:" { on = 1; next }
    on && $0 ~ "^\\[  " kind " *\\] [A-Za-z_0-9/.]+" { sub(/^\[[^]]*\] /, ""); print; next }
    on { on = 0 }' "$1"
}

# Median frame ms per method and light count: the points of results.csv on
# the bench's "lights" axis (one size), as a markdown table.
bench_time_table() {  # RESULTS_CSV
  awk -F, '
    NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    {
      n = split($col["axes"], axes, ";"); on = 0
      for (i = 1; i <= n; ++i) on = on || axes[i] == "lights"
      if (!on || $col["status"] != "ok") next
      m = $col["method"]; l = $col["lights"] + 0
      size = $col["width"] "x" $col["height"]
      if (!(m in seen)) { seen[m] = 1; methods[++nm] = m }
      if (!(l in lseen)) { lseen[l] = 1; lights[++nl] = l }
      if (!((m, l) in ms)) ms[m, l] = $col["median_ms"]
    }
    END {
      if (!nm) exit
      for (i = 1; i <= nl; ++i) for (j = i + 1; j <= nl; ++j) if (lights[j] < lights[i]) { t = lights[i]; lights[i] = lights[j]; lights[j] = t }
      printf "Median frame ms at %s by light count (results.csv, axis lights):\n\n| method |", size
      for (i = 1; i <= nl; ++i) printf " %d |", lights[i]
      printf "\n| --- |"; for (i = 1; i <= nl; ++i) printf " ---: |"; printf "\n"
      for (k = 1; k <= nm; ++k) {
        printf "| %s |", methods[k]
        for (i = 1; i <= nl; ++i) printf " %s |", ((methods[k], lights[i]) in ms) ? sprintf("%.2f", ms[methods[k], lights[i]]) : ""
        printf "\n"
      }
      printf "\n"
    }' "$1"
}

# The reference frames against llvmpipe's (run.sh's compare_frames). Fails
# when a frame llvmpipe rendered could not be rendered here.
frames_section() {  # RESULTS
  local list=$1/frames/list.txt st n
  [[ -f "$list" ]] || return 0
  echo "## Frames against llvmpipe's"
  echo
  echo -n "Every shipped pipeline on ${GPUCHECK_FRAME_SCENES[*]}, 320x180, against the same frames rendered on"
  echo " llvmpipe by --pack ($(cat "$1/frames/seconds" 2>/dev/null || echo '?') s):"
  for st in same within over refused-both refused-here only-here; do
    n=$(awk -v s="$st" '$2 == s' "$list" | wc -l)
    echo -n " $st $n;"
  done
  echo
  echo
  echo "over: a channel differs by more than the suites' tolerance (both PNGs in details.tar.gz under"
  echo "frames/images/); refused-here: llvmpipe rendered it, this machine did not."
  echo
  if awk '$2 == "over" || $2 == "refused-here" || $2 == "only-here"' "$list" | grep -q .; then
    echo "| frame | status | detail |"
    echo "| --- | --- | --- |"
    awk '$2 == "over" || $2 == "refused-here" || $2 == "only-here" {
      d = $0; sub(/^[^ ]+ [^ ]+ ?/, "", d); gsub(/\|/, "/", d); printf "| %s | %s | %s |\n", $1, $2, d }' "$list"
    echo
  fi
  ! awk '$2 == "refused-here"' "$list" | grep -q .
}

suite_row() {  # RESULTS NAME PROGRAM FILTER
  local d=$1/suites/$2 rc seconds passed failed skipped ran status
  rc=$(cat "$d/exit" 2>/dev/null || echo "?")
  seconds=$(cat "$d/seconds" 2>/dev/null || echo "?")
  read -r passed failed skipped ran < <(gtest_counts "$d/log.txt" 2>/dev/null || echo "0 0 0")
  if [[ -z "$ran" ]]; then
    case "$rc" in 124 | 137) status="timed out" ;; *) status="no summary (exit $rc)" ;; esac
  elif [[ "$rc" == 0 && "$failed" == 0 ]]; then
    status=pass
  else
    status="FAIL (exit $rc)"
  fi
  echo "| $2 | \`$3 --gtest_filter='$4'\` | $passed | $failed | $skipped | ${seconds} s | $status |"
  [[ "$status" == pass ]]
}

write_report() {  # RESULTS OUTFILE
  local r=$1 f=$2 name prog filter failed_suites=0 images=0 total_p=0 total_f=0 total_s=0 p x s ran img
  [[ -f "$r/suites.list" ]] || die "$r is not a gpu-check results folder (no suites.list)"
  {
    echo "# rgraph GPU check"
    echo
    echo "$(date -u '+%Y-%m-%d %H:%M UTC')."
    if [[ -f "$r/manifest.env" ]]; then
      echo "Packed from commit $(sed -n 's/^GPUCHECK_COMMIT=//p' "$r/manifest.env"), $(sed -n "s/^GPUCHECK_PACKED_AT='\\(.*\\)'/\\1/p" "$r/manifest.env")."
    fi
    echo
    echo "## Machine and GL strings"
    echo
    sed 's/^/    /' "$r/machine.txt" 2>/dev/null || echo "    (no machine.txt)"
    echo
    echo "## Suites"
    echo
    echo "| suite | program | passed | failed | skipped | time | status |"
    echo "| --- | --- | ---: | ---: | ---: | ---: | --- |"
    while read -r name prog filter; do
      suite_row "$r" "$name" "$prog" "$filter" || failed_suites=$((failed_suites + 1))
      read -r p x s ran < <(gtest_counts "$r/suites/$name/log.txt" 2>/dev/null || echo "0 0 0")
      total_p=$((total_p + p)) total_f=$((total_f + x)) total_s=$((total_s + s))
    done <"$r/suites.list"
    echo
    while read -r name prog filter; do
      local log=$r/suites/$name/log.txt listed
      listed=$(gtest_listed "$log" FAILED 2>/dev/null)
      [[ -n "$listed" ]] && { echo "Failed in $name:"; echo; sed 's/^/- /' <<<"$listed"; echo; }
      listed=$(gtest_listed "$log" SKIPPED 2>/dev/null)
      [[ -n "$listed" ]] && { echo "Skipped in $name:"; echo; sed 's/^/- /' <<<"$listed"; echo; }
      if [[ -f "$log" && -z "$(gtest_counts "$log" | cut -d' ' -f4)" ]]; then
        echo "Last lines of $name's log:"; echo; tail -n 15 "$log" | sed 's/^/    /'; echo
      fi
    done <"$r/suites.list"

    echo "## Images that differ beyond the tests' tolerances"
    echo
    echo "Saved by failing tests (details.tar.gz: suites/SUITE/images/), and both sides of each reference"
    echo "frame over the tolerance (frames/images/: NAME.llvmpipe.png, NAME.here.png)."
    echo
    while read -r name prog filter; do
      for img in "$r/suites/$name/images"/*.png; do
        [[ -f "$img" ]] || continue
        echo "- $name: $(basename "$img")"
        images=$((images + 1))
      done
    done <"$r/suites.list"
    for img in "$r/frames/images"/*.png; do
      [[ -f "$img" ]] || continue
      echo "- frames: $(basename "$img")"
      images=$((images + 1))
    done
    ((images > 0)) || echo "None."
    echo

    frames_section "$r" || failed_suites=$((failed_suites + 1))

    echo "## rgraph bench --quick"
    echo
    if [[ ! -d "$r/bench" ]]; then
      echo "Not run (--no-bench)."
    else
      echo "Exit $(cat "$r/bench/exit" 2>/dev/null || echo '?') in $(cat "$r/bench/seconds" 2>/dev/null || echo '?') s."
      echo
      sed -n '/^rgraph bench:/,$p' "$r/bench/log.txt" 2>/dev/null | sed 's/^/    /'
      echo
      [[ -f "$r/bench/results.csv" ]] && bench_time_table "$r/bench/results.csv"
      if [[ -f "$r/bench/figures.md" ]]; then
        cat "$r/bench/figures.md"
      else
        echo "No figures.md; the log ends:"; echo; tail -n 20 "$r/bench/log.txt" 2>/dev/null | sed 's/^/    /'
      fi
      [[ "$(cat "$r/bench/exit" 2>/dev/null)" == 0 && -f "$r/bench/figures.md" ]] || failed_suites=$((failed_suites + 1))
    fi
    echo
    echo "## Verdict"
    echo
    echo "$total_p passed, $total_f failed, $total_s skipped"
    echo "$failed_suites of the checks (suites, frames, bench) did not pass; $images images saved."
  } >"$f"
  echo "GPUCHECK_VERDICT=$( ((failed_suites == 0)) && echo pass || echo fail)" >"$r/verdict.env"
}
