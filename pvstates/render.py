"""Offscreen PNG renders of a dustlift run (ParaView pvbatch).

Usage (Debian's ParaView is GLX-only, so an X server is needed even offscreen):
    bash scripts/with-xvfb.sh pvbatch pvstates/render.py OUTDIR [--all | --time T] [--figures DIR]
        [--layer-height H] [--state pvstates/pressure_parcels.pvsm] [--save-state FILE]
    bash scripts/with-xvfb.sh pvbatch pvstates/render.py OUTDIR --field NAME [--field NAME ...]
        [--x XMIN XMAX] [--y YMIN YMAX] [--stretch F] [--log] [--range LO HI] [--parcels]
        [--size WIDTH HEIGHT] [--colormap PRESET] [--all | --time T] [--save-state FILE]

Writes into OUTDIR/figures/ (or --figures) for the last output time (every time with --all,
the output nearest T seconds with --time):
  pressure_NNNNNN.png   gas pressure, parcels overlaid as black points if parcels.pvd
                        exists (paper Fig. 8 style)
  vorticity_NNNNNN.png  gas vorticity w_z = dv/dx - du/dy (symmetric diverging map) in the
                        band 0 <= y - y_min <= H near the dust layer
  state_NNNNNN.png      with --state: the view of a saved ParaView state, its readers
                        pointed at OUTDIR's gas.pvd / parcels.pvd
Every call without --field also writes OUTDIR/pressure_parcels.pvsm: the pressure + parcels
pipeline as a ParaView state whose readers name gas.pvd and parcels.pvd without a folder, a
live time label and a colour range that follows each time's data (open it in the GUI with
"Search files under specified directory" = OUTDIR). --save-state FILE writes that state
elsewhere too.

With --field, instead, one view per field named (FIELDS below; velocity is the speed |u|):
  <field>_NNNNNN.png    the field, optionally on a log colour scale (--log: cells below
                        the range's low end are left out, white), within a zoom box (--x,
                        --y in metres; default the whole grid), with the y axis stretched F
                        times (--stretch: the axis labels stay in metres), parcels as black
                        points (--parcels)
and OUTDIR/<field>.pvsm, the state of that view (relative file names as above; --save-state
writes the first field's state elsewhere too). The colour range is the field's range inside
the box (--range LO HI fixes it; with --log the low end is the smallest positive value, at
least 1e-5 of the high end).
--size sets the PNG's pixels (default 1600 wide, the height from the box's aspect).

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

# The gas cell arrays a --field view shows: (array, component or None for the magnitude of a
# vector, colour-bar title, default colour map, symmetric range around 0).
FIELDS = {
    "pressure": ("pressure", 0, "pressure [Pa]", "Jet", False),
    "density": ("density", 0, "density [kg/m^3]", "Viridis (matplotlib)", False),
    "temperature": ("temperature", 0, "temperature [K]", "Inferno (matplotlib)", False),
    "mach": ("mach", 0, "Mach number [1]", "Viridis (matplotlib)", False),
    "velocity": ("velocity", None, "speed [m/s]", "Viridis (matplotlib)", False),
    "velocity_x": ("velocity", 0, "velocity u [m/s]", "Cool to Warm", True),
    "velocity_y": ("velocity", 1, "velocity v [m/s]", "Cool to Warm", True),
    "vorticity": ("vorticity", 0, "vorticity [1/s]", "Cool to Warm", True),
    "alpha_p": ("alpha_p", 0, "particle volume fraction alpha_p [1]", "Viridis (matplotlib)", False),
    "dust_concentration": ("dust_concentration", 0, "dust concentration [kg/m^3]", "Inferno (matplotlib)", False),
}


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("outdir", help="run output folder holding gas.pvd (and parcels.pvd)")
    p.add_argument("--all", action="store_true", help="render every output time, not only the last")
    p.add_argument("--figures", help="folder for the PNGs (default OUTDIR/figures)")
    p.add_argument("--layer-height", type=float, default=0.0,
                   help="m; height of the vorticity view above the floor (default: 3x the "
                        "parcels' top, or a quarter of the domain for gas-only runs)")
    p.add_argument("--state", help="a .pvsm state to render with OUTDIR's data")
    p.add_argument("--save-state", help="also write the view's state (relative file names) to this .pvsm")
    p.add_argument("--time", type=float, help="s; render the output nearest this time (not with --all)")
    p.add_argument("--field", action="append", choices=sorted(FIELDS),
                   help="render this gas field instead of the pressure and vorticity pair (repeatable)")
    p.add_argument("--x", nargs=2, type=float, metavar=("XMIN", "XMAX"), help="m; the zoom box along x")
    p.add_argument("--y", nargs=2, type=float, metavar=("YMIN", "YMAX"), help="m; the zoom box along y")
    p.add_argument("--stretch", type=float, default=1.0,
                   help="vertical exaggeration: y drawn this many times longer than x (default 1)")
    p.add_argument("--log", action="store_true", help="log colour scale")
    p.add_argument("--range", nargs=2, type=float, metavar=("LO", "HI"), help="fixed colour range")
    p.add_argument("--parcels", action="store_true", help="overlay the parcels as black points (--field views)")
    p.add_argument("--size", nargs=2, type=int, metavar=("WIDTH", "HEIGHT"), help="the PNG's size in pixels")
    p.add_argument("--colormap", help="a ParaView colour-map preset (default per field)")
    args = p.parse_args(argv)
    if args.all and args.time is not None:
        p.error("give --all or --time, not both")
    if not args.field:
        for name in ("x", "y", "range", "size", "colormap"):
            if getattr(args, name) is not None:
                p.error("--%s needs --field" % name)
        if args.log or args.parcels or args.stretch != 1.0:
            p.error("--log, --parcels and --stretch need --field")
    if not args.stretch > 0.0:
        p.error("--stretch must be positive")
    for name in ("x", "y", "range"):
        box = getattr(args, name)
        if box is not None and not box[1] > box[0]:
            p.error("--%s: the second value must be larger than the first" % name)
    if args.log and args.range is not None and not args.range[0] > 0.0:
        p.error("--log needs a positive --range")
    if args.size is not None and (args.size[0] < 200 or args.size[1] < 200):
        p.error("--size: at least 200 x 200 pixels")
    return args


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


def frame(view, xmin, xmax, ymin, ymax, stretch=1.0):
    """Parallel camera showing [xmin, xmax] x [ymin, ymax] between the margins, the floor
    ymin just above the colour bar; y drawn `stretch` times longer (the displays are scaled
    by that along y, so the camera frames the scaled box)."""
    ymin, ymax = ymin * stretch, ymax * stretch
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


def nice_ticks(lo, hi, count=6):
    """About `count` round tick values (1, 2 or 5 times a power of ten apart) in [lo, hi]."""
    import math
    raw = (hi - lo) / count
    power = 10.0 ** math.floor(math.log10(raw))
    step = next(m * power for m in (1.0, 2.0, 5.0, 10.0) if m * power >= raw)
    first = math.ceil(lo / step - 1e-9)
    ticks = []
    k = first
    while k * step <= hi + 1e-9 * step:
        ticks.append(round(k * step, 12))
        k += 1
    return ticks


def show_axes(view, box=None, stretch=1.0):
    """Axes along the data's edges (or the zoom box's: `box` = [xmin, xmax, ymin, ymax]) with
    ticks in metres: the image's length scale, in true coordinates when y is stretched."""
    grid = view.AxesGrid
    grid.Visibility = 1
    if box is not None:
        # The bounds are where the grid is drawn (y stretched); its labels divide by the scale.
        grid.DataScale = [1.0, stretch, 1.0]
        grid.UseCustomBounds = 1
        grid.CustomBounds = [box[0], box[1], box[2] * stretch, box[3] * stretch, 0.0, 0.0]
        grid.XAxisUseCustomLabels = 1
        grid.XAxisLabels = nice_ticks(box[0], box[1])
        grid.YAxisUseCustomLabels = 1
        grid.YAxisLabels = nice_ticks(box[2], box[3])
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


def gas_file_at(gas_pvd, t):
    """The .vtr (or .pvtr) file the collection lists for time t (the nearest time)."""
    with open(gas_pvd) as f:
        entries = re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', f.read())
    if not entries:
        fail("no data sets listed in " + gas_pvd)
    best = min(entries, key=lambda e: abs(float(e[0]) - t))
    return os.path.join(os.path.dirname(gas_pvd), best[1])


def box_range(gas_pvd, t, field, box):
    """(lo, hi, smallest positive value) of a --field within the box [xmin, xmax, ymin, ymax]
    at time t: over the cells whose centres lie inside (all cells when none does). Read from
    the gas file itself (VTK's XML reader), as exact numbers."""
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLPRectilinearGridReader, vtkXMLRectilinearGridReader
    path = gas_file_at(gas_pvd, t)
    reader = vtkXMLPRectilinearGridReader() if path.endswith(".pvtr") else vtkXMLRectilinearGridReader()
    reader.SetFileName(path)
    reader.Update()
    data = reader.GetOutput()
    array, component, _, _, _ = FIELDS[field]
    values = data.GetCellData().GetArray(array)
    if values is None:
        fail("array '%s' missing in %s" % (array, path))
    v = vtk_to_numpy(values)
    if v.ndim > 1:
        v = np.linalg.norm(v, axis=1) if component is None else v[:, component]
    xs = vtk_to_numpy(data.GetXCoordinates())
    ys = vtk_to_numpy(data.GetYCoordinates())
    xc, yc = 0.5 * (xs[1:] + xs[:-1]), 0.5 * (ys[1:] + ys[:-1])
    inside = ((yc[:, None] >= box[2]) & (yc[:, None] <= box[3]) &
              (xc[None, :] >= box[0]) & (xc[None, :] <= box[1])).ravel()  # x fastest, as VTK orders cells
    if inside.any():
        v = v[inside]
    v = v[np.isfinite(v)]
    if len(v) == 0:
        return 0.0, 1.0, 0.0
    positive = v[v > 0]
    return float(v.min()), float(v.max()), float(positive.min()) if len(positive) else 0.0


def box_clip(source, box):
    """`source` cut to the box [xmin, xmax, ymin, ymax] (exactly, through the cells it crosses)."""
    clip = pv.Clip(registrationName="zoom box of " + source.GetXMLLabel(), Input=source)
    clip.ClipType = "Box"
    clip.ClipType.Position = [box[0], box[2], -1.0]
    clip.ClipType.Length = [box[1] - box[0], box[3] - box[2], 2.0]
    clip.Invert = 1  # keep what lies inside
    try:
        clip.Exact = 1  # cut at the box's faces, not by the cells' corner values
    except AttributeError:
        pass
    return clip


def colour_range(args, field, lo, hi, smallest_positive):
    """The colour map's range: --range, else the data's (symmetric about 0 for signed fields;
    on a log scale from the smallest positive value, at least 1e-5 of the largest)."""
    if args.range is not None:
        return args.range[0], args.range[1]
    if args.log:
        hi = max(hi, 1e-300)
        return max(smallest_positive, hi * 1e-5), hi
    if FIELDS[field][4]:
        m = max(abs(lo), abs(hi), 1e-30)
        return -m, m
    return (lo, hi) if hi > lo else (lo, lo + (abs(lo) * 1e-6 or 1.0))


class FieldView:
    """One --field view: the field in the zoom box, y stretched, parcels on top; `at(t)` shows
    another time (the colour range follows the data in the box, unless --range)."""

    def __init__(self, args, field, gas, parcels, bounds):
        self.args, self.field, self.gas = args, field, gas
        array, component, title, preset, _ = FIELDS[field]
        box = [args.x[0] if args.x else bounds[0], args.x[1] if args.x else bounds[1],
               args.y[0] if args.y else bounds[2], args.y[1] if args.y else bounds[3]]
        self.box = box
        stretch = args.stretch
        size = list(args.size) if args.size else image_size(box[1] - box[0], (box[3] - box[2]) * stretch)
        self.view = view = white_view(size)
        zoomed = box != list(bounds[:4])
        self.sources = []
        shown = self.keep(box_clip(gas, box)) if zoomed else gas
        self.threshold = None
        if args.log:
            # A log scale has no place for zero (no dust) or what lies below its range: those
            # cells are left out, so the white background shows.
            self.threshold = shown = self.keep(pv.Threshold(registrationName="above the log range", Input=shown,
                                                            Scalars=["CELLS", array], UpperThreshold=1e300,
                                                            ThresholdMethod="Between"))
        disp = pv.Show(shown, view)
        disp.Representation = "Surface"
        disp.Scale = [1.0, stretch, 1.0]
        pv.ColorBy(disp, ("CELLS", array, "Magnitude" if component is None else ["X", "Y", "Z"][component]))
        self.lut = lut = pv.GetColorTransferFunction(array)
        lut.ApplyPreset(args.colormap or preset, True)
        if component is not None and array == "velocity":
            lut.VectorMode = "Component"
            lut.VectorComponent = component
        # A saved state keeps the range: it was chosen for the box (and for a log scale).
        lut.AutomaticRescaleRangeMode = "Never"
        style_bar(lut, view, title + (" (log scale)" if args.log else ""))
        if args.parcels and parcels is not None:
            shown_parcels = self.keep(box_clip(parcels, box)) if zoomed else parcels
            pdisp = pv.Show(shown_parcels, view)
            pdisp.Representation = "Points"
            pdisp.Scale = [1.0, stretch, 1.0]
            # About a parcel's diameter on screen, 1 to 8 pixels.
            parcels.UpdatePipeline()
            info = parcels.PointData["diameter"]
            diameter = info.GetRange(0)[1] if info is not None else 0.0
            usable_w = max(size[0] - LEFT_MARGIN - RIGHT_MARGIN, 1)
            pdisp.PointSize = min(8.0, max(1.0, diameter * usable_w / (box[1] - box[0])))
            pdisp.ColorArrayName = ["POINTS", ""]  # solid colour
            pdisp.AmbientColor = [0.0, 0.0, 0.0]
            pdisp.DiffuseColor = [0.0, 0.0, 0.0]
        self.keep(time_label(view, gas))
        show_axes(view, box, stretch)
        self.framed = False

    def keep(self, source):
        self.sources.append(source)
        return source

    def at(self, t):
        """Shows time t, the colour range of its data in the box."""
        self.view.ViewTime = t
        lo, hi, smallest_positive = box_range(self.gas.FileName, t, self.field, self.box)
        lo, hi = colour_range(self.args, self.field, lo, hi, smallest_positive)
        if self.threshold is not None:
            self.threshold.LowerThreshold = lo
        if self.args.log and self.lut.UseLogScale:
            self.lut.UseLogScale = 0  # rescaled in linear space, mapped to log space again below
        self.lut.RescaleTransferFunction(lo, hi)
        if self.args.log:
            self.lut.MapControlPointsToLogSpace()
            self.lut.UseLogScale = 1
        if not self.framed:
            box = self.box
            frame(self.view, box[0], box[1], box[2], box[3], self.args.stretch)
            self.framed = True

    def delete(self):
        pv.Delete(self.view)
        for source in reversed(self.sources):
            pv.Delete(source)


def render_fields(args, gas, parcels, times, times_wanted, bounds, figures, outdir):
    """The --field views: a PNG per field and time, and each field's state (its one view, at
    the last time rendered)."""
    for n, field in enumerate(args.field):
        fv = FieldView(args, field, gas, parcels, bounds)
        for index, t in times_wanted(times):
            fv.at(t)
            save(fv.view, os.path.join(figures, "%s_%06d.png" % (field, index)))
        pv.SetActiveView(fv.view)
        states = [os.path.join(outdir, field + ".pvsm")] + ([args.save_state] if args.save_state and n == 0 else [])
        for state in states:
            save_relative_state(os.path.abspath(state), outdir)
            print("wrote", state)
        fv.delete()  # the next field's state holds its own view only


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
        if args.time is not None:
            return [min(indexed, key=lambda it: abs(it[1] - args.time))]
        return indexed if args.all else indexed[-1:]

    if args.state:
        render_state(os.path.abspath(args.state), outdir, figures, times_wanted)
        print("render.py: %.1f s" % (time.time() - start))
        return
    if not os.path.isfile(gas_pvd):
        fail("no gas.pvd in " + outdir)
    gas = pv.PVDReader(registrationName="gas.pvd", FileName=gas_pvd)
    gas.CellArrays = sorted({FIELDS[f][0] for f in args.field}) if args.field else ["pressure", "vorticity"]
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
    if args.field:
        render_fields(args, gas, parcels, times, times_wanted, bounds, figures, outdir)
        print("render.py: %d field(s) at %d time(s) in %.1f s" % (len(args.field), len(times_wanted(times)),
                                                                  time.time() - start))
        return
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
