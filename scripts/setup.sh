#!/usr/bin/env bash
# Installs what geofair needs on Debian 12 (apt-get, pip) and builds it into build/.
# Run as root or with sudo available.
set -euo pipefail
cd "$(dirname "$0")/.."
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends \
  cmake g++ make libeigen3-dev libopenmesh-dev libsuitesparse-dev libopenblas-dev pybind11-dev \
  libcgal-dev libcgal-demo \
  blender python3-numpy xvfb clang-14 libclang-rt-14-dev >/dev/null
# Blender as a Python module: the 4.5 LTS line, the current long-term release for Python 3.11.
python3 -m pip install -q --disable-pip-version-check \
  "pybind11>=2.12" pytest ruff numpy scipy matplotlib "bpy==4.5.*"

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
