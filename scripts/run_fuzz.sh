#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, AddressSanitizer + UBSan) into build-fuzz/ and runs each
# from the seed corpus: fuzz_fair (fair, mean_curvature, the Laplacians, boundary normals),
# fuzz_fill (fill_holes, rim trim and keep) and fuzz_remesh (fair with the region remeshed),
# SECONDS seconds (default 30) split evenly among them. A crash, sanitizer report or abort
# fails the run. A long run: bash scripts/run_fuzz.sh 3600
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_TO_RUN="${1:-30}"
TARGETS=(fuzz_fair fuzz_fill fuzz_remesh)
EACH=$(( SECONDS_TO_RUN / ${#TARGETS[@]} ))
if [ "$EACH" -lt 1 ]; then EACH=1; fi
# Through ccache where installed, keyed on the paths under the clone as relative ones (and,
# with debug info, not on the build folder: an object's debug info may then name another
# clone's build folder), so another clone on this machine reuses them.
launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=)
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1
fi
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DGEOFAIR_FUZZ=ON "${launcher[@]}" >/dev/null
cmake --build build-fuzz --target "${TARGETS[@]}" -j"$(nproc)" >/dev/null
for target in "${TARGETS[@]}"; do
  corpus="$(mktemp -d)"
  cp native/fuzz/corpus/* "$corpus"/
  echo "== $target ($EACH s)"
  build-fuzz/native/"$target" -max_total_time="$EACH" -rss_limit_mb=4096 \
    -print_final_stats=1 "$corpus" 2>&1 | grep -E "^(Done|stat::number_of_executed_units)|ERROR|SUMMARY|crash"
  rm -rf "$corpus"
done
