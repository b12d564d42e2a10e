#!/usr/bin/python3
"""The dust clouds of a sweep's runs side by side (PNG, matplotlib Agg).

Usage: /usr/bin/python3 analysis/plot_cloud_study.py SWEEPDIR [--out FILE] [--table FILE]

Reads SWEEPDIR/summary.csv (the runs and their varied keys) and each run's
series/dust_cloud.csv, and draws against time, one curve per run: the lifted mass (g per
metre of span: absolute, so runs with layers of different mass compare), the heights under
which 90 % of the lifted mass lies, the lifted mass inside the explosible band of the filtered
concentration, and the distances of the first and the densest lifted column behind the shock. Each run is labelled by its varied keys' last
words and values with units ("thickness = 0.5 mm", analysis/sweep_labels.py). Writes
SWEEPDIR/dust_cloud.png (or --out) and prints a Markdown table of each run's cloud at its
last output, the lifted share of its own layer included (also written to --table when
given). Exits 1 when no run has a dust-cloud series.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_figures import read_series  # noqa: E402  (a series CSV -> dict of numpy columns)
from plot_sweep import read_table  # noqa: E402  (a CSV -> dict of column -> list of strings)
from sweep_labels import run_labels  # noqa: E402  ("thickness = 0.5 mm" per run)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("sweepdir")
    parser.add_argument("--out", help="PNG path (default SWEEPDIR/dust_cloud.png)")
    parser.add_argument("--table", help="also write the Markdown table here")
    args = parser.parse_args(argv)
    summary = read_table(os.path.join(args.sweepdir, "summary.csv"))
    labels = run_labels(args.sweepdir, summary)
    runs = []
    for k, run in enumerate(summary["run"]):
        path = os.path.join(args.sweepdir, run, "series", "dust_cloud.csv")
        if os.path.exists(path):
            runs.append((labels[k], read_series(path)))
    if not runs:
        print("plot_cloud_study.py: no run in %s has a dust-cloud series" % args.sweepdir, file=sys.stderr)
        return 1

    fig, axes = plt.subplots(2, 2, figsize=(11, 7.5), sharex=True)
    for k, (label, s) in enumerate(runs):
        t = s["time_s"] * 1e3
        colour = "C%d" % k
        axes[0, 0].plot(t, s["lifted_mass_kg_per_m"] * 1e3, ".-", color=colour, label=label)
        axes[0, 1].plot(t, s["height_p90_m"] * 1e3, ".-", color=colour, label=label)
        axes[1, 0].plot(t, s["explosible_mass_kg_per_m"] * 1e3, ".-", color=colour, label=label)
        axes[1, 1].plot(t, s["first_lifted_behind_shock_m"] * 1e3, ".-", color=colour,
                        label=label + ": first lifted column")
        axes[1, 1].plot(t, s["densest_lifted_behind_shock_m"] * 1e3, ".--", color=colour,
                        label=label + ": densest lifted column")
    titles = [("Lifted dust mass", "lifted mass [g per m of span]"),
              ("Height holding 90 % of the lifted mass", "height above layer top [mm]"),
              ("Lifted mass inside the explosible band (filtered concentration)", "mass [g per m of span]"),
              ("Lifted columns behind the shock", "distance behind the shock [mm]")]
    for ax, (title, ylabel) in zip(axes.flat, titles):
        ax.set_title(title)
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("time [ms]")
    axes[0, 0].legend(fontsize=8)
    axes[1, 1].legend(fontsize=7)
    fig.tight_layout()
    out = args.out or os.path.join(args.sweepdir, "dust_cloud.png")
    fig.savefig(out, dpi=120)
    plt.close(fig)
    print("wrote", out)

    lines = ["| run | t [ms] | lifted [g/m] | share [%] | h50 / h90 / h99 [mm] | cloud top [mm] | "
             "explosible mass [g/m] / area [mm²] (filter [mm]) | entrainment rate [kg/(m s)] | "
             "lifted T max / mean [K] | first / densest lifted column behind shock [mm] |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for label, s in runs:
        k = -1
        lines.append("| %s | %.3f | %.3g | %.3g | %.3g / %.3g / %.3g | %.3g | %.3g / %.3g (%.3g) | %.3g "
                     "| %.1f / %.1f | %.3g / %.3g |" % (
            label, s["time_s"][k] * 1e3, s["lifted_mass_kg_per_m"][k] * 1e3,
            s["lifted_share_1"][k] * 100.0, s["height_p50_m"][k] * 1e3, s["height_p90_m"][k] * 1e3,
            s["height_p99_m"][k] * 1e3, s["cloud_top_m"][k] * 1e3, s["explosible_mass_kg_per_m"][k] * 1e3,
            s["explosible_area_m2"][k] * 1e6, s["filter_width_m"][k] * 1e3,
            s["entrainment_rate_kg_per_m_s"][k],
            s["lifted_temperature_max_K"][k], s["lifted_temperature_mean_K"][k],
            s["first_lifted_behind_shock_m"][k] * 1e3, s["densest_lifted_behind_shock_m"][k] * 1e3))
    table = "\n".join(lines)
    print(table)
    if args.table:
        with open(args.table, "w") as f:
            f.write(table + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
