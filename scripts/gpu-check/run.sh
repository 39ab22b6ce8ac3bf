# shellcheck shell=bash disable=SC2034
# scripts/gpu-check.sh --from DIR --out OUTDIR: the check itself (sourced).
#
# The programs carry absolute paths from the machine that built them (the
# source root in RGRAPH_SOURCE_DIR and friends, the build's lib/ in their
# RUNPATH). The archive keeps that layout, so once the source root leads to
# the unpacked copy everything resolves as it did there: a symbolic link
# where the path is free (a bare machine), else a bind mount in a private
# mount namespace (`unshare -m`, root), which also serves a dry run on the
# machine that packed it, where the path is the real checkout; where neither
# works (a sandbox without mount namespaces), root moves the folder aside for
# the run and puts it back.

# Seconds each suite and the bench may take before they are stopped (the
# whole check has 8 minutes on the device; one hung suite must not eat it).
# A software renderer (a dry run on llvmpipe) gets the second figure: its
# bench --quick alone takes 5-6 minutes on 2 cores.
GPUCHECK_TIMEOUTS_GPU="300 300"
GPUCHECK_TIMEOUTS_SOFTWARE="900 1200"
GPUCHECK_SOFTWARE_RE='llvmpipe|softpipe|SwiftShader|software'
# Largest channel difference (of 255) a reference frame may have against
# llvmpipe's before the report shows both: the suites' own image tolerance.
GPUCHECK_FRAME_TOLERANCE=${GPUCHECK_FRAME_TOLERANCE:-1}
GPUCHECK_NVIDIA_EGL_VENDOR=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json

run_main() {  # DIR OUT JOBS SUITES BENCH
  local dir out work root status=0
  dir=$(cd "$1" 2>/dev/null && pwd) || die "no folder '$1' (make it with --pack)"
  [[ -f "$dir/$GPUCHECK_ARCHIVE" ]] || die "$dir has no $GPUCHECK_ARCHIVE (make it with --pack)"
  mkdir -p "$2" && out=$(cd "$2" && pwd)
  work=$(mktemp -d /tmp/rgraph-gpucheck.XXXXXX)
  GPUCHECK_WORK=$work
  trap 'gpucheck_cleanup' EXIT
  trap 'exit 130' INT TERM
  local t0=$SECONDS
  tar -xzf "$dir/$GPUCHECK_ARCHIVE" -C "$work" || die "cannot unpack $dir/$GPUCHECK_ARCHIVE"
  # shellcheck disable=SC1090
  source "$work/$GPUCHECK_MANIFEST"
  printf 'GPUCHECK_JOBS=%q\nGPUCHECK_ONLY=%q\nGPUCHECK_BENCH=%q\n' "$3" "$4" "$5" >"$work/options.env"
  root=$GPUCHECK_SOURCE_ROOT
  note "unpacked in $((SECONDS - t0)) s into $work; the tests' source root is $root"

  if [[ ! -e "$root" && ! -L "$root" ]] || stale_link "$root"; then
    link_root "$root" "$work"
    run_checks "$work" || status=$?
  else
    if [[ -z "${GPUCHECK_NO_NAMESPACE:-}" ]]; then  # set: try the fallback below (tests)
      note "$root exists: running in a private mount namespace with the unpacked tree mounted over it"
      unshare -m bash "$gpucheck_dir/../gpu-check.sh" --in-namespace "$work" || status=$?
    fi
    if [[ ! -f "$work/namespace-entered" ]]; then
      # No mount namespace here (no unshare, no CAP_SYS_ADMIN, a sandbox
      # without them): move the folder aside for the run; gpucheck_cleanup
      # puts it back, also when the check is stopped.
      [[ "$(id -u)" == 0 ]] || die "cannot mount over $root, and only root may move it aside: pack from a build whose source path is free there"
      note "no mount namespace: moving $root aside to $root.gpucheck-aside for the run"
      mv "$root" "$root.gpucheck-aside" || die "cannot move $root aside"
      GPUCHECK_ASIDE=$root
      link_root "$root" "$work"
      status=0
      run_checks "$work" || status=$?
    fi
  fi
  gpucheck_restore_root
  [[ -f "$work/results/done" ]] || die "the check stopped before it finished (exit $status); partial results in $work"
  write_report "$work/results" "$out/report.md"
  tar -C "$work/results" -czf "$out/details.tar.gz" .
  note "report: $out/report.md; logs, bench files, images: $out/details.tar.gz ($((SECONDS - t0)) s in all)"
  grep -q '^GPUCHECK_VERDICT=pass$' "$work/results/verdict.env"
}

# A link left by an earlier run (its target, an unpacked copy, is gone or is ours).
stale_link() {
  [[ -L "$1" ]] && [[ "$(readlink "$1")" == /tmp/rgraph-gpucheck.*/src ]]
}

link_root() {  # ROOT WORK
  mkdir -p "$(dirname "$1")"
  ln -sfn "$2/src" "$1"
  GPUCHECK_LINK=$1
}

# The source path as it was: our link removed, a folder moved aside back.
gpucheck_restore_root() {
  if [[ -n "${GPUCHECK_LINK:-}" && -L "$GPUCHECK_LINK" ]]; then rm -f "$GPUCHECK_LINK"; fi
  GPUCHECK_LINK=
  if [[ -n "${GPUCHECK_ASIDE:-}" && ! -e "$GPUCHECK_ASIDE" ]]; then mv "$GPUCHECK_ASIDE.gpucheck-aside" "$GPUCHECK_ASIDE"; fi
  GPUCHECK_ASIDE=
}

gpucheck_cleanup() {
  gpucheck_restore_root
  [[ -n "${GPUCHECK_WORK:-}" && -z "${GPUCHECK_KEEP:-}" ]] && rm -rf "$GPUCHECK_WORK"
  return 0
}

# Under unshare -m: the unpacked tree (and its ../shared) mounted over the
# source root, then the checks. The mounts end with this process.
run_in_namespace() {  # WORK
  local work=$1 root shared
  # shellcheck disable=SC1090
  source "$work/$GPUCHECK_MANIFEST"
  root=$GPUCHECK_SOURCE_ROOT
  mount --make-rprivate / 2>/dev/null || true
  mount --bind "$work/src" "$root" 2>/dev/null || exit 3  # the caller moves the folder aside instead
  touch "$work/namespace-entered"
  shared=$(dirname "$root")/shared
  if [[ -d "$work/shared" ]]; then
    mkdir -p "$shared"
    mount --bind "$work/shared" "$shared" || die "cannot mount $work/shared over $shared"
  fi
  run_checks "$work"
}

# The environment of the programs: the carried libraries first, the GPU
# vendor's EGL, caches and temporary files inside the work folder.
check_environment() {  # WORK
  local work=$1 libs=$1/lib d
  # Ours only where the machine has none: see GPUCHECK_BASE_PACKAGES_RE.
  if ! ldconfig -p 2>/dev/null | grep -q 'libstdc++\.so\.6 '; then libs=$libs:$work/lib-base; fi
  for d in /usr/local/nvidia/lib64 /usr/local/nvidia/lib; do [[ -d "$d" ]] && libs=$libs:$d; done
  export LD_LIBRARY_PATH=$libs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
  if [[ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" && -f "$GPUCHECK_NVIDIA_EGL_VENDOR" ]]; then
    export __EGL_VENDOR_LIBRARY_FILENAMES=$GPUCHECK_NVIDIA_EGL_VENDOR
  fi
  mkdir -p "$work/home" "$work/cache/xdg"
  export HOME=$work/home RGRAPH_CACHE_DIR=$work/cache/rgraph XDG_CACHE_HOME=$work/cache/xdg
}

# GL_VENDOR / GL_RENDERER / GL_VERSION of the context the suites get, as
# "KEY: value" lines, with the EGL platform and device: the "context" object
# of `rgraph render --stats` JSON (vendor, renderer, version, platform,
# egl_device, egl_device_description).
gl_strings() {  # BIN TMP
  local bin=$1 tmp=$2 key value context
  mkdir -p "$tmp"
  "$bin/rgraph" --log-level debug render --width 64 --height 64 --out "$tmp/frame.png" \
    --stats "$tmp/stats.json" >"$tmp/render.log" 2>&1 || echo "(rgraph render failed: $(tail -n 1 "$tmp/render.log"))"
  # The stats file's "context" object (rgraph render --stats; one key a line).
  context=$(sed -n '/"context": {/,/}/p' "$tmp/stats.json" 2>/dev/null || true)
  for key in vendor renderer version platform egl_device egl_device_description; do
    value=$(grep -m1 "^ *\"$key\":" <<<"$context" | sed -e 's/,$//' -e "s/^ *\"$key\": *//" -e 's/^"\(.*\)"$/\1/' || true)
    case $key in
      vendor | renderer | version) echo "GL_${key^^}: ${value:-(not in the stats file)}" ;;
      platform) echo "EGL platform: ${value:-(not in the stats file)}" ;;
      egl_device) echo "EGL device: ${value:-(none)}" ;;
      egl_device_description) [[ -z "$value" || "$value" == null ]] || echo "EGL device description: $value" ;;
    esac
  done
}

# One suite: its log, gtest XML, exit status, seconds, and the PNGs its tests
# saved (render_util's saveImage under RGRAPH_TEST_OUTPUT, the stability
# tests' stability-output/ in the working folder: both only on a failure).
run_suite() {  # WORK NAME PROGRAM FILTER
  local work=$1 name=$2 prog=$3 filter=$4 res=$1/results/suites/$2 t0=$SECONDS rc=0
  mkdir -p "$res/run" "$work/tmp/$name"
  (cd "$res/run" && TMPDIR=$work/tmp/$name RGRAPH_TEST_OUTPUT=$res/run/images \
    timeout -k 10 "$GPUCHECK_SUITE_TIMEOUT" "$GPUCHECK_SOURCE_ROOT/$GPUCHECK_BUILD_REL/bin/$prog" \
    --gtest_filter="$filter" --gtest_output="xml:$res/gtest.xml" >"$res/log.txt" 2>&1) || rc=$?
  echo "$rc" >"$res/exit"
  echo "$((SECONDS - t0))" >"$res/seconds"
  mkdir -p "$res/images"
  find "$res/run" -name '*.png' -exec mv {} "$res/images/" \;
  rm -rf "$res/run" "$work/tmp/$name"
  note "$name: exit $rc in $((SECONDS - t0)) s"
}

# The reference frames rendered here against the packed ones: results/frames/
# list.txt ("NAME STATUS DETAIL": same, within, over, refused-here,
# refused-both, only-here), and both PNGs of each frame over the tolerance.
compare_frames() {  # WORK BIN
  local work=$1 bin=$2 res=$1/results/frames name pipeline scene ref status detail t0=$SECONDS
  mkdir -p "$res/images" "$work/tmp/frames"
  : >"$res/list.txt"
  while read -r name pipeline scene; do
    ref=$work/frames/$name
    render_frame "$bin/rgraph" "$GPUCHECK_SOURCE_ROOT" "$pipeline" "$scene" "$work/tmp/frames/$name"
    local here=$work/tmp/frames/$name
    if [[ -f "$ref.refused" && -f "$here.refused" ]]; then
      status=refused-both detail=$(head -n 1 "$here.refused")
    elif [[ -f "$here.refused" ]]; then
      status=refused-here detail=$(head -n 1 "$here.refused")
    elif [[ -f "$ref.refused" ]]; then
      status=only-here detail=$(head -n 1 "$ref.refused")
    elif cmp -s "$ref.png" "$here.png"; then
      status=same detail=
    else
      detail=$("$bin/rgraph_png_compare" "$ref.png" "$here.png" "$GPUCHECK_FRAME_TOLERANCE" 2>&1) && status=within || status=over
      if [[ $status == over ]]; then
        cp "$ref.png" "$res/images/$name.llvmpipe.png"
        cp "$here.png" "$res/images/$name.here.png"
      fi
    fi
    echo "$name $status ${detail//$'\n'/ }" >>"$res/list.txt"
  done < <(reference_frames "$work/src")
  echo "$((SECONDS - t0))" >"$res/seconds"
  rm -rf "$work/tmp/frames"
  note "frames: $(grep -c ' over ' "$res/list.txt" || true) of $(wc -l <"$res/list.txt") over $GPUCHECK_FRAME_TOLERANCE/255 in $((SECONDS - t0)) s"
}

run_checks() {  # WORK
  local work=$1 results=$1/results bin s name prog filter jobs running=0
  # shellcheck disable=SC1090
  source "$work/options.env"
  source "$work/$GPUCHECK_MANIFEST"
  # Through the source path, not the unpacked one: the programs find their
  # plugins from /proc/self/exe, and the tests expect the compiled-in folder.
  bin=$GPUCHECK_SOURCE_ROOT/$GPUCHECK_BUILD_REL/bin
  check_environment "$work"
  mkdir -p "$results"
  cp "$work/$GPUCHECK_MANIFEST" "$work/packages.txt" "$results/"
  {
    echo "host: $(uname -n), $(nproc) cores, $(uname -m)"
    command -v nvidia-smi >/dev/null &&
      nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>/dev/null | sed 's/^/GPU: /'
    echo "LD_LIBRARY_PATH: $LD_LIBRARY_PATH"
    echo "__EGL_VENDOR_LIBRARY_FILENAMES: ${__EGL_VENDOR_LIBRARY_FILENAMES:-(unset: the glvnd default folders)}"
    gl_strings "$bin" "$work/tmp/gl"
  } >"$results/machine.txt"
  sed 's/^/  /' "$results/machine.txt" >&2
  local timeouts=$GPUCHECK_TIMEOUTS_GPU
  grep -Eq "^GL_RENDERER: .*($GPUCHECK_SOFTWARE_RE)" "$results/machine.txt" && timeouts=$GPUCHECK_TIMEOUTS_SOFTWARE
  GPUCHECK_SUITE_TIMEOUT=${GPUCHECK_SUITE_TIMEOUT:-${timeouts% *}}
  GPUCHECK_BENCH_TIMEOUT=${GPUCHECK_BENCH_TIMEOUT:-${timeouts#* }}
  echo "timeouts: ${GPUCHECK_SUITE_TIMEOUT} s a suite, ${GPUCHECK_BENCH_TIMEOUT} s the bench" >>"$results/machine.txt"

  jobs=${GPUCHECK_JOBS:-$(($(nproc) > 4 ? 4 : 1))}
  : >"$results/suites.list"
  for s in "${GPUCHECK_SUITES[@]}"; do
    read -r name prog filter <<<"$s"
    [[ -z "$GPUCHECK_ONLY" || ",$GPUCHECK_ONLY," == *",$name,"* ]] || continue
    echo "$name $prog $filter" >>"$results/suites.list"
    run_suite "$work" "$name" "$prog" "$filter" &
    running=$((running + 1))
    if ((running >= jobs)); then wait -n || true; running=$((running - 1)); fi
  done
  wait
  [[ -s "$results/suites.list" ]] || die "--suites '$GPUCHECK_ONLY' names no suite (see --help)"

  [[ -d "$work/frames" ]] && compare_frames "$work" "$bin"

  if [[ "$GPUCHECK_BENCH" == 1 ]]; then
    local t0=$SECONDS rc=0
    mkdir -p "$results/bench"
    (cd "$work/tmp" && timeout -k 10 "$GPUCHECK_BENCH_TIMEOUT" "$bin/rgraph" bench --quick \
      --out "$results/bench" >"$results/bench/log.txt" 2>&1) || rc=$?
    echo "$rc" >"$results/bench/exit"
    echo "$((SECONDS - t0))" >"$results/bench/seconds"
    note "bench: exit $rc in $((SECONDS - t0)) s"
  fi
  touch "$results/done"
}
