#!/usr/bin/python3
"""Compare a shock-tube run's final state with the exact Riemann solution.

Usage: /usr/bin/python3 analysis/sod_compare.py OUTDIR [--row J] [--gamma G]
           [--left RHO,U,P] [--right RHO,U,P] [--x0 X]

Reads the last gas file listed in OUTDIR/gas.pvd (VTK's Python module, which Debian's
python3-paraview provides to /usr/bin/python3), takes one row of cells (default the middle
one), and plots density, x-velocity and pressure against the exact solution (ideal gas,
Toro ch. 4) at the file's time. The initial states, split position and gamma come from
OUTDIR/scene.resolved.toml ([initial] kind = "riemann") unless given; without either the
Sod problem (1, 0, 1 | 0.125, 0, 0.1 at x0 = 0.5, gamma = 1.4) is assumed.
Writes OUTDIR/figures/sod_compare.png and prints the L1 error of each quantity.
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


# ---------------------------------------------------------------- exact Riemann solver
def _f(p, rho, u, pk, g):
    """Toro's pressure function f_K and its derivative."""
    a = np.sqrt(g * pk / rho)
    if p > pk:
        A, B = 2.0 / ((g + 1.0) * rho), (g - 1.0) / (g + 1.0) * pk
        s = np.sqrt(A / (p + B))
        return (p - pk) * s, s * (1.0 - 0.5 * (p - pk) / (p + B))
    r = (p / pk) ** ((g - 1.0) / (2.0 * g))
    return 2.0 * a / (g - 1.0) * (r - 1.0), (p / pk) ** (-(g + 1.0) / (2.0 * g)) / (rho * a)


def star_state(L, R, g):
    rl, ul, pl = L
    rr, ur, pr = R
    p = max(1e-8, 0.5 * (pl + pr))
    for _ in range(100):  # Newton on f_L + f_R + du = 0
        fl, dl = _f(p, rl, ul, pl, g)
        fr, dr = _f(p, rr, ur, pr, g)
        step = (fl + fr + ur - ul) / (dl + dr)
        p_new = max(1e-12, p - step)
        if abs(p_new - p) < 1e-14 * p:
            p = p_new
            break
        p = p_new
    fl, _ = _f(p, rl, ul, pl, g)
    fr, _ = _f(p, rr, ur, pr, g)
    return p, 0.5 * (ul + ur) + 0.5 * (fr - fl)


def sample(s, L, R, g, ps, us):
    """(rho, u, p) at similarity coordinate s = (x - x0) / t."""
    def side(K, sign):
        rk, uk, pk = K
        ak = np.sqrt(g * pk / rk)
        if ps > pk:  # shock
            sk = uk + sign * ak * np.sqrt((g + 1) / (2 * g) * ps / pk + (g - 1) / (2 * g))
            if sign * (s - sk) >= 0:
                return rk, uk, pk
            rs = rk * (ps / pk + (g - 1) / (g + 1)) / ((g - 1) / (g + 1) * ps / pk + 1)
            return rs, us, ps
        head = uk + sign * ak
        a_star = ak * (ps / pk) ** ((g - 1) / (2 * g))
        tail = us + sign * a_star
        if sign * (s - head) >= 0:
            return rk, uk, pk
        if sign * (s - tail) <= 0:
            return rk * (ps / pk) ** (1 / g), us, ps
        c = 2 / (g + 1) - sign * (g - 1) / ((g + 1) * ak) * (uk - s)
        u = 2 / (g + 1) * (-sign * ak + (g - 1) / 2 * uk + s)
        return rk * c ** (2 / (g - 1)), u, pk * c ** (2 * g / (g - 1))
    return side(L, -1.0) if s <= us else side(R, +1.0)


def exact(x, t, x0, L, R, g):
    ps, us = star_state(L, R, g)
    out = np.array([sample((xi - x0) / t, L, R, g, ps, us) for xi in x])
    return out[:, 0], out[:, 1], out[:, 2]


# ---------------------------------------------------------------- reading the run
def last_dataset(outdir):
    root = ET.parse(os.path.join(outdir, "gas.pvd")).getroot()
    entries = [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")]
    if not entries:
        raise SystemExit("sod_compare.py: gas.pvd lists no dataset")
    t, f = entries[-1]
    return t, os.path.join(outdir, f)


def read_row(path, row):
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLRectilinearGridReader
    reader = vtkXMLRectilinearGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    xn = vtk_to_numpy(grid.GetXCoordinates())
    nx, ny = len(xn) - 1, grid.GetDimensions()[1] - 1
    if grid.GetNumberOfCells() != nx * ny or nx <= 0:
        raise SystemExit("sod_compare.py: %s holds no cells (failed to load?)" % path)
    j = ny // 2 if row is None else row
    cd = grid.GetCellData()
    def col(name, comp=0):
        a = vtk_to_numpy(cd.GetArray(name))
        a = a.reshape(ny, nx, -1)[:, :, comp] if a.ndim > 1 else a.reshape(ny, nx)
        return a[j]
    return 0.5 * (xn[1:] + xn[:-1]), col("density"), col("velocity", 0), col("pressure")


def scene_setup(outdir):
    path = os.path.join(outdir, "scene.resolved.toml")
    if not os.path.isfile(path):
        return None
    import tomllib
    with open(path, "rb") as f:
        scene = tomllib.load(f)
    ini, gas = scene.get("initial", {}), scene.get("gas", {})
    if ini.get("kind") != "riemann":
        return None
    R_gas = gas.get("gas_constant", 288.19)
    def state(s):
        rho = s["rho"] if "rho" in s else s["p"] / (R_gas * s["T"])
        return (rho, s.get("u", 0.0), s["p"])
    return state(ini["left"]), state(ini["right"]), ini["position"], gas.get("gamma", 1.4)


def cell_widths(x):
    """Widths of the cells whose centres are x (faces midway, the ends mirrored)."""
    return np.diff(np.concatenate([[x[0] - (x[1] - x[0]) / 2], 0.5 * (x[1:] + x[:-1]), [x[-1] + (x[-1] - x[-2]) / 2]]))


def l1_error(numeric, exact_at_cells, dx):
    """Cell-width-weighted mean |numeric - exact|: the L1 error of one quantity."""
    return float(np.sum(np.abs(numeric - exact_at_cells) * dx) / np.sum(dx))


def l1_errors(outdir, row=None):
    """L1 errors of density, velocity and pressure of a riemann run's last output against
    the exact solution (its states from scene.resolved.toml), and that output's time."""
    setup = scene_setup(outdir)
    if not setup:
        raise SystemExit("sod_compare.py: %s is not a riemann run" % outdir)
    L, R, x0, g = setup
    t, path = last_dataset(outdir)
    if t <= 0:
        raise SystemExit("sod_compare.py: the last dataset is at t = 0")
    x, rho, u, pres = read_row(path, row)
    cr, cu, cp = exact(x, t, x0, L, R, g)
    dx = cell_widths(x)
    return {"density": l1_error(rho, cr, dx), "velocity": l1_error(u, cu, dx), "pressure": l1_error(pres, cp, dx)}, t


def main(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("outdir")
    p.add_argument("--row", type=int)
    p.add_argument("--gamma", type=float)
    p.add_argument("--left")
    p.add_argument("--right")
    p.add_argument("--x0", type=float)
    a = p.parse_args(argv)
    L, R, x0, g = (1.0, 0.0, 1.0), (0.125, 0.0, 0.1), 0.5, 1.4
    setup = scene_setup(a.outdir)
    if setup:
        L, R, x0, g = setup
    if a.left:
        L = tuple(float(v) for v in a.left.split(","))
    if a.right:
        R = tuple(float(v) for v in a.right.split(","))
    x0 = a.x0 if a.x0 is not None else x0
    g = a.gamma if a.gamma is not None else g

    t, path = last_dataset(a.outdir)
    x, rho, u, pres = read_row(path, a.row)
    if t <= 0:
        raise SystemExit("sod_compare.py: the last dataset is at t = 0")
    xe = np.linspace(x.min(), x.max(), 2000)
    er, eu, ep = exact(xe, t, x0, L, R, g)
    cr, cu, cp = exact(x, t, x0, L, R, g)
    dx = cell_widths(x)
    fig, axes = plt.subplots(3, 1, figsize=(7, 9), sharex=True)
    for ax, num, ex, cell_exact, label in ((axes[0], rho, er, cr, "density [kg/m$^3$]"),
                                           (axes[1], u, eu, cu, "velocity [m/s]"),
                                           (axes[2], pres, ep, cp, "pressure [Pa]")):
        ax.plot(xe, ex, "k-", lw=1, label="exact")
        ax.plot(x, num, "o", ms=2.5, color="tab:red", label="dustlift")
        l1 = l1_error(num, cell_exact, dx)
        ax.set_ylabel(label)
        ax.set_title("L1 error %.3e" % l1, fontsize=9)
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        print("%-10s L1 error %.6e" % (label.split(" [")[0], l1))
    axes[2].set_xlabel("x [m]")
    fig.suptitle("Riemann problem at t = %.6g s" % t)
    out = os.path.join(a.outdir, "figures")
    os.makedirs(out, exist_ok=True)
    path = os.path.join(out, "sod_compare.png")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    print("wrote", path)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
