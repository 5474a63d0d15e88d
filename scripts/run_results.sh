#!/usr/bin/env bash
# Reproduces the paper's figures and claims: builds (Release), then regenerates
# docs/RESULTS.md and docs/results/*.png (scripts/results.py; about 5-10 minutes on 2 cores).
# Extra arguments go to results.py (--out DIR, --failures DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -Wno-dev >/dev/null
cmake --build build -j2 >/dev/null
# This checkout's dev/ first: an editable geofair_dev of another clone would write its docs.
PYTHONPATH="$PWD/build/python:$PWD/dev${PYTHONPATH:+:$PYTHONPATH}" exec python3 scripts/results.py "$@"
