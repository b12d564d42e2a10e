#!/usr/bin/python3
"""Overlay the dust-surface height h(x) of every run of a sweep (`dustlift sweep`).

Usage: /usr/bin/python3 analysis/plot_sweep.py DIR [--out PNG] [--title TEXT]

Reads DIR/summary.csv (one row per run: its folder, the varied keys, exit status, ...) and
each run's DIR/<run>/series/surface_height.csv and shock_position.csv, and writes one PNG
(default DIR/surface_height.png) with two panels at each run's last output time: h against
x, and h against the distance behind the shock (x_shock - x), the frame in which runs of
different shock speeds or lengths compare. Curves are labelled by the varied keys' last
words and values with units ("thickness = 0.5 mm", analysis/sweep_labels.py); a run that failed (exit status 3) is drawn dashed up to where it got.
"""
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sweep_labels import run_labels  # noqa: E402  ("thickness = 0.5 mm" per run)


def read_table(path):
    """CSV with a header row -> dict of column name -> list of strings."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    return {name: [r[k] for r in body] for k, name in enumerate(header)}


def numeric(path):
    table = read_table(path)
    return {k: np.array([float(v) for v in vals]) for k, vals in table.items()}


def last_profile(run_dir):
    """(time, x, h) of the last surface-height output, or None."""
    path = os.path.join(run_dir, "series", "surface_height.csv")
    if not os.path.exists(path):
        return None
    s = numeric(path)
    if len(s["time_s"]) == 0:
        return None
    t = s["time_s"].max()
    keep = s["time_s"] == t
    return t, s["x_m"][keep], s["height_m"][keep]


def shock_at(run_dir, t):
    """Shock position at the last sample at or before t (NaN without a series)."""
    path = os.path.join(run_dir, "series", "shock_position.csv")
    if not os.path.exists(path):
        return float("nan")
    s = numeric(path)
    before = s["time_s"] <= t
    return s["x_m"][before][-1] if before.any() else float("nan")


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dir", help="sweep output folder (holds summary.csv)")
    parser.add_argument("--out", help="PNG path (default DIR/surface_height.png)")
    parser.add_argument("--title", default=None, help="figure title (default: the folder name)")
    args = parser.parse_args(argv)

    summary_path = os.path.join(args.dir, "summary.csv")
    if not os.path.exists(summary_path):
        print(f"plot_sweep: no {summary_path}", file=sys.stderr)
        return 2
    summary = read_table(summary_path)
    labels = run_labels(args.dir, summary)

    fig, (ax_x, ax_s) = plt.subplots(2, 1, figsize=(8, 7.5))
    drawn = 0
    for k, run in enumerate(summary["run"]):
        run_dir = os.path.join(args.dir, run)
        profile = last_profile(run_dir)
        if profile is None:
            print(f"{run}: no surface height series")
            continue
        t, x, h = profile
        xs = shock_at(run_dir, t)
        failed = summary["exit_status_1"][k] not in ("0", "0.0")
        label = labels[k]
        if failed:
            label += f" (exit {summary['exit_status_1'][k]} at t={t * 1e3:.3g} ms)"
        style = "--" if failed else "-"
        ax_x.plot(x * 1e3, h * 1e3, style, lw=1.2, label=label)
        if np.isfinite(xs):
            ax_s.plot((xs - x) * 1e3, h * 1e3, style, lw=1.2, label=label)
        drawn += 1
        print(f"{run}: t = {t * 1e3:.4g} ms, shock at {xs * 1e3:.4g} mm, max h = {np.nanmax(h) * 1e3:.4g} mm")
    if drawn == 0:
        print("plot_sweep: no run has a surface height series", file=sys.stderr)
        return 1
    ax_x.set_xlabel("x [mm]")
    ax_s.set_xlabel("distance behind the shock, x_shock - x [mm]")
    for ax in (ax_x, ax_s):
        ax.set_ylabel("surface height h [mm]")
        ax.grid(alpha=0.3)
    ax_s.invert_xaxis()  # the shock on the right, as in the x panel
    ax_x.legend(fontsize=7, loc="best")
    ax_x.set_title(args.title or os.path.basename(os.path.normpath(args.dir)))
    fig.tight_layout()
    out = args.out or os.path.join(args.dir, "surface_height.png")
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
