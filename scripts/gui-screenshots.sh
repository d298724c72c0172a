#!/usr/bin/env bash
# Copies the window screenshots that docs/gui.md shows from the GUI tests' output into
# docs/images/gui/. Run the GUI tests first (cd build && ctest -L gui); the pictures are
# those the tests took, under Xvfb at 1400 x 900.
#   scripts/gui-screenshots.sh [BUILD_DIR]   (default: build)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
dest="$root/docs/images/gui"
mkdir -p "$dest"
for shot in patch_aortoplasty/window_plan patch_aortoplasty/window \
            resection/window_plan resection/window \
            widening/window_plan widening/window \
            subclavian_flap/window_plan subclavian_flap/window; do
  src="$build/tests/gui/$shot.png"
  [ -s "$src" ] || { echo "gui-screenshots: $src missing: run the GUI tests first" >&2; exit 1; }
  cp "$src" "$dest/${shot//\//_}.png"
done
echo "gui-screenshots: $(ls "$dest" | wc -l) pictures in $dest"
