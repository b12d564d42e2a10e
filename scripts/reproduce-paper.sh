#!/usr/bin/env bash
# Regenerates docs/results.md's runs, numbers and figures: every run of the paper scene
# (cases/paper/vertical_shock.toml, 0.6 ms) that the comparison with Shimura & Matsuo uses,
# then analysis/paper_results.py over them.
#
# Usage: bash scripts/reproduce-paper.sh [OUTROOT] [--jobs N] [--only NAME[,NAME...]] [--list]
#   OUTROOT  folder of the runs (default out/paper), one sub-folder per run
#   --jobs   runs at a time, each on one thread (default 2: two runs on two cores
#            beat one run on two threads, docs/performance.md)
#   --only   just these runs (names as --list prints them)
# A run whose folder already ends in "done:" is kept; one with a checkpoint continues from
# it (an interrupted reproduction loses minutes, not runs). Needs an existing build
# (scripts/setup-and-run.sh or cmake --build --preset release).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
exe="$root/build/release/dustlift"
paper_scene="$root/cases/paper/vertical_shock.toml"
proxy_scene="$root/cases/paper/proxy.toml"

outroot=out/paper; jobs=2; only=""; list=0
while [ $# -gt 0 ]; do
  case "$1" in
    --jobs) jobs=$2; shift 2 ;;
    --only) only=$2; shift 2 ;;
    --list) list=1; shift ;;
    -*) echo "reproduce-paper.sh: unknown option $1" >&2; exit 2 ;;
    *) outroot=$1; shift ;;
  esac
done

# name | scene (paper: vertical_shock.toml to 0.6 ms; proxy: proxy.toml to 0.3 ms, both with
# the columnar layer they adopt, docs/results.md) | overrides.
runs=(
  "paper|paper|"
  "clm0|paper|coupling.magnus_coefficient=0"
  "cap03|paper|coupling.volume_fraction_cap=0.3"
  "h0p30|paper|coupling.magnus_coefficient=0 particles.contact.damping=3.0e-4"
  "clm0p5|paper|coupling.magnus_coefficient=0.5"
  "grid500|paper|grid.x.cell_size=5.0e-4 grid.x.cells_below=150 grid.y.cell_size=5.0e-4 grid.y.cells_above=12"
  "h0p50|paper|coupling.magnus_coefficient=0 particles.contact.damping=5.0e-4"
  "parcel200|paper|grid.x.cell_size=5.0e-4 grid.x.cells_below=150 grid.y.cell_size=5.0e-4 grid.y.cells_above=12 particles.parcel_diameter=2.0e-4"
  "grid1000|paper|grid.x.cell_size=1.0e-3 grid.x.cells_below=75 grid.y.cell_size=1.0e-3 grid.y.cells_above=6"
  "jittered|paper|particles.layer.arrangement=jittered_lattice"
  "clm0p1|paper|coupling.magnus_coefficient=0.1"
  "hexagonal|paper|particles.layer.arrangement=hexagonal"
  "xi2_none|paper|coupling.volume_fraction_correction=none"
  "nodegrid|paper|grid.y.uniform_start=-0.001875 grid.y.cells_below=1 grid.y.uniform_end=0.031875"
  "influence250|paper|coupling.influence_width=2.5e-4"
  "kn500k|paper|coupling.magnus_coefficient=0 particles.contact.k_n=5.0e5 particles.contact.k_t=1000"
  "kn100k|paper|coupling.magnus_coefficient=0 particles.contact.k_n=1.0e5 particles.contact.k_t=200"
  "kt10|paper|coupling.magnus_coefficient=0 particles.contact.k_t=10"
  "kt1000|paper|coupling.magnus_coefficient=0 particles.contact.k_t=1000"
  "kt10000|paper|coupling.magnus_coefficient=0 particles.contact.k_t=10000"
  "proxy_paper|proxy|"
  "proxy_jittered_clm1|proxy|particles.layer.arrangement=jittered_lattice"
  "proxy_hexagonal|proxy|particles.layer.arrangement=hexagonal"
  "proxy_nocoulomb|proxy|particles.contact.coulomb=false"
  "proxy_cap03|proxy|coupling.volume_fraction_cap=0.3"
  "proxy_clm0|proxy|coupling.magnus_coefficient=0"
  "proxy_clm10|proxy|coupling.magnus_coefficient=10"
  "proxy_kt10|proxy|coupling.magnus_coefficient=0 particles.contact.k_t=10"
  "proxy_kt1000|proxy|coupling.magnus_coefficient=0 particles.contact.k_t=1000"
  "proxy_kt10000|proxy|coupling.magnus_coefficient=0 particles.contact.k_t=10000"
  "proxy_kn100k|proxy|coupling.magnus_coefficient=0 particles.contact.k_n=1.0e5 particles.contact.k_t=200"
  "proxy_kn500k|proxy|coupling.magnus_coefficient=0 particles.contact.k_n=5.0e5 particles.contact.k_t=1000"
  "proxy_jittered|proxy|coupling.magnus_coefficient=0 particles.layer.arrangement=jittered_lattice"
  "proxy_xi2_none|proxy|coupling.volume_fraction_correction=none"
  "proxy_xi2_linear|proxy|coupling.volume_fraction_correction=linear"
  "proxy_nodegrid|proxy|grid.y.uniform_start=-0.001875 grid.y.cells_below=1 grid.y.uniform_end=0.011875"
  "proxy_nopressure|proxy|coupling.pressure_force=false"
  "proxy_nodrag|proxy|coupling.drag=false"
  "proxy_nodegrid_cap03|proxy|grid.y.uniform_start=-0.001875 grid.y.cells_below=1 grid.y.uniform_end=0.011875 coupling.volume_fraction_cap=0.3"
  "proxy_nodegrid_linear|proxy|grid.y.uniform_start=-0.001875 grid.y.cells_below=1 grid.y.uniform_end=0.011875 coupling.volume_fraction_correction=linear"
  "proxy_nodegrid_none|proxy|grid.y.uniform_start=-0.001875 grid.y.cells_below=1 grid.y.uniform_end=0.011875 coupling.volume_fraction_correction=none"
  "proxy_kn500k_clm1|proxy|particles.contact.k_n=5.0e5 particles.contact.k_t=1000"
  "loosetop|paper|particles.layer.loose_top_rows=2 particles.layer.loose_top_fill=0.5"
  "loosetop_xi2_none|paper|particles.layer.loose_top_rows=2 particles.layer.loose_top_fill=0.5 coupling.volume_fraction_correction=none"
  "loosetop_xi2_linear|paper|particles.layer.loose_top_rows=2 particles.layer.loose_top_fill=0.5 coupling.volume_fraction_correction=linear"
  "loosetop_clm0|paper|particles.layer.loose_top_rows=2 particles.layer.loose_top_fill=0.5 coupling.magnus_coefficient=0"
  "proxy_loosetop|proxy|particles.layer.loose_top_rows=2 particles.layer.loose_top_fill=0.5"
  "proxy_loosetop_xi2_none|proxy|particles.layer.loose_top_rows=2 particles.layer.loose_top_fill=0.5 coupling.volume_fraction_correction=none"
  "proxy_loosetop_xi2_linear|proxy|particles.layer.loose_top_rows=2 particles.layer.loose_top_fill=0.5 coupling.volume_fraction_correction=linear"
  "proxy_loosetop1|proxy|particles.layer.loose_top_rows=1 particles.layer.loose_top_fill=0.5"
  "proxy_loosetop1_xi2_linear|proxy|particles.layer.loose_top_rows=1 particles.layer.loose_top_fill=0.5 coupling.volume_fraction_correction=linear"
  "proxy_loosetop1_xi2_none|proxy|particles.layer.loose_top_rows=1 particles.layer.loose_top_fill=0.5 coupling.volume_fraction_correction=none"
  "proxy_centre_in_cell|proxy|coupling.influence_width=0"
)

if [ "$list" = 1 ]; then
  for r in "${runs[@]}"; do echo "${r%%|*}: ${r#*|}" | tr '|' ' '; done
  exit 0
fi
[ -x "$exe" ] || { echo "reproduce-paper.sh: build first ($exe missing)" >&2; exit 2; }
mkdir -p "$outroot"

run_one() {  # name scene overrides...
  local name=$1 which=$2; shift 2
  local out="$outroot/$name" scene=$paper_scene end=0.6e-3
  if [ "$which" = proxy ]; then scene=$proxy_scene; end=0.3e-3; fi
  if [ -f "$out/run.log" ] && grep -q '^done:' "$out/run.log"; then
    echo "$name: done already"; return 0
  fi
  local sets=(--set run.end_time=$end)
  for kv in "$@"; do sets+=(--set "$kv"); done
  local start=$SECONDS status=0
  if [ -f "$out/checkpoint.h5" ]; then
    "$exe" run --restart "$out/checkpoint.h5" --set run.end_time=$end --threads 1 >"$outroot/$name.log" 2>&1 || status=$?
  else
    "$exe" run "$scene" "${sets[@]}" --out "$out" --overwrite --threads 1 >"$outroot/$name.log" 2>&1 || status=$?
  fi
  echo "$name: exit $status after $((SECONDS - start)) s"
  return 0
}
export -f run_one
export exe paper_scene proxy_scene outroot

selected=()
for r in "${runs[@]}"; do
  name=${r%%|*}
  if [ -z "$only" ] || [[ ",$only," == *",$name,"* ]]; then selected+=("$r"); fi
done
start=$SECONDS
# One line per run; trailing blanks stripped: xargs -L would join a line ending in one (a run
# without overrides, like "paper") with the next.
printf '%s\n' "${selected[@]}" | tr '|' ' ' | sed 's/[[:space:]]*$//' | xargs -P "$jobs" -L 1 bash -c 'run_one "$@"' _
echo "runs: $((SECONDS - start)) s"
/usr/bin/python3 "$root/analysis/paper_results.py" "$outroot" --docs "$root/docs/results" --results-md "$root/docs/results.md"
