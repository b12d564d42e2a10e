#!/usr/bin/env bash
# 1 rank against 2 ranks on the paper grid (docs/parallel.md), in one sitting:
# cases/paper/vertical_shock_gas.toml to END, REPS rounds of three runs in turn,
#   A: 1 rank x 2 threads (OpenMP only, today's default), B: 2 ranks x 1 thread (MPI only),
#   C: 1 rank x 1 thread (the yardstick both divide),
# then the medians of each and the ratios A/B, C/A, C/B (wall time of the time loop, from
# run.log's `done:` line), the halo volume per rank and step from B's `work:` line, and the
# loopback timings of bench_mpi_halo_exchange. Results are bitwise the same in A, B and C
# (checked on the last round's checkpoints when python3-h5py is present).
#   bash bench/mpi_ranks.sh [BUILD_DIR] [END] [REPS] [SCENE]
# Defaults: build/release, 0.2e-3 s (about 1 min per round), 3 rounds, the paper grid without
# dust; SCENE = cases/paper/vertical_shock.toml times the paper scene with its dust (the
# work line then splits the time into gas, coupling, DEM and the observers' gather).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build/release}
end=${2:-0.2e-3}
reps=${3:-3}
scene=${4:-$here/cases/paper/vertical_shock_gas.toml}
work=$(mktemp -d -t dustlift-mpi-ranks.XXXXXX)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
mpirun=(mpirun --oversubscribe --bind-to none)
common=(--set "run.end_time=$end" --set output.interval=1e-4 --set output.vtk=false --overwrite)

wall() { sed -n 's/^done: .* in \([0-9.]*\) s wall$/\1/p' "$1/run.log"; }
median() { sort -g | awk '{v[NR]=$1} END {print (NR % 2) ? v[(NR+1)/2] : (v[NR/2] + v[NR/2+1]) / 2}'; }

for r in $(seq 1 "$reps"); do
  "$build/dustlift" run "$scene" -t 2 --out "$work/A" "${common[@]}" > /dev/null 2>&1
  echo "A $(wall "$work/A")" >> "$work/times"
  OMP_NUM_THREADS=1 "${mpirun[@]}" -np 2 "$build/dustlift" run "$scene" -t 1 --out "$work/B" "${common[@]}" > /dev/null 2>&1
  echo "B $(wall "$work/B")" >> "$work/times"
  "$build/dustlift" run "$scene" -t 1 --out "$work/C" "${common[@]}" > /dev/null 2>&1
  echo "C $(wall "$work/C")" >> "$work/times"
  echo "round $r: $(tail -3 "$work/times" | tr '\n' ' ')"
done
a=$(awk '$1 == "A" {print $2}' "$work/times" | median)
b=$(awk '$1 == "B" {print $2}' "$work/times" | median)
c=$(awk '$1 == "C" {print $2}' "$work/times" | median)
echo "$(basename "$scene") to $end s; medians of $reps (s):"
echo "  A 1 rank x 2 threads: $a   (all: $(awk '$1 == "A" {printf "%s ", $2}' "$work/times"))"
echo "  B 2 ranks x 1 thread: $b   (all: $(awk '$1 == "B" {printf "%s ", $2}' "$work/times"))"
echo "  C 1 rank x 1 thread:  $c   (all: $(awk '$1 == "C" {printf "%s ", $2}' "$work/times"))"
awk -v a="$a" -v b="$b" -v c="$c" 'BEGIN {printf "  A/B %.3f   speed-up over one thread: OpenMP %.2fx, MPI %.2fx\n", a / b, c / a, c / b}'
grep -E '^(work|time)' "$work/A/run.log" | sed 's/^/  A /'
grep -E '^(work|time)' "$work/B/run.log" | sed 's/^/  B /'
if /usr/bin/python3 -c 'import h5py' 2> /dev/null; then
  /usr/bin/python3 - "$work" << 'PY'
import sys, h5py, numpy as np
w = sys.argv[1]
files = {k: h5py.File(f"{w}/{k}/checkpoint.h5") for k in "ABC"}
names = [n for n in files["A"]["gas"]]
same = all(np.array_equal(files["A"]["gas"][n][()].view(np.uint8), files[k]["gas"][n][()].view(np.uint8))
           for k in "BC" for n in names)
print(f"  gas state of A, B and C bitwise equal: {same} ({len(names)} arrays)")
PY
fi
echo "loopback (bench_mpi_halo_exchange, 2 ranks):"
"${mpirun[@]}" -np 2 "$build/bench/bench_mpi_halo_exchange" | sed 's/^/  /'
