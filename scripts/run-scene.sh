#!/usr/bin/env bash
# Runs one scene with an existing build, then makes figures and offscreen renders.
# Usage: bash scripts/run-scene.sh SCENE OUTDIR [dustlift run options...] [-- render.py options...]
# SCENE and OUTDIR are taken relative to the current folder (the script does not change it).
# Options after `--` go to pvstates/render.py instead of its default pressure and vorticity
# views, e.g. `-- --field dust_concentration --log --x 0 0.05 --y -0.002 0.006 --stretch 2`.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
if [ $# -lt 2 ]; then
  echo "usage: bash scripts/run-scene.sh SCENE OUTDIR [dustlift run options...] [-- render.py options...]" >&2
  exit 2
fi
scene=$1; out=$2; shift 2
run_options=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do run_options+=("$1"); shift; done
[ $# -gt 0 ] && shift  # the --
render_options=("$@")
"$root/build/release/dustlift" run "$scene" --out "$out" ${run_options[@]+"${run_options[@]}"}
/usr/bin/python3 "$root/analysis/make_figures.py" "$out"
# A private X server per render (scripts/with-xvfb.sh; xvfb-run -a races for displays);
# one more attempt if the render still fails.
for attempt in 1 2; do
  if bash "$root/scripts/with-xvfb.sh" pvbatch "$root/pvstates/render.py" "$out" \
    ${render_options[@]+"${render_options[@]}"}; then
    echo "output in $out"
    exit 0
  fi
  echo "run-scene.sh: render attempt $attempt failed" >&2
done
echo "run-scene.sh: the renders failed (the run and its figures are in $out)" >&2
exit 1
