# Sourced by the GUI tests: the helpers every one of them needs.
#
# start_xvfb starts an Xvfb server of our own and exports DISPLAY. Xvfb picks a
# free display number and writes it to fd 3 once it accepts connections (safe when several
# GUI tests start at once); the server is killed when the sourcing script exits.
#   start_xvfb DIR   (DIR receives the display number and Xvfb's log)
start_xvfb() {
  local dir=$1
  Xvfb -displayfd 3 -screen 0 1600x1000x24 -nolisten tcp 3>"$dir/display" >"$dir/xvfb.log" 2>&1 &
  xvfb_pid=$!
  trap 'kill "$xvfb_pid" 2>/dev/null || true' EXIT
  for _ in $(seq 200); do [ -s "$dir/display" ] && break; sleep 0.05; done
  local display
  display=$(tr -d '[:space:]' <"$dir/display")
  [ -n "$display" ] || { echo "gui test: Xvfb did not start" >&2; cat "$dir/xvfb.log" >&2; exit 1; }
  export DISPLAY=":${display}"
}

# A fresh output directory OUT with its own Xvfb, and the test script SCRIPT copied to
# OUT/script.jsonl with OUT/ and SRC/ standing for the output directory and the script's own.
#   gui_test_dir OUT SCRIPT
gui_test_dir() {
  local out=$1 script=$2 src
  rm -rf "$out"
  mkdir -p "$out"
  start_xvfb "$out"
  src=$(cd "$(dirname "$script")" && pwd)
  sed -e "s|OUT/|$out/|g" -e "s|SRC/|$src/|g" "$script" >"$out/script.jsonl"
}

# Whether two report.json files give the same position hashes (and at least one); prints them.
#   same_geometry REPORT_A REPORT_B
same_geometry() {
  local a b
  a=$(grep -o '"position_hash": "[0-9a-f]*"' "$1")
  b=$(grep -o '"position_hash": "[0-9a-f]*"' "$2")
  echo "window: $a"
  echo "replay: $b"
  [ -n "$a" ] && [ "$a" = "$b" ]
}
