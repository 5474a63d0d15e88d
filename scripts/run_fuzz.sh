#!/usr/bin/env bash
# Builds the libFuzzer target (clang, AddressSanitizer + UBSan) into build-fuzz/ and runs it
# for SECONDS seconds (default 30) from the seed corpus. A crash, sanitizer report or abort
# fails the run. A long run: bash scripts/run_fuzz.sh 3600
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_TO_RUN="${1:-30}"
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DGEOFAIR_FUZZ=ON >/dev/null
cmake --build build-fuzz --target fuzz_fair -j"$(nproc)" >/dev/null
corpus="$(mktemp -d)"
cp native/fuzz/corpus/* "$corpus"/
build-fuzz/native/fuzz_fair -max_total_time="$SECONDS_TO_RUN" -rss_limit_mb=4096 \
  -print_final_stats=1 "$corpus" 2>&1 | grep -E "^(Done|stat::number_of_executed_units)|ERROR|SUMMARY|crash"
rm -rf "$corpus"
