#!/usr/bin/env bash
# The main job: Blender (headless) fairs a region of a real mesh with the add-on and writes
# the result and a before/after picture to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p out
blender --background --factory-startup --python-exit-code 1 \
  --python scripts/main_job.py -- --addon build/addon --out out
