// Inviscid flux row kernels instantiated for the calorically perfect gas (see flux_rows_kernels.hpp).
#include "solver/gas/flux_rows_kernels.hpp"

namespace dustlift {

template void inviscid_flux_row<CaloricallyPerfectGas>(const CaloricallyPerfectGas&, const MusclSettings&, const FaceRowInput&,
                                       const FaceRowScratch&, const FaceRowOutput&, double, double);

}  // namespace dustlift
