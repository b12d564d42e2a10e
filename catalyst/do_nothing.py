# script-version: 2
# dustlift Catalyst pipeline that does nothing: the benchmark of the adaptor's own cost
# (bench/catalyst_cost.sh) and a template to start one's own from.
from paraview.simple import *
from paraview import catalyst

gas = TrivialProducer(registrationName='gas')
parcels = TrivialProducer(registrationName='parcels')

options = catalyst.Options()


def catalyst_execute(info):
    pass
