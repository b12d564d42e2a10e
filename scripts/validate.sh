#!/usr/bin/env bash
# Regenerates docs/validation.md: the shock-particle-curtain runs of cases/validation/ (every
# setting docs/validation.md compares, and the resolution study of the recommended one), then
# the comparison with the measured fronts (analysis/validation.py). About 11 min on 2 cores.
# Usage: bash scripts/validate.sh [RUNS_DIR]   (default out/validation; DUSTLIFT, THREADS override)
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${DUSTLIFT:-build/release/dustlift}
OUT=${1:-out/validation}
THREADS=${THREADS:-2}
SCENE=cases/validation/curtain_ms166.toml
mkdir -p "$OUT"
start=$(date +%s)
run() {
  local name=$1; shift
  echo "validate: $name"
  "$BIN" run "$SCENE" --out "$OUT/$name" --overwrite --threads "$THREADS" "$@" > "$OUT/$name.log" 2>&1
}
ADDED="--set coupling.added_mass=true"
# The closures and forces compared, on a 16 mm channel (646 parcels, 20 s a run): the same
# parcels for every setting.
H16="--set grid.y.end=0.016 --set grid.y.cells=64 --set particles.layer.y_max=0.016"
run paper $H16
run tenneti $H16 --set coupling.volume_fraction_correction=tenneti
run paper_added_mass $H16 $ADDED
run tenneti_added_mass $H16 --set coupling.volume_fraction_correction=tenneti $ADDED
run linear_added_mass $H16 --set coupling.volume_fraction_correction=linear $ADDED
run none_added_mass $H16 --set coupling.volume_fraction_correction=none $ADDED
run standard_drag $H16 --set coupling.compressibility_correction=false --set coupling.volume_fraction_correction=none \
  --set coupling.pressure_force=false --set coupling.magnus=false --set coupling.rotation_torque=false
# The recommended closures (the paper's effects with the added mass) at other resolutions:
# cells (16 mm channel), and the number of parcels sampling the curtain (the channel height);
# the scene itself is the 64 mm channel.
run rec_cells_05 $ADDED --set grid.y.end=0.016 --set particles.layer.y_max=0.016 --set grid.y.cells=32 \
  --set grid.x.cell_size=0.5e-3 --set grid.x.cells_below=30 --set grid.x.cells_above=25
run rec_cells_0125 $ADDED --set grid.y.end=0.016 --set particles.layer.y_max=0.016 --set grid.y.cells=128 \
  --set grid.x.cell_size=0.125e-3 --set grid.x.cells_below=120 --set grid.x.cells_above=100
run rec_height_4mm $ADDED --set grid.y.end=0.004 --set grid.y.cells=16 --set particles.layer.y_max=0.004
run rec_height_32mm $ADDED --set grid.y.end=0.032 --set grid.y.cells=128 --set particles.layer.y_max=0.032
run recommended $ADDED
run rec_height_128mm $ADDED --set grid.y.end=0.128 --set grid.y.cells=512 --set particles.layer.y_max=0.128
wall=$(( $(date +%s) - start ))
/usr/bin/python3 analysis/validation.py "$OUT" --wall "$wall" --markdown docs/validation.md --figures docs/validation \
  --recommended recommended --date "$(date -u +%Y-%m-%d)"
