"""Offscreen PNG renders of a dustlift run (ParaView pvbatch).

Usage (Debian's ParaView is GLX-only, so an X server is needed even offscreen):
    xvfb-run -a pvbatch pvstates/render.py OUTDIR [--all] [--figures DIR]
        [--layer-height H] [--state pvstates/pressure_parcels.pvsm] [--save-state FILE]

Writes into OUTDIR/figures/ (or --figures) for the last output time (every time with --all):
  pressure_NNNNNN.png   gas pressure, parcels overlaid as black points if parcels.pvd
                        exists (paper Fig. 8 style)
  vorticity_NNNNNN.png  gas vorticity w_z = dv/dx - du/dy (symmetric diverging map) in the
                        band 0 <= y - y_min <= H near the dust layer
  state_NNNNNN.png      with --state: the view of a saved ParaView state, its readers
                        pointed at OUTDIR's gas.pvd / parcels.pvd
Every call also writes OUTDIR/pressure_parcels.pvsm: the pressure + parcels pipeline as a
ParaView state whose readers name gas.pvd and parcels.pvd without a folder, a live time label
and a colour range that follows each time's data (open it in the GUI with "Search files
under specified directory" = OUTDIR). --save-state FILE writes that state elsewhere too.
pvbatch exits 0 even when data fail to load: this script exits 1 on any problem it
detects, but callers should check the PNGs themselves.
"""
import argparse
import os
import re
import sys
import time

from paraview import simple as pv

WIDTH = 1600


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("outdir", help="run output folder holding gas.pvd (and parcels.pvd)")
    p.add_argument("--all", action="store_true", help="render every output time, not only the last")
    p.add_argument("--figures", help="folder for the PNGs (default OUTDIR/figures)")
    p.add_argument("--layer-height", type=float, default=0.0,
                   help="m; height of the vorticity view above the floor (default: 3x the "
                        "parcels' top, or a quarter of the domain for gas-only runs)")
    p.add_argument("--state", help="a .pvsm state to render with OUTDIR's data")
    p.add_argument("--save-state", help="also write the pressure + parcels state (relative file names) to this .pvsm")
    return p.parse_args(argv)


def fail(message):
    print("render.py: error: " + message, file=sys.stderr)
    sys.exit(1)


def white_view(size):
    view = pv.CreateView("RenderView")
    view.ViewSize = size
    view.OrientationAxesVisibility = 0
    try:  # ParaView >= 5.10 takes the background from the palette unless told otherwise
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    view.Background = [1.0, 1.0, 1.0]
    view.CameraParallelProjection = 1
    return view


BAR_MARGIN = 170   # px kept free below the data for the x axis and the colour bar
TOP_MARGIN = 40    # px kept free above the data for the time label
LEFT_MARGIN = 110  # px kept free left of the data for the y axis
RIGHT_MARGIN = 40


def frame(view, xmin, xmax, ymin, ymax):
    """Parallel camera showing [xmin, xmax] x [ymin, ymax] between the margins, the floor
    ymin just above the colour bar."""
    pv.Render(view)  # the first render resets the camera: frame after it
    w, h = view.ViewSize
    usable = max(h - BAR_MARGIN - TOP_MARGIN, 1)
    usable_w = max(w - LEFT_MARGIN - RIGHT_MARGIN, 1)
    scale = 0.5 * max((ymax - ymin) * h / float(usable), (xmax - xmin) * h / float(usable_w))
    world_per_px = 2.0 * scale / h
    cx = 0.5 * (xmin + xmax) - 0.5 * (LEFT_MARGIN - RIGHT_MARGIN) * world_per_px
    cy = ymin + scale - BAR_MARGIN * world_per_px
    view.CameraPosition = [cx, cy, 1.0]
    view.CameraFocalPoint = [cx, cy, 0.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelScale = scale


def image_size(dx, dy):
    height = int(min(max(WIDTH * dy / dx, 300), 1200)) + BAR_MARGIN + TOP_MARGIN
    return [WIDTH, height]


def show_axes(view):
    """Axes along the data's edges with ticks in metres: the image's length scale."""
    grid = view.AxesGrid
    grid.Visibility = 1
    grid.XTitle = "x [m]"
    grid.YTitle = " "  # the time label names the unit: a title here would sit on the tick labels
    grid.ShowEdges = 0
    grid.ShowGrid = 0
    grid.ShowTicks = 1
    grid.AxesToLabel = 3  # the x axis along the bottom edge, the y axis along the left edge
    for prefix in ("X", "Y"):
        setattr(grid, prefix + "TitleColor", [0.0, 0.0, 0.0])
        setattr(grid, prefix + "LabelColor", [0.0, 0.0, 0.0])
        setattr(grid, prefix + "TitleFontSize", 16)
        setattr(grid, prefix + "LabelFontSize", 13)
    grid.GridColor = [0.0, 0.0, 0.0]


def style_bar(lut, view, title):
    bar = pv.GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.TitleColor = [0, 0, 0]
    bar.LabelColor = [0, 0, 0]
    bar.Orientation = "Horizontal"
    bar.WindowLocation = "Lower Center"
    bar.ScalarBarLength = 0.5
    # The end labels of the range sit on the nearest tick labels of a symmetric range.
    bar.AddRangeLabels = 0
    bar.TitleFontSize = 16
    bar.LabelFontSize = 14
    bar.Visibility = 1


def time_label(view, source):
    """A label that follows the view's time (a state saved with it stays live)."""
    text = pv.PythonAnnotation(registrationName="time label", Input=source)
    text.Expression = "'t = %.4f ms    (x, y in m)' % (t_value * 1e3)"
    disp = pv.Show(text, view)
    disp.Color = [0, 0, 0]
    disp.FontSize = 14
    disp.WindowLocation = "Upper Left Corner"
    return text


def save_relative_state(path, outdir):
    """Saves the session as a .pvsm that loads for any run folder ("Search files under
    specified directory"), not only the one it was saved from: the readers name their files
    relative to the run folder (gas.pvd, parcels.pvd), and the animation scene keeps no
    start, end or current time, so it takes them from the data it is loaded with (a saved
    end time would stop another run's animation there)."""
    pv.SaveState(path)
    with open(path) as f:
        text = f.read()
    prefix = os.path.join(os.path.abspath(outdir), "")
    text = text.replace('value="' + prefix, 'value="')
    scene = re.search(r'<Proxy group="animation" type="AnimationScene" id="(\d+)".*?</Proxy>', text, re.S)
    if scene:
        block = scene.group(0)
        for name in ("StartTime", "EndTime", "AnimationTime"):
            block = re.sub(r'\n\s*<Property name="%s" id="%s\.%s".*?</Property>' % (name, scene.group(1), name), "",
                           block, flags=re.S)
        text = text.replace(scene.group(0), block)
    with open(path, "w") as f:
        f.write(text)


def cell_range(source, name, t):
    source.UpdatePipeline(t)
    info = source.CellData[name]
    if info is None:
        fail("array '%s' missing in %s" % (name, source.FileName))
    return info.GetRange(0)


def pressure_view(gas, parcels, t, bounds):
    xmin, xmax, ymin, ymax = bounds[0], bounds[1], bounds[2], bounds[3]
    view = white_view(image_size(xmax - xmin, ymax - ymin))
    view.ViewTime = t
    disp = pv.Show(gas, view)
    disp.Representation = "Surface"
    pv.ColorBy(disp, ("CELLS", "pressure"))
    lut = pv.GetColorTransferFunction("pressure")
    lut.ApplyPreset("Jet", True)
    # The range follows the data of each time shown (also in a saved state, where a fixed
    # range would saturate another run's data).
    lut.AutomaticRescaleRangeMode = "Clamp and update every timestep"
    lo, hi = cell_range(gas, "pressure", t)
    lut.RescaleTransferFunction(lo, hi if hi > lo else lo + 1.0)
    style_bar(lut, view, "pressure [Pa]")
    if parcels is not None:
        pdisp = pv.Show(parcels, view)
        pdisp.Representation = "Points"
        pdisp.PointSize = 2.0
        pdisp.ColorArrayName = ["POINTS", ""]  # solid colour
        pdisp.AmbientColor = [0.0, 0.0, 0.0]
        pdisp.DiffuseColor = [0.0, 0.0, 0.0]
    time_label(view, gas)
    show_axes(view)
    frame(view, xmin, xmax, ymin, ymax)
    return view


def vorticity_view(gas, parcels, t, bounds, layer_height):
    xmin, xmax, ymin = bounds[0], bounds[1], bounds[2]
    if layer_height <= 0.0:
        top = None
        if parcels is not None:
            parcels.UpdatePipeline(t)
            pb = parcels.GetDataInformation().GetBounds()
            if pb[3] >= pb[2]:
                top = pb[3]
        layer_height = 3.0 * (top - ymin) if top is not None and top > ymin else 0.25 * (bounds[3] - ymin)
    ymax = min(bounds[3], ymin + layer_height)
    view = white_view(image_size(xmax - xmin, ymax - ymin))
    view.ViewTime = t
    disp = pv.Show(gas, view)
    disp.Representation = "Surface"
    pv.ColorBy(disp, ("CELLS", "vorticity"))
    lut = pv.GetColorTransferFunction("vorticity")
    lut.ApplyPreset("Cool to Warm", True)
    lo, hi = cell_range(gas, "vorticity", t)
    m = max(abs(lo), abs(hi), 1e-30)
    lut.RescaleTransferFunction(-m, m)
    style_bar(lut, view, "vorticity [1/s]")
    if parcels is not None:
        pdisp = pv.Show(parcels, view)
        pdisp.Representation = "Points"
        pdisp.PointSize = 1.0
        pdisp.ColorArrayName = ["POINTS", ""]  # solid colour
        pdisp.AmbientColor = [0.3, 0.3, 0.3]
        pdisp.DiffuseColor = [0.3, 0.3, 0.3]
    time_label(view, gas)
    show_axes(view)
    frame(view, xmin, xmax, ymin, ymax)
    return view


def save(view, path):
    pv.Render(view)
    pv.SaveScreenshot(path, view, ImageResolution=list(view.ViewSize), TransparentBackground=0)
    if not os.path.isfile(path) or os.path.getsize(path) == 0:
        fail("no image written to " + path)
    print("wrote", path)


def render_state(state, outdir, figures, times_wanted):
    # Loading a state builds every representation of its displays, the image-slice one too,
    # which reports (as a VTK error) that the rectilinear gas grid is not image data; the
    # surface shown is right. Errors are silenced while the state loads; what it shows is
    # checked below (its readers' times, a written image).
    from paraview import vtk as pvvtk  # noqa: E402
    pvvtk.vtkObject.GlobalWarningDisplayOff()
    try:
        pv.LoadState(state, data_directory=outdir, restrict_to_data_directory=True)
    finally:
        pvvtk.vtkObject.GlobalWarningDisplayOn()
    view = pv.GetActiveView() or pv.GetRenderViews()[0]
    sources = pv.GetSources()
    times = sorted({t for src in sources.values() for t in getattr(src, "TimestepValues", []) or []})
    if not times:
        fail("the state's readers found no time steps under " + outdir)
    # The state's camera fits the run it was saved from: refit it to this run's gas data.
    gas = [src for src in sources.values() if str(getattr(src, "FileName", "")).endswith("gas.pvd")]
    if gas:
        gas[0].UpdatePipeline(times[-1])
        b = gas[0].GetDataInformation().GetBounds()
        frame(view, b[0], b[1], b[2], b[3])
    scene = pv.GetAnimationScene()
    # The animation takes its range from the data (a state with a locked end time would stop
    # at the end of the run it was saved from).
    print("state: %d times from %g to %g s; animation from %g to %g s" % (len(times), times[0], times[-1],
                                                                          scene.StartTime, scene.EndTime))
    for index, t in times_wanted(times):
        scene.AnimationTime = t
        view.ViewTime = t
        # The GUI rescales "update every timestep" colour maps on a time change; pvbatch does not.
        for src in sources.values():
            disp = pv.GetDisplayProperties(src, view)
            lut = getattr(disp, "LookupTable", None)
            if lut is not None and "every timestep" in str(getattr(lut, "AutomaticRescaleRangeMode", "")):
                disp.RescaleTransferFunctionToDataRange(False, True)
        save(view, os.path.join(figures, "state_%06d.png" % index))


def main(argv):
    args = parse_args(argv)
    outdir = os.path.abspath(args.outdir)
    gas_pvd = os.path.join(outdir, "gas.pvd")
    parcels_pvd = os.path.join(outdir, "parcels.pvd")
    figures = os.path.abspath(args.figures or os.path.join(outdir, "figures"))
    os.makedirs(figures, exist_ok=True)
    start = time.time()

    def times_wanted(times):
        indexed = list(enumerate(times))
        return indexed if args.all else indexed[-1:]

    if args.state:
        render_state(os.path.abspath(args.state), outdir, figures, times_wanted)
        print("render.py: %.1f s" % (time.time() - start))
        return
    if not os.path.isfile(gas_pvd):
        fail("no gas.pvd in " + outdir)
    gas = pv.PVDReader(registrationName="gas.pvd", FileName=gas_pvd)
    gas.CellArrays = ["pressure", "vorticity"]
    times = list(gas.TimestepValues) if gas.TimestepValues else [0.0]
    parcels = None
    if os.path.isfile(parcels_pvd):
        parcels = pv.PVDReader(registrationName="parcels.pvd", FileName=parcels_pvd)
    gas.UpdatePipeline(times[-1])
    bounds = gas.GetDataInformation().GetBounds()
    if gas.GetDataInformation().GetNumberOfCells() == 0:
        fail("gas data in %s has no cells (failed to load?)" % gas_pvd)
    # The views are deleted together at the end: deleting the first render view before the
    # next one is made (Mesa llvmpipe under Xvfb) made its first render print four VTK "ERR"
    # lines about shader vertex attributes, though the image came out right.
    views = []
    for index, t in times_wanted(times):
        view = pressure_view(gas, parcels, t, bounds)
        views.append(view)
        save(view, os.path.join(figures, "pressure_%06d.png" % index))
        if index == len(times) - 1:
            pv.SetActiveView(view)
            for state in [os.path.join(outdir, "pressure_parcels.pvsm")] + ([args.save_state] if args.save_state else []):
                save_relative_state(os.path.abspath(state), outdir)
                print("wrote", state)
        view = vorticity_view(gas, parcels, t, bounds, args.layer_height)
        views.append(view)
        save(view, os.path.join(figures, "vorticity_%06d.png" % index))
    for view in views:
        pv.Delete(view)
    print("render.py: %d time(s) in %.1f s" % (len(times_wanted(times)), time.time() - start))


if __name__ == "__main__":
    main(sys.argv[1:])
