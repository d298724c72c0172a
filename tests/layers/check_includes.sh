#!/usr/bin/env bash
# The layers of docs/architecture.md, checked on the sources' #include lines:
# - engine/ includes no GL, window, ImGui, renderer, session or GUI header;
# - render/ includes no engine, session or GUI header (plain arrays in);
# - app/'s session layer (sutura::session) includes no GUI or window header; only the executable's
#   `sutura gui` subcommand (app/src/gui_command.*) starts the GUI;
# - ui/ reads the engine only for picking: the BVH and the mesh it is built on, in
#   scene_picker.hpp and orbit_camera.hpp; everything else goes through sutura/app;
# - ui/ reads no object's simulation data (SceneObject::sim, engine::SurfaceAttributes) itself:
#   no member access `.sim` / `->sim` (spaces allowed) and no SurfaceAttributes. Any struct's
#   member called sim counts, and so does a comment or a string that names one: say it otherwise.
# Only direct includes are seen: what the ui gets through a session-layer header is the session
# layer's to offer. Needs `lastpipe` (bash without job control, as ctest runs it).
# Usage: check_includes.sh SOURCE_DIR. Prints every offending line; exit 1 if there is one, 2 if
# SOURCE_DIR has no engine, render, app and ui.
set -u
shopt -s lastpipe
src=${1:?source directory}
for d in engine render app ui; do
  [ -d "$src/$d" ] || { echo "check_includes: no $src/$d (give the source directory)" >&2; exit 2; }
done
status=0
offend() {  # $1: the rule; stdin: grep -n lines that break it
  local lines
  lines=$(cat)
  [ -z "$lines" ] && return 0
  sed "s/^/layer violation ($1): /" <<<"$lines"
  status=1
}
includes() { grep -rn --include='*.hpp' --include='*.cpp' -E '^[[:space:]]*#[[:space:]]*include' "$@"; }

includes "$src/engine" | grep -E '<(GL|GLES[0-9]*|EGL|GLFW)/|glfw|imgui|[Oo][Ss][Mm]esa|["<]sutura/(render|app|ui)/' \
  | offend "engine: no GL, window, ImGui, render, app or ui"
includes "$src/render" | grep -E '["<]sutura/(engine|app|ui)/' | offend "render: plain arrays in"
includes "$src/app" | grep -E '["<]sutura/ui/|imgui|<GLFW/|glfw' | grep -vE '^[^:]*/app/src/gui_command\.(hpp|cpp):' \
  | offend "app: the session layer has no GUI"
includes "$src/ui" | grep -E '["<]sutura/engine/' \
  | grep -vE '^[^:]*/(scene_picker|orbit_camera)\.hpp:[0-9]+:#include "sutura/engine/(geometry/bvh|mesh)\.hpp"$' \
  | offend "ui: the engine only for picking"
grep -rn --include='*.hpp' --include='*.cpp' --include='*.h' --include='*.inl' \
  -E '(\.|->)[[:space:]]*sim\b|SurfaceAttributes' "$src/ui" \
  | offend "ui: an object's simulation data through the session layer"
[ "$status" -eq 0 ] && echo "layers: every #include keeps to its layer"
exit "$status"
