#!/usr/bin/env bash
# GUI test: runs the real `sutura gui` window under its own Xvfb server and drives it with a
# scripted-input file (events go through the same input queue as real ones), then checks
# that the recorded session replays headlessly to the same geometry (position hashes in the
# GUI's report.json and the replay's), and that the snapshot the script saved shows what the
# window showed (COMPARE_VIEW: tests/gui/compare_view.cpp, on the window.png taken after it).
# Leaves the window screenshots in OUT.
#   run_gui_test.sh SUTURA_EXE SCRIPT OUT COMPARE_VIEW
set -euo pipefail
exe=$1 script=$2 out=$3 compare_view=$4
source "$(dirname "${BASH_SOURCE[0]}")/xvfb.sh"
gui_test_dir "$out" "$script"
"$exe" gui --out "$out" --record "$out/recorded.jsonl" \
  --script "$out/script.jsonl" --width 1400 --height 900

for f in window.png gui_snapshot.png report.json recorded.jsonl; do
  [ -s "$out/$f" ] || { echo "gui test: $out/$f missing" >&2; exit 1; }
done

# SCRIPT's companion NAME.recorded_contains (optional): strings the recording must hold, one
# per line (e.g. the snapshot's clip plane of gui.cut_open).
expected="${script%.script.jsonl}.recorded_contains"
if [ -e "$expected" ]; then
  while IFS= read -r want; do
    [ -z "$want" ] && continue
    grep -qF -- "$want" "$out/recorded.jsonl" || {
      echo "gui test: the recording does not contain $want" >&2
      exit 1
    }
  done < "$expected"
fi

"$exe" replay "$out/recorded.jsonl" --out "$out/replayed" --quiet
same_geometry "$out/report.json" "$out/replayed/report.json" || {
  echo "gui test: the replayed session does not reproduce the GUI's geometry" >&2
  exit 1
}
cmp "$out/gui_snapshot.png" "$out/replayed/gui_snapshot.png" || {
  echo "gui test: the replayed snapshot differs from the GUI's" >&2
  exit 1
}
"$compare_view" "$out/window.png" "$out/gui_snapshot.png" || {
  echo "gui test: the snapshot differs from the window's view" >&2
  exit 1
}
if [ -e "$out/meshes/result.obj" ]; then
  cmp "$out/meshes/result.obj" "$out/replayed/meshes/result.obj" || {
    echo "gui test: the replayed mesh export differs from the GUI's" >&2
    exit 1
  }
fi
if [ -e "$out/patch_template.pdf" ]; then
  cmp "$out/patch_template.pdf" "$out/replayed/patch_template.pdf" || {
    echo "gui test: the replayed cutting template differs from the GUI's" >&2
    exit 1
  }
fi
if [ -e "$out/plan_report.html" ]; then
  # The report hashes the recording as written when it ran; the script records nothing after
  # it, so the replay's report must be the same bytes. Poppler must read the PDF.
  grep -q 'id="materials"' "$out/plan_report.html" || {
    echo "gui test: the plan report has no materials section" >&2; exit 1; }
  pdftoppm -r 10 -f 1 -l 1 -png "$out/plan_report.pdf" "$out/plan_report_page" || {
    echo "gui test: poppler cannot read the plan report's PDF" >&2; exit 1; }
  for f in plan_report.html plan_report.pdf; do
    cmp "$out/$f" "$out/replayed/$f" || {
      echo "gui test: the replayed $f differs from the GUI's" >&2
      exit 1
    }
  done
fi
echo "gui test: ok ($out)"
