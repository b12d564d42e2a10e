// Inviscid flux row kernels instantiated for the thermally perfect air (see flux_rows_kernels.hpp).
#include "solver/gas/flux_rows_kernels.hpp"

namespace dustlift {

template void inviscid_flux_row<ThermallyPerfectAir>(const ThermallyPerfectAir&, const MusclSettings&, const FaceRowInput&,
                                       const FaceRowScratch&, const FaceRowOutput&, double, double);

}  // namespace dustlift
