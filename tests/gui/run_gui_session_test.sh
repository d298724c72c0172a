#!/usr/bin/env bash
# GUI test: `sutura gui SESSION` replays SESSION, continues it in a new recording that starts
# as its copy, and never writes SESSION; the recording replays headlessly to the window's
# geometry.
#   run_gui_session_test.sh SUTURA_EXE SESSION SCRIPT OUT
set -euo pipefail
exe=$1 session=$2 script=$3 out=$4
source "$(dirname "${BASH_SOURCE[0]}")/xvfb.sh"
gui_test_dir "$out" "$script"

cp "$session" "$out/opened.jsonl"
cp "$session" "$out/opened.orig"
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
same_geometry "$out/report.json" "$out/replayed/report.json" ||
  fail "the replayed recording does not reproduce the window's geometry"
echo "gui session test: ok ($out)"
