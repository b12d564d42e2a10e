#!/usr/bin/python3
"""The shock-particle-curtain validation: ensembles of runs of cases/validation/curtain_ms166.toml
against the measured curtain fronts (Wagner et al. 2012, as plotted by Ling et al. 2012, Fig. 14).

Usage:
  /usr/bin/python3 analysis/validation.py --list
      the runs to make, one per line: folder, seeds, then the scene overrides (tab-separated);
      scripts/validate.sh reads it, so the settings live here only
  /usr/bin/python3 analysis/validation.py RUNS_DIR [--wall SECONDS] [--markdown docs/validation.md]
                                          [--figures docs/validation] [--command "..."] [--date D]

RUNS_DIR holds RUNS_DIR/<setting>/seed<k>/ run folders with series/parcel_fronts.csv,
series/line_of_sight.csv and series/parcel_force_totals.csv. Fronts are measured from the
curtain's initial upstream edge (particles.layer.x_min) at t from the start (the shock is at that
edge at t = 0).

The experiment's fronts are the edges a schlieren image through the tube shows: a line of sight
across ~1e5 beads. A run's front is therefore the edge of its line of sight (the optical depth
n (pi d^2/4) D of the beads through the tube's 76.2 mm, in 0.25 mm bins, against 1: the light
dimmed to 1/e), and a setting's front is that of its ensemble: the optical depth averaged over its
seeds, so that each bead sample adds to one picture as the experiment's beads do. The outermost
parcels (an extreme of the sample, which moves out as the sample grows) and the 1 % / 99 % points
are shown beside it.

A front's agreement at a measured time is |ours - measured| / tolerance, the tolerance being the
error bar's half-length on the side of the difference (where the bar hides behind its marker, the
marker's half size). Within the bars: every such ratio <= 1.
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

H16 = ["grid.y.end=0.016", "grid.y.cells=64", "particles.layer.y_max=0.016"]
SEEDS = 5
CLOSURE = "coupling.volume_fraction_correction"
# (folder, label, what it switches, overrides): every setting on the 16 mm channel (646 parcels a
# run) with SEEDS bead samples; the scene itself is the recommended physics.
SETTINGS = [
    ("recommended", "recommended: Osnes + resolved added mass",
     "Osnes et al. 2023 drag; added mass of the resolved flow (Parmar et al. 2008, Béguin et al. 2016); pressure, "
     "Magnus, torque, heat: the scene as it is", []),
    ("osnes", "Osnes, no added mass", "as recommended without the added mass", ["coupling.added_mass=false"]),
    ("tenneti", "Tenneti + resolved added mass", "Tenneti et al. 2011 as published instead of Osnes",
     [f'{CLOSURE}="tenneti"']),
    ("sangani", "Sangani + resolved added mass", "the paper's compressible drag with Sangani's crowding instead of Osnes",
     [f'{CLOSURE}="sangani"']),
    ("paper", "the paper's closures", "Sangani's crowding, no added mass (the paper's effects)",
     [f'{CLOSURE}="sangani"', "coupling.added_mass=false"]),
    ("ling2012", "Ling et al. 2012's closures", "Sangani's crowding with the added mass as -C_M V_p grad p and Zuber's "
     "factor", [f'{CLOSURE}="sangani"', 'coupling.added_mass_fluid_acceleration="pressure_gradient"',
                'coupling.added_mass_volume_fraction="zuber"']),
    ("standard", "standard drag only", "Clift-Gauvin drag alone (Ling et al.'s reference line)",
     ["coupling.compressibility_correction=false", f'{CLOSURE}="none"', "coupling.added_mass=false",
      "coupling.pressure_force=false", "coupling.magnus=false", "coupling.rotation_torque=false"]),
]
# (folder, label, seeds, overrides): the recommended physics on other samples and beads
STUDIES = [
    ("height_4mm", "4 mm channel (162 parcels a run)", SEEDS,
     ["grid.y.end=0.004", "grid.y.cells=16", "particles.layer.y_max=0.004"]),
    ("height_64mm", "64 mm channel (2,588 parcels a run): the scene", 2, []),
    ("polydisperse", "beads of 106-125 µm in four classes (the sieve range; 556 parcels a run)", 3,
     []),
    # The curtain's volume fraction is "about 20 %" (Wagner et al. 2012), "about 15 %" in the
    # facility's first report (Beresh et al. 2010); the spreading depends on it (DeMauro et al. 2017).
    ("phi_015", "a curtain of 15 % solid instead of 21 %", 3, H16 + ["particles.layer.volume_fraction=0.15"]),
    ("cells_05", "0.5 mm cells (4.3 bead diameters)", SEEDS,
     H16[:1] + ["grid.y.cells=32", "particles.layer.y_max=0.016", "grid.x.cell_size=0.5e-3",
                "grid.x.cells_below=30", "grid.x.cells_above=25"]),
    ("cells_0125", "0.125 mm cells (1.1 bead diameters)", 1,
     H16[:1] + ["grid.y.cells=128", "particles.layer.y_max=0.016", "grid.x.cell_size=0.125e-3",
                "grid.x.cells_below=120", "grid.x.cells_above=100"]),
]
TABLE_TIMES_US = [120, 240, 360, 480, 600, 690]
THRESHOLDS = [0.3, 1.0, 3.0]  # optical depths the edge is shown at (1: the scene's)


SCENE = "cases/validation/curtain_ms166.toml"
# Studies on a scene of their own (a size distribution replaces particles.diameter, which an
# override cannot remove).
STUDY_SCENES = {"polydisperse": "cases/validation/curtain_ms166_sieve.toml"}


def runs_to_make():
    """(folder, seeds, scene, overrides) of every run."""
    for name, _, _, overrides in SETTINGS:
        yield name, SEEDS, SCENE, H16 + overrides
    for name, _, seeds, overrides in STUDIES:
        yield name, seeds, STUDY_SCENES.get(name, SCENE), overrides


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


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    data = np.array([[float(v) for v in r] for r in rows[1:] if r])
    return {h: data[:, k] for k, h in enumerate(rows[0])}


def read_seed(folder):
    """One run: its fronts (mm from the curtain's upstream edge), optical-depth profile, force
    totals and wall time."""
    with open(os.path.join(folder, "scene.resolved.toml"), "rb") as f:
        scene = tomllib.load(f)
    x0 = scene["particles"]["layer"]["x_min"]
    fr = read_csv(os.path.join(folder, "series", "parcel_fronts.csv"))
    fronts = {k: (fr[k + "_m"] - x0) * 1e3 for k in ("x_min", "x_p01", "x_p99", "x_max", "x_sight_up", "x_sight_down")}
    sight = read_csv(os.path.join(folder, "series", "line_of_sight.csv"))
    # The bins' width: the resolved scene's key, or (a derived default, written as a comment)
    # the smallest spacing of the bin centres.
    bin_m = scene.get("output", {}).get("line_of_sight", {}).get("bin")
    if bin_m is None:
        steps = np.diff(np.unique(np.round(sight["x_m"], 12)))
        bin_m = float(steps[steps > 0].min())
    totals = read_csv(os.path.join(folder, "series", "parcel_force_totals.csv"))
    wall = np.nan
    for line in open(os.path.join(folder, "run.log")):
        if line.startswith("done:") and " s wall" in line:
            wall = float(line.split(" in ")[-1].split(" s wall")[0])
    return {"t_us": fr["time_s"] * 1e6, "fronts": fronts, "sight": sight, "totals": totals, "wall": wall,
            "x0": x0, "bin": bin_m}


def edges(tau_by_bin, bin_mm, threshold):
    """Outermost crossings of `threshold` of {bin index: tau} (bins of width bin_mm at index * bin_mm),
    linear between bin centres, as the solver finds them (insitu/parcel_fronts.cpp)."""
    if not tau_by_bin:
        return np.nan, np.nan
    first, last = min(tau_by_bin), max(tau_by_bin)
    tau = np.array([tau_by_bin.get(k, 0.0) for k in range(first, last + 1)])
    centre = (np.arange(first, last + 1) + 0.5) * bin_mm
    up = down = np.nan
    hit = np.nonzero(tau >= threshold)[0]
    if len(hit):
        b = hit[0]
        before = tau[b - 1] if b > 0 else 0.0
        up = centre[b] - bin_mm * (tau[b] - threshold) / (tau[b] - before)
        b = hit[-1]
        after = tau[b + 1] if b + 1 < len(tau) else 0.0
        down = centre[b] + bin_mm * (tau[b] - threshold) / (tau[b] - after)
    return up, down


def ensemble(seeds, threshold=1.0):
    """The line-of-sight fronts of the seeds' mean optical depth (mm from the upstream edge), at
    the first seed's output times."""
    t_us = seeds[0]["t_us"]
    bin_mm = seeds[0]["bin"] * 1e3
    up, down = np.full(len(t_us), np.nan), np.full(len(t_us), np.nan)
    for k, t in enumerate(t_us):
        mean = {}
        for s in seeds:
            rows = np.isclose(s["sight"]["time_s"] * 1e6, t, atol=1e-3)
            for x, tau in zip(s["sight"]["x_m"][rows], s["sight"]["optical_depth_1"][rows]):
                b = int(np.floor(x / s["bin"]))
                mean[b] = mean.get(b, 0.0) + tau / len(seeds)
        u, d = edges(mean, bin_mm, threshold)
        up[k], down[k] = u - seeds[0]["x0"] * 1e3, d - seeds[0]["x0"] * 1e3
    return t_us, up, down


def agreement(t_us, ours, measured):
    """|ours - measured| / the bar on that side, at each measured time."""
    x = np.interp(measured[:, 0], t_us, ours)
    diff = x - measured[:, 1]
    tol = np.where(diff >= 0, measured[:, 3], measured[:, 2])
    return x, np.abs(diff) / tol


def score(t_us, up, down, exp):
    _, a = agreement(t_us, up, exp["upstream"])
    _, b = agreement(t_us, down, exp["downstream"])
    both = np.concatenate([a, b])
    return {"up_in": int((a <= 1).sum()), "up_n": len(a), "down_in": int((b <= 1).sum()), "down_n": len(b),
            "rms": float(np.sqrt(np.mean(both ** 2))), "worst": float(both.max()),
            "all_in": float(((a <= 1).sum() + (b <= 1).sum()) / len(both))}


def force_share(seeds, after_us=20.0):
    """The summed added-mass force against the summed pressure-gradient force after `after_us`
    (the shock crosses the 2 mm curtain in 3.5 us): (|their sums over the particles and the
    outputs| ratio, mean over the seeds; the largest ratio at one output, over the seeds). NaN
    without the added mass."""
    sums, worst = [], np.nan
    for s in seeds:
        tot = s["totals"]
        if "added_mass_x_N_per_m" not in tot or "pressure_x_N_per_m" not in tot:
            return np.nan, np.nan
        later = tot["time_s"] * 1e6 > after_us
        am, pr = tot["added_mass_x_N_per_m"][later], tot["pressure_x_N_per_m"][later]
        sums.append(abs(am.sum()) / abs(pr.sum()))
        worst = np.nanmax([worst, (np.abs(am) / np.abs(pr)).max()])
    return float(np.mean(sums)), float(worst)


def summarise(folder):
    seeds = []
    if not os.path.isdir(folder):
        return None
    for name in sorted(os.listdir(folder)):
        path = os.path.join(folder, name)
        if name.startswith("seed") and os.path.exists(os.path.join(path, "series", "line_of_sight.csv")):
            seed = read_seed(path)
            if np.isfinite(seed["wall"]):  # finished (an unfinished run's log has no "done:")
                seeds.append(seed)
    if not seeds:
        return None
    t_us, up, down = ensemble(seeds)
    n = min(len(s["t_us"]) for s in seeds)
    stack = lambda key: np.array([s["fronts"][key][:n] for s in seeds])  # noqa: E731
    return {"seeds": seeds, "t_us": t_us, "up": up, "down": down,
            "by_threshold": {th: ensemble(seeds, th) for th in THRESHOLDS},
            "seed_up": stack("x_sight_up"), "seed_down": stack("x_sight_down"),
            "x_min": stack("x_min").mean(0), "x_max": stack("x_max").mean(0),
            "x_p01": stack("x_p01").mean(0), "x_p99": stack("x_p99").mean(0), "n": n,
            "wall": np.mean([s["wall"] for s in seeds]), "force_share": force_share(seeds)}


def plot(sets, exp, ling, path):
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.5), sharey=True)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for ax, which in zip(axes, ("closures", "recommended")):
        for front, fill in (("upstream", "black"), ("downstream", "white")):
            e = exp[front]
            ax.errorbar(e[:, 1], e[:, 0], xerr=[e[:, 2], e[:, 3]], fmt="s", mfc=fill, mec="black", ecolor="black",
                        ms=5, capsize=2, label=f"experiment, {front} front", zorder=5)
        ax.plot(ling["present_upstream_mm"], ling["t_us"], "k--", lw=1, label="Ling et al. 2012 simulation")
        ax.plot(ling["present_downstream_mm"], ling["t_us"], "k--", lw=1)
        if which == "closures":
            for k, (name, label, _, _) in enumerate(SETTINGS):
                if name in sets:
                    s = sets[name]
                    ax.plot(s["up"], s["t_us"], "-", color=colours[k % 10], lw=1.5, label=label)
                    ax.plot(s["down"], s["t_us"], "-", color=colours[k % 10], lw=1.5)
            ax.set_title(f"line-of-sight fronts of {SEEDS}-seed ensembles, 16 mm channel")
        else:
            s = sets.get("recommended")
            if s is not None:
                t = s["t_us"][:s["n"]]
                for key in ("seed_up", "seed_down"):
                    ax.fill_betweenx(t, s[key].min(0), s[key].max(0), color=colours[0], alpha=0.25, lw=0)
                ax.plot(s["up"], s["t_us"], "-", color=colours[0], lw=1.8,
                        label="recommended: ensemble line of sight (band: the seeds' own)")
                ax.plot(s["down"], s["t_us"], "-", color=colours[0], lw=1.8)
                ax.plot(s["x_min"], t, ":", color=colours[1], lw=1.2, label="outermost parcels (seed mean)")
                ax.plot(s["x_max"], t, ":", color=colours[1], lw=1.2)
                ax.plot(s["x_p01"], t, "-.", color=colours[2], lw=1.0, label="1 % and 99 % points")
                ax.plot(s["x_p99"], t, "-.", color=colours[2], lw=1.0)
            for k, name in enumerate(("height_64mm", "polydisperse")):
                if name in sets:
                    o = sets[name]
                    label = dict((x[0], x[1]) for x in STUDIES)[name]
                    ax.plot(o["up"], o["t_us"], "-", color=colours[3 + k], lw=1.2, label=label)
                    ax.plot(o["down"], o["t_us"], "-", color=colours[3 + k], lw=1.2)
            ax.set_title("the recommended physics")
        ax.set_xlabel("front position from the curtain's initial upstream edge (mm)")
        ax.set_xlim(-1, 70)
        ax.set_ylim(0, 720)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="lower right")
    axes[0].set_ylabel("time since the shock reached the curtain (µs)")
    fig.suptitle("Shock (Ms 1.66) over a particle curtain: upstream and downstream fronts")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


BEGIN = "<!-- generated by analysis/validation.py: begin -->"
END = "<!-- generated by analysis/validation.py: end -->"


def at_times(t_us, x, exp, front):
    e = exp[front]
    return [np.interp(e[int(np.argmin(np.abs(e[:, 0] - t))), 0], t_us, x) for t in TABLE_TIMES_US]


def write_markdown(a, sets, scores, exp, figrel, runs_count):
    lines = [BEGIN, ""]
    w = lines.append
    # A resumed regeneration's own clock misses the runs it kept: then the runs' summed wall times.
    wall = a.wall if np.isfinite(a.wall) else sum(s["wall"] * len(s["seeds"]) for s in sets.values())
    w(f"Generated by `{a.command}` on {a.date}: {wall / 60:.1f} min for the {runs_count} runs below, one after "
      f"another on 2 threads of a 2-core machine.")
    w("")
    w(f"![fronts]({figrel}/curtain_ms166_fronts.png)")
    w("")
    w(f"**The closures**, each as an ensemble of {SEEDS} bead samples (seeds) on the 16 mm channel (646 parcels a "
      "run). Fronts: the line of sight of the ensemble's mean optical depth. Score: of the measured points, those "
      "within the error bar (upstream, downstream), and the RMS of |ours − measured| / bar over all of them. "
      "Added mass / pressure: the added-mass force summed over the particles and the outputs after 20 µs (the "
      "shock has crossed the curtain by 3.5 µs) against the pressure-gradient force summed likewise, and in "
      "brackets the largest ratio at one output. (What each setting costs: [accuracy-cost.md](accuracy-cost.md).)")
    w("")
    w("| setting | what it switches | upstream in bars | downstream in bars | RMS (bars) | worst (bars) | "
      "added mass / pressure |")
    w("|---|---|---|---|---|---|---|")
    for name, label, what, _ in SETTINGS:
        if name not in sets:
            continue
        s, sc = sets[name], scores[name]
        total, worst = s["force_share"]
        share = "—" if np.isnan(total) else f"{total:.2f} ({worst:.2f})"
        w(f"| {label} | {what} | {sc['up_in']}/{sc['up_n']} | {sc['down_in']}/{sc['down_n']} | {sc['rms']:.2f} | "
          f"{sc['worst']:.2f} | {share} |")
    w("")
    w("**The recommended physics** on other bead samples and beads (line-of-sight fronts of each ensemble):")
    w("")
    w("| run | seeds | upstream in bars | downstream in bars | RMS (bars) | downstream front at 361 µs: line of "
      "sight / outermost / 99 % |")
    w("|---|---|---|---|---|---|")
    ed = exp["downstream"]
    k360 = int(np.argmin(np.abs(ed[:, 0] - 360)))
    t360 = ed[k360, 0]
    rows = [("recommended", "16 mm channel (646 parcels a run)", SEEDS)] + [(n, l, k) for n, l, k, _ in STUDIES]
    for name, label, _ in rows:
        if name not in sets:
            continue
        s, sc = sets[name], scores[name]
        t = s["t_us"][:s["n"]]
        w(f"| {label} | {len(s['seeds'])} | {sc['up_in']}/{sc['up_n']} | {sc['down_in']}/{sc['down_n']} | "
          f"{sc['rms']:.2f} | {np.interp(t360, s['t_us'], s['down']):.2f} / {np.interp(t360, t, s['x_max']):.2f} / "
          f"{np.interp(t360, t, s['x_p99']):.2f} mm (measured {ed[k360, 1]:.2f}) |")
    w("")
    if "recommended" in sets:
        s = sets["recommended"]
        w("The edge's threshold: the recommended ensemble's fronts at 690 µs for an optical depth of "
          + ", ".join(f"{th:g}" for th in THRESHOLDS) + " (1 is the scene's):")
        w("")
        w("| optical depth | upstream at 690 µs | downstream at 690 µs | upstream in bars | downstream in bars |")
        w("|---|---|---|---|---|")
        for th in THRESHOLDS:
            t_us, up, down = s["by_threshold"][th]
            sc = score(t_us, up, down, exp)
            w(f"| {th:g} | {np.interp(690, t_us, up):.2f} mm | {np.interp(690, t_us, down):.2f} mm | "
              f"{sc['up_in']}/{sc['up_n']} | {sc['down_in']}/{sc['down_n']} |")
        w("")
    shown = [(n, l) for n, l, _, _ in SETTINGS if n in sets]
    w("Fronts at six times (mm from the initial upstream edge; measured with the bar's reach below/above, or ±< the "
      "marker where the bar hides behind it):")
    w("")
    w("| t (µs) | measured upstream | measured downstream | " + " | ".join(f"{l}: up / down" for _, l in shown) + " |")
    w("|---" * (3 + len(shown)) + "|")
    cols = {n: (at_times(sets[n]["t_us"], sets[n]["up"], exp, "upstream"),
                at_times(sets[n]["t_us"], sets[n]["down"], exp, "downstream")) for n, _ in shown}
    for k, t in enumerate(TABLE_TIMES_US):
        row = []
        for front in ("upstream", "downstream"):
            e = exp[front]
            i = int(np.argmin(np.abs(e[:, 0] - t)))
            bar = f"±<{e[i, 2]:.2f}" if e[i, 4] else f"−{e[i, 2]:.2f}/+{e[i, 3]:.2f}"
            row.append(f"{e[i, 1]:.2f} ({bar})")
        w(f"| {t} | {row[0]} | {row[1]} | " + " | ".join(f"{cols[n][0][k]:.2f} / {cols[n][1][k]:.2f}"
                                                        for n, _ in shown) + " |")
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


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("runs", nargs="?")
    p.add_argument("--list", action="store_true", help="print the runs to make and exit")
    p.add_argument("--wall", type=float, default=np.nan, help="wall seconds of the whole regeneration")
    p.add_argument("--markdown", default=None)
    p.add_argument("--figures", default=None)
    p.add_argument("--command", default="bash scripts/validate.sh")
    p.add_argument("--date", default="")
    a = p.parse_args(argv)
    if a.list:
        for name, seeds, scene, overrides in runs_to_make():
            print("\t".join([name, str(seeds), scene] + overrides))
        return 0
    if not a.runs:
        p.error("RUNS_DIR is needed (or --list)")
    exp, ling = read_experiment(), read_ling()
    names = [s[0] for s in SETTINGS] + [s[0] for s in STUDIES]
    sets = {n: s for n in names if (s := summarise(os.path.join(a.runs, n))) is not None}
    if not sets:
        print(f"validation.py: no ensemble with series/line_of_sight.csv in {a.runs}", file=sys.stderr)
        return 1
    scores = {n: score(s["t_us"], s["up"], s["down"], exp) for n, s in sets.items()}
    for n, sc in scores.items():
        s = sets[n]
        print(f"{n} ({len(s['seeds'])} seeds): upstream {sc['up_in']}/{sc['up_n']} and downstream "
              f"{sc['down_in']}/{sc['down_n']} within the bars, RMS {sc['rms']:.2f} bars, worst {sc['worst']:.2f}; "
              f"added mass / pressure {s['force_share'][0]:.3f} (at one output at most {s['force_share'][1]:.3f}); "
              f"wall {s['wall']:.1f} s a run")
    if a.markdown:
        figdir = a.figures or os.path.join(os.path.dirname(a.markdown), "validation")
        os.makedirs(figdir, exist_ok=True)
        plot(sets, exp, ling, os.path.join(figdir, "curtain_ms166_fronts.png"))
        write_markdown(a, sets, scores, exp, os.path.relpath(figdir, os.path.dirname(a.markdown)),
                       sum(len(s["seeds"]) for s in sets.values()))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
