#!/usr/bin/env bash
# rgraph's GPU check: the image suites and `rgraph bench --quick` on a bare
# machine with a GPU (no compiler, no package registry), one report.
# Here:  scripts/gpu-check.sh --pack DIR        (carried folder from ./build)
# There: scripts/gpu-check.sh --from DIR --out OUTDIR
# docs/gpu-check.md says why it is built this way; --help says what it needs.
set -euo pipefail

gpucheck_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/gpu-check
# shellcheck source=gpu-check/common.sh
source "$gpucheck_dir/common.sh"

usage() {
  cat <<'EOF'
usage: scripts/gpu-check.sh --pack DIR [--build BUILD]
       scripts/gpu-check.sh --from DIR --out OUTDIR [--jobs N] [--suites a,b] [--no-bench]
       scripts/gpu-check.sh --report RESULTS OUTFILE
       scripts/gpu-check.sh --help

Runs the render, clustered, oracle, tiled, aa, stability, plugin, stalls
and gl_calls test suites and `rgraph bench --quick` on a machine with a GPU that has no
compiler and no package registry, and writes one report: the GL strings,
each suite's passed/failed/skipped counts, the bench's tables, every image a
test saved because it differed beyond the test's tolerance, and the shipped
pipelines' frames that differ from llvmpipe's (rendered by --pack here) by
more than 1/255.

--pack DIR     (here, after building) writes DIR/rgraph-gpucheck.tar.gz and
               DIR/scripts/: the build's programs, librgraph and plugins
               (strip --strip-debug copies), the tracked source files the
               tests read, ../shared/assets, the reference frames (every
               pipelines/ file on learnopengl and many-lights:64, 320x180,
               rendered here), and the shared libraries the
               programs link that are not glibc, taken from this machine's
               Debian packages with `apt-get download` + `dpkg -x` (the list
               comes from ldd + dpkg -S; the GL/EGL loaders libegl1
               libglvnd0 libopengl0 libgl1 libglx0 always; never Mesa's
               vendor libraries). Fails if DIR plus the repo's tracked files
               exceed 64 MiB. Needs: a configured and built BUILD (default
               ./build: targets rgraph_cli rgraph_render_tests
               rgraph_oracle_tests rgraph_tiled_tests rgraph_aa_tests
               rgraph_stability_tests rgraph_plugin_tests rgraph_stall_tests
               rgraph_gl_calls_tests rgraph_png_compare),
               git, dpkg, apt-get.
--from DIR     (there) unpacks DIR's archive under /tmp, makes the source
               path the tests were built with (see docs/gpu-check.md) point at
               it, sets LD_LIBRARY_PATH, __EGL_VENDOR_LIBRARY_FILENAMES (the
               NVIDIA vendor file, when /usr/local/nvidia has one), the cache
               and temp folders itself, runs the suites and the bench, and
               writes OUTDIR/report.md and OUTDIR/details.tar.gz (logs,
               gtest XML, the bench's files, the saved images). Needs bash,
               coreutils, tar, gzip; root, or a free source path.
               Exit 0 only when every suite and the bench passed.
--jobs N       suites run N at a time (default: 1 on 4 cores or fewer, else 4);
               the bench always runs alone, after them.
--suites LIST  only these suites (comma-separated names from the list above).
--no-bench     skip `rgraph bench --quick`.
--report R F   writes the report F from a results folder R (what --from
               leaves in its work folder; for tests of the report).

Environment: GPUCHECK_SUITE_TIMEOUT, GPUCHECK_BENCH_TIMEOUT (seconds; 300
each on a GPU, 900 and 1200 on a software renderer), GPUCHECK_FRAME_TOLERANCE
(of 255, default 1), GPUCHECK_KEEP=1 keeps
the work folder under /tmp, __EGL_VENDOR_LIBRARY_FILENAMES (kept if set).

On a lent GPU machine with the device tool's `run` (repo root there):
  here:  cmake --build build -j2 --target rgraph_cli rgraph_render_tests \
           rgraph_oracle_tests rgraph_tiled_tests rgraph_aa_tests \
           rgraph_stability_tests rgraph_plugin_tests rgraph_png_compare
         scripts/gpu-check.sh --pack .gpucheck    (.gpucheck/ is git-ignored)
  run:   carry [".gpucheck"], timeout_s 600, command
           bash .gpucheck/scripts/gpu-check.sh --from .gpucheck --out $OUT
  The report comes back as report.md and details.tar.gz under files_at.
EOF
}

mode=""
dir=""
out=""
build=""
jobs=""
suites=""
bench=1
report_args=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    -h | --help) usage; exit 0 ;;
    --pack) mode=pack; dir=${2:?--pack needs a folder}; shift ;;
    --from) mode=run; dir=${2:?--from needs a folder}; shift ;;
    --out) out=${2:?--out needs a folder}; shift ;;
    --build) build=${2:?--build needs a folder}; shift ;;
    --jobs) jobs=${2:?--jobs needs a number}; shift ;;
    --suites) suites=${2:?--suites needs a list}; shift ;;
    --no-bench) bench=0 ;;
    --report) mode=report; report_args=("${2:?--report needs RESULTS OUTFILE}" "${3:?--report needs RESULTS OUTFILE}"); shift 2 ;;
    --in-namespace) mode=namespace; dir=${2:?}; shift ;;  # internal: run.sh re-enters here under unshare -m
    *) die "unknown argument '$1' (see --help)" ;;
  esac
  shift
done

case "$mode" in
  pack)
    source "$gpucheck_dir/pack.sh"
    pack_main "$dir" "${build:-$(cd "$gpucheck_dir/../.." && pwd)/build}"
    ;;
  run)
    [[ -n "$out" ]] || die "--from needs --out OUTDIR"
    [[ -z "$jobs" || "$jobs" =~ ^[1-9][0-9]*$ ]] || die "--jobs wants a positive number, not '$jobs'"
    source "$gpucheck_dir/run.sh"
    source "$gpucheck_dir/report.sh"
    run_main "$dir" "$out" "$jobs" "$suites" "$bench"
    ;;
  namespace)
    source "$gpucheck_dir/run.sh"
    run_in_namespace "$dir"
    ;;
  report)
    source "$gpucheck_dir/report.sh"
    write_report "${report_args[0]}" "${report_args[1]}"
    ;;
  *) usage >&2; exit 2 ;;
esac
