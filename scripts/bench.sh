#!/usr/bin/env bash
# Builds and runs every benchmark program; prints their tables (record them in
# docs/performance.md with the machine and date).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/build.sh"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); $(date -u +%F)"
for b in "$root"/build/tests/bench/bench_*; do
  [ -x "$b" ] || continue
  echo "== $(basename "$b")"
  if [ "$(basename "$b")" = bench_gui ]; then  # a real window: needs an X display
    if [ -n "${DISPLAY:-}" ]; then "$b"; else xvfb-run -a -s "-screen 0 1600x1000x24" "$b"; fi
    continue
  fi
  "$b" --benchmark_counters_tabular=true
done
