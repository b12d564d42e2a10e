#!/usr/bin/python3
"""What a choice of physics does to dust lifting: the numbers a dust-lifting study reports, side
by side for runs of one scene that differ in their closures (a Markdown table).

Usage: /usr/bin/python3 analysis/closure_sensitivity.py LABEL=RUN LABEL=RUN ... [--time SECONDS]

For each run (a finished run folder) at --time (default: the last output of the first run):
  lifting delay    the distance behind the shock where the surface first stands 0.1 mm above the
                   layer's top, as docs/results.md reads it (analysis/paper_compare.py)
  h at x           the dust-surface height above the layer's top at the stations of docs/results.md
                   (smoothed as there), and the scene's own stations (surface_height_stations.csv)
  lifted mass      series/dust_cloud.csv: the dust above the layer (g per metre of span) and its
                   share of the layer
  first lifted     how far behind the shock the first lifted dust lies (dust_cloud.csv)
  band peaks       the surface band's upward contact force and downward drag, 0.01 ms windows
The last column is the second run against the first, in % (the first run is the reference).
"""
import argparse
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import paper_compare  # noqa: E402


def last_row_before(path, t):
    """The row of a series at the last time <= t (floats; None when the file is missing)."""
    if not os.path.exists(path):
        return None
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    best = None
    for r in rows:
        if float(r["time_s"]) <= t * (1 + 1e-9):
            best = r
    return {k: float(v) if v not in ("", "nan") else math.nan for k, v in best.items()} if best else None


def last_time(run):
    with open(os.path.join(run, "series", "dust_cloud.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    return float(rows[-1]["time_s"])


def numbers(run, t):
    c = paper_compare.compare(run, t)
    cloud = last_row_before(os.path.join(run, "series", "dust_cloud.csv"), t) or {}
    out = {"lifting delay (mm)": c.get("lifting_delay_mm", math.nan)}
    for s in paper_compare.STATIONS:
        key = "h_at_%03dmm_mm" % round(s * 1e3)
        out[f"h at {s * 1e3:.0f} mm (mm)"] = c.get(key, math.nan)
    stations = last_row_before(os.path.join(run, "series", "surface_height_stations.csv"), t) or {}
    for k, v in stations.items():
        if k.startswith("height_at_x"):
            x_mm = float(k[len("height_at_x"):-2].replace("p", ".")) * 1e3
            out[f"surface at the station x = {x_mm:.0f} mm (mm)"] = v * 1e3
    out["lifted mass (g/m)"] = cloud.get("lifted_mass_kg_per_m", math.nan) * 1e3
    out["lifted share (%)"] = cloud.get("lifted_share_1", math.nan) * 100
    shock, first = cloud.get("shock_x_m", math.nan), cloud.get("first_lifted_behind_shock_m", math.nan)
    out["first lifted dust behind the shock (mm)"] = first * 1e3
    surface = c.get("surface", {})
    out["surface band: contact up, peak (µN)"] = surface.get("contact_up_10us_uN", math.nan)
    out["surface band: drag, most downward (µN)"] = surface.get("drag_down_10us_uN", math.nan)
    out["_shock_mm"] = shock * 1e3
    return out


def fmt(v):
    if not math.isfinite(v):
        return "—"
    return f"{v:.3g}" if abs(v) < 100 else f"{v:.0f}"


def table(labels, results):
    head = "| quantity | " + " | ".join(labels) + (" | second vs first |" if len(labels) > 1 else " |")
    lines = [head, "|---" * (len(labels) + 1 + (len(labels) > 1)) + "|"]
    for q in results[0]:
        vals = [r[q] for r in results]
        if q.startswith("_") or not any(math.isfinite(v) for v in vals):
            continue
        row = f"| {q} | " + " | ".join(fmt(v) for v in vals) + " |"
        if len(labels) > 1:
            a, b = vals[0], vals[1]
            rel = (b - a) / abs(a) * 100 if math.isfinite(a) and math.isfinite(b) and a != 0 else math.nan
            row += f" {rel:+.0f} % |" if math.isfinite(rel) else " — |"
        lines.append(row)
    return "\n".join(lines)


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("runs", nargs="+", help="LABEL=RUN_FOLDER")
    p.add_argument("--time", type=float, default=None, help="s (default: the first run's last output)")
    a = p.parse_args(argv)
    pairs = []
    for item in a.runs:
        if "=" not in item:
            p.error(f"'{item}': give LABEL=RUN_FOLDER")
        label, run = item.split("=", 1)
        if not os.path.exists(os.path.join(run, "series", "dust_cloud.csv")):
            p.error(f"{run}: no series/dust_cloud.csv (not a finished run folder?)")
        pairs.append((label, run))
    t = a.time if a.time is not None else last_time(pairs[0][1])
    results = [numbers(run, t) for _, run in pairs]
    print(f"At t = {t * 1e3:.3g} ms (shock at x = {results[0]['_shock_mm']:.0f} mm):\n")
    print(table([lbl for lbl, _ in pairs], results))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
