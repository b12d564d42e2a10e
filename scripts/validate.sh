#!/usr/bin/env bash
# Regenerates docs/validation.md: the shock-particle-curtain runs of cases/validation/ (every
# setting docs/validation.md compares, each as an ensemble of bead samples, and the studies of the
# recommended physics; the list is analysis/validation.py's), then the comparison with the
# measured fronts (analysis/validation.py). About 25 min on 2 cores.
# Usage: bash scripts/validate.sh [RUNS_DIR]   (default out/validation; DUSTLIFT, THREADS override)
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${DUSTLIFT:-build/release/dustlift}
OUT=${1:-out/validation}
THREADS=${THREADS:-2}
SCENE=cases/validation/curtain_ms166.toml
mkdir -p "$OUT"
start=$(date +%s)
runs=0
while IFS=$'\t' read -r name seeds rest; do
  overrides=()
  if [ -n "$rest" ]; then
    IFS=$'\t' read -r -a keys <<< "$rest"
    for k in "${keys[@]}"; do overrides+=(--set "$k"); done
  fi
  for ((s = 0; s < seeds; s++)); do
    echo "validate: $name seed $s"
    mkdir -p "$OUT/$name"
    "$BIN" run "$SCENE" --out "$OUT/$name/seed$s" --overwrite --threads "$THREADS" \
      --set "particles.layer.seed=$((2012 + s))" "${overrides[@]}" > "$OUT/$name/seed$s.log" 2>&1
    runs=$((runs + 1))
  done
done < <(/usr/bin/python3 analysis/validation.py --list)
wall=$(( $(date +%s) - start ))
echo "validate: $runs runs in $wall s"
/usr/bin/python3 analysis/validation.py "$OUT" --wall "$wall" --markdown docs/validation.md \
  --figures docs/validation --date "$(date -u +%Y-%m-%d)"
