# shellcheck shell=bash disable=SC2034
# scripts/gpu-check.sh --pack DIR: the carried folder (sourced, not run).
#
# The test programs find their data through paths compiled in from CMake
# (RGRAPH_SOURCE_DIR, RGRAPH_TEST_DATA_DIR, RGRAPH_CLI, the plugin fixture
# folder, ../shared/assets...). Instead of teaching every test another way,
# the archive keeps the build's own layout, source root and all, and
# run.sh makes that source path lead to the unpacked copy.

# Folders of the build tree the suites use at run time, besides bin/: the
# library and plugins (lib/, share/: their manifests and shaders), the plugin
# loader's fixtures and the broken-shader plugin's root.
GPUCHECK_BUILD_PARTS=(lib share tests/plugin/fixtures tests/plugin/broken-shader-root)

# Debian packages whose libraries a bare machine has or must not get from
# us: glibc (it must match the machine's loader) and Mesa's vendor
# libraries and what only they need (the GPU's vendor must win).
GPUCHECK_SKIP_PACKAGES_RE='^(libc6|libc6-.*|libegl-mesa0|libglx-mesa0|libgl1-mesa-dri|libglapi-mesa|libgbm1|mesa-.*)$'
# The GL/EGL loaders (glvnd): the NVIDIA driver brings only its vendor
# libraries, and our programs link the loaders, so they always travel.
GPUCHECK_LOADER_PACKAGES=(libegl1 libglvnd0 libopengl0 libgl1 libglx0)
# Libraries every distribution has; carried in lib-base/, which run.sh puts
# on LD_LIBRARY_PATH only when the machine lacks them (a newer system copy
# must not be shadowed by ours: the GPU driver's libraries may need it).
GPUCHECK_BASE_PACKAGES_RE='^(libstdc\+\+6|libgcc-s1)$'

is_elf() { [[ "$(head -c 4 "$1" 2>/dev/null | od -An -c | tr -d ' ')" == '177ELF' ]]; }

cmake_cache_value() {  # KEY BUILD
  sed -n "s/^$1:[A-Z]*=//p" "$2/CMakeCache.txt" | head -n 1
}

# Copies the build's files into STAGE/<path relative to the source root>,
# ELF files as strip --strip-debug copies (the build is -g1: ~380 MB).
pack_build_tree() {  # BUILD DEST
  local build=$1 dest=$2 prog part f rel
  mkdir -p "$dest/bin"
  for prog in "${GPUCHECK_PROGRAMS[@]}" $(suite_programs); do
    [[ -x "$build/bin/$prog" ]] || die "$build/bin/$prog is missing: build it first (see --help)"
    strip --strip-debug -o "$dest/bin/$prog" "$build/bin/$prog"
  done
  for part in "${GPUCHECK_BUILD_PARTS[@]}"; do
    [[ -d "$build/$part" ]] || die "$build/$part is missing: build the suites' targets first (see --help)"
    while IFS= read -r -d '' f; do
      rel=${f#"$build"/}
      mkdir -p "$dest/$(dirname "$rel")"
      if [[ -L "$f" ]]; then
        cp -P "$f" "$dest/$rel"
      elif is_elf "$f"; then
        strip --strip-debug -o "$dest/$rel" "$f"
      else
        cp -p "$f" "$dest/$rel"
      fi
    done < <(find "$build/$part" \( -type f -o -type l \) -not -path '*/CMakeFiles/*' -not -name '*.a' -print0)
  done
}

# The Debian packages that own the libraries FILES... link (ldd, recursively
# resolved), one per line, without the build's own libraries.
linked_packages() {
  local f lib real owner
  for f in "$@"; do ldd "$f" 2>/dev/null; done | awk '$2 == "=>" && $3 ~ /^\// {print $3}' | sort -u |
    while IFS= read -r lib; do
      real=$(readlink -f "$lib")
      owner=$(dpkg -S "$lib" 2>/dev/null || dpkg -S "$real" 2>/dev/null ||
              dpkg -S "/usr$real" 2>/dev/null || dpkg -S "${real#/usr}" 2>/dev/null || true)
      if [[ -z "$owner" ]]; then
        case "$real" in "$GPUCHECK_STAGE"/* | "$GPUCHECK_SRC"/*) continue ;; esac  # the build's own
        die "no Debian package owns $lib (linked by the build): install it from a package, or carry it by hand"
      fi
      echo "${owner%%:*}"
    done | sort -u
}

# The .deb of the installed version of PKG (arch as installed), from apt's
# cache or `apt-get download`.
fetch_deb() {  # PKG DEST
  local pkg=$1 dest=$2 ver arch deb
  ver=$(dpkg-query -W -f '${Version}' "$pkg" 2>/dev/null) || die "package $pkg is not installed here"
  arch=$(dpkg-query -W -f '${Architecture}' "$pkg")
  deb=/var/cache/apt/archives/${pkg}_${ver//:/%3a}_${arch}.deb
  if [[ -f "$deb" ]]; then
    cp "$deb" "$dest/"
  else
    # The installed version, else the archive's (a stable update that
    # replaced it keeps the ABI).
    (cd "$dest" && apt-get download -q "$pkg=$ver" >/dev/null 2>&1) ||
      (cd "$dest" && apt-get download -q "$pkg" >/dev/null 2>&1 && note "$pkg: $ver is gone from the archive; took its current version") ||
      die "cannot get $pkg $ver: apt-get download failed (apt-get update first?)"
  fi
}

# Shared libraries of the packages, extracted with dpkg -x: lib/ and
# lib-base/ of STAGE. Writes the package list to STAGE/packages.txt.
pack_libraries() {  # STAGE ELF...
  local stage=$1 pkg deb tmp dest
  shift
  tmp=$(mktemp -d)
  {
    printf '%s\n' "${GPUCHECK_LOADER_PACKAGES[@]}"
    linked_packages "$@"
  } | sort -u | grep -Ev "$GPUCHECK_SKIP_PACKAGES_RE" >"$tmp/packages"
  mkdir -p "$stage/lib" "$stage/lib-base" "$tmp/debs"
  while IFS= read -r pkg; do
    fetch_deb "$pkg" "$tmp/debs"
    deb=$(ls "$tmp/debs/${pkg}_"*.deb)
    rm -rf "$tmp/root" && dpkg -x "$deb" "$tmp/root"
    dest=$stage/lib
    [[ "$pkg" =~ $GPUCHECK_BASE_PACKAGES_RE ]] && dest=$stage/lib-base
    find "$tmp/root" \( -type f -o -type l \) -name '*.so*' -not -name '*.py' -path '*/lib/*' -not -path '*/gconv/*' \
      -exec cp -P {} "$dest/" \;
    basename "$deb" .deb >>"$stage/packages.txt"
    rm -f "$deb"
  done <"$tmp/packages"
  rm -rf "$tmp"
}

# The reference frames as this machine renders them (llvmpipe, here).
pack_reference_frames() {  # RGRAPH SRC DEST
  local name pipeline scene cache
  mkdir -p "$3"
  cache=$(mktemp -d)
  while read -r name pipeline scene; do
    RGRAPH_CACHE_DIR=$cache render_frame "$1" "$2" "$pipeline" "$scene" "$3/$name"
  done < <(reference_frames "$2")
  rm -rf "$cache"
}

pack_main() {  # DIR BUILD
  local dir=$1 build src assets stage rel tracked size
  build=$(cd "$2" 2>/dev/null && pwd) || die "no build folder '$2' (configure and build it first: see --help)"
  [[ -f "$build/CMakeCache.txt" ]] || die "$build is not a CMake build folder"
  src=$(cmake_cache_value CMAKE_HOME_DIRECTORY "$build")
  [[ -d "$src" ]] || die "the build's source folder '$src' is gone"
  case "$build/" in "$src"/*) ;; *) die "the build folder must lie inside its source folder ($src)" ;; esac
  rel=${build#"$src"/}
  mkdir -p "$dir" && dir=$(cd "$dir" && pwd)
  case "$dir/" in "$build"/*) die "--pack DIR must not lie inside the build folder" ;; esac

  stage=$(mktemp -d /tmp/rgraph-gpucheck-pack.XXXXXX)
  GPUCHECK_STAGE=$stage GPUCHECK_SRC=$src
  trap 'rm -rf "$GPUCHECK_STAGE"' EXIT
  note "packing $build (sources $src) into $dir"
  # The tracked source files as they are on disk (what the build was made from).
  git -C "$src" ls-files -z | (cd "$src" && tar --null -T - -cf - 2>/dev/null) | (mkdir -p "$stage/src" && tar -xf - -C "$stage/src")
  pack_build_tree "$build" "$stage/src/$rel"
  assets=$src/../shared/assets
  if [[ -d "$assets" ]]; then
    mkdir -p "$stage/shared" && cp -a "$(readlink -f "$assets")" "$stage/shared/assets"
  else
    note "no $assets: the glTF model tests will fail there"
  fi
  note "rendering the reference frames on $(reference_frames "$src" | wc -l) pipeline/scene pairs"
  pack_reference_frames "$build/bin/rgraph" "$src" "$stage/frames"
  local elves=()
  while IFS= read -r -d '' f; do is_elf "$f" && elves+=("$f"); done \
    < <(find "$stage/src/$rel" -type f -print0)
  pack_libraries "$stage" "${elves[@]}"
  {
    echo "GPUCHECK_SOURCE_ROOT=$src"
    echo "GPUCHECK_BUILD_REL=$rel"
    echo "GPUCHECK_COMMIT=$(git -C "$src" rev-parse HEAD)$(git -C "$src" diff --quiet HEAD 2>/dev/null || echo '+changes')"
    echo "GPUCHECK_PACKED_AT='$(date -u '+%Y-%m-%d %H:%M UTC') on $(uname -n)'"
  } >"$stage/$GPUCHECK_MANIFEST"

  tar -C "$stage" -cf - . | gzip -6 >"$dir/$GPUCHECK_ARCHIVE"
  mkdir -p "$dir/scripts/gpu-check"
  cp "$gpucheck_dir/../gpu-check.sh" "$dir/scripts/"
  cp "$gpucheck_dir"/*.sh "$dir/scripts/gpu-check/"

  size=$(du -sb "$dir" | cut -f1)
  tracked=$(git -C "$src" ls-files -z | (cd "$src" && xargs -0 du -cb 2>/dev/null) | awk '$2 == "total" {t += $1} END {print t + 0}')
  note "$(wc -l <"$stage/packages.txt") Debian packages' libraries; $dir: $((size / 1024)) KiB," \
    "tracked files $((tracked / 1024)) KiB, $(((size + tracked) / 1024)) KiB of $((GPUCHECK_CARRY_LIMIT / 1024)) KiB"
  ((size + tracked <= GPUCHECK_CARRY_LIMIT)) || die "$dir and the tracked files exceed 64 MiB: they cannot travel"
  echo "$dir"
}
