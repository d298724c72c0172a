#!/usr/bin/env bash
# Installs the Debian 12 packages Sutura needs to build, test and run.
#   install-deps.sh           what the ordinary build, tests and GUI need
#   install-deps.sh --clang   those and clang 14 with its sanitizer and libFuzzer runtimes
#                             (libclang-rt-14-dev) and OpenMP (libomp-dev): the sanitized suite
#                             (scripts/test.sh --sanitize) and the fuzzers (scripts/fuzz.sh)
# Idempotent: when every package is already present it does nothing (no apt-get update).
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config
  libeigen3-dev
  libsuitesparse-dev libopenblas0-pthread libopenblas-dev
  libosmesa6-dev libgl-dev libglfw3-dev
  libimgui-dev
  libassimp-dev
  libcgal-dev libboost-dev libgmp-dev libmpfr-dev
  libstb-dev
  nlohmann-json3-dev
  libcli11-dev
  libgtest-dev libgmock-dev
  libbenchmark-dev
  xvfb xauth xdotool x11-utils
  poppler-utils
  nettle-dev
  libxml2-dev
)
case "${1:-}" in
  "") ;;
  --clang) PACKAGES+=(clang libclang-rt-14-dev libomp-dev) ;;
  *) echo "usage: install-deps.sh [--clang]" >&2; exit 2 ;;
esac

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present" >&2
  exit 0
fi

echo "install-deps: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
