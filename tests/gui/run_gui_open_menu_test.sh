#!/usr/bin/env bash
# GUI test: File > Open session in a window that was planning something else. The first
# recording keeps what was committed before; SESSION is replayed, never written, and continued
# in a new recording in the output directory that replays headlessly to the window's geometry.
#   run_gui_open_menu_test.sh SUTURA_EXE SESSION SCRIPT OUT
set -euo pipefail
exe=$1 session=$2 script=$3 out=$4
source "$(dirname "${BASH_SOURCE[0]}")/xvfb.sh"
gui_test_dir "$out" "$script"

cp "$session" "$out/opened.jsonl"
cp "$session" "$out/opened.orig"
"$exe" gui --out "$out" --record "$out/first.jsonl" \
  --script "$out/script.jsonl" --width 1400 --height 900

fail() { echo "gui open-menu test: $*" >&2; exit 1; }
[ -s "$out/window.png" ] || fail "$out/window.png missing"
cmp "$out/opened.jsonl" "$out/opened.orig" || fail "the opened session was written"
# The first recording: its header, the generated strip and its snapshot (rendered off-screen
# before the switch: the window must still draw after it), nothing of the uncommitted draft.
[ "$(wc -l <"$out/first.jsonl")" -eq 3 ] || fail "first.jsonl should hold the header and two actions"
grep -q '"op":"generate"' "$out/first.jsonl" || fail "first.jsonl lacks the strip"
grep -q '"op":"snapshot"' "$out/first.jsonl" || fail "first.jsonl lacks the snapshot"
[ -s "$out/gui_snapshot.png" ] || fail "the first session's snapshot is missing"
second=$(ls "$out"/session-*.jsonl)
[ "$(echo "$second" | wc -l)" -eq 1 ] || fail "expected one new recording, found: $second"
lines=$(wc -l <"$out/opened.orig")
head -n "$lines" "$second" | cmp - "$out/opened.orig" ||
  fail "the new recording does not start with the opened session"
[ "$(wc -l <"$second")" -eq $((lines + 1)) ] || fail "the new recording should add one action"
"$exe" replay "$second" --out "$out/replayed" --quiet
same_geometry "$out/report.json" "$out/replayed/report.json" ||
  fail "the replayed recording does not reproduce the window's geometry"
echo "gui open-menu test: ok ($out)"
