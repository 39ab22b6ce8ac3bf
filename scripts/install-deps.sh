#!/usr/bin/env bash
# Installs every build, test and run dependency of rgraph from Debian 12 packages.
# Idempotent and non-interactive: packages already present are skipped by apt.
set -euo pipefail

PACKAGES=(
  cmake g++ make pkg-config git
  libopengl-dev libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  libglfw3-dev libglm-dev glslang-dev glslang-tools libtinygltf-dev libimgui-dev
  libspdlog-dev libfmt-dev libgtest-dev libgmock-dev libbenchmark-dev
  nlohmann-json3-dev libstb-dev libcli11-dev
  libcairo2-dev fonts-dejavu-core
  xvfb xauth
  clang-14 libclang-rt-14-dev
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
