"""The numbers a run's README summary quotes, from its output folder (docs/output.md).

Usage:
    /usr/bin/python3 analysis/summarize_run.py OUTDIR [--times T1 T2 ...] [--median-range X0 X1]
        [--station X]

For each time T (s; default: the last output) the shock position and the dust surface
height h(x) at the output time nearest to T: its maximum and where, its median over
[X0, X1] (m; default: every column with dust) and its value at the station X (m; default:
the middle of the profile, linear between column centres). Then the last gas .vtr: cells,
whether every value is finite, the smallest density and pressure and the largest alpha_p.
Reads series/series.h5 (h5py) and the .vtr through ParaView's VTK modules.
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np


def series(h5, name):
    """{column: array} of group `name`, in the order of its "columns" attribute."""
    group = h5[name]
    return {c: group[c][()] for c in group.attrs["columns"].split(",")}


def nearest(times, t):
    return times[np.argmin(np.abs(times - t))]


def surface_lines(h5, t_wanted, median_range, station):
    lines = []
    shock = series(h5, "shock_position") if "shock_position" in h5 else None
    surface = series(h5, "surface_height") if "surface_height" in h5 else None
    if shock is not None:
        t = nearest(shock["time"], t_wanted)
        x = shock["x"][shock["time"] == t][0]
        lines.append("shock x at t = %.2f ms: %.1f mm" % (t * 1e3, x * 1e3))
    if surface is not None:
        t = nearest(surface["time"], t_wanted)
        at = surface["time"] == t
        x, h = surface["x"][at], surface["height"][at]
        lo, hi = median_range if median_range else (x.min(), x.max())
        inside = (x >= lo) & (x <= hi)
        xs = station if station is not None else 0.5 * (x.min() + x.max())
        k = int(np.argmax(h))
        lines.append("t = %.2f ms: surface height max %.2f mm (at x = %.0f mm); median over %.0f-%.0f mm %.2f mm; "
                     "at x=%.0f mm %.2f mm" % (t * 1e3, h[k] * 1e3, x[k] * 1e3, lo * 1e3, hi * 1e3,
                                               np.median(h[inside]) * 1e3, xs * 1e3, np.interp(xs, x, h) * 1e3))
    return lines


def last_gas_line(outdir):
    pvd = os.path.join(outdir, "gas.pvd")
    if not os.path.isfile(pvd):
        return None
    files = [d.get("file") for d in ET.parse(pvd).getroot().iter("DataSet")]
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLPRectilinearGridReader, vtkXMLRectilinearGridReader
    # A run on several MPI ranks lists .pvtr files that join the ranks' pieces.
    reader = vtkXMLPRectilinearGridReader() if files[-1].endswith(".pvtr") else vtkXMLRectilinearGridReader()
    reader.SetFileName(os.path.join(outdir, files[-1]))
    reader.Update()
    grid = reader.GetOutput()
    cells = grid.GetCellData()
    arrays = {cells.GetArrayName(k): vtk_to_numpy(cells.GetArray(k)) for k in range(cells.GetNumberOfArrays())}
    finite = all(np.isfinite(a).all() for a in arrays.values())
    ap = arrays["alpha_p"].max()
    return ("last gas file %s: cells %d, finite %s, rho min %.3f, p min %.4g, alpha_p max %.3f (alpha_g min %.3f)"
            % (os.path.basename(files[-1]), grid.GetNumberOfCells(), finite, arrays["density"].min(),
               arrays["pressure"].min(), ap, 1.0 - ap))


def main(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("outdir")
    p.add_argument("--times", type=float, nargs="+", help="s (default: the last output)")
    p.add_argument("--median-range", type=float, nargs=2, metavar=("X0", "X1"), help="m")
    p.add_argument("--station", type=float, help="m")
    args = p.parse_args(argv)
    path = os.path.join(args.outdir, "series", "series.h5")
    if not os.path.isfile(path):
        print("summarize_run.py: error: no %s" % path, file=sys.stderr)
        return 1
    with h5py.File(path, "r") as h5:
        times = args.times
        if not times:
            times = [series(h5, "shock_position")["time"][-1] if "shock_position" in h5 else np.inf]
        for t in times:
            for line in surface_lines(h5, t, args.median_range, args.station):
                print(line)
    line = last_gas_line(args.outdir)
    if line:
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
