#!/usr/bin/env bash
# Replays one robustness reproduction (tests/robustness/expected.txt) and checks its outcome:
# "ok" = exit 0; otherwise exit 1 with the expected text in the error. The time limit is
# ctest's TIMEOUT. Usage: run_case.sh SUTURA SESSION OUT_DIR EXPECTED
set -uo pipefail
sutura="$1" session="$2" out="$3" expected="$4"
rm -rf "$out"
log=$("$sutura" replay "$session" --out "$out" -q 2>&1)
rc=$?
if [[ "$expected" == ok ]]; then
  [[ $rc -eq 0 ]] || { echo "expected success, got exit $rc: $log"; exit 1; }
else
  [[ $rc -eq 1 ]] || { echo "expected a clear error (exit 1), got exit $rc: $log"; exit 1; }
  [[ "$log" == *"sutura: error: $session$expected"* ]] || { echo "expected '$session$expected' in: $log"; exit 1; }
fi
[[ -f "$out/report.json" ]] || { echo "no report.json"; exit 1; }
echo "ok: $log"
