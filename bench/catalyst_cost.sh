#!/usr/bin/env bash
# Cost of the ParaView Catalyst adaptor (docs/catalyst.md), medians of REPS runs of the
# quickstart scene for STEPS steps in one sitting:
#   off      no [insitu.catalyst] section (nothing of ParaView loaded)
#   nothing  catalyst/do_nothing.py at every step: the adaptor's own cost per delivery
#            (gathering the arrays, wrapping them, RequestDataDescription + CoProcess)
#   render   catalyst/pressure_parcels.py every RENDER_EVERY steps: a 1600 x 500 PNG render
# and the start-up cost (ParaView + Python import, Xvfb) as the wall-time difference left
# after the per-delivery costs. Usage: bash bench/catalyst_cost.sh [BUILD_DIR] [REPS] [STEPS]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build/release}
reps=${2:-5}
steps=${3:-300}
render_every=${RENDER_EVERY:-20}
work=$(mktemp -d -t dustlift-catalyst-bench.XXXXXX)
trap 'rm -rf "$work"' EXIT
scene="$here/cases/quickstart.toml"
common=(--set "run.max_steps=$steps" --set run.progress_interval=1000 --set output.interval=0)

run_one() {  # name, extra TOML section file or "" -> prints wall, deliveries, ms/delivery, gather ms
  local name=$1 section=$2 k=$3 s="$scene"
  if [ -n "$section" ]; then
    s="$work/$name.toml"
    cat "$scene" "$section" > "$s"
  fi
  "$build/dustlift" run "$s" --out "$work/$name.$k" "${common[@]}" > /dev/null 2>&1
  /usr/bin/python3 - "$work/$name.$k/run.log" <<'PY'
import re, sys
log = open(sys.argv[1]).read()
wall = float(re.search(r"done: .* after (\d+) steps in ([0-9.]+) s wall", log).group(2))
m = re.search(r"catalyst: (\d+) deliveries, ([0-9.]+) s in the pipelines", log)
g = re.search(r"catalyst: (\d+) frames gathered in ([0-9.]+) s", log)
d = int(m.group(1)) if m else 0
print(wall, d, 1e3 * float(m.group(2)) / d if d else 0.0, 1e3 * float(g.group(2)) / d if d else 0.0)
PY
}

cat > "$work/nothing.sec" <<EOF2

[insitu.catalyst]
scripts = ["$here/catalyst/do_nothing.py"]
interval_steps = 1
EOF2
cat > "$work/render.sec" <<EOF2

[insitu.catalyst]
scripts = ["$here/catalyst/pressure_parcels.py"]
interval_steps = $render_every
EOF2

for k in $(seq 1 "$reps"); do
  for name in off nothing render; do
    sec=""
    [ "$name" != off ] && sec="$work/$name.sec"
    echo "$name $(run_one "$name" "$sec" "$k")" >> "$work/results.txt"
  done
done
/usr/bin/python3 - "$work/results.txt" "$steps" "$render_every" "$(nproc)" <<'PY'
import statistics as st, sys
rows = [l.split() for l in open(sys.argv[1])]
steps, every = int(sys.argv[2]), int(sys.argv[3])
def med(name, col): return st.median(float(r[col]) for r in rows if r[0] == name)
off, nothing, render = med("off", 1), med("nothing", 1), med("render", 1)
dn, dr = med("nothing", 2), med("render", 2)
pn, pr = med("nothing", 3), med("render", 3)
gn, gr = med("nothing", 4), med("render", 4)
startup = nothing - off - dn * (pn + gn) / 1e3
print(f"quickstart scene, {steps} steps, {len(rows)//3} runs each, medians ({sys.argv[4]} cores)")
print("| case | wall s | deliveries | pipeline ms/delivery | gather ms/delivery | wall vs off |")
print("|---|---|---|---|---|---|")
print(f"| no Catalyst section | {off:.2f} | 0 | - | - | 1.00 |")
print(f"| do-nothing script every step | {nothing:.2f} | {dn:.0f} | {pn:.2f} | {gn:.2f} | {nothing/off:.2f} |")
print(f"| pressure + parcels PNG every {every} steps | {render:.2f} | {dr:.0f} | {pr:.1f} | {gr:.2f} | {render/off:.2f} |")
print(f"start-up (ParaView + Python import, Xvfb, finalize): {startup:.2f} s")
PY
