#!/usr/bin/env bash
# Regenerates docs/validation.md: the shock-particle-curtain runs of cases/validation/ (every
# setting docs/validation.md compares, each as an ensemble of bead samples, and the studies of the
# recommended physics; the list is analysis/validation.py's), then the comparison with the
# measured fronts (analysis/validation.py). About 25 min on 2 cores.
# A run whose log reports it done is kept, so an interrupted validation resumes where it stopped;
# FRESH=1 reruns everything.
# Usage: bash scripts/validate.sh [RUNS_DIR]   (default out/validation; DUSTLIFT, THREADS override)
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${DUSTLIFT:-build/release/dustlift}
OUT=${1:-out/validation}
THREADS=${THREADS:-2}
mkdir -p "$OUT"
start=$(date +%s)
runs=0
kept=0
while IFS=$'\t' read -r name seeds scene rest; do
  overrides=()
  if [ -n "$rest" ]; then
    IFS=$'\t' read -r -a keys <<< "$rest"
    for k in "${keys[@]}"; do overrides+=(--set "$k"); done
  fi
  for ((s = 0; s < seeds; s++)); do
    mkdir -p "$OUT/$name"
    if [ -z "${FRESH:-}" ] && grep -q '^done: t = ' "$OUT/$name/seed$s.log" 2> /dev/null; then
      echo "validate: $name seed $s already done"
      kept=$((kept + 1))
      continue
    fi
    echo "validate: $name seed $s"
    "$BIN" run "$scene" --out "$OUT/$name/seed$s" --overwrite --threads "$THREADS" \
      --set "particles.layer.seed=$((2012 + s))" "${overrides[@]}" > "$OUT/$name/seed$s.log" 2>&1
    runs=$((runs + 1))
  done
done < <(/usr/bin/python3 analysis/validation.py --list)
wall=$(( $(date +%s) - start ))
echo "validate: $runs runs in $wall s"
wall_arg=()
[ "$kept" -eq 0 ] && wall_arg=(--wall "$wall")
/usr/bin/python3 analysis/validation.py "$OUT" "${wall_arg[@]}" --markdown docs/validation.md \
  --figures docs/validation --date "$(date -u +%Y-%m-%d)"
