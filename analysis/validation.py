#!/usr/bin/python3
"""The shock-particle-curtain validation: runs of cases/validation/curtain_ms166.toml against
the measured curtain fronts (Wagner et al. 2012, as plotted by Ling et al. 2012, Fig. 14).

Usage: /usr/bin/python3 analysis/validation.py RUNS_DIR [--wall SECONDS] [--markdown docs/validation.md]
                                              [--figures docs/validation] [--command "..."]

RUNS_DIR holds one run folder per setting (scripts/validate.sh names them, see SETTINGS) with
series/parcel_fronts.csv. Fronts are measured from the curtain's initial upstream edge
(particles.layer.x_min of the run's resolved scene) at t from the start (the shock is at that
edge at t = 0). The upstream front is the outermost parcel upstream (x_min), the downstream
one the outermost downstream (x_max); the 1 % / 99 % points are drawn too.

A run's agreement at a measured time is |ours - measured| / tolerance, the tolerance being the
error bar's half-length on the side of the difference (where the bar hides behind its marker,
the marker's half size: the bar is shorter). Within the bars: every such ratio <= 1.
"""
import argparse
import csv
import os
import sys
import tomllib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "cases", "validation", "data")

# (folder, label, what it switches; closures and forces of docs/coupling.md)
SETTINGS = [
    ("paper", "paper effects (Sangani)", "drag x Parmar xi_1 x Sangani xi_2, pressure, Magnus, torque, heat (the paper's)"),
    ("tenneti", "Tenneti", "as paper, Tenneti et al. 2011 for the dense array instead of Sangani"),
    ("paper_added_mass", "Sangani + added mass", "as paper + added mass (Parmar 2008 x Zuber)"),
    ("tenneti_added_mass", "Tenneti + added mass", "as Tenneti + added mass"),
    ("linear_added_mass", "linear + added mass", "as paper with 1 + 5.94 alpha_p + added mass"),
    ("none_added_mass", "no crowding + added mass", "isolated-sphere drag (xi_2 = 1) + added mass"),
    ("standard_drag", "standard drag only", "Clift-Gauvin drag only (no xi_1, xi_2, pressure, added mass, Magnus, torque)"),
]
# The recommended run: the scene as it is (paper effects + added mass, 64 mm channel)
RECOMMENDED_LABEL = "recommended: Sangani + added mass, 2,588 parcels"
# (folder, label) of the resolution study of the recommended closures (paper effects + added mass)
CONVERGENCE = [
    ("rec_cells_05", "0.5 mm cells, 16 mm channel (646 parcels)"),
    ("paper_added_mass", "0.25 mm cells, 16 mm channel (646 parcels)"),
    ("rec_cells_0125", "0.125 mm cells (1.1 particle diameters), 16 mm channel"),
    ("rec_height_4mm", "0.25 mm cells, 4 mm channel (162 parcels)"),
    ("rec_height_32mm", "0.25 mm cells, 32 mm channel (1,292 parcels)"),
    ("recommended", "0.25 mm cells, 64 mm channel (2,588 parcels): the scene"),
    ("rec_height_128mm", "0.25 mm cells, 128 mm channel (5,176 parcels)"),
]
TABLE_TIMES_US = [120, 240, 360, 480, 600, 690]


def read_experiment(path=os.path.join(DATA, "curtain_ms166_fronts_experiment.csv")):
    """{front: array of (t_us, x_mm, minus_mm, plus_mm, hidden)}: the bar's reach below and above
    (hidden = 1: the bar does not reach beyond the marker, whose half size is given instead)."""
    out = {"upstream": [], "downstream": []}
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    header = rows[0]
    for r in rows[1:]:
        d = dict(zip(header, r))
        x = float(d["x_mm"])
        if d["x_low_mm"]:
            minus, plus, hidden = x - float(d["x_low_mm"]), float(d["x_high_mm"]) - x, 0.0
        else:
            minus = plus = float(d["bar_below_mm"])
            hidden = 1.0
        out[d["front"]].append((float(d["t_us"]), x, minus, plus, hidden))
    return {k: np.array(v) for k, v in out.items()}


def read_ling(path=os.path.join(DATA, "curtain_ms166_fronts_ling2012_simulation.csv")):
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    header = rows[0]
    cols = {h: [] for h in header}
    for r in rows[1:]:
        for h, v in zip(header, r):
            cols[h].append(float(v) if v else np.nan)
    return {h: np.array(v) for h, v in cols.items()}


def read_run(folder):
    """(t_us, {x_min, x_p01, x_p99, x_max} in mm from the curtain's upstream edge), wall s."""
    with open(os.path.join(folder, "scene.resolved.toml"), "rb") as f:
        scene = tomllib.load(f)
    x0 = scene["particles"]["layer"]["x_min"]
    with open(os.path.join(folder, "series", "parcel_fronts.csv"), newline="") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    data = np.array([[float(v) for v in r] for r in rows[1:] if r])
    col = {h: data[:, k] for k, h in enumerate(header)}
    t_us = col["time_s"] * 1e6
    fronts = {k: (col[k + "_m"] - x0) * 1e3 for k in ("x_min", "x_p01", "x_p99", "x_max")}
    wall = np.nan
    log = os.path.join(folder, "run.log")
    if os.path.exists(log):
        for line in open(log):
            if line.startswith("done:") and " s wall" in line:
                wall = float(line.split(" in ")[-1].split(" s wall")[0])
    return t_us, fronts, wall


def agreement(t_us, ours, measured):
    """|ours - measured| / the bar on that side, at each measured time."""
    x = np.interp(measured[:, 0], t_us, ours)
    diff = x - measured[:, 1]
    tol = np.where(diff >= 0, measured[:, 3], measured[:, 2])
    return x, np.abs(diff) / tol


def score(run, exp):
    """Within-bar counts and the RMS of the bar-normalised error over both fronts."""
    t, fronts, _ = run
    _, up = agreement(t, fronts["x_min"], exp["upstream"])
    _, down = agreement(t, fronts["x_max"], exp["downstream"])
    both = np.concatenate([up, down])
    return {"up_in": int((up <= 1).sum()), "up_n": len(up), "down_in": int((down <= 1).sum()), "down_n": len(down),
            "rms": float(np.sqrt(np.mean(both ** 2))), "worst": float(both.max())}


def plot(runs, exp, ling, labels, recommended, path):
    fig, axes = plt.subplots(1, 2, figsize=(12, 5), sharey=True)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for ax, which in zip(axes, ("all", "recommended")):
        for front, marker, fill in (("upstream", "s", "black"), ("downstream", "s", "white")):
            e = exp[front]
            ax.errorbar(e[:, 1], e[:, 0], xerr=[e[:, 2], e[:, 3]], fmt=marker, mfc=fill, mec="black", ecolor="black",
                        ms=5, capsize=2, label=f"experiment, {front} front", zorder=5)
        ax.plot(ling["present_upstream_mm"], ling["t_us"], "k--", lw=1, label="Ling et al. 2012 simulation")
        ax.plot(ling["present_downstream_mm"], ling["t_us"], "k--", lw=1)
        shown = labels if which == "all" else [recommended]
        for k, name in enumerate(shown):
            if name not in runs:
                continue
            t, fronts, _ = runs[name]
            c = colours[k % len(colours)]
            label = dict((s[0], s[1]) for s in SETTINGS).get(name, RECOMMENDED_LABEL if name == recommended else name)
            ax.plot(fronts["x_min"], t, "-", color=c, lw=1.5, label=label)
            ax.plot(fronts["x_max"], t, "-", color=c, lw=1.5)
            if which == "recommended":
                ax.plot(fronts["x_p01"], t, ":", color=c, lw=1.5, label="1 % and 99 % of the particles")
                ax.plot(fronts["x_p99"], t, ":", color=c, lw=1.5)
        ax.set_xlabel("front position from the curtain's initial upstream edge (mm)")
        ax.set_title("the closures compared (16 mm channel)" if which == "all" else RECOMMENDED_LABEL)
        ax.set_xlim(-1, 70)
        ax.set_ylim(0, 720)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="lower right")
    axes[0].set_ylabel("time since the shock reached the curtain (µs)")
    fig.suptitle("Shock (Ms 1.66) over a particle curtain: upstream and downstream fronts")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("runs")
    p.add_argument("--recommended", default="recommended")
    p.add_argument("--wall", type=float, default=np.nan, help="wall seconds of the whole regeneration")
    p.add_argument("--markdown", default=None)
    p.add_argument("--figures", default=None)
    p.add_argument("--command", default="bash scripts/validate.sh")
    p.add_argument("--date", default="")
    a = p.parse_args(argv)
    exp, ling = read_experiment(), read_ling()
    runs = {}
    for name in [s[0] for s in SETTINGS] + [c[0] for c in CONVERGENCE]:
        folder = os.path.join(a.runs, name)
        if os.path.exists(os.path.join(folder, "series", "parcel_fronts.csv")):
            runs[name] = read_run(folder)
    if not runs:
        print(f"validation.py: no run with series/parcel_fronts.csv in {a.runs}", file=sys.stderr)
        return 1
    scores = {n: score(r, exp) for n, r in runs.items()}
    for n, s in scores.items():
        print(f"{n}: upstream {s['up_in']}/{s['up_n']} and downstream {s['down_in']}/{s['down_n']} within the bars, "
              f"RMS {s['rms']:.2f} bars, worst {s['worst']:.2f}, wall {runs[n][2]:.1f} s")
    if a.markdown:
        figdir = a.figures or os.path.join(os.path.dirname(a.markdown), "validation")
        os.makedirs(figdir, exist_ok=True)
        plot(runs, exp, ling, [s[0] for s in SETTINGS], a.recommended, os.path.join(figdir, "curtain_ms166_fronts.png"))
        write_markdown(a, runs, scores, exp, os.path.relpath(figdir, os.path.dirname(a.markdown)))
    return 0


BEGIN = "<!-- generated by analysis/validation.py: begin -->"
END = "<!-- generated by analysis/validation.py: end -->"


def write_markdown(a, runs, scores, exp, figrel):
    """Replaces the generated block of the markdown file (between BEGIN and END) with the
    figure, the tables and the command; the prose around it is the document's own."""
    rec = a.recommended
    lines = [BEGIN, ""]
    w = lines.append
    w(f"Generated by `{a.command}` on {a.date}: {a.wall / 60:.1f} min for the {len(runs)} runs below, one after "
      f"another on 2 threads of a 2-core machine.")
    w("")
    w(f"![fronts]({figrel}/curtain_ms166_fronts.png)")
    w("")
    w("The closures and forces compared, each on the same 16 mm channel (646 parcels). Score: of the measured points, "
      "those the run's front meets within the error bar (upstream, downstream), and the RMS of |ours − measured| / bar "
      "over all of them; wall: the whole run to 700 µs.")
    w("")
    w("| setting | what it switches | upstream in bars | downstream in bars | RMS (bars) | worst (bars) | wall |")
    w("|---|---|---|---|---|---|---|")
    for name, label, what in SETTINGS:
        if name not in scores:
            continue
        s = scores[name]
        w(f"| {label}{' (**recommended closures**)' if name == 'paper_added_mass' else ''} | {what} | {s['up_in']}/{s['up_n']} | "
          f"{s['down_in']}/{s['down_n']} | {s['rms']:.2f} | {s['worst']:.2f} | {runs[name][2]:.1f} s |")
    w("")
    ling = read_ling()
    t_rec, fr_rec, _ = runs[rec]
    for front, col, key in (("upstream", "present_upstream_mm", "x_min"), ("downstream", "present_downstream_mm", "x_max")):
        ok = np.isfinite(ling[col])
        diff = np.interp(ling["t_us"][ok], t_rec, fr_rec[key]) - ling[col][ok]
        w(f"Against Ling et al.'s own simulation of the experiment (their full model, digitised curve), the recommended "
          f"setting's {front} front differs by {np.sqrt(np.mean(diff ** 2)):.2f} mm RMS and {np.abs(diff).max():.2f} mm "
          f"at most over their {ok.sum()} points.")
        w("")
    w(f"The recommended run ({RECOMMENDED_LABEL}): upstream front within the bars at "
      f"{scores[rec]['up_in']}/{scores[rec]['up_n']} measured times, downstream at {scores[rec]['down_in']}/"
      f"{scores[rec]['down_n']}, RMS {scores[rec]['rms']:.2f} bars, worst {scores[rec]['worst']:.2f}; {runs[rec][2]:.0f} s.")
    w("")
    w("Fronts at six times (mm from the initial upstream edge; measured with the bar's reach below/above, "
      "or ±< the marker where the bar hides behind it):")
    w("")
    shown = [(rec, "recommended (2,588 parcels)")] + [(name, label) for name, label, _ in SETTINGS if name in runs]
    w("| t (µs) | measured upstream | measured downstream | " + " | ".join(f"{l}: up / down" for _, l in shown) + " |")
    w("|---" * (3 + len(shown)) + "|")
    for t in TABLE_TIMES_US:
        row = []
        for front in ("upstream", "downstream"):
            e = exp[front]
            k = int(np.argmin(np.abs(e[:, 0] - t)))
            bar = f"±<{e[k, 2]:.2f}" if e[k, 4] else f"−{e[k, 2]:.2f}/+{e[k, 3]:.2f}"
            row.append(f"{e[k, 1]:.2f} ({bar})")
        cells = []
        for name, _ in shown:
            tt, fr, _ = runs[name]
            eu, ed = exp["upstream"], exp["downstream"]
            tu = eu[int(np.argmin(np.abs(eu[:, 0] - t))), 0]
            td = ed[int(np.argmin(np.abs(ed[:, 0] - t))), 0]
            cells.append(f"{np.interp(tu, tt, fr['x_min']):.2f} / {np.interp(td, tt, fr['x_max']):.2f}")
        w(f"| {t} | {row[0]} | {row[1]} | " + " | ".join(cells) + " |")
    w("")
    w("The recommended closures (Sangani + added mass) at other resolutions: cells, and the channel height and with "
      "it the number of parcels that sample the curtain (the outermost parcels are extremes of that sample).")
    w("")
    w("| run | upstream in bars | downstream in bars | RMS (bars) | downstream front at 361 µs | its 99 % point | wall |")
    w("|---|---|---|---|---|---|---|")
    ed = exp["downstream"]
    k360 = int(np.argmin(np.abs(ed[:, 0] - 360)))
    for name, label in CONVERGENCE:
        key = name
        if key not in runs:
            continue
        s = scores[key]
        tt, fr, wall = runs[key]
        w(f"| {label} | {s['up_in']}/{s['up_n']} | {s['down_in']}/{s['down_n']} | {s['rms']:.2f} | "
          f"{np.interp(ed[k360, 0], tt, fr['x_max']):.2f} mm (measured {ed[k360, 1]:.2f}) | "
          f"{np.interp(ed[k360, 0], tt, fr['x_p99']):.2f} mm | {wall:.1f} s |")
    w("")
    w(END)
    block = "\n".join(lines)
    text = open(a.markdown).read() if os.path.exists(a.markdown) else f"# Validation against experiment\n\n{BEGIN}\n{END}\n"
    if BEGIN not in text or END not in text:
        raise SystemExit(f"validation.py: {a.markdown} has no generated block ({BEGIN} ... {END})")
    head, rest = text.split(BEGIN, 1)
    tail = rest.split(END, 1)[1]
    with open(a.markdown, "w") as f:
        f.write(head + block + tail)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
