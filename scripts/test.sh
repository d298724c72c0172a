#!/usr/bin/env bash
# Quick start, command 2: install, build (Release) and run the whole test suite through ctest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/build.sh"
cd "$root/build"
ctest --output-on-failure -j "${SUTURA_JOBS:-$(nproc)}"
