#!/usr/bin/env bash
# Cross-compiles geofair here with zig (PyPI ziglang, as scripts/build_wheel.sh) for the
# platforms the release workflow builds on its own runners, as far as this machine can:
#   macOS arm64 and x86_64: the portable set and OpenMesh (fetched) by CMake, the module
#     linked as a Mach-O dylib (the objects given to zig's linker directly: it cannot read
#     the archives), then llvm-nm/llvm-objdump: PyInit_geofair exported, libSystem the only
#     library loaded (Python's symbols resolved by the interpreter: -undefined dynamic_lookup).
#   Windows x86_64 (MinGW headers; the wheels use MSVC): the library's sources compiled.
# Prints what it checked (the compilers' output: build/cross/build.log); exits non-zero on the
# first failure. Not part of the tests (minutes
# of compiling per target); docs/PACKAGING.md has its last result.
set -euo pipefail
cd "$(dirname "$0")/.."
python3 -c 'import ziglang' 2>/dev/null || python3 -m pip install --quiet "ziglang==0.17.1"
zig=$(python3 -c 'import os, ziglang; print(os.path.join(os.path.dirname(ziglang.__file__), "zig"))')
nm=$(command -v llvm-nm || command -v llvm-nm-14)
objdump=$(command -v llvm-objdump || command -v llvm-objdump-14)
out="$PWD/build/cross"
mkdir -p "$out"
log="$out/build.log"  # the compilers' output
: > "$log"

wrappers() {  # wrappers DIR TARGET: cc, c++, ar (Darwin's archive format) and ranlib
  mkdir -p "$1"
  for tool in cc c++; do
    printf '#!/bin/sh\nexec "%s" %s -target %s "$@"\n' "$zig" "$tool" "$2" > "$1/$tool"
  done
  printf '#!/bin/sh\nexec "%s" ar --format=darwin "$@"\n' "$zig" > "$1/ar"
  printf '#!/bin/sh\nexec "%s" ranlib "$@"\n' "$zig" > "$1/ranlib"
  chmod +x "$1"/*
}

for arch in aarch64 x86_64; do
  target="$arch-macos"
  tools="$out/$target/tools"
  build="$out/$target/build"
  wrappers "$tools" "$target"
  cmake -S . -B "$build" -DCMAKE_SYSTEM_NAME=Darwin -DCMAKE_SYSTEM_PROCESSOR="$arch" \
    -DCMAKE_C_COMPILER="$tools/cc" -DCMAKE_CXX_COMPILER="$tools/c++" -DCMAKE_AR="$tools/ar" \
    -DCMAKE_RANLIB="$tools/ranlib" -DCMAKE_INSTALL_NAME_TOOL=/bin/true \
    -DCMAKE_INTERPROCEDURAL_OPTIMIZATION=OFF -DCMAKE_BUILD_TYPE=Release \
    -DGEOFAIR_PORTABLE=ON -DGEOFAIR_FETCH_OPENMESH=ON -DGEOFAIR_OPENMP=OFF >>"$log" 2>&1
  cmake --build "$build" -j"$(nproc)" --target geofair_core OpenMeshCoreStatic OpenMeshToolsStatic >>"$log" 2>&1
  # The module's own link reads the archives and fails; its object is what is needed.
  cmake --build "$build" -j"$(nproc)" --target geofair >>"$log" 2>&1 || true
  test -f "$build/native/CMakeFiles/geofair.dir/python/bindings.cpp.o"
  module="$out/$target/geofair.cpython-darwin.so"
  mapfile -t objects < <(find "$build/native/CMakeFiles" "$build/_deps/openmesh-build" -name '*.o' \
    \( -path '*geofair.dir*' -o -path '*geofair_core.dir*' -o -path '*Static.dir*' \))
  "$tools/c++" -O2 -shared -Wl,-undefined,dynamic_lookup -o "$module" "${objects[@]}"
  exports=$("$nm" -g --defined-only "$module")
  grep -q ' T _PyInit_geofair$' <<< "$exports" || { echo "$target: no PyInit_geofair" >&2; exit 1; }
  loads=$("$objdump" --macho --dylibs-used "$module" | tail -n +2 | grep -v "$module" | awk '{print $1}')
  [ "$loads" = "/usr/lib/libSystem.B.dylib" ] || { echo "$target: loads $loads" >&2; exit 1; }
  echo "$target: $(file -b "$module" | cut -d, -f1); exports PyInit_geofair; loads $loads"
done

target=x86_64-windows-gnu
openmesh=$(find "$out" -path '*_deps/openmesh-src/OpenMesh/src' -type d | head -1)
mkdir -p "$out/$target"
for source in native/src/*.cpp; do
  "$zig" c++ -target "$target" -std=c++17 -O1 -c "$source" -Inative/include -I/usr/include/eigen3 \
    -I"$openmesh" -DGEOFAIR_PORTABLE -D_USE_MATH_DEFINES -w -o "$out/$target/$(basename "$source" .cpp).obj" \
    >>"$log" 2>&1
done
echo "$target: the library's $(ls native/src/*.cpp | wc -l) sources compiled"
