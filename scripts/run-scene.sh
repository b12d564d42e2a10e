#!/usr/bin/env bash
# Runs one scene with an existing build, then makes figures and offscreen renders.
# Usage: bash scripts/run-scene.sh SCENE OUTDIR [extra dustlift run options, e.g. --overwrite]
# SCENE and OUTDIR are taken relative to the current folder (the script does not change it).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
if [ $# -lt 2 ]; then
  echo "usage: bash scripts/run-scene.sh SCENE OUTDIR [dustlift run options...]" >&2
  exit 2
fi
scene=$1; out=$2; shift 2
"$root/build/release/dustlift" run "$scene" --out "$out" "$@"
/usr/bin/python3 "$root/analysis/make_figures.py" "$out"
# A private X server per render (scripts/with-xvfb.sh; xvfb-run -a races for displays);
# one more attempt if the render still fails.
for attempt in 1 2; do
  if bash "$root/scripts/with-xvfb.sh" pvbatch "$root/pvstates/render.py" "$out"; then
    echo "output in $out"
    exit 0
  fi
  echo "run-scene.sh: render attempt $attempt failed" >&2
done
echo "run-scene.sh: the renders failed (the run and its figures are in $out)" >&2
exit 1
