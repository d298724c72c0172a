#!/usr/bin/env bash
# Fuzzes the session parser and runner (fuzz_session), the mesh loader (fuzz_mesh) and the
# geometric ops on a tube (fuzz_ops) with libFuzzer under AddressSanitizer and
# UndefinedBehaviorSanitizer, each for SECONDS (default 300), starting from the corpora ctest replays (tests/fuzz/corpus, tests/robustness, the
# bundled sessions and meshes). Builds with clang in build-fuzz/ (never while another build
# runs: 2 cores). Findings (crashes, leaks, sanitizer reports, inputs slower than 30 s) land in
# build-fuzz/findings/; add each, once fixed, to tests/fuzz/corpus so ctest keeps it fixed.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]   (targets: session mesh ops; default all)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-300}"
targets=("${@:2}")
[ ${#targets[@]} -gt 0 ] || targets=(session mesh ops)
for t in "${targets[@]}"; do
  case "$t" in session|mesh|ops) ;; *) echo "fuzz.sh: no target '$t' (session, mesh, ops)" >&2; exit 2 ;; esac
done
bash "$root/scripts/install-deps.sh" --clang
build="$root/build-fuzz"
flags="-fsanitize=address,undefined,fuzzer-no-link -fno-omit-frame-pointer -fno-sanitize-recover=undefined"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
  -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
  -DSUTURA_FUZZ=ON -DSUTURA_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" -j "${SUTURA_JOBS:-$(nproc)}" --target "${targets[@]/#/fuzz_}"
mkdir -p "$build/findings"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1
export LSAN_OPTIONS="suppressions=$root/tests/fuzz/lsan.supp"
run() {  # target, then seed directories; skipped unless asked for
  local target="$1"; shift
  [[ " ${targets[*]} " == *" $target "* ]] || return 0
  local corpus="$build/corpus/$target"
  mkdir -p "$corpus"
  echo "fuzz: $target for $seconds s" >&2
  "$build/tests/fuzz_$target" "$corpus" "$@" -max_total_time="$seconds" -timeout=30 \
    -rss_limit_mb=4096 -artifact_prefix="$build/findings/$target-" -print_final_stats=1
}
run session "$root/tests/fuzz/corpus/session" "$root/tests/robustness" "$root/assets/sessions"
# The mesh target reads a first byte that picks the format; its seeds are prefixed by it.
seeds="$build/corpus/mesh-seeds"
rm -rf "$seeds" && mkdir -p "$seeds"
for f in "$root"/tests/fuzz/corpus/mesh/* "$root"/assets/anatomy/coarse/*.ply "$root"/tests/robustness/*/*.obj; do
  case "$f" in *.stl) b='\x00' ;; *.obj) b='\x01' ;; *.ply) b='\x02' ;; *) continue ;; esac
  { printf "$b"; cat "$f"; } > "$seeds/$(basename "$(dirname "$f")")-$(basename "$f")"
done
run mesh "$seeds"
run ops "$root/tests/fuzz/corpus/ops"
echo "fuzz: done; findings in $build/findings/: $(ls "$build/findings" | wc -l)" >&2
