#!/usr/bin/env bash
# The libraries only some paths need are not loaded by the others (issue 28): `sutura --version`
# and a replay that neither draws nor reads a mesh file must not load OSMesa (and LLVM with it),
# assimp, or GLFW (and X11 with it); the dynamic loader's log (LD_DEBUG=libs) lists what a run
# loads.
#   lazy_libraries.sh SUTURA OUT
set -euo pipefail
exe=$1 out=$2
rm -rf "$out" && mkdir -p "$out"
cat > "$out/s.jsonl" <<'SESSION'
{"format": "sutura-session", "version": 3}
{"op": "generate", "object": "t", "shape": "tube", "radius": 4, "length": 20, "segments_around": 16, "segments_along": 10}
{"op": "material", "object": "t", "youngs_modulus": 1.0, "poisson_ratio": 0.45, "thickness": 0.6}
{"op": "fix", "object": "t", "boundary": "all"}
{"op": "pressure", "object": "t", "pressure": 0.0107}
{"op": "solve"}
SESSION
check() {
  local what=$1; shift
  local log="$out/$what.log"
  LD_DEBUG=libs "$@" > "$out/$what.out" 2> "$log"
  if grep -E 'calling init: .*(libOSMesa|libLLVM|libassimp|libglfw|libX11)' "$log"; then
    echo "lazy_libraries: $what loaded a library it does not use" >&2
    exit 1
  fi
  grep -q 'calling init: .*libc\.so' "$log" || {
    echo "lazy_libraries: $what: no loader log (LD_DEBUG unsupported?)" >&2; exit 1; }
  echo "lazy_libraries: $what loads neither OSMesa, assimp nor GLFW"
}
check version "$exe" --version
check replay "$exe" replay "$out/s.jsonl" --out "$out/replay" --quiet
# ... and the path that draws does load OSMesa, on demand.
echo '{"op": "snapshot", "file": "s.png", "width": 64, "height": 64}' >> "$out/s.jsonl"
LD_DEBUG=libs "$exe" replay "$out/s.jsonl" --out "$out/drawn" --quiet 2> "$out/drawn.log" > /dev/null
grep -q 'calling init: .*libOSMesa' "$out/drawn.log" || {
  echo "lazy_libraries: the snapshot did not load OSMesa" >&2; exit 1; }
[ -s "$out/drawn/s.png" ] || { echo "lazy_libraries: no snapshot" >&2; exit 1; }
if grep -E 'calling init: .*(libglfw|libX11)' "$out/drawn.log"; then
  echo "lazy_libraries: an off-screen snapshot loaded GLFW" >&2; exit 1
fi
echo "lazy_libraries: a snapshot loads OSMesa when it draws, and no window library"
