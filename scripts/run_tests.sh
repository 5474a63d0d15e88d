#!/usr/bin/env bash
# Runs every test: the native library through the Python module, the add-on's bpy-free
# logic, and the add-on inside Blender 3.4 (Debian) and the bpy module from PyPI.
set -euo pipefail
cd "$(dirname "$0")/.."
export PYTHONPATH="$PWD/build/python${PYTHONPATH:+:$PYTHONPATH}"
exec python3 -m pytest -q "$@" tests
