#!/usr/bin/env bash
# Crash safety of GUI recordings (issue 27), with the real window under its own Xvfb:
#  - killed: a GUI driven through generate, fix, pressure and the start of a simulation is
#    killed with SIGKILL while it runs; every action it took is in its recording, each line
#    whole, and the recording replays headlessly to the end.
#  - two at once: two GUIs started together with the same --out each record to a file of
#    their own, and each file replays.
#   run_gui_kill_test.sh SUTURA_EXE SRC_DIR OUT
set -euo pipefail
exe=$1 src=$2 out=$3
rm -rf "$out"
mkdir -p "$out"
source "$src/xvfb.sh"
start_xvfb "$out"
fail() { echo "gui kill test: $*" >&2; exit 1; }

# --- killed mid-run
sed -e "s|OUT/|$out/|g" "$src/killed_mid_run.script.jsonl" >"$out/killed.script.jsonl"
"$exe" gui --out "$out/killed" --record "$out/killed.jsonl" --script "$out/killed.script.jsonl" \
  --width 1200 --height 800 >"$out/killed.log" 2>&1 &
gui=$!
for _ in $(seq 1200); do [ -s "$out/killed_here.png" ] && break; sleep 0.1; done
[ -s "$out/killed_here.png" ] || { kill -9 "$gui" 2>/dev/null; cat "$out/killed.log" >&2; fail "the GUI never reached the simulation"; }
kill -9 "$gui"
wait "$gui" 2>/dev/null && fail "the GUI was not killed" || true
[ "$(tail -c 1 "$out/killed.jsonl" | od -An -c | tr -d ' ')" = '\n' ] || fail "the recording ends in a partial line"
for op in generate fix pressure simulate; do
  grep -q "\"op\": *\"$op\"" "$out/killed.jsonl" || { cat "$out/killed.jsonl" >&2; fail "the recording lost the $op action"; }
done
"$exe" replay "$out/killed.jsonl" --out "$out/killed-replayed" --quiet || fail "the killed GUI's recording does not replay"
grep -q '"status": "ok"' "$out/killed-replayed/report.json" || fail "the replay's report is not ok"

# --- two at once, one --out
sed -e "s|OUT/|$out/|g" "$src/two_at_once.script.jsonl" >"$out/two.script.jsonl"
mkdir -p "$out/shared"
for i in 1 2; do
  "$exe" gui --out "$out/shared" --script "$out/two.script.jsonl" --width 1000 --height 700 \
    >"$out/two-$i.log" 2>&1 &
  pids[$i]=$!
done
for i in 1 2; do wait "${pids[$i]}" || { cat "$out/two-$i.log" >&2; fail "GUI $i failed"; }; done
mapfile -t recordings < <(ls "$out/shared"/session-*.jsonl)
[ "${#recordings[@]}" -eq 2 ] || fail "expected 2 recordings in $out/shared, found ${#recordings[@]}"
for r in "${recordings[@]}"; do
  [ "$(grep -c '"op": *"generate"' "$r")" -eq 1 ] || fail "$r does not hold exactly one GUI's actions"
  "$exe" replay "$r" --out "$r.replayed" --quiet || fail "$r does not replay"
done
echo "gui kill test: ok ($out)"
