#!/usr/bin/python3
"""What accuracy costs in time: the studies of docs/accuracy-cost.md, run and reported.

Usage: /usr/bin/python3 analysis/accuracy_cost.py [--build build/release] [--work DIR]
           [--report docs/accuracy-cost.md] [--jobs 1] [--reuse] [--tiny --coupled-scene S]

Runs every study with `dustlift sweep` (each run on one thread, `--jobs` sweeps at a time, so
the wall times of a report are comparable with each other; the coupled runs in `--repeats`
rounds, their wall time the median), then writes the report (Markdown),
its raw CSV (REPORT_DIR/accuracy-cost/accuracy_cost.csv) and PNG plots of error against wall
time (log-log, each point labelled by its setting, the Pareto front drawn in black).

Studies:
  gas      Sod and Toro's test 3: density L1 error against the exact Riemann solution
           (analysis/sod_compare.py, the project's checker) for first order, MUSCL-2 and MUSCL-3
           with minmod and van Albada, 100-3200 cells, CFL 0.3 and 0.6.
  thermo   the Mach 1.44 shock (cases/verification/shock_mach144.toml) in calorically and
           thermally perfect air: cost and post-shock temperature.
  coupled  the report proxy (cases/paper/report_proxy.toml, the paper's physics on an 80 mm
           layer to 0.15 ms): dust-surface height h(x) at the end and band-force peaks against
           each study's finest run (grid 1000/500/250 um; parcel 200/100 um at 500 um cells;
           DEM Courant 0.05-0.4; k_n 500-50,000 N/m; skipping resting cells and parcels, exactly
           and within run.rest_tolerance = 1e-10), and
           the cost of each optional effect from one run with it off.
--tiny runs two-by-two versions of the studies on --coupled-scene (the suite's test).
--reuse keeps the sweeps whose summary.csv already lists every run as finished.
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import time
import tomllib
from concurrent.futures import ThreadPoolExecutor

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import sod_compare  # noqa: E402
from paper_compare import SMOOTHING, running_median  # noqa: E402

SCHEMES = [("first_order", "minmod", "1st"), ("muscl2", "minmod", "M2-mm"), ("muscl2", "van_albada", "M2-vA"),
           ("muscl3", "minmod", "M3-mm"), ("muscl3", "van_albada", "M3-vA")]


# ------------------------------------------------------------------ study definitions
def gas_studies(tiny):
    cells = [50, 100] if tiny else [100, 200, 400, 800, 1600, 3200]
    cfls = [0.6] if tiny else [0.3, 0.6]
    schemes = [SCHEMES[0], SCHEMES[3]] if tiny else SCHEMES
    problems = [("sod", "cases/verification/sod.toml")] if tiny else [
        ("sod", "cases/verification/sod.toml"), ("toro3", "cases/verification/toro3.toml")]
    out = []
    for name, scene in problems:
        for cfl in cfls:
            out.append({
                "name": f"gas_{name}_cfl{cfl}", "problem": name, "cfl": cfl, "scene": os.path.join(ROOT, scene),
                "vary": ["gas.scheme.reconstruction=" + ",".join(s[0] for s in schemes) +
                         ";gas.scheme.limiter=" + ",".join(s[1] for s in schemes),
                         "grid.x.cells=" + ",".join(str(c) for c in cells)],
                "set": [f"gas.scheme.cfl={cfl}", "output.interval=0"]})
    return out


def coupled_settings(tiny):
    """(study, label, overrides) of every coupled run; the first of each study is its reference."""
    def grid(w, below, above):
        return {"grid.x.cell_size": w, "grid.y.cell_size": w, "grid.x.cells_below": below, "grid.y.cells_above": above}
    if tiny:
        return [("courant", "nu 0.1", {"particles.courant": 0.1}), ("courant", "nu 0.2", {"particles.courant": 0.2}),
                ("effects", "all on", {}), ("effects", "no Magnus", {"coupling.magnus": "false"})]
    s = [("grid", "250 um", grid(2.5e-4, 24, 16)), ("grid", "500 um", grid(5e-4, 12, 8)),
         ("grid", "1000 um", grid(1e-3, 6, 4)),
         ("parcel", "100 um parcels", dict(grid(5e-4, 12, 8), **{"particles.parcel_diameter": 1e-4})),
         ("parcel", "200 um parcels", dict(grid(5e-4, 12, 8), **{"particles.parcel_diameter": 2e-4}))]
    s += [("courant", f"nu {c}", {"particles.courant": c}) for c in (0.05, 0.1, 0.2, 0.4)]
    # The chaos floor: a change that should not matter (the gas time step 1e-6 relative; the DEM
    # sub-step count is an integer, so a DEM Courant change that small changes nothing) against the base.
    s += [("noise", "CFL 0.5", {"gas.scheme.cfl": 0.5}), ("noise", "CFL 0.5000005", {"gas.scheme.cfl": 0.5000005})]
    s += [("k_n", f"k_n {k:g}", {"particles.contact.k_n": k}) for k in (5e4, 5e3, 5e2)]
    s += [("skip", "skipping off", {"run.skip_at_rest": "false"}), ("skip", "skipping on", {"run.skip_at_rest": "true"}),
          ("skip", "skipping within 1e-10", {"run.skip_at_rest": "true", "run.rest_tolerance": 1e-10})]
    s += [("effects", "all on", {}), ("effects", "inviscid", {"gas.transport.model": "inviscid"}),
          ("effects", "no Magnus", {"coupling.magnus": "false"}),
          ("effects", "no pressure force", {"coupling.pressure_force": "false"}),
          ("effects", "no rotation torque", {"coupling.rotation_torque": "false"}),
          ("effects", "no heat transfer", {"coupling.heat_transfer": "false"}),
          ("effects", "calorically perfect", {"gas.thermo": "calorically_perfect"}),
          ("effects", "one-way coupling", {"coupling.two_way": "false"}),
          # Options beyond the paper (off by default; docs/coupling.md, docs/validation.md): what
          # switching them on costs and changes.
          ("effects", "+ added mass", {"coupling.added_mass": "true"}),
          ("effects", "Tenneti drag", {"coupling.volume_fraction_correction": "tenneti"}),
          ("effects", "Osnes drag", {"coupling.volume_fraction_correction": "osnes"}),
          ("effects", "recommended physics (Osnes + added mass)",
           {"coupling.volume_fraction_correction": "osnes", "coupling.added_mass": "true"})]
    return s


def value_text(v):
    return v if isinstance(v, str) else repr(v)


def coupled_sweeps(binary, settings, scene, jobs, repeats):
    """The coupled runs as `jobs` sweeps of one combined axis each (every key in every row, at
    the base scene's value where a setting leaves it): all run at once, none twice."""
    base = flat_scene(binary, scene)
    keys = sorted({k for _, _, o in settings for k in o})
    unique = []
    for st in settings:
        row = tuple(value_text(st[2].get(k, base.get(k))) for k in keys)
        if row not in [u[0] for u in unique]:
            unique.append((row, st))
    chunks = [unique[i::jobs] for i in range(jobs)]
    out = []
    # Whole rounds one after another: a slow spell of the shared machine then slows every
    # setting of a round alike, and the median over rounds is each setting's cost.
    for r in range(repeats):
        for n, chunk in enumerate(chunks):
            if not chunk:
                continue
            axis = ";".join(k + "=" + ",".join(row[i] for row, _ in chunk) for i, k in enumerate(keys))
            out.append({"name": f"coupled_{n}_round{r + 1}", "scene": scene, "vary": [axis],
                        "set": ["output.interval=0"]})
    return out, keys, base


def flat_scene(binary, path):
    """Every key of the resolved scene (`dustlift info`, defaults filled in by the parser, the
    one source of defaults) as 'a.b.c' -> value text as --vary writes it."""
    text = subprocess.run([binary, "info", path], capture_output=True, text=True, check=True).stdout
    doc = tomllib.loads(text[text.index("# Resolved scene"):])
    flat = {}

    def walk(prefix, t):
        for k, v in t.items():
            if isinstance(v, dict):
                walk(prefix + k + ".", v)
            elif not isinstance(v, list):
                flat[prefix + k] = "true" if v is True else "false" if v is False else value_text(v)
    walk("", doc)
    return flat


# ------------------------------------------------------------------ running
def sweep_done(out):
    path = os.path.join(out, "summary.csv")
    if not os.path.isfile(path):
        return False
    rows = read_summary(path)
    return bool(rows) and all(float(r["exit_status_1"]) == 0 for r in rows)


def run_sweep(binary, sweep, work, reuse):
    out = os.path.join(work, sweep["name"])
    cmd = [binary, "sweep", sweep["scene"], "--out", out, "--threads", "1", "--overwrite"]
    for v in sweep["vary"]:
        cmd += ["--vary", v]
    for s in sweep["set"]:
        cmd += ["--set", s]
    # Reused only when the same sweep finished: its arguments are kept beside it.
    signature = "\n".join(cmd[2:]) + "\n"
    sig_path = out + ".args"
    seconds_path = out + ".seconds"
    if reuse and sweep_done(out) and os.path.isfile(sig_path) and open(sig_path).read() == signature:
        return out, float(open(seconds_path).read()) if os.path.isfile(seconds_path) else 0.0, True
    with open(sig_path, "w") as f:
        f.write(signature)
    t0 = time.time()
    with open(out + ".log", "w") as log:
        r = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT)
    if r.returncode not in (0, 3):
        raise SystemExit(f"accuracy_cost.py: {' '.join(cmd)} failed ({r.returncode}); see {out}.log")
    with open(seconds_path, "w") as f:
        f.write(f"{time.time() - t0:.3f}\n")
    return out, time.time() - t0, False


def read_summary(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def run_folder(sweep_dir, row):
    return os.path.join(sweep_dir, row["run"])


# ------------------------------------------------------------------ measurements
def surface_profile(folder):
    """h(x) at the last time of series/surface_height.csv as the 5 mm running median that
    docs/results.md reads the paper's curves with (one lone parcel lifts its column's surface
    by millimetres: the raw columns compare noise), NaN-free."""
    data = np.genfromtxt(os.path.join(folder, "series", "surface_height.csv"), delimiter=",", names=True)
    t = data["time_s"]
    last = data[t == t.max()]
    x, h = last["x_m"], running_median(last["x_m"], last["height_m"])
    ok = np.isfinite(h)
    return x[ok], h[ok]


def height_difference(folder, ref_folder, x_max):
    """max and mean |h - h_ref| over 0 < x < x_max on the reference's columns (interpolated)."""
    x, h = surface_profile(folder)
    xr, hr = surface_profile(ref_folder)
    sel = (xr > 0) & (xr < x_max) & (xr >= x.min()) & (xr <= x.max())
    if not sel.any():
        return float("nan"), float("nan")
    d = np.abs(np.interp(xr[sel], x, h) - hr[sel])
    return float(np.max(d)), float(np.mean(d))


def band_peak_difference(row, ref, band="surface"):
    """Largest |peak - peak_ref| over the band's force components (N), and which one."""
    best, which = 0.0, ""
    for key in row:
        if key.startswith(band + "_") and key.endswith("_peak_N"):
            a, b = float(row[key]), float(ref[key])
            if math.isfinite(a) and math.isfinite(b) and abs(a - b) >= best:
                best, which = abs(a - b), key[len(band) + 1:-len("_peak_N")]
    return best, which


def post_shock_temperature(folder):
    """Median T of the cells behind the shock (p above the mean of pre- and post-shock)."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLRectilinearGridReader
    t, path = sod_compare.last_dataset(folder)
    r = vtkXMLRectilinearGridReader()
    r.SetFileName(path)
    r.Update()
    cd = r.GetOutput().GetCellData()
    p, T = vtk_to_numpy(cd.GetArray("pressure")), vtk_to_numpy(cd.GetArray("temperature"))
    behind = p > 0.5 * (p.min() + p.max())
    return float(np.median(T[behind]))


def pareto(points):
    """Indices of the points no other point beats in both cost and error."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best = [], float("inf")
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


# ------------------------------------------------------------------ report
def plot_gas(rows, problem, path):
    fig, ax = plt.subplots(figsize=(8, 6))
    mine = [r for r in rows if r["problem"] == problem]
    colours = dict(zip([s[2] for s in SCHEMES], ["tab:gray", "tab:blue", "tab:cyan", "tab:red", "tab:orange"]))
    for scheme in colours:
        for cfl, style in ((0.3, "o--"), (0.6, "s-")):
            pts = sorted((r["wall_s"], r["error"], r["cells"]) for r in mine if r["scheme"] == scheme and r["cfl"] == cfl)
            if not pts:
                continue
            ax.plot([p[0] for p in pts], [p[1] for p in pts], style, color=colours[scheme], ms=4,
                    label=f"{scheme}, CFL {cfl}")
            for p in pts:
                ax.annotate(str(p[2]), (p[0], p[1]), fontsize=6, xytext=(2, 2), textcoords="offset points")
    pts = [(r["wall_s"], r["error"]) for r in mine]
    front = sorted(pts[i] for i in pareto(pts))
    ax.step([p[0] for p in front], [p[1] for p in front], "k-", where="post", lw=1.2, label="Pareto front")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time of the run [s] (1 thread)")
    ax.set_ylabel("density L1 error")
    ax.set_title(f"{problem}: accuracy against cost (labels: cells)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_coupled(rows, path, floor):
    """Mean |dh| against wall time; each study's reference (|dh| = 0 by definition) on the floor
    line; the Pareto front over the other settings."""
    fig, ax = plt.subplots(figsize=(8, 6))
    markers = {"grid": "s", "parcel": "D", "courant": "o", "k_n": "^", "skip": "v", "effects": "x", "noise": "*"}
    for study, m in markers.items():
        mine = [r for r in rows if r["study"] == study]
        if not mine:
            continue
        ax.plot([r["wall_s"] for r in mine], [max(r["mean_error"], floor) for r in mine], m, ms=6, label=study)
        for r in mine:
            if r["mean_error"] > 0:
                ax.annotate(r["setting"], (r["wall_s"], r["mean_error"]), fontsize=6, xytext=(3, 3),
                            textcoords="offset points")
    others = [r for r in rows if r["mean_error"] > 0 and math.isfinite(r["mean_error"])]
    pts = [(r["wall_s"], r["mean_error"]) for r in others]
    front = sorted(pts[i] for i in pareto(pts))
    ax.step([p[0] for p in front], [p[1] for p in front], "k-", where="post", lw=1.2, label="Pareto front")
    ax.axhline(floor, color="0.6", lw=0.8, ls=":")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time of the run [s] (1 thread)")
    ax.set_ylabel("mean |h - h_ref| (5 mm running median) over 0 < x < x_shock [m]")
    ax.set_title(f"coupled proxy: surface height error against cost\n(references, |dh| = 0, drawn on the dotted line {floor:.2g} m)",
                 fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def write_csv(path, gas_rows, thermo_rows, coupled_rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["study", "setting", "reference", "error", "error_unit", "wall_s", "steps", "mean_error_m",
                    "band_peak_difference_N", "band_peak_component", "post_shock_T_K", "folder"])
        for r in gas_rows:
            w.writerow([f"gas_{r['problem']}", r["label"], "exact Riemann solution", r["error"], "density L1",
                        r["wall_s"], r["steps"], "", "", "", "", os.path.relpath(r["folder"], ROOT)])
        for r in thermo_rows:
            w.writerow(["thermo", r["setting"], r["reference"], r["error"], "K (post-shock T)", r["wall_s"], r["steps"],
                        "", "", "", r["T"], os.path.relpath(r["folder"], ROOT)])
        for r in coupled_rows:
            w.writerow([r["study"], r["setting"], r["reference"], r["error"], "m (max |dh|)", r["wall_s"], r["steps"],
                        r["mean_error"], r["peak_diff"], r["peak_which"], "", os.path.relpath(r["folder"], ROOT)])


def report(args, gas_rows, thermo_rows, coupled_rows, elapsed, out_dir):
    lines = ["# What accuracy costs in time",
             "",
             f"Generated by `/usr/bin/python3 analysis/accuracy_cost.py` on {time.strftime('%Y-%m-%d')} "
             f"({os.cpu_count()} cores; {args.jobs} run{'s' if args.jobs > 1 else ''} at a time, each on one thread; the whole report took "
             f"{elapsed / 60:.0f} min). Raw numbers: `accuracy-cost/accuracy_cost.csv`. Wall times are whole runs "
             "(`dustlift sweep`'s `wall_time`), comparable within this report; error and cost of each row "
             "come from the same run." + (" With several runs at a time the timings of runs that shared the cores "
             "with different partners scatter by ~15 %." if args.jobs > 1 else ""),
             ""]
    if gas_rows:
        lines += ["## Gas: shock tubes against the exact solution", "",
                  "Density L1 error of the final state against the exact Riemann solution "
                  "(`analysis/sod_compare.py`'s `l1_errors`, tested in `tests/unit/test_analysis_scripts.cpp`), "
                  "by scheme (1st: first order; M2: MUSCL κ = −1; M3: MUSCL κ = 1/3; mm: minmod, vA: van Albada), "
                  "cells and CFL number.", ""]
        for problem in sorted({r["problem"] for r in gas_rows}):
            mine = [r for r in gas_rows if r["problem"] == problem]
            lines += [f"### {problem}", "", f"![{problem}](accuracy-cost/gas_{problem}.png)", "",
                      "| scheme | CFL | " + " | ".join(f"{c} cells" for c in sorted({r['cells'] for r in mine})) + " |",
                      "|---|---|" + "---|" * len({r['cells'] for r in mine})]
            for scheme in [s[2] for s in SCHEMES]:
                for cfl in sorted({r["cfl"] for r in mine}):
                    cells = [r for r in mine if r["scheme"] == scheme and r["cfl"] == cfl]
                    if not cells:
                        continue
                    cells.sort(key=lambda r: r["cells"])
                    lines.append(f"| {scheme} | {cfl} | " + " | ".join(
                        f"{r['error']:.2e} ({r['wall_s']:.2f} s)" for r in cells) + " |")
            pts = [(r["wall_s"], r["error"]) for r in mine]
            front = sorted((mine[i] for i in pareto(pts)), key=lambda r: r["wall_s"])
            lines += ["", "Pareto front (cheapest first): " + "; ".join(
                f"{r['label']} {r['error']:.2e} in {r['wall_s']:.2f} s" for r in front) + ".", ""]
    if thermo_rows:
        lines += ["## Gas: calorically against thermally perfect air (Mach 1.44 shock)", "",
                  "| model | post-shock T | wall | difference to thermally perfect |", "|---|---|---|---|"]
        for r in thermo_rows:
            lines.append(f"| {r['setting']} | {r['T']:.2f} K | {r['wall_s']:.2f} s | {r['error']:.2f} K |")
        lines.append("")
    if coupled_rows:
        studies = {r["study"] for r in coupled_rows}
        lines += ["## Coupled: the report proxy against each study's finest run", "",
                  f"Scene `{os.path.relpath(args.coupled_scene, ROOT)}`. Error: max |h − h_ref| of the dust-surface "
                  f"height (α_p = 1e-4, sub-cell; its {SMOOTHING * 1e3:g} mm running median, as docs/results.md "
                  "reads the paper's curves) at the end time over 0 < x < the reference's shock position; "
                  "band: the largest difference of the surface band's force peaks (contact, drag, pressure, Magnus; "
                  "`dustlift sweep`'s summary). Each row names its reference.", "",
                  "![coupled](accuracy-cost/coupled.png)", "",
                  "Wall: the median of the rounds (each round runs every setting once, one after another), "
                  "their range in brackets.", "",
                  "| study | setting | reference | max \\|Δh\\| | mean \\|Δh\\| | band peak Δ | wall | steps |",
                  "|---|---|---|---|---|---|---|---|"]
        for r in coupled_rows:
            lines.append(f"| {r['study']} | {r['setting']} | {r['reference']} | {r['error'] * 1e6:.3g} µm | "
                         f"{r['mean_error'] * 1e6:.3g} µm | "
                         f"{r['peak_diff'] * 1e6:.1f} µN ({r['peak_which']}) | {r['wall_s']:.1f} s "
                         f"({r['wall_min']:.1f}–{r['wall_max']:.1f}) | {r['steps']} |")
        if "effects" in studies:
            base = next(r for r in coupled_rows if r["study"] == "effects" and r["setting"] == r["reference"])
            lines += ["", "### The cost of each optional effect", "",
                      f"Share of the all-on run's wall time ({base['wall_s']:.1f} s) that switching the effect off "
                      "saves (negative: costs; for the options beyond the paper, switching them on), and what it "
                      "changes:", "", "| effect | wall | share saved | max \\|Δh\\| |",
                      "|---|---|---|---|"]
            for r in coupled_rows:
                if r["study"] == "effects" and r is not base:
                    lines.append(f"| {r['setting']} | {r['wall_s']:.1f} s | {100 * (1 - r['wall_s'] / base['wall_s']):+.1f} % "
                                 f"| {r['error'] * 1e6:.3g} µm |")
        noise = [r for r in coupled_rows if r["study"] == "noise" and r["setting"] != r["reference"]]
        floor = noise[0]["mean_error"] if noise else 0.0
        lines += ["", "## How to choose", ""]
        if noise:
            lines += [f"The coupled answer is chaotic at the level of single parcels: a time step changed by one part "
                      f"in a million (the gas CFL number of the `noise` row) moves the surface by {noise[0]['error'] * 1e3:.2f} mm at worst "
                      f"and {floor * 1e3:.3f} mm on average over x. Differences below that floor are not "
                      "resolved by one run; the criterion below uses the mean |Δh|.", ""]
        for study in ["grid", "parcel", "courant", "k_n", "skip"]:
            mine = [r for r in coupled_rows if r["study"] == study]
            if not mine:
                continue
            ref = next(r for r in mine if r["setting"] == r["reference"])
            _, h_ref = surface_profile(ref["folder"])
            lift = float(np.max(h_ref) - np.min(h_ref)) if len(h_ref) else float("nan")  # smoothed
            ok = [r for r in mine if r["mean_error"] <= 0.05 * lift]
            cheapest = min(ok, key=lambda r: r["wall_s"]) if ok else ref
            within_floor = [r["setting"] for r in mine if r is not ref and r["mean_error"] <= floor]
            lines.append(f"- {study}: the cheapest setting within 5 % of the finest answer (mean |Δh| ≤ "
                         f"{0.05 * lift * 1e3:.3f} mm, 5 % of the reference's {lift * 1e3:.2f} mm of lifting) is "
                         f"**{cheapest['setting']}**, {cheapest['wall_s']:.1f} s against {ref['wall_s']:.1f} s "
                         f"(×{ref['wall_s'] / cheapest['wall_s']:.2f})"
                         + (f"; within the chaos floor: {', '.join(within_floor)}." if within_floor else "."))
    for problem in sorted({r["problem"] for r in gas_rows}):
        mine = [r for r in gas_rows if r["problem"] == problem]
        default = [r for r in mine if r["scheme"] == "M3-mm" and r["cells"] == 400 and r["cfl"] == max(x["cfl"] for x in mine)]
        if default:
            d = default[0]
            ok = [r for r in mine if r["error"] <= d["error"]]
            c = min(ok, key=lambda r: r["wall_s"])
            lines.append(f"- gas ({problem}): the accuracy of the default scheme at 400 cells ({d['label']}, "
                         f"L1 {d['error']:.2e}, {d['wall_s']:.2f} s) is reached cheapest by **{c['label']}** "
                         f"({c['error']:.2e}, {c['wall_s']:.2f} s).")
    os.makedirs(out_dir, exist_ok=True)
    with open(args.report, "w") as f:
        f.write("\n".join(lines) + "\n")


# ------------------------------------------------------------------ main
def main(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--build", default=os.path.join(ROOT, "build", "release"))
    p.add_argument("--work", default=os.path.join(ROOT, "build", "accuracy-cost"), help="folder of the sweeps")
    p.add_argument("--report", default=os.path.join(ROOT, "docs", "accuracy-cost.md"))
    p.add_argument("--jobs", type=int, default=1, help="sweeps at a time (each run on one thread; 1: timings undisturbed)")
    p.add_argument("--reuse", action="store_true", help="keep finished sweeps of an earlier call")
    p.add_argument("--repeats", type=int, default=3, help="rounds of the coupled runs (wall time: their median)")
    p.add_argument("--tiny", action="store_true", help="two-by-two studies (the suite's test)")
    p.add_argument("--coupled-scene", default=os.path.join(ROOT, "cases", "paper", "report_proxy.toml"))
    p.add_argument("--thermo-scene", default=os.path.join(ROOT, "cases", "verification", "shock_mach144.toml"))
    args = p.parse_args(argv)
    args.coupled_scene = os.path.abspath(args.coupled_scene)
    binary = os.path.join(args.build, "dustlift")
    os.makedirs(args.work, exist_ok=True)
    t0 = time.time()

    gas = gas_studies(args.tiny)
    settings = coupled_settings(args.tiny)
    repeats = 1 if args.tiny else max(1, args.repeats)
    coupled, keys, base = coupled_sweeps(binary, settings, args.coupled_scene, max(1, args.jobs), repeats)
    thermo = [] if args.tiny else [{"name": "thermo", "scene": args.thermo_scene,
                                    "vary": ["gas.thermo=thermally_perfect,calorically_perfect"],
                                    "set": ["output.interval=0"]}]
    sweeps = thermo + gas + coupled
    with ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        done = dict(zip([s["name"] for s in sweeps],
                        pool.map(lambda s: run_sweep(binary, s, args.work, args.reuse), sweeps)))

    gas_rows = []
    for s in gas:
        folder = done[s["name"]][0]
        for row in read_summary(os.path.join(folder, "summary.csv")):
            scheme = next(x[2] for x in SCHEMES if x[0] == row["gas_scheme_reconstruction"]
                          and x[1] == row["gas_scheme_limiter"])
            errors, _ = sod_compare.l1_errors(run_folder(folder, row))
            cells = int(row["grid_x_cells"])
            gas_rows.append({"problem": s["problem"], "scheme": scheme, "cfl": s["cfl"], "cells": cells,
                             "label": f"{scheme} {cells} cells CFL {s['cfl']}", "error": errors["density"],
                             "wall_s": float(row["wall_time_s"]), "steps": int(float(row["steps_1"])),
                             "folder": run_folder(folder, row)})

    thermo_rows = []
    if thermo:
        folder = done["thermo"][0]
        rows = read_summary(os.path.join(folder, "summary.csv"))
        temps = {r["gas_thermo"]: (post_shock_temperature(run_folder(folder, r)), r) for r in rows}
        t_ref = temps["thermally_perfect"][0]
        for model, (T, r) in temps.items():
            thermo_rows.append({"setting": model.replace("_", " "), "reference": "thermally perfect", "T": T,
                                "error": abs(T - t_ref), "wall_s": float(r["wall_time_s"]),
                                "steps": int(float(r["steps_1"])), "folder": run_folder(folder, r)})

    # Coupled: find each setting's run by its row of key values.
    by_values = {}  # key values -> [(folder, row) of each round]
    for s in coupled:
        folder = done[s["name"]][0]
        for row in read_summary(os.path.join(folder, "summary.csv")):
            values = tuple(row[k.replace(".", "_")] for k in keys)
            by_values.setdefault(values, []).append((folder, row))

    def lookup(overrides):
        want = tuple(value_text(overrides.get(k, base.get(k))) for k in keys)
        for values, hit in by_values.items():
            if all(same_value(a, b) for a, b in zip(values, want)):
                return hit
        raise SystemExit(f"accuracy_cost.py: no run for {overrides}")

    coupled_rows = []
    references = {}
    for study, label, overrides in settings:
        rounds = lookup(overrides)
        folder, row = rounds[0]
        walls = sorted(float(r["wall_time_s"]) for _, r in rounds)
        # Every round is the same computation (bitwise): the same steps, or the report is wrong.
        if len({r["steps_1"] for _, r in rounds}) != 1:
            raise SystemExit(f"accuracy_cost.py: the rounds of {label} took different steps")
        if study not in references:
            references[study] = (label, folder, row)
        ref_label, ref_folder, ref_row = references[study]
        x_shock = float(ref_row["shock_x_m"])
        peak, which = band_peak_difference(row, ref_row)
        worst, mean = height_difference(run_folder(folder, row), run_folder(ref_folder, ref_row), x_shock)
        coupled_rows.append({"study": study, "setting": label, "reference": ref_label, "error": worst, "mean_error": mean,
                             "peak_diff": peak, "peak_which": which, "wall_s": float(np.median(walls)),
                             "wall_min": walls[0], "wall_max": walls[-1], "rounds": len(walls),
                             "steps": int(float(row["steps_1"])), "folder": run_folder(folder, row)})

    out_dir = os.path.join(os.path.dirname(os.path.abspath(args.report)), "accuracy-cost")
    os.makedirs(out_dir, exist_ok=True)
    write_csv(os.path.join(out_dir, "accuracy_cost.csv"), gas_rows, thermo_rows, coupled_rows)
    for problem in sorted({r["problem"] for r in gas_rows}):
        plot_gas(gas_rows, problem, os.path.join(out_dir, f"gas_{problem}.png"))
    if coupled_rows:
        finite = [r["mean_error"] for r in coupled_rows if r["mean_error"] > 0 and math.isfinite(r["mean_error"])]
        plot_coupled(coupled_rows, os.path.join(out_dir, "coupled.png"), min(finite) / 3 if finite else 1e-6)
    # A --reuse call adds the reused sweeps' own wall times, so the stated run time stays true.
    elapsed = time.time() - t0 + sum(v[1] for v in done.values() if v[2]) / max(1, args.jobs)
    report(args, gas_rows, thermo_rows, coupled_rows, elapsed, out_dir)
    print(f"accuracy_cost.py: {len(gas_rows) + len(thermo_rows) + len(coupled_rows)} rows, "
          f"{(time.time() - t0) / 60:.1f} min -> {args.report}")


def same_value(a, b):
    try:
        return math.isclose(float(a), float(b), rel_tol=1e-12)
    except ValueError:
        return str(a).strip('"') == str(b).strip('"')


if __name__ == "__main__":
    main(sys.argv[1:])
