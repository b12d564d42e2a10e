#!/usr/bin/python3
"""Every number Shimura & Matsuo state about one run of the paper scene, measured on ours.

Usage: /usr/bin/python3 analysis/paper_compare.py RUN_DIR [--json OUT] [--time T]

Surface heights: h(x) at the stations, the lifting delay (the rule of
insitu/lifting_delay.cpp: the distance from the shock back to where h first exceeds the
undisturbed top by 0.1 mm; the median surface at t = 0, or the columns' top for a layer with
a looser top; none once the shock is beyond the layer's x_max) and the plateau are taken from the running median of h over
5 mm of x (20 columns of the paper grid); the delay of the raw columns is given too.

RUN_DIR is an output folder of `dustlift run` (cases/paper/vertical_shock.toml or a study
run of it). Reads its series (series/*.csv) and gas VTK files (vtk/gas_*.vtr, or .pvtr of an MPI run, through
Debian's python3-vtk9) and prints one JSON object; docs/results.md explains each entry and
analysis/paper_results.py turns several runs into its tables and figures.

Conventions (docs/coupling.md, "Magnus convention"): our rotations and vorticity are
counter-clockwise positive; the paper's Omega_g and omega_p are clockwise positive, so the
"*_paper" entries are the negatives of our columns. Forces are per parcel as the band
series write them (with n_xy = 1 one real particle's force, as the paper plots them),
reported here in micro-newtons.

Band forces: the band series hold 1 us bins of the time since shock arrival tau
(output.band_bin_width). The paper plots contact forces averaged over 0.01 ms and the other
forces without saying how they were sampled; so every peak is given for the 1 us bins and
for 10 us windows (the sample-weighted mean over consecutive bins), the second being the
paper's stated averaging.
"""
import argparse
import json
import math
import os
import re
import sys
import tomllib

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_sweep import numeric  # noqa: E402  (CSV with a header -> dict of numpy columns)

SMOOTHING = 5.0e-3           # m: width of the running median of h(x) (20 columns of 250 um)
LIFT_THRESHOLD = 1.0e-4      # m above the undisturbed top that counts as lifted (sweep default)
DELAY_THRESHOLDS = (0.05e-3, 0.1e-3, 0.2e-3, 0.5e-3)  # m: the lifting delay at each (sensitivity)
STATIONS = [0.050, 0.100, 0.150, 0.200, 0.250]   # m: the h(x) read-outs of docs/results.md
WINDOW = 1.0e-5              # s: the paper's 0.01 ms averaging window


def series(run, name):
    path = os.path.join(run, "series", name + ".csv")
    return numeric(path) if os.path.exists(path) else None


def shock_at(shock, t):
    """Shock x at time t, linear between samples."""
    return float(np.interp(t, shock["time_s"], shock["x_m"]))


def profile_at(surface, t):
    times = np.unique(surface["time_s"])
    t_near = times[np.argmin(np.abs(times - t))]
    keep = surface["time_s"] == t_near
    return float(t_near), surface["x_m"][keep], surface["height_m"][keep]


def running_median(x, h, width=SMOOTHING):
    """Median of h over |x' - x| <= width / 2 at each x (NaN columns left out). The
    surface height of a dilute cloud jumps by cells between neighbouring columns (a lone
    parcel puts its column's surface at a cell's top face, docs/output.md); the paper's
    curves are read as the trend of those columns."""
    out = np.full_like(h, math.nan)
    lo = np.searchsorted(x, x - 0.5 * width, side="left")
    hi = np.searchsorted(x, x + 0.5 * width, side="right")
    for k in range(len(x)):
        w = h[lo[k]:hi[k]]
        w = w[np.isfinite(w)]
        if len(w):
            out[k] = np.median(w)
    return out


def loose_top_surface(run):
    """The top of the parcels' columns (particles.layer.y_max) of a run whose layer has a
    looser top (docs/dem.md, "A looser top"), else None. The sub-cell surface height reads
    such a top cell as partly filled (-0.10 mm for two half-filled rows of 250 um cells) and
    the first shock-driven shuffle of its loose parcels fills it, so lifting is measured from
    the columns' top instead."""
    path = os.path.join(run, "scene.resolved.toml")
    if not os.path.exists(path):
        return None
    with open(path, "rb") as f:
        layer = tomllib.load(f).get("particles", {}).get("layer", {})
    if int(layer.get("loose_top_rows", 0)) > 0:
        return float(layer.get("y_max", 0.0))
    return None


def layer_end(run):
    """The layer's downstream end particles.layer.x_max of a run (its scene.resolved.toml),
    or infinity when the file or the key is missing."""
    path = os.path.join(run, "scene.resolved.toml")
    if not os.path.exists(path):
        return math.inf
    with open(path, "rb") as f:
        layer = tomllib.load(f).get("particles", {}).get("layer", {})
    return float(layer.get("x_max", math.inf))


def lifting_delay(x, h, shock_x, top, x_max=math.inf, threshold=LIFT_THRESHOLD):
    """The same rule as insitu/lifting_delay.cpp: from the shock backwards, the first column
    whose height exceeds top + threshold, interpolated to the crossing; NaN once the shock
    has left the layer (shock_x > x_max)."""
    if not shock_x <= x_max:
        return math.nan
    level = top + threshold
    below = None
    for k in range(len(x) - 1, -1, -1):
        if x[k] > shock_x or math.isnan(h[k]):
            continue
        if h[k] > level:
            if below is None:
                return shock_x - x[k]
            s = (level - h[below]) / (h[k] - h[below])
            return shock_x - (x[below] + s * (x[k] - x[below]))
        below = k
    return math.nan


def windowed(tau, samples, value, width):
    """Sample-weighted means of `value` over consecutive windows of `width` in tau:
    (window centres, means)."""
    ok = np.isfinite(value) & (samples > 0)
    tau, samples, value = tau[ok], samples[ok], value[ok]
    if len(tau) == 0:
        return np.array([]), np.array([])
    index = np.floor(tau / width).astype(int)
    centres, means = [], []
    for i in np.unique(index):
        m = index == i
        centres.append((i + 0.5) * width)
        means.append(float(np.sum(samples[m] * value[m]) / np.sum(samples[m])))
    return np.array(centres), np.array(means)


def extreme(tau, value, sign):
    """(value, tau) of the largest value of the given sign (+1 max, -1 min)."""
    ok = np.isfinite(value)
    if not ok.any():
        return math.nan, math.nan
    v = np.where(ok, sign * value, -np.inf)
    k = int(np.argmax(v))
    return float(value[k]), float(tau[k])


def mean_between(tau, samples, value, t0, t1):
    m = (tau >= t0) & (tau < t1) & np.isfinite(value) & (samples > 0)
    if not m.any():
        return math.nan
    return float(np.sum(samples[m] * value[m]) / np.sum(samples[m]))


def band_numbers(band):
    """Peaks and means of one band's force series, in uN and us."""
    tau, n = band["tau_s"], band["samples_1"]
    out = {}
    # (name, 1 us column, 0.01 ms column, sign): the contact force has its own 0.01 ms
    # window column (written by the band filter), the others are averaged here.
    for name, column, window_column, sign in (
            ("contact_up", "contact_y_N", "contact_window_y_N", +1), ("drag_down", "drag_y_N", "drag_y_N", -1),
            ("pressure_down", "pressure_y_N", "pressure_y_N", -1), ("magnus_up", "magnus_y_N", "magnus_y_N", +1)):
        v, t = extreme(tau, band[column], sign)
        out[name + "_1us_uN"], out[name + "_1us_tau_us"] = v * 1e6, t * 1e6
        wt, wv = windowed(tau, n, band[window_column], WINDOW)
        v, t = extreme(wt, wv, sign)
        out[name + "_10us_uN"], out[name + "_10us_tau_us"] = v * 1e6, t * 1e6
        if name == "contact_up":
            contact_windows = wt, wv
    # The first upward contact: the first 0.01 ms window whose mean is positive and not below
    # the next one's (the impact right after the downward push). In our layer a later, larger
    # one follows when the surface parcels land on the rebounding layer (docs/results.md).
    wt, wv = contact_windows
    # "Positive" means at least 1 % of the largest window: a mean of rounding noise (1e-20 uN
    # where the parcels touch nothing) is not an impact.
    floor = 0.01 * max([v for v in wv if np.isfinite(v)] + [0.0])
    first = next((k for k in range(len(wv)) if wv[k] > floor and (k + 1 == len(wv) or wv[k] >= wv[k + 1])), None)
    out["contact_first_up_10us_uN"] = wv[first] * 1e6 if first is not None else math.nan
    out["contact_first_up_10us_tau_us"] = wt[first] * 1e6 if first is not None else math.nan
    out["drag_y_late_uN"] = mean_between(tau, n, band["drag_y_N"], 1.0e-4, 3.0e-4) * 1e6
    out["magnus_y_late_uN"] = mean_between(tau, n, band["magnus_y_N"], 1.0e-4, 2.0e-4) * 1e6
    out["contact_y_late_uN"] = mean_between(tau, n, band["contact_y_N"], 1.0e-4, 2.0e-4) * 1e6
    gas = mean_between(tau, n, band["gas_rotation_rad_per_s"], 0.9e-4, 1.1e-4)
    particle = mean_between(tau, n, band["particle_rotation_rad_per_s"], 0.9e-4, 1.1e-4)
    out["gas_rotation_paper_0p1ms"] = -gas
    out["particle_rotation_paper_0p1ms"] = -particle
    out["gas_over_particle_rotation_0p1ms"] = gas / particle if particle != 0 else math.nan
    out["particle_rotation_paper_mean_0p05_0p3ms"] = -mean_between(
        tau, n, band["particle_rotation_rad_per_s"], 0.5e-4, 3.0e-4)
    h0 = mean_between(tau, n, band["height_m"], 0.0, 1.0e-6)
    out["height_change_0p1ms_mm"] = (mean_between(tau, n, band["height_m"], 0.95e-4, 1.05e-4) - h0) * 1e3
    out["height_change_0p3ms_mm"] = (mean_between(tau, n, band["height_m"], 2.95e-4, 3.05e-4) - h0) * 1e3
    return out


def read_vtr(path):
    import vtk  # python3-vtk9 (Debian)
    from vtk.util.numpy_support import vtk_to_numpy
    # A run on several MPI ranks writes its gas as a .pvtr joining the ranks' pieces.
    r = vtk.vtkXMLPRectilinearGridReader() if path.endswith(".pvtr") else vtk.vtkXMLRectilinearGridReader()
    r.SetFileName(path)
    r.Update()
    g = r.GetOutput()
    xn = vtk_to_numpy(g.GetXCoordinates())
    yn = vtk_to_numpy(g.GetYCoordinates())
    nx, ny = len(xn) - 1, len(yn) - 1
    cells = g.GetCellData()
    def field(name, comp=None):
        a = vtk_to_numpy(cells.GetArray(name))
        if comp is not None:
            a = a[:, comp]
        return a.reshape(ny, nx)
    t = g.GetFieldData().GetArray("TimeValue").GetValue(0)
    return {"t": t, "x": 0.5 * (xn[1:] + xn[:-1]), "y": 0.5 * (yn[1:] + yn[:-1]), "p": field("pressure"),
            "u": field("velocity", 0), "vorticity": field("vorticity"), "alpha_p": field("alpha_p")}


def gas_files(run):
    """(time, path) of every gas output, from the run's gas.pvd collection."""
    pvd = os.path.join(run, "gas.pvd")
    if not os.path.exists(pvd):
        return []
    entries = re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', open(pvd).read())
    return [(float(t), os.path.join(run, f)) for t, f in entries]


def gas_at(run, t):
    """The gas output nearest to time t (None without outputs)."""
    files = gas_files(run)
    if not files:
        return None
    return read_vtr(min(files, key=lambda tf: abs(tf[0] - t))[1])


def shock_row(g, j, p0):
    """x of the shock in row j: the largest x where p exceeds 1.05 p0 (the series' threshold)."""
    above = np.nonzero(g["p"][j] > 1.05 * p0)[0]
    return float(g["x"][above[-1]]) if len(above) else math.nan


def field_numbers(run, top):
    """Fig. 9 (shock shape at 0.5 ms), Fig. 13 (vorticity above the layer), Fig. 8d (pressure
    near the layer's leading part) from the gas VTK files."""
    out = {}
    g = gas_at(run, 5.0e-4)
    if g is None:
        return out
    out["field_time_ms"] = g["t"] * 1e3
    p0 = float(np.median(g["p"][:, -5]))
    rows = {"y_m1p0mm": -1.0e-3, "y_m0p1mm": -0.125e-3, "y_p1mm": 1.0e-3, "y_p5mm": 5.0e-3, "y_p20mm": 20.0e-3}
    for name, y in rows.items():
        j = int(np.argmin(np.abs(g["y"] - y)))
        out["shock_x_" + name + "_mm"] = shock_row(g, j, p0) * 1e3
    # Fig. 9c: inside the layer the gas slows right behind the shock (paper: x < 232 mm at 0.5 ms)
    j_in = int(np.argmin(np.abs(g["y"] + 1.0e-3)))
    j_out = int(np.argmin(np.abs(g["y"] - 5.0e-3)))
    xs = out["shock_x_y_m1p0mm_mm"] * 1e-3
    behind = (g["x"] > 0.05) & (g["x"] < xs - 0.005)
    out["u_inside_over_outside_behind_shock"] = float(np.mean(g["u"][j_in][behind]) / np.mean(g["u"][j_out][behind]))
    # Fig. 13b: the gas rotation above the layer, paper convention (-vorticity/2), over
    # 0 < y - top < 2 mm behind the shock and past the leading edge (50 mm < x < x_s - 5 mm)
    xsurf = out["shock_x_y_p1mm_mm"] * 1e-3
    band = (g["y"] > top) & (g["y"] < top + 2.0e-3)
    cols = (g["x"] > 0.05) & (g["x"] < xsurf - 0.005)
    w = -0.5 * g["vorticity"][np.ix_(band, cols)]
    out["gas_rotation_paper_above_layer_mean"] = float(np.mean(w))
    out["gas_rotation_paper_above_layer_positive_share"] = float(np.mean(w > 0))
    # Fig. 8d: pressure just above the layer near its leading edge, at every output time
    fig8 = []
    for _, f in gas_files(run):
        h = read_vtr(f)
        j = int(np.argmin(np.abs(h["y"] - (top + 0.5e-3))))
        def p_at(x):
            return float(np.interp(x, h["x"], h["p"][j]))
        m = (h["x"] >= 0.0) & (h["x"] <= 0.08)
        fig8.append({"t_ms": h["t"] * 1e3, "p_10mm_kPa": p_at(0.010) / 1e3, "p_20mm_kPa": p_at(0.020) / 1e3,
                     "p_40mm_kPa": p_at(0.040) / 1e3, "x_mm": (h["x"][m] * 1e3).tolist(),
                     "p_kPa": (h["p"][j][m] / 1e3).tolist()})
    out["fig8d_pressure_above_layer"] = fig8
    # Fig. 8d: p rising over 10-20 mm and falling over 20-40 mm (a maximum near 20 mm), at
    # the outputs after t = 0
    out["fig8d_peak_near_20mm_at_ms"] = [q["t_ms"] for q in fig8[1:]
                                          if q["p_20mm_kPa"] > q["p_10mm_kPa"] and q["p_20mm_kPa"] > q["p_40mm_kPa"]]
    return out


def compare(run, t_profile):
    out = {"run": run}
    shock = series(run, "shock_position")
    surface = series(run, "surface_height")
    out["shock_x_mm"] = shock_at(shock, t_profile) * 1e3 if shock is not None else math.nan
    top = math.nan
    if surface is not None:
        _, _, h0 = profile_at(surface, 0.0)
        top = float(np.median(h0))
        columns_top = loose_top_surface(run)
        if columns_top is not None:
            out["surface_at_t0_mm"] = top * 1e3
            top = columns_top
        t, x, h_raw = profile_at(surface, t_profile)
        h = running_median(x, h_raw)
        out["profile_time_ms"] = t * 1e3
        out["layer_top_mm"] = top * 1e3
        for s in STATIONS:
            inside = s <= x[-1] - 0.5 * SMOOTHING
            out["h_at_%03dmm_mm" % round(s * 1e3)] = float(np.interp(s, x, h)) * 1e3 if inside else math.nan
        xs = shock_at(shock, t) if shock is not None else math.nan
        x_max = layer_end(run)
        out["lifting_delay_mm"] = lifting_delay(x, h, xs, top, x_max) * 1e3
        # How much the delay owes to the threshold that says where lifting "begins" (the paper
        # reads it off its curves and states none): the rule at other lifts above the top.
        out["lifting_delay_by_threshold_mm"] = {
            "%g mm" % (t * 1e3): lifting_delay(x, h, xs, top, x_max, threshold=t) * 1e3 for t in DELAY_THRESHOLDS}
        # the lifted height: the highest surface between x = 50 mm (past the leading edge,
        # where the diffracted shock throws the layer up, Fig. 8) and the shock
        m = (x > 0.05) & (x < xs) & np.isfinite(h)
        out["max_lift_50mm_to_shock_mm"] = float(np.max(h[m]) - top) * 1e3 if m.any() else math.nan
        out["profile_x_mm"] = (x * 1e3).tolist()
        out["profile_h_mm"] = ((h - top) * 1e3).tolist()
        out["profile_h_raw_mm"] = ((h_raw - top) * 1e3).tolist()
        out["lifting_delay_raw_mm"] = lifting_delay(x, h_raw, xs, top, x_max) * 1e3
    for band in ("surface", "middle"):
        b = series(run, "forces_" + band)
        if b is not None and len(b["tau_s"]):
            out[band] = band_numbers(b)
    if math.isfinite(top):
        out.update(field_numbers(run, top))
    return out


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run")
    ap.add_argument("--json", help="write the JSON here as well as to stdout")
    ap.add_argument("--time", type=float, default=6.0e-4, help="profile time in s (default 0.6 ms)")
    a = ap.parse_args(argv)
    result = compare(a.run, a.time)
    text = json.dumps(result, indent=1, allow_nan=True)
    if a.json:
        with open(a.json, "w") as f:
            f.write(text + "\n")
    brief = {k: v for k, v in result.items() if not k.startswith("profile_") and k != "fig8d_pressure_above_layer"}
    print(json.dumps(brief, indent=1, allow_nan=True))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
