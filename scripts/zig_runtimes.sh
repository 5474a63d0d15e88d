#!/usr/bin/env bash
# Builds zig's runtimes for the two targets the shipped packages are compiled for
# (x86_64-linux-gnu.2.28: glibc's stubs, libc++, libc++abi, libunwind; x86_64-windows-gnu:
# MinGW-w64's C runtime and the same C++ runtime) into zig's cache, by linking a small C++
# program as CMake's checks do (no -O) and as the modules do (-O3, shared).
#
#   bash scripts/zig_runtimes.sh [TARGET ...]     (default: both)
#
# zig compiles a runtime the first time it links for a target and caches it; that compile
# runs on one core for minutes, so scripts/setup.sh runs this, a target
# each, in the background beside the builds that use every core, and scripts/build_wheel.sh
# and scripts/build_windows.py then find the runtimes cached. Needs the ziglang package.
set -euo pipefail
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then targets=(x86_64-linux-gnu.2.28 x86_64-windows-gnu); fi
zig=$(python3 -c 'import os, ziglang; print(os.path.join(os.path.dirname(ziglang.__file__), "zig"))')
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf '#include <iostream>\n#include <vector>\nint main() { std::vector<int> v{1}; std::cout << v.size(); }\n' \
  >"$work/probe.cpp"
for target in "${targets[@]}"; do
  start=$SECONDS
  "$zig" c++ -target "$target" "$work/probe.cpp" -o "$work/probe-$target"
  "$zig" c++ -target "$target" -O3 -fPIC -shared "$work/probe.cpp" -o "$work/probe-$target.so"
  echo "zig runtimes for $target: $((SECONDS - start)) s"
done
