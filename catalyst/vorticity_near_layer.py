# script-version: 2
# dustlift Catalyst pipeline: gas vorticity w_z near the dust layer (the paper's Fig. 13 view)
# in situ, with a symmetric diverging colour map, one PNG per delivery, written to
# OUTDIR/catalyst/vorticity_<step>.png. The view is the band from the floor to 4x the layer
# height (found from the parcels' top at the first delivery).
from paraview.simple import *
from paraview import catalyst
import os, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # dustlift_views beside this script
from dustlift_views import black_scalar_bar, fit_camera, white_2d_view

gas = TrivialProducer(registrationName='gas')
parcels = TrivialProducer(registrationName='parcels')

view = white_2d_view(1600, 400)

band = Clip(registrationName='near_layer', Input=gas)
band.ClipType = 'Plane'
band.ClipType.Normal = [0.0, 1.0, 0.0]
band.Invert = 1
band.Crinkleclip = 1

display = Show(band, view)
ColorBy(display, ('CELLS', 'vorticity'))
lut = GetColorTransferFunction('vorticity')
lut.ApplyPreset('Cool to Warm', True)
display.SetScalarBarVisibility(view, True)
black_scalar_bar(lut, view, 'w_z [1/s]')

png = CreateExtractor('PNG', view, registrationName='vorticity_png')
png.Writer.FileName = 'vorticity_{timestep:06d}.png'
png.Writer.ImageResolution = [1600, 400]


options = catalyst.Options()
options.ExtractsOutputDirectory = 'catalyst'

_band_top = None


def catalyst_execute(info):
    global _band_top
    if _band_top is None:
        gas.UpdatePipeline(info.time)
        parcels.UpdatePipeline(info.time)
        bounds_gas = gas.GetDataInformation().GetBounds()
        bounds_parcels = parcels.GetDataInformation().GetBounds()
        floor = bounds_gas[2]
        top = bounds_parcels[3] if bounds_parcels[3] >= bounds_parcels[2] else floor + 0.25 * (bounds_gas[3] - floor)
        _band_top = floor + 4.0 * max(top - floor, 1e-6)
        band.ClipType.Origin = [0.0, _band_top, 0.0]
    # Symmetric range about zero so that the sign of w_z reads off the colour.
    band.UpdatePipeline(info.time)
    r = band.CellData['vorticity'].GetRange()
    m = max(abs(r[0]), abs(r[1]), 1e-12)
    lut.RescaleTransferFunction(-m, m)
    fit_camera(view, band, info.time)
