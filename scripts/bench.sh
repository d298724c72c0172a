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
# Surgical repairs end to end: wall time of every bundled planning session and of the large
# ones (assets/sessions/large, not run by ctest), from the start of the replay to equilibrium.
echo "== repair sessions (wall time of sutura replay, seconds)"
out="$(mktemp -d)"
for s in "$root"/assets/sessions/*.jsonl "$root"/assets/sessions/large/*.jsonl; do
  start=$(date +%s%N)
  status=ok
  "$root/build/app/sutura" replay "$s" --out "$out/$(basename "$s" .jsonl)" -q || status=failed
  ms=$(( ($(date +%s%N) - start) / 1000000 ))
  printf '%-40s %6d.%01d  %s\n' "$(basename "$s")" $((ms / 1000)) $((ms % 1000 / 100)) "$status"
done
rm -rf "$out"
