#!/usr/bin/env bash
# `sutura report SESSION --out DIR`: replays the session, then writes DIR/plan_report.html and
# DIR/plan_report.pdf and prints their paths; the HTML has every section, poppler reads every
# page of the PDF, a second run writes the same bytes, and the report adds nothing to the replay
# (same position hash as `replay`).
#   report_command.sh SUTURA SESSION OUT
set -euo pipefail
exe=$1 session=$2 out=$3
rm -rf "$out" && mkdir -p "$out"
"$exe" report "$session" --out "$out/report" --quiet > "$out/stdout.txt"
printf '%s\n' "$out/report/plan_report.html" "$out/report/plan_report.pdf" | cmp - "$out/stdout.txt" || {
  echo "report_command: stdout does not list the two files" >&2; exit 1; }
for id in reproduce plan views lumen measurements equilibrium design template materials; do
  grep -q "<section id=\"$id\"" "$out/report/plan_report.html" || {
    echo "report_command: no section '$id' in the HTML" >&2; exit 1; }
done
pages=$(grep -c '/Type /Page /Parent' "$out/report/plan_report.pdf")
[ "$pages" -ge 3 ] || { echo "report_command: $pages pages" >&2; exit 1; }
pdftoppm -r 20 -png "$out/report/plan_report.pdf" "$out/page"
[ "$(ls "$out"/page-*.png | wc -l)" -eq "$pages" ] || {
  echo "report_command: poppler did not rasterise every page" >&2; exit 1; }
"$exe" report "$session" --out "$out/again" --quiet > /dev/null
for f in plan_report.html plan_report.pdf; do
  cmp "$out/report/$f" "$out/again/$f" || { echo "report_command: a second run wrote another $f" >&2; exit 1; }
done
"$exe" replay "$session" --out "$out/replay" --quiet
hash() { grep -o '"position_hash": *"[0-9a-f]*"' "$1" | sort; }
[ "$(hash "$out/report/report.json")" = "$(hash "$out/replay/report.json")" ] || {
  echo "report_command: the report's replay ends elsewhere than a plain replay" >&2; exit 1; }
echo "report_command: ok ($pages pages)"
