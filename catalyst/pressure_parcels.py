# script-version: 2
# dustlift Catalyst pipeline: the paper's Fig. 8 view in situ. Gas pressure over the channel
# with the parcels as black points, one PNG per delivery, written to
# OUTDIR/catalyst/pressure_parcels_<step>.png.
# Use: [insitu.catalyst] scripts = ["catalyst/pressure_parcels.py"], interval_steps = N.
from paraview.simple import *
from paraview import catalyst
import os, sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # dustlift_views beside this script
from dustlift_views import black_scalar_bar, fit_camera, white_2d_view

gas = TrivialProducer(registrationName='gas')          # vtkRectilinearGrid, cell data
parcels = TrivialProducer(registrationName='parcels')  # vtkPolyData, point data + id

view = white_2d_view(1600, 500)

gas_display = Show(gas, view)
ColorBy(gas_display, ('CELLS', 'pressure'))
pressure_lut = GetColorTransferFunction('pressure')
pressure_lut.ApplyPreset('Jet', True)
gas_display.SetScalarBarVisibility(view, True)
black_scalar_bar(pressure_lut, view, 'p [Pa]')

parcel_display = Show(parcels, view)
parcel_display.SetRepresentationType('Points')
parcel_display.ColorArrayName = ['POINTS', '']
parcel_display.AmbientColor = [0.0, 0.0, 0.0]
parcel_display.DiffuseColor = [0.0, 0.0, 0.0]
parcel_display.PointSize = 1.0


png = CreateExtractor('PNG', view, registrationName='pressure_png')
png.Writer.FileName = 'pressure_parcels_{timestep:06d}.png'
png.Writer.ImageResolution = [1600, 500]


options = catalyst.Options()
options.ExtractsOutputDirectory = 'catalyst'


def catalyst_execute(info):
    # The colour range follows each step's pressure (the shock raises it as it runs in).
    gas_display.RescaleTransferFunctionToDataRange(False, True)
    fit_camera(view, gas, info.time)
