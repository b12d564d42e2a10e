#!/usr/bin/env bash
# Runs one scene with an existing build, then makes figures and offscreen renders.
# Usage: bash scripts/run-scene.sh SCENE OUTDIR [extra dustlift run options...]
set -euo pipefail
cd "$(dirname "$0")/.."
scene=$1; out=$2; shift 2
./build/release/dustlift run "$scene" --out "$out" "$@"
if [ -f analysis/make_figures.py ]; then
  /usr/bin/python3 analysis/make_figures.py "$out"
fi
if [ -f pvstates/render.py ]; then
  xvfb-run -a pvbatch pvstates/render.py "$out"
fi
echo "output in $out"
