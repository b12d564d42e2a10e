#!/usr/bin/env bash
# How OpenMP threads wait, measured on a late stretch of the paper scene (docs/performance.md,
# "Waiting threads"): a run to 0.6 ms is made once (or reused), then continued from its
# checkpoint to END on 2 threads with each wait policy, on free cores and beside a process
# spinning on one core, and on 1 thread. Every continuation must end in the same state
# (checked: the checkpoints' bytes of every dataset, not only the wall times).
#   bash bench/wait_policy.sh [BUILD_DIR] [END] [RUN_DIR]
# BUILD_DIR default build/release; END default 0.62e-3 s; RUN_DIR a finished paper run to
# 0.6 ms to reuse (default: made in a temporary folder, about 4 minutes on 2 threads).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build/release}
end=${2:-0.62e-3}
work=$(mktemp -d -t dustlift-wait-bench.XXXXXX)
busy_pid=""
trap '[ -n "$busy_pid" ] && kill "$busy_pid" 2>/dev/null; rm -rf "$work"' EXIT
base=${3:-}
if [ -z "$base" ]; then
  base="$work/base"
  echo "making the 0.6 ms run (about 4 min on 2 threads) ..."
  "$build/dustlift" run "$here/cases/paper/vertical_shock.toml" --set run.end_time=0.6e-3 -t 2 --out "$base" > /dev/null 2>&1
fi
[ -f "$base/checkpoint.h5" ] || { echo "no checkpoint.h5 in $base" >&2; exit 2; }

continue_run() {  # name threads busy(0/1) env... -> prints "name wall_s"
  local name=$1 threads=$2 busy=$3; shift 3
  rm -rf "$work/$name"
  cp -r "$base" "$work/$name"
  if [ "$busy" = 1 ]; then
    (while :; do :; done) &
    busy_pid=$!
  fi
  env "$@" "$build/dustlift" run --restart "$work/$name/checkpoint.h5" --set run.end_time="$end" -t "$threads" > /dev/null 2>&1
  if [ -n "$busy_pid" ]; then kill "$busy_pid"; wait "$busy_pid" 2>/dev/null || true; busy_pid=""; fi
  printf '%-34s %8s s\n' "$name" "$(sed -n 's/^done: .* in \([0-9.]*\) s wall$/\1/p' "$work/$name/run.log" | tail -1)"
}

echo "continuing to t = $end s:"
continue_run one_thread 1 0 -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT
continue_run passive_free 2 0 -u GOMP_SPINCOUNT OMP_WAIT_POLICY=passive
continue_run default_free 2 0 -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT
continue_run spin30000_free 2 0 -u OMP_WAIT_POLICY GOMP_SPINCOUNT=30000
continue_run passive_beside_busy_core 2 1 -u GOMP_SPINCOUNT OMP_WAIT_POLICY=passive
continue_run default_beside_busy_core 2 1 -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT
/usr/bin/python3 - "$work" <<'PY'
import sys, h5py, numpy as np
work = sys.argv[1]
names = ["one_thread", "passive_free", "default_free", "spin30000_free", "passive_beside_busy_core",
         "default_beside_busy_core"]
def arrays(path):
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda n, o: out.__setitem__(n, o[()].tobytes()) if isinstance(o, h5py.Dataset) else None)
    return out
ref = arrays(f"{work}/{names[0]}/checkpoint.h5")
for n in names[1:]:
    other = arrays(f"{work}/{n}/checkpoint.h5")
    differ = [k for k in ref if other.get(k) != ref[k]]
    print(f"{n}: {len(differ)} of {len(ref)} checkpoint datasets differ from one_thread")
    if differ:
        sys.exit(1)
PY
