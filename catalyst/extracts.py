# script-version: 2
# dustlift Catalyst pipeline: the full gas and parcel states as ParaView extracts,
# OUTDIR/catalyst/gas_<step>.pvtr and parcels_<step>.pvtp (every array of the .vtr/.vtp, the
# parcels with their id). The cadence is the scene's [insitu.catalyst] interval; set
# Trigger.Frequency below to thin it further.
from paraview.simple import *
from paraview import catalyst

gas = TrivialProducer(registrationName='gas')
parcels = TrivialProducer(registrationName='parcels')

gas_extract = CreateExtractor('VTR', gas, registrationName='gas_vtr')
gas_extract.Writer.FileName = 'gas_{timestep:06d}.pvtr'
parcel_extract = CreateExtractor('VTP', parcels, registrationName='parcels_vtp')
parcel_extract.Writer.FileName = 'parcels_{timestep:06d}.pvtp'

options = catalyst.Options()
options.ExtractsOutputDirectory = 'catalyst'
