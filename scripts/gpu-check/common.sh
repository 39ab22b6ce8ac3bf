# shellcheck shell=bash disable=SC2034
# Shared by scripts/gpu-check.sh's parts (sourced, not run).

die() {
  echo "error: $*" >&2
  exit 1
}

note() { echo "gpu-check: $*" >&2; }

# The suites, in report order: name, gtest program under <build>/bin, filter.
# Clustered shading's tests live in the render program; they are split off
# by name so that each runs once.
GPUCHECK_SUITES=(
  "render rgraph_render_tests -*Clustered*:ForwardPlus*"
  "clustered rgraph_render_tests *Clustered*:ForwardPlus*"
  "oracle rgraph_oracle_tests *"
  "tiled rgraph_tiled_tests *"
  "aa rgraph_aa_tests *"
  "stability rgraph_stability_tests *"
  "plugin rgraph_plugin_tests *"
)

# The programs the suites need besides their own: the CLI (bench, GL
# strings; the plugin suite runs it too).
GPUCHECK_PROGRAMS=(rgraph)

# Names of the archive and of its manifest inside it.
GPUCHECK_ARCHIVE=rgraph-gpucheck.tar.gz
GPUCHECK_MANIFEST=manifest.env

# What may travel to the device (the device tool's limit), in bytes.
GPUCHECK_CARRY_LIMIT=$((64 * 1024 * 1024))

suite_programs() {
  local s name prog filter
  for s in "${GPUCHECK_SUITES[@]}"; do
    read -r name prog filter <<<"$s"
    echo "$prog"
  done | sort -u
}
