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
  "stalls rgraph_stall_tests *"
  "gl_calls rgraph_gl_calls_tests *"
)

# The programs the suites need besides their own: the CLI (bench, GL
# strings, the reference frames; the plugin suite runs it too) and the PNG
# comparer (tests/embed/tools/png_compare.cpp).
GPUCHECK_PROGRAMS=(rgraph rgraph_png_compare)

# Reference frames: every shipped pipeline on these scenes at 320x180,
# rendered on llvmpipe by --pack and again on the device, then compared.
# The suites compare methods with each other on one GL implementation; these
# frames show what differs between implementations.
GPUCHECK_FRAME_SCENES=(learnopengl many-lights:64)
GPUCHECK_FRAME_SIZE=(--width 320 --height 180)

# "NAME PIPELINE SCENE" per reference frame; SRC is the source root.
reference_frames() {  # SRC
  local p scene
  for p in "$1"/pipelines/*.json "$1"/pipelines/examples/*.json; do
    [[ -f "$p" ]] || continue  # a pattern that matched nothing
    for scene in "${GPUCHECK_FRAME_SCENES[@]}"; do
      echo "$(basename "$p" .json)@${scene//:/_} ${p#"$1"/} $scene"
    done
  done
}

# Renders one reference frame: OUT.png, or OUT.refused with the message.
render_frame() {  # RGRAPH SRC PIPELINE SCENE OUT
  if (cd "$2" && "$1" render "$3" --scene "$4" "${GPUCHECK_FRAME_SIZE[@]}" --out "$5.png" >/dev/null 2>"$5.err"); then
    rm -f "$5.err"
  else
    mv "$5.err" "$5.refused"
  fi
}

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
