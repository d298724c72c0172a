#!/usr/bin/env bash
# Quick start, command 1: install, build (Release) and replay the default session headlessly.
# Writes before/after PNG snapshots, the final meshes and report.json into out/.
# Usage: scripts/run.sh [SESSION] [OUT_DIR]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/build.sh" --target sutura
session="${1:-$root/assets/sessions/default.jsonl}"
out="${2:-$root/out}"
"$root/build/app/sutura" replay "$session" --out "$out"
