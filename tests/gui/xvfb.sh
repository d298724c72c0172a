# Sourced by the GUI tests: starts an Xvfb server of our own and exports DISPLAY. Xvfb picks a
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
