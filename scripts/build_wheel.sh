#!/usr/bin/env bash
# Builds the Linux wheels of geofair into dist/, one per CPython (pybind11 has no stable ABI):
# the default python3 (3.11: Blender 4.2 to 5.0) and pyenv's 3.12 and 3.13 (3.13: Blender 5.1
# and later), where installed.
#
# GEOFAIR_WHEEL=manylinux_2_28 (default): the wheels that are shipped. zig (PyPI `ziglang`)
#   compiles for glibc 2.28 (Blender's own Linux builds, EL8, the VFX Reference Platform) with
#   LLVM's libc++ linked in statically; the portable dependency set (Eigen's sparse solvers,
#   no SuiteSparse, BLAS or OpenMP) and OpenMesh built from source and linked statically, so
#   the module needs nothing but glibc. auditwheel repair checks and tags it.
# GEOFAIR_WHEEL=system: this machine's GCC, SuiteSparse, OpenBLAS and OpenMP (faster on large
#   regions, docs/PACKAGING.md); auditwheel copies those libraries into geofair.libs/ and the
#   tag follows this machine's glibc (manylinux_2_35 on Debian 12).
#
#   pip wheel .        scikit-build-core over the CMake build (pyproject.toml)
#   auditwheel repair  the manylinux tag, every library beyond the allow-list in geofair.libs/
#   scripts/wheel_licenses.py  adds the bundled libraries' copyright files to the wheel
# Needs what scripts/setup.sh installs. PYTHONS="/path/to/python3.X ..." for another set.
set -euo pipefail
cd "$(dirname "$0")/.."
KIND="${GEOFAIR_WHEEL:-manylinux_2_28}"
if [ -z "${PYTHONS:-}" ]; then
  PYTHONS="python3"
  PYENV_ROOT="${PYENV_ROOT:-$HOME/.pyenv}"
  for minor in 12 13; do
    candidate=$(ls -d "$PYENV_ROOT"/versions/3."$minor".*/bin/python3."$minor" 2>/dev/null | sort -V | tail -1 || true)
    if [ -n "$candidate" ]; then PYTHONS="$PYTHONS $candidate"; fi
  done
fi
case "$KIND" in
  manylinux_2_28)
    # CMake takes a compiler as one program: wrappers around the zig binary of the ziglang
    # package (by path: pip's isolated build environment hides this Python's packages).
    python3 -c 'import ziglang' 2>/dev/null || python3 -m pip install --quiet ziglang
    zig=$(python3 -c 'import os, ziglang; print(os.path.join(os.path.dirname(ziglang.__file__), "zig"))')
    zig_dir="$PWD/build/zig"
    mkdir -p "$zig_dir"
    for tool in cc c++; do
      printf '#!/bin/sh\nexec "%s" %s -target x86_64-linux-gnu.2.28 "$@"\n' "$zig" "$tool" > "$zig_dir/$tool"
      chmod +x "$zig_dir/$tool"
    done
    export CMAKE_ARGS="-DCMAKE_C_COMPILER=$zig_dir/cc -DCMAKE_CXX_COMPILER=$zig_dir/c++ \
-DGEOFAIR_PORTABLE=ON -DGEOFAIR_FETCH_OPENMESH=ON -DGEOFAIR_OPENMP=OFF"
    plat=(--plat manylinux_2_28_x86_64 --only-plat)
    ;;
  system)
    plat=()
    ;;
  *)
    echo "GEOFAIR_WHEEL=$KIND: expected manylinux_2_28 or system" >&2
    exit 2
    ;;
esac
rm -rf dist/raw
mkdir -p dist/raw
rm -f dist/geofair-*.whl
for python in $PYTHONS; do
  tag=$("$python" -c 'import sys; print(f"cp{sys.version_info[0]}{sys.version_info[1]}")')
  echo "== $KIND $tag: $python"
  "$python" -m pip wheel . --no-deps -w dist/raw -Cbuild-dir="build/wheel-$KIND-$tag"
done
# auditwheel and the licence step run in the default python3 for every wheel.
for raw in dist/raw/geofair-*.whl; do
  python3 -m auditwheel repair "${plat[@]}" -w dist "$raw"
done
rm -rf dist/raw
for wheel in dist/geofair-*.whl; do
  compiled_in=()
  if [ "$KIND" = manylinux_2_28 ]; then
    tag=$(basename "$wheel" | cut -d- -f3)
    zig_lib=$(python3 -c 'import os, ziglang; print(os.path.dirname(ziglang.__file__))')/lib
    compiled_in=("OpenMesh=build/wheel-$KIND-$tag/_deps/openmesh-src/OpenMesh/LICENSE"
      "libcxx=$zig_lib/libcxx/LICENSE.TXT" "libcxxabi=$zig_lib/libcxxabi/LICENSE.TXT"
      "libunwind=$zig_lib/libunwind/LICENSE.TXT")
  fi
  python3 scripts/wheel_licenses.py "$wheel" "${compiled_in[@]}"
  python3 -m auditwheel show "$wheel"
done
