#!/usr/bin/env bash
# The paper's dust layer as plain DEM on 1 and 2 ranks (docs/parallel.md), in one
# sitting: bench_mpi_dem_layer_ranks (60,000 parcels, 400 mm x 2 mm, 1 m/s random, STEPS
# steps), REPS rounds of three runs in turn,
#   A: 1 rank x 2 threads (OpenMP only), B: 2 ranks x 1 thread (MPI only), C: 1 rank x 1 thread,
# then the medians, the ratios A/B, C/A, C/B, B's exchange volume per rank and step, and
# whether the three final states are bitwise equal (checksums of the gathered state).
#   bash bench/mpi_dem_ranks.sh [BUILD_DIR] [STEPS] [REPS]
# Defaults: build/release, 4000 steps (a few seconds per run), 3 rounds.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build/release}
steps=${2:-4000}
reps=${3:-3}
bench=$build/bench/bench_mpi_dem_layer_ranks
work=$(mktemp -d -t dustlift-mpi-dem.XXXXXX)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
export DUSTLIFT_BENCH_STEPS=$steps
mpirun=(mpirun --oversubscribe --bind-to none)

wall() { sed -n 's/^wall \([0-9.]*\) s .*/\1/p' "$1"; }
median() { sort -g | awk '{v[NR]=$1} END {print (NR % 2) ? v[(NR+1)/2] : (v[NR/2] + v[NR/2+1]) / 2}'; }

for r in $(seq 1 "$reps"); do
  OMP_NUM_THREADS=2 "$bench" > "$work/A.out"
  OMP_NUM_THREADS=1 "${mpirun[@]}" -np 2 "$bench" > "$work/B.out"
  OMP_NUM_THREADS=1 "$bench" > "$work/C.out"
  for k in A B C; do echo "$k $(wall "$work/$k.out")" >> "$work/times"; done
  echo "round $r: $(tail -3 "$work/times" | tr '\n' ' ')"
done
a=$(awk '$1 == "A" {print $2}' "$work/times" | median)
b=$(awk '$1 == "B" {print $2}' "$work/times" | median)
c=$(awk '$1 == "C" {print $2}' "$work/times" | median)
echo "DEM layer, 60,000 parcels, $steps steps; medians of $reps (s):"
echo "  A 1 rank x 2 threads: $a   (all: $(awk '$1 == "A" {printf "%s ", $2}' "$work/times"))"
echo "  B 2 ranks x 1 thread: $b   (all: $(awk '$1 == "B" {printf "%s ", $2}' "$work/times"))"
echo "  C 1 rank x 1 thread:  $c   (all: $(awk '$1 == "C" {printf "%s ", $2}' "$work/times"))"
awk -v a="$a" -v b="$b" -v c="$c" 'BEGIN {printf "  A/B %.3f   speed-up over one thread: OpenMP %.2fx, MPI %.2fx\n", a / b, c / a, c / b}'
grep '^rank' "$work/B.out" | sed 's/^/  B /'
sums=$(grep -h '^checksum' "$work/A.out" "$work/B.out" "$work/C.out" | sort -u | wc -l)
echo "  final states of A, B and C bitwise equal: $([ "$sums" = 1 ] && echo true || echo false) ($(grep -h '^checksum' "$work/B.out"))"
