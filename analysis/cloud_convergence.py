#!/usr/bin/python3
"""A convergence study's dust clouds: each run's cloud at its last output, and how far apart
the runs that differ in one setting lie (Markdown tables; a PNG of the lifted mass).

Usage: /usr/bin/python3 analysis/cloud_convergence.py RUNDIR... [--out FILE] [--table FILE]

Each RUNDIR is a run folder (or a sweep folder: its runs are taken). A run is labelled by its
parcel ratio (particles.parcel_ratio, else the parcel diameter) and its cell size
(grid.x.cell_size) from its scene.resolved.toml, and read from series/dust_cloud.csv:

  lifted            lifted_mass_kg_per_m at the last output, g/m
  above 1 mm        mass_above_h0p001_kg_per_m: the lifted mass more than 1 mm above the
                    initial layer top, g/m (a height well above every parcel's size)
  explosible        explosible_mass_kg_per_m at the last output, g/m
  explosible area   explosible_area_m2 at the last output, mm^2
  explosible, 2nd half  the mean of explosible_mass_kg_per_m over the outputs of the second
                    half of the run, g/m (one output's band varies by some 20 % from the next)
  entrainment       entrainment_rate_kg_per_m_s at the last output, and its mean over the
                    second half of the run (the lifted mass gained over it / its length), kg/(m s)
  per class         classK_lifted_mass_kg_per_m at the last output, g/m

The second table gives, for every pair of runs that differ in the ratio alone or in the cell
alone, the relative difference of each quantity, (b - a) / a, in %. Where the runs end with a
checkpoint.h5, a third table gives each class's lifted parcels (centre above the lift height at
the end) over the parcels of its top row (centre within one parcel diameter of the initial
layer top): near 1 the class lost about its top row, so its lifted mass is set by its parcel
size, not resolved by it (docs/dust-cloud.md, "A convergence study"). Where the runs have
series/dust_concentration_histogram.csv, a fourth table gives each run's lifted mass at the last
output between the histogram edge nearest 0.05 kg/m^3 (the band's default lower edge) and each
edge from 1 to 4 kg/m^3: the explosible mass the band would hold with that upper edge, to the
histogram's resolution (10 bins a decade), which shows how much of a difference between runs
the upper edge's placement makes. Writes the PNG (lifted mass,
mass above 1 mm and explosible mass against time, one curve per run) to --out (default
convergence.png beside the first RUNDIR).
"""
import argparse
import os
import sys
import tomllib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_figures import read_series  # noqa: E402


def run_folders(paths):
    """Run folders: the paths that hold series/dust_cloud.csv, and the runs of sweep folders."""
    runs = []
    for p in paths:
        if os.path.exists(os.path.join(p, "series", "dust_cloud.csv")):
            runs.append(p)
            continue
        for name in sorted(os.listdir(p)):
            q = os.path.join(p, name)
            if os.path.exists(os.path.join(q, "series", "dust_cloud.csv")):
                runs.append(q)
    return runs


def setting(run):
    """(parcel ratio, cell size in m) of a run, from its resolved scene."""
    with open(os.path.join(run, "scene.resolved.toml"), "rb") as f:
        scene = tomllib.load(f)
    particles = scene.get("particles", {})
    ratio = particles.get("parcel_ratio")
    if isinstance(ratio, list):
        ratio = tuple(ratio)
    if ratio is None:
        ratio = "D = %g um" % (1e6 * particles.get("parcel_diameter", float("nan")))
    cell = scene["grid"]["x"].get("cell_size")
    return ratio, cell


def cloud(run):
    """The quantities of the module docstring at the last output, and the series."""
    s = read_series(os.path.join(run, "series", "dust_cloud.csv"))
    t = s["time_s"]
    last = -1
    half = np.searchsorted(t, 0.5 * t[last])
    lifted = s["lifted_mass_kg_per_m"]
    q = {
        "lifted": lifted[last] * 1e3,
        "above 1 mm": s["mass_above_h0p001_kg_per_m"][last] * 1e3
        if "mass_above_h0p001_kg_per_m" in s else float("nan"),
        "explosible": s["explosible_mass_kg_per_m"][last] * 1e3,
        "entrainment": s["entrainment_rate_kg_per_m_s"][last],
        "entrainment, 2nd half": (lifted[last] - lifted[half]) / (t[last] - t[half]),
        "explosible area": s["explosible_area_m2"][last] * 1e6
        if "explosible_area_m2" in s else float("nan"),
        "explosible, 2nd half": s["explosible_mass_kg_per_m"][half:].mean() * 1e3,
    }
    k = 0
    while "class%d_lifted_mass_kg_per_m" % k in s:
        q["class %d" % k] = s["class%d_lifted_mass_kg_per_m" % k][last] * 1e3
        k += 1
    return q, s


def upper_edge_masses(run):
    """{upper edge (kg/m^3): lifted mass (g/m) in the bins from the edge nearest 0.05 kg/m^3
    up to it} at the last output, for the histogram edges from 1 to 4 kg/m^3; None without a
    histogram series."""
    path = os.path.join(run, "series", "dust_concentration_histogram.csv")
    if not os.path.exists(path):
        return None
    h = read_series(path)
    if h is None:
        return None
    rows = h["time_s"] == h["time_s"][-1]
    low, high, mass = (h[k][rows] for k in ("concentration_low_kg_per_m3",
                                            "concentration_high_kg_per_m3", "mass_kg_per_m"))
    start = np.argmin(np.abs(np.log(low / 0.05)))
    return {high[k]: mass[start:k + 1].sum() * 1e3
            for k in range(start, len(high)) if 1.0 <= high[k] <= 4.0 + 1e-9}


def lift_level(run):
    """(initial layer top, lift height) in m from the resolved scene; a derived lift height is
    a comment line there ("#   output.cloud_lift_height = ...")."""
    path = os.path.join(run, "scene.resolved.toml")
    with open(path, "rb") as f:
        scene = tomllib.load(f)
    top = scene.get("particles", {}).get("layer", {}).get("y_max", 0.0)
    height = scene.get("output", {}).get("cloud_lift_height")
    if height is None:
        with open(path) as f:
            for line in f:
                words = line.lstrip("# ").split()
                if len(words) >= 3 and words[0] == "output.cloud_lift_height" and words[1] == "=":
                    height = float(words[2])
    return top, height


def top_rows(run):
    """Per class: lifted parcels at the end over the parcels of its top row, from the run's
    checkpoint.h5; None without a checkpoint or a lift height."""
    path = os.path.join(run, "checkpoint.h5")
    top, height = lift_level(run)
    if not os.path.exists(path) or height is None:
        return None
    import h5py
    with h5py.File(path, "r") as f:
        p = {k: f["parcels/" + k][()] for k in ("y", "y_initial", "size_class", "diameter")}
    ratios = []
    for k in range(int(p["size_class"].max()) + 1):
        c = p["size_class"] == k
        row0 = c & (top - p["y_initial"] < p["diameter"])
        lifted = c & (p["y"] > top + height)
        ratios.append(lifted.sum() / row0.sum() if row0.any() else float("nan"))
    return ratios


def label(ratio, cell):
    if isinstance(ratio, str):
        r = ratio
    else:
        r = "ratio " + (", ".join("%g" % v for v in ratio) if isinstance(ratio, tuple) else "%g" % ratio)
    return "%s, %g mm cells" % (r, cell * 1e3)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+")
    parser.add_argument("--out", help="PNG path")
    parser.add_argument("--table", help="also write the Markdown tables here")
    args = parser.parse_args(argv)
    runs = run_folders(args.runs)
    if not runs:
        print("cloud_convergence.py: no run with a dust-cloud series", file=sys.stderr)
        return 1
    data = []
    for run in runs:
        ratio, cell = setting(run)
        q, s = cloud(run)
        data.append((ratio, cell, q, s))
    data.sort(key=lambda d: (str(d[0]), -d[1]))
    keys = list(data[0][2].keys())
    units = {"lifted": "g/m", "above 1 mm": "g/m", "explosible": "g/m",
             "entrainment": "kg/(m s)", "entrainment, 2nd half": "kg/(m s)",
             "explosible area": "mm^2"}
    lines = ["| run | t [ms] | " + " | ".join(
        "%s [%s]" % (k, units.get(k, "g/m")) for k in keys) + " |",
        "|---|---|" + "---|" * len(keys)]
    for ratio, cell, q, s in data:
        lines.append("| %s | %.3f | " % (label(ratio, cell), s["time_s"][-1] * 1e3)
                     + " | ".join("%.4g" % q[k] for k in keys) + " |")
    lines += ["", "| pair (a -> b) | " + " | ".join("%s [%%]" % k for k in keys) + " |",
              "|---|" + "---|" * len(keys)]
    for i, (ra, ca, qa, _) in enumerate(data):
        for rb, cb, qb, _ in data[i + 1:]:
            if (ra == rb) == (ca == cb):
                continue  # the same run, or two settings changed at once
            diffs = " | ".join("%+.1f" % (100.0 * (qb[k] - qa[k]) / qa[k])
                               if qa[k] and np.isfinite(qa[k]) and np.isfinite(qb[k]) else "n/a"
                               for k in keys)
            lines.append("| %s -> %s | %s |" % (label(ra, ca), label(rb, cb), diffs))
    rows = [(ratio, cell, top_rows(run)) for ratio, cell, run in
            sorted(((setting(r) + (r,)) for r in runs), key=lambda d: (str(d[0]), -d[1]))]
    if all(r[2] is not None for r in rows):
        n = max(len(r[2]) for r in rows)
        lines += ["", "| run (lifted parcels / top row) | " +
                  " | ".join("class %d" % k for k in range(n)) + " |",
                  "|---|" + "---|" * n]
        for ratio, cell, r in rows:
            lines.append("| %s | " % label(ratio, cell) + " | ".join("%.2f" % v for v in r) + " |")
    edges = [(ratio, cell, upper_edge_masses(run)) for ratio, cell, run in
             sorted(((setting(r) + (r,)) for r in runs), key=lambda d: (str(d[0]), -d[1]))]
    if all(e[2] for e in edges):
        uppers = sorted(edges[0][2])
        lines += ["", "| run (mass from 0.05 kg/m^3 up to [g/m]) | " +
                  " | ".join("%.3g kg/m^3" % u for u in uppers) + " |",
                  "|---|" + "---|" * len(uppers)]
        for ratio, cell, e in edges:
            lines.append("| %s | " % label(ratio, cell) +
                         " | ".join("%.4g" % e.get(u, float("nan")) for u in uppers) + " |")
    table = "\n".join(lines)
    print(table)
    if args.table:
        with open(args.table, "w") as f:
            f.write(table + "\n")

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2), sharex=True)
    for k, (ratio, cell, q, s) in enumerate(data):
        t = s["time_s"] * 1e3
        style = "-" if cell == min(d[1] for d in data) else "--"
        axes[0].plot(t, s["lifted_mass_kg_per_m"] * 1e3, style, marker=".", color="C%d" % k,
                     label=label(ratio, cell))
        if "mass_above_h0p001_kg_per_m" in s:
            axes[1].plot(t, s["mass_above_h0p001_kg_per_m"] * 1e3, style, marker=".",
                         color="C%d" % k, label=label(ratio, cell))
        axes[2].plot(t, s["explosible_mass_kg_per_m"] * 1e3, style, marker=".", color="C%d" % k,
                     label=label(ratio, cell))
    axes[0].set_title("Lifted mass (centre above the lift height)")
    axes[1].set_title("Lifted mass more than 1 mm above the layer top")
    axes[2].set_title("Lifted mass inside the explosible band")
    for ax in axes:
        ax.set_xlabel("time [ms]")
        ax.set_ylabel("mass [g per m of span]")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    out = args.out or os.path.join(os.path.dirname(os.path.abspath(runs[0])), "convergence.png")
    fig.savefig(out, dpi=110)
    print("wrote %s" % out, file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
