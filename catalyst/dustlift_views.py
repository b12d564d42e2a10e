"""Helpers shared by dustlift's Catalyst scripts (not a pipeline itself): a white 2-D render
view, a colour bar in black, and a camera that fills the view with a source's x-y bounds."""
from paraview.simple import CreateView, GetScalarBar


def white_2d_view(width, height):
    view = CreateView('RenderView')
    view.ViewSize = [width, height]
    view.Background = [1.0, 1.0, 1.0]
    view.OrientationAxesVisibility = 0
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:  # older ParaView: the background is always the view's own
        pass
    view.InteractionMode = '2D'
    return view


def black_scalar_bar(lut, view, title):
    bar = GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ''
    bar.TitleColor = [0, 0, 0]
    bar.LabelColor = [0, 0, 0]
    return bar


def fit_camera(view, source, time):
    """Parallel projection onto the x-y plane filling the view with `source`'s bounds
    (ResetCamera fits the bounding sphere, which leaves a long channel a thin strip)."""
    source.UpdatePipeline(time)
    b = source.GetDataInformation().GetBounds()
    cx, cy = 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3])
    w, h = max(b[1] - b[0], 1e-12), max(b[3] - b[2], 1e-12)
    aspect = float(view.ViewSize[0]) / float(view.ViewSize[1])
    view.CameraPosition = [cx, cy, 1.0]
    view.CameraFocalPoint = [cx, cy, 0.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 0.52 * max(h, w / aspect)
