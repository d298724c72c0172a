#!/usr/bin/env bash
# GUI test: `sutura gui SESSION` replays SESSION, continues it in a new recording that starts
# as its copy, and never writes SESSION; the recording replays headlessly to the window's
# geometry.
#   run_gui_session_test.sh SUTURA_EXE SESSION SCRIPT OUT
set -euo pipefail
exe=$1 session=$2 script=$3 out=$4
rm -rf "$out"
mkdir -p "$out"

source "$(dirname "${BASH_SOURCE[0]}")/xvfb.sh"
start_xvfb "$out"

cp "$session" "$out/opened.jsonl"
cp "$session" "$out/opened.orig"
src=$(cd "$(dirname "$script")" && pwd)
sed -e "s|OUT/|$out/|g" -e "s|SRC/|$src/|g" "$script" >"$out/script.jsonl"
"$exe" gui "$out/opened.jsonl" --out "$out" --record "$out/recorded.jsonl" \
  --script "$out/script.jsonl" --width 1400 --height 900

fail() { echo "gui session test: $*" >&2; exit 1; }
[ -s "$out/window.png" ] || fail "$out/window.png missing"
cmp "$out/opened.jsonl" "$out/opened.orig" || fail "the opened session was written"
lines=$(wc -l <"$out/opened.orig")
head -n "$lines" "$out/recorded.jsonl" | cmp - "$out/opened.orig" ||
  fail "the recording does not start with the opened session"
[ "$(wc -l <"$out/recorded.jsonl")" -gt "$lines" ] || fail "nothing recorded after the opened session"

"$exe" replay "$out/recorded.jsonl" --out "$out/replayed" --quiet
gui_hashes=$(grep -o '"position_hash": "[0-9a-f]*"' "$out/report.json")
replay_hashes=$(grep -o '"position_hash": "[0-9a-f]*"' "$out/replayed/report.json")
[ -n "$gui_hashes" ] && [ "$gui_hashes" = "$replay_hashes" ] ||
  fail "the replayed recording does not reproduce the window's geometry"
echo "gui session test: ok ($out)"
