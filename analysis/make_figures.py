#!/usr/bin/python3
"""Figures from a dustlift run's ready-to-plot series (PNG, matplotlib Agg).

Usage: /usr/bin/python3 analysis/make_figures.py OUTDIR [--max-curves N]

Reads OUTDIR/series/*.csv (header "name_unit,...", e.g. u_m_per_s; first column the abscissa) and writes
into OUTDIR/figures/ whatever the present series allow:
  shock_position.png           x_s(t) with a least-squares line through the t > 0 points;
                               its slope (the shock speed) is in the legend and printed
  surface_height.png           dust-surface height h(x) at the output times (Fig. 9 style),
                               above the initial layer top (particles.layer.y_max)
  surface_height_stations.png  h(t) at the station columns, above the initial layer top
  forces_<band>.png            band-averaged horizontal and vertical force parts and mean
                               height against time since shock arrival (Figs. 10-11 style)
  magnus_inputs_<band>.png     relative, particle and gas rotation (Fig. 12 style)
  dust_cloud.png               the lifted dust against time: mass and share (per size class
                               too), heights holding 50/90/99 % of it and the cloud top,
                               the mass and area inside the explosible band of the filtered
                               concentration (fines too), the entrainment rate and the fluxes
                               through the heights, temperatures, distances behind the shock
  dust_entrainment.png         entrainment rate per metre of layer and the cloud's height
                               against the distance behind the shock, one curve per output
  dust_concentration_histogram.png  lifted mass per filtered-concentration bin at a few
                               outputs, the explosible band shaded
A gas-only run has only shock_position. Exits 1 if OUTDIR/series holds no series.
"""
import argparse
import csv
import glob
import os
import sys
import tomllib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_series(path):
    """{header: column array} in file order; None for a file with a header only."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if len(rows) < 2:
        return None
    header = rows[0]
    data = np.array([[float(v) for v in r] for r in rows[1:] if r], dtype=float)
    return {name: data[:, k] for k, name in enumerate(header)}


def layer_top(outdir):
    """The initial layer's top (particles.layer.y_max of OUTDIR/scene.resolved.toml): surface
    heights are drawn above it. 0 when the run has no resolved scene or no layer."""
    try:
        with open(os.path.join(outdir, "scene.resolved.toml"), "rb") as f:
            scene = tomllib.load(f)
        return float(scene["particles"]["layer"]["y_max"])
    except (OSError, KeyError, ValueError, tomllib.TOMLDecodeError):
        return 0.0


def shock_position(series, out):
    t, x = series["time_s"], series["x_m"]
    ok = np.isfinite(x)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(t[ok] * 1e3, x[ok] * 1e3, "o", ms=3, label="shock position")
    # Fit t > 0 only: at t = 0 of a Riemann start the filter sees the diaphragm, whose
    # offset from the captured shock's foot differs (Sod: 0.8 % too fast with it).
    fit = ok & (t > 0)
    # A shock that has left the domain sits at the last column: fit only up to its exit.
    if fit.sum() > 2:
        x_end = np.nanmax(x[ok])
        stuck = np.abs(x - x_end) < 1e-6 * max(1.0, abs(x_end))
        if stuck.sum() > 1 and (fit & ~stuck).sum() >= 2:
            fit = fit & ~stuck
    if fit.sum() < 2:
        fit = ok
    if fit.sum() >= 2:
        speed, intercept = np.polyfit(t[fit], x[fit], 1)
        tt = np.linspace(t[fit].min(), t[fit].max(), 2)
        ax.plot(tt * 1e3, (speed * tt + intercept) * 1e3, "-", label="linear fit: %.1f m/s" % speed)
        print("shock speed (linear fit): %.9g m/s" % speed)
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("shock position x [mm]")
    ax.set_title("Shock position against time (slope: the shock speed)")
    ax.legend()
    ax.grid(alpha=0.3)
    return save(fig, out, "shock_position.png")


def surface_height(series, out, max_curves, top):
    t, x, h = series["time_s"], series["x_m"], series["height_m"] - top
    times = np.unique(t)
    if len(times) > max_curves:  # evenly spaced subset, always with the last time
        times = times[np.unique(np.linspace(0, len(times) - 1, max_curves).round().astype(int))]
    fig, ax = plt.subplots(figsize=(7, 4))
    colors = plt.cm.viridis(np.linspace(0, 1, len(times)))
    for c, tk in zip(colors, times):
        sel = t == tk
        order = np.argsort(x[sel])
        ax.plot(x[sel][order] * 1e3, h[sel][order] * 1e3, color=c, label="t = %.3f ms" % (tk * 1e3))
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("surface height above the initial top [mm]")
    ax.set_title("Dust surface (where the particle volume fraction falls below 1e-4)")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.legend(fontsize=7, ncol=2)
    ax.grid(alpha=0.3)
    return save(fig, out, "surface_height.png")


def station_label(name):
    """'height_at_x0p05_m' -> 'x = 0.05 m' (the station's x is written into the column name
    with '.' as 'p' and '-' as 'm', so that the name is an identifier)."""
    x = name[len("height_at_x"):-len("_m")]
    return "x = %s m" % ("-" + x[1:] if x.startswith("m") else x).replace("p", ".")


def surface_stations(series, out, top):
    names = list(series)
    fig, ax = plt.subplots(figsize=(6, 4))
    for name in names[1:]:
        ax.plot(series[names[0]] * 1e3, (series[name] - top) * 1e3, label=station_label(name))
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("surface height above the initial top [mm]")
    ax.set_title("Dust surface height at fixed stations")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return save(fig, out, "surface_height_stations.png")


def forces(series, out, band):
    tau = series["tau_s"] * 1e3
    fig, axes = plt.subplots(3, 1, figsize=(7, 9), sharex=True)
    parts = [("drag", "drag"), ("pressure", "pressure gradient"), ("magnus", "Magnus"),
             ("contact_window", "contact (0.01 ms mean)")]
    for ax, comp, label in ((axes[0], "x", "horizontal"), (axes[1], "y", "vertical")):
        for key, name in parts:
            col = "%s_%s_N" % (key, comp)
            if col in series and np.isfinite(series[col]).any():
                ax.plot(tau, series[col], label=name)
        ax.axhline(0.0, color="k", lw=0.5)
        ax.set_ylabel("%s force per parcel [N]" % label)
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    axes[2].plot(tau, series["height_m"] * 1e3, "k-")
    axes[2].set_ylabel("mean height [mm]")
    axes[2].set_xlabel("time since shock arrival [ms]")
    axes[2].grid(alpha=0.3)
    axes[2].set_title("mean height of the band's parcels")
    axes[0].set_title("Forces on the parcels that started in band %s (per real particle)" % band)
    return save(fig, out, "forces_%s.png" % band)


def magnus_inputs(series, out, band):
    cols = [("relative_rotation_rad_per_s", "relative rotation"), ("particle_rotation_rad_per_s", "particle rotation"),
            ("gas_rotation_rad_per_s", "gas rotation")]
    present = [(c, n) for c, n in cols if c in series and np.isfinite(series[c]).any()]
    if not present:
        return None
    fig, ax = plt.subplots(figsize=(7, 4))
    for c, n in present:
        ax.plot(series["tau_s"] * 1e3, series[c], label=n)
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel("time since shock arrival [ms]")
    ax.set_ylabel("rotation [rad/s]")
    ax.set_title("Rotation rates behind the Magnus force, band %s" % band)
    ax.legend()
    ax.grid(alpha=0.3)
    return save(fig, out, "magnus_inputs_%s.png" % band)


def cloud_settings(outdir):
    """The explosible band [lower, upper] (kg/m^3) of OUTDIR/scene.resolved.toml (the
    defaults when it is missing)."""
    try:
        with open(os.path.join(outdir, "scene.resolved.toml"), "rb") as f:
            out = tomllib.load(f).get("output", {})
    except (OSError, tomllib.TOMLDecodeError):
        out = {}
    return float(out.get("explosible_lower", 0.05)), float(out.get("explosible_upper", 2.0))


def dust_cloud(series, out):
    t = series["time_s"] * 1e3
    fig, axes = plt.subplots(6, 1, figsize=(7, 15.5), sharex=True)
    ax = axes[0]
    ax.plot(t, series["lifted_mass_kg_per_m"] * 1e3, "k-", label="all sizes")
    classes = sorted({n.split("_")[0] for n in series if n.startswith("class")})
    for c in classes:
        ax.plot(t, series[c + "_lifted_mass_kg_per_m"] * 1e3, "--", label="size class " + c[len("class"):])
    ax.set_ylabel("lifted mass [g per m of span]")
    share = ax.twinx()
    share.plot(t, series["lifted_share_1"] * 100.0, color="tab:red", lw=0.8)
    share.set_ylabel("share of the layer [%]", color="tab:red")
    ax.set_title("Dust lifted above the initial layer top")
    ax.legend(fontsize=7)
    ax = axes[1]
    for q, style in (("p50", "-"), ("p90", "--"), ("p99", ":")):
        ax.plot(t, series["height_%s_m" % q] * 1e3, "k" + style, label="%s %% of the lifted mass below" % q[1:])
    ax.plot(t, series["cloud_top_m"] * 1e3, "-", color="tab:blue", label="cloud top (concentration edge)")
    ax.set_ylabel("height above layer top [mm]")
    ax.set_title("How high the cloud reaches")
    ax.legend(fontsize=7)
    ax = axes[2]
    ax.plot(t, series["explosible_mass_kg_per_m"] * 1e3, "k.-", label="all sizes")
    ax.plot(t, series["fines_explosible_mass_kg_per_m"] * 1e3, ".--", color="tab:green", label="fines")
    ax.set_ylabel("mass [g per m of span]")
    area = ax.twinx()
    area.plot(t, series["explosible_area_m2"] * 1e6, color="tab:red", lw=0.8)
    area.set_ylabel("area [mm$^2$]", color="tab:red")
    width, quantum = series["filter_width_m"][-1], series["concentration_quantum_kg_per_m3"][-1]
    ax.set_title("Inside the explosible band (%.3g mm sliding box; one parcel = %.3g kg/m$^3$)"
                 % (width * 1e3, quantum), fontsize=9)
    ax.legend(fontsize=7)
    ax = axes[3]
    ax.plot(t, series["entrainment_rate_kg_per_m_s"], "k.-", label="leaving the layer (lift height)")
    for name in series:
        if name.startswith("flux_at_h"):
            height = name[len("flux_at_h"):-len("_kg_per_m_s")].replace("p", ".")
            ax.plot(t, series[name], "--", marker=".", label="through %g mm" % (float(height) * 1e3))
    ax.set_ylabel("rate [kg/(m s)]")
    ax.set_title("Entrainment: net mass rising through each level (between outputs)")
    ax.legend(fontsize=7)
    ax = axes[4]
    ax.plot(t, series["lifted_temperature_max_K"], "k-", label="largest")
    ax.plot(t, series["lifted_temperature_mean_K"], "k--", label="mass-weighted mean")
    ax.set_ylabel("temperature [K]")
    ax.set_title("Temperature of the lifted dust")
    ax.legend(fontsize=7)
    ax = axes[5]
    ax.plot(t, series["first_lifted_behind_shock_m"] * 1e3, "k-", label="first lifted column", marker=".")
    ax.plot(t, series["densest_lifted_behind_shock_m"] * 1e3, "k--", label="densest lifted column", marker=".")
    ax.set_ylabel("distance behind the shock [mm]")
    ax.set_title("Where the lifting is, seen from the shock")
    ax.set_xlabel("time [ms]")
    ax.legend(fontsize=7)
    for a in axes:
        a.grid(alpha=0.3)
    return save(fig, out, "dust_cloud.png")


def output_times(series, count):
    """Up to `count` of the series' distinct times, evenly spread, the last included."""
    times = np.unique(series["time_s"])
    if len(times) <= count:
        return times
    return times[np.linspace(0, len(times) - 1, count).round().astype(int)]


def dust_entrainment(series, out):
    fig, axes = plt.subplots(2, 1, figsize=(7, 8), sharex=True)
    colours = plt.cm.viridis(np.linspace(0.0, 0.9, 6))
    for colour, time in zip(colours, output_times(series, 6)):
        rows = series["time_s"] == time
        xi = series["distance_behind_shock_m"][rows] * 1e3
        label = "t = %.3g ms" % (time * 1e3)
        axes[0].plot(xi, series["entrainment_rate_kg_per_m2_s"][rows], ".-", color=colour, label=label)
        axes[1].plot(xi, series["height_max_m"][rows] * 1e3, "-", color=colour, label=label)
        axes[1].plot(xi, series["height_p90_m"][rows] * 1e3, ":", color=colour)
    axes[0].set_ylabel("entrainment rate [kg/(m$^2$ s)]")
    axes[0].set_title("Mass leaving the layer per metre of layer and second (where it started)", fontsize=10)
    axes[0].legend(fontsize=7)
    axes[1].set_ylabel("height above layer top [mm]")
    axes[1].set_title("Dispersion height: highest lifted parcel (solid), 90 % of the lifted mass (dotted)",
                      fontsize=10)
    axes[1].set_xlabel("distance behind the shock [mm]")
    for a in axes:
        a.grid(alpha=0.3)
        a.axvline(0.0, color="grey", lw=0.8)
    return save(fig, out, "dust_entrainment.png")


def dust_concentration_histogram(series, out, band):
    fig, ax = plt.subplots(figsize=(7, 4.5))
    colours = plt.cm.viridis(np.linspace(0.0, 0.9, 4))
    for colour, time in zip(colours, output_times(series, 4)):
        rows = series["time_s"] == time
        lo, hi = series["concentration_low_kg_per_m3"][rows], series["concentration_high_kg_per_m3"][rows]
        mass = series["mass_kg_per_m"][rows] * 1e3
        ax.stairs(mass, np.append(lo, hi[-1]), color=colour, label="t = %.3g ms" % (time * 1e3))
    ax.axvspan(band[0], band[1], color="tab:orange", alpha=0.2, label="explosible band")
    ax.set_xscale("log")
    ax.set_xlabel("filtered dust concentration [kg/m$^3$]")
    ax.set_ylabel("lifted mass [g per m of span]")
    ax.set_title("Lifted mass by the concentration of the filter boxes holding it")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    return save(fig, out, "dust_concentration_histogram.png")


def save(fig, out, name):
    path = os.path.join(out, name)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    print("wrote", path)
    return path


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("outdir")
    parser.add_argument("--max-curves", type=int, default=10, help="surface profiles drawn at most")
    args = parser.parse_args(argv)
    series_dir = os.path.join(args.outdir, "series")
    files = sorted(glob.glob(os.path.join(series_dir, "*.csv")))
    if not files:
        print("make_figures.py: no series in %s" % series_dir, file=sys.stderr)
        return 1
    out = os.path.join(args.outdir, "figures")
    os.makedirs(out, exist_ok=True)
    written = []
    for path in files:
        name = os.path.splitext(os.path.basename(path))[0]
        series = read_series(path)
        if series is None:
            print("skipped %s (no rows yet)" % path)
            continue
        if name == "shock_position":
            written.append(shock_position(series, out))
        elif name == "surface_height":
            written.append(surface_height(series, out, args.max_curves, layer_top(args.outdir)))
        elif name == "surface_height_stations":
            written.append(surface_stations(series, out, layer_top(args.outdir)))
        elif name == "dust_cloud":
            written.append(dust_cloud(series, out))
        elif name == "dust_entrainment":
            written.append(dust_entrainment(series, out))
        elif name == "dust_concentration_histogram":
            written.append(dust_concentration_histogram(series, out, cloud_settings(args.outdir)))
        elif name.startswith("forces_"):
            band = name[len("forces_"):]
            written.append(forces(series, out, band))
            written.append(magnus_inputs(series, out, band))
        else:
            print("skipped %s (no figure for this series)" % path)
    print("make_figures.py: %d figure(s)" % len([w for w in written if w]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
