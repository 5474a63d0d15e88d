#!/usr/bin/env bash
# Runs every test: the C++ unit tests of the numerical building blocks (ctest), the native
# library through the Python module, the add-on's bpy-free logic, and the add-on inside
# Blender 3.4 (Debian) and the bpy module from PyPI.
set -euo pipefail
cd "$(dirname "$0")/.."
# The project venv that scripts/setup.sh makes (where it is: else the python3 on PATH).
if [ -f .venv/bin/activate ]; then
  # shellcheck disable=SC1091
  source .venv/bin/activate
fi
export PYTHONPATH="$PWD/build/python${PYTHONPATH:+:$PYTHONPATH}"
# Style first (ruff.toml): a lint failure fails the run like a test would.
python3 -m ruff check addon tests bench scripts examples dev native/python/cli
python3 -m ruff format --check addon tests bench scripts examples dev native/python/cli
# Shape: no function of the library or the add-on over 80 lines (lizard names it), and no
# header of the library's internals includes an API header above types.h, errors.h, tuning.h.
python3 -m lizard -l cpp -l python -L 80 -C 1000 -a 100 -w native/src addon
python3 scripts/check_layers.py
# The C++ unit tests (native/tests, GoogleTest).
ctest --test-dir build --output-on-failure --no-tests=error
# A short libFuzzer run of the C++ entry points (scripts/run_fuzz.sh SECONDS for a long one).
bash scripts/run_fuzz.sh 30
# The solver tests against the portable build (GEOFAIR_PORTABLE: Eigen's sparse solvers, what
# a source build without SuiteSparse gets; no shipped package uses it).
GEOFAIR_BUILD="$PWD/build-portable" PYTHONPATH="$PWD/build-portable/python" python3 -m pytest -q \
  -p no:cacheprovider tests/test_fairing.py tests/test_newton.py tests/test_bilaplacian.py
# Two workers (pytest-xdist), each test file on one of them: a file's module fixtures (a
# wheel's venv, Blender's profile, wine's prefix) are made once.
exec python3 -m pytest -q -n 2 --dist loadfile "$@" tests
