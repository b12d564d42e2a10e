#!/usr/bin/env bash
# Threads against ranks on every scene of cases/ (docs/parallel.md, "Which layout"), in one
# sitting: each scene run whole, as a user runs it, REPS rounds of two runs in turn,
#   T: 1 rank x CORES threads (`dustlift run SCENE -t CORES`),
#   R: CORES ranks x 1 thread (`mpirun -np CORES dustlift run SCENE -t 1`),
# timed from the command's start to its exit (start-up and outputs included), then per scene
# the medians, R/T and what `dustlift info` recommends. A scene the ranks refuse (exit 2, e.g. a
# periodic channel with particles) is listed as such.
#   bash bench/layouts.sh [BUILD_DIR] [REPS] [CORES] [SCENE...]
# Defaults: build/release, 2 rounds, 2 cores, every scene of cases/ (studies and data apart;
# about 30 min on 2 cores).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build/release}
reps=${2:-2}
cores=${3:-2}
shift $(($# < 3 ? $# : 3))
if [ $# -gt 0 ]; then
  scenes=("$@")
else
  mapfile -t scenes < <(cd "$here" && find cases -name '*.toml' -not -path '*/studies/*' -not -path '*/data/*' | sort)
fi
work=$(mktemp -d -t dustlift-layouts.XXXXXX)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
mpirun=(mpirun --oversubscribe --bind-to none -np "$cores")

timed() {  # prints the wall seconds of the command, or "refused" / "failed (exit N)"
  local start end rc=0
  start=$(date +%s.%N)
  "$@" > "$work/out.txt" 2>&1 || rc=$?
  end=$(date +%s.%N)
  if [ "$rc" -eq 0 ]; then
    awk -v a="$start" -v b="$end" 'BEGIN {printf "%.3f\n", b - a}'
  elif [ "$rc" -eq 2 ]; then
    echo refused
  else
    echo "failed (exit $rc)"
  fi
}
median() { sort -g | awk '{v[NR]=$1} END {if (NR == 0) print "-"; else print (NR % 2) ? v[(NR+1)/2] : (v[NR/2] + v[NR/2+1]) / 2}'; }

printf '%-45s %10s %10s %7s  %s\n' scene "T (s)" "R (s)" "R/T" "info recommends"
for scene in "${scenes[@]}"; do
  path=$scene
  [ -f "$path" ] || path=$here/$scene
  : > "$work/T" && : > "$work/R"
  for _ in $(seq 1 "$reps"); do
    rm -rf "$work/run"
    timed "$build/dustlift" run "$path" -t "$cores" --out "$work/run" >> "$work/T"
    rm -rf "$work/run"
    OMP_NUM_THREADS=1 timed "${mpirun[@]}" "$build/dustlift" run "$path" -t 1 --out "$work/run" >> "$work/R"
  done
  t=$({ grep -E '^[0-9.]+$' "$work/T" || true; } | median)
  r=$({ grep -E '^[0-9.]+$' "$work/R" || true; } | median)
  if grep -qv -E '^[0-9.]+$' "$work/R"; then r=$(grep -v -E '^[0-9.]+$' "$work/R" | head -1 | tr ' ' '_'); fi
  ratio=$(awk -v t="$t" -v r="$r" 'BEGIN {if (r + 0 > 0 && t + 0 > 0) printf "%.3f", r / t; else print "-"}')
  advice=$("$build/dustlift" info "$path" -t "$cores" --no-estimate 2>/dev/null | sed -n 's/^layout: //p' | cut -c1-60)
  printf '%-45s %10s %10s %7s  %s\n' "$scene" "$t" "$r" "$ratio" "${advice:--}"
  echo "  all T: $(tr '\n' ' ' < "$work/T")  all R: $(tr '\n' ' ' < "$work/R")"
done
