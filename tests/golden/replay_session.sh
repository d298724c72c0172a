#!/usr/bin/env bash
# Replays a bundled session (the replay's output and exit code as they are), then compares the
# objects' position hashes in its report.json with the golden ones for the BLAS kernels the
# replay used (position_hashes.txt). A session or kernels without an entry are only replayed,
# and the log says so; so is every session with GOLDEN "none" (a build that rounds otherwise).
#   replay_session.sh SUTURA SESSION OUT GOLDEN KEY      (KEY: e.g. sessions/two_strips)
set -uo pipefail
exe=$1 session=$2 out=$3 golden=$4 key=$5
"$exe" replay "$session" --out "$out" || exit $?
if [ "$golden" = none ]; then
  echo "golden: this build is not compared with the recorded position hashes"
  exit 0
fi
report="$out/report.json"
kernels=$(grep -o '"blas": "[^"]*"' "$report" | head -n 1 | sed 's/"blas": "\(.*\)"/\1/')
got=$(grep -o '"position_hash": "[0-9a-f]*"' "$report" | sed 's/.*: "\(.*\)"/\1/' | tr '\n' ' ' | sed 's/ $//')
if [ -z "$kernels" ] || [ -z "$got" ]; then
  echo "golden: $report names no BLAS kernels or no position hash (has its format changed?)" >&2
  exit 1
fi
table=$(grep -v '^#' "$golden" | tr -d '\r')
line=$(echo "$table" | awk -F' [|] ' -v k="$key" -v b="$kernels" '$1 == k && $2 == b {print $3}' | sed 's/[[:space:]]*$//')
if [ -z "$line" ]; then
  if echo "$table" | awk -F' [|] ' -v k="$key" '$1 == k {f = 1} END {exit !f}'; then
    echo "golden: no position hashes of $key for the BLAS kernels '$kernels': not compared"
  else
    echo "golden: $key has no golden position hashes: not compared"
  fi
  exit 0
fi
if [ "$got" != "$line" ]; then
  echo "golden: $key replayed to position hashes '$got', recorded '$line' ($kernels):" \
       "what this session means has changed (tests/golden/position_hashes.txt)" >&2
  exit 1
fi
echo "golden: $key replayed to its recorded position hashes ($got, $kernels)"
