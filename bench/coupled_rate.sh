#!/usr/bin/env bash
# The coupled parcel-sub-step rate against the standalone DEM, measured in one sitting
# (docs/performance.md, "Measured"): the standalone DEM benchmark (bench_dem_layer, median of
# REPS repetitions) right before and right after a paper-scene run to END on THREADS threads,
# then the coupled rate (parcel-sub-steps stepped per second of coupled time: sample, implicit exchange,
# deposit, DEM contacts, integration, rebuilds; from the run's `work:` and `time:` lines)
# as a share of the mean of the two standalone medians. The host's speed drifts, which is
# why the yardstick is measured on both sides of the run and both values are printed.
#   bash bench/coupled_rate.sh [BUILD_DIR] [THREADS] [END] [REPS] [SCENE]
# Defaults: build/release, 2 threads, 0.6e-3 s (about 4 min on 2 threads), 3 repetitions,
# cases/paper/vertical_shock.toml.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build/release}
threads=${2:-2}
end=${3:-0.6e-3}
reps=${4:-3}
scene=${5:-$here/cases/paper/vertical_shock.toml}
work=$(mktemp -d -t dustlift-coupled-rate.XXXXXX)
trap 'rm -rf "$work"' EXIT

standalone() {  # median particle-steps/s (M) of bench_dem_layer at $threads threads
  # One repetition prints the run itself; several print their aggregates, of which the median.
  local row='real_time'
  [ "$reps" -gt 1 ] && row='real_time_median'
  "$build/bench/bench_dem_layer" --benchmark_filter="/$threads/" --benchmark_repetitions="$reps" \
    --benchmark_report_aggregates_only=true 2>/dev/null |
    sed -n "s/^BM_DemReferenceLayer\/[0-9]*\/iterations:1\/$row .*particle_steps_per_s=\([0-9.]*\)M.*/\1/p"
}

before=$(standalone)
"$build/dustlift" run "$scene" --set run.end_time="$end" -t "$threads" --out "$work/run" > "$work/out.txt" 2>&1
after=$(standalone)
[ -n "$before" ] && [ -n "$after" ] || { echo "bench_dem_layer printed no rate" >&2; exit 1; }
python3 - "$before" "$after" "$work/run/run.log" "$threads" <<'PY'
import re, sys
before, after = float(sys.argv[1]), float(sys.argv[2])
log = open(sys.argv[3]).read()
threads = sys.argv[4]
done = re.findall(r"^done: .*$", log, re.M)[-1]
stepped = int(re.findall(r"([0-9]+) parcel-sub-steps", log)[-1])
times = {k.strip(): float(v) for k, v in re.findall(r"([A-Za-z ]+?) ([0-9.]+) s", log.split("time:")[-1])}
phases = ("coupling sample", "implicit exchange", "deposit", "DEM contacts", "integration", "rebuilds")
coupled = sum(times[p] for p in phases)
rate = stepped / coupled / 1e6
mean = 0.5 * (before + after)
print(done)
print("coupled phases: " + ", ".join(f"{p} {times[p]:.3g} s" for p in phases) + f"; total {coupled:.1f} s")
print(f"coupled rate {rate:.1f} M parcel-sub-steps/s on {threads} thread(s); standalone DEM "
      f"{before:.1f} M/s before, {after:.1f} M/s after (medians): {100 * rate / mean:.1f} % of their mean")
PY
