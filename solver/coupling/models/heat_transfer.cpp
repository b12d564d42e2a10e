#include "solver/coupling/models/heat_transfer.hpp"

namespace dustlift::aero {

double heat_flow(double lambda, double nusselt, double d, double t_gas, double t_particle) {
  return HeatTransferModel::heat_flow(HeatTransferModel::coefficient(d, lambda, nusselt), t_gas,
                                      t_particle);
}

}  // namespace dustlift::aero

namespace dustlift {

std::string HeatTransferModel::description() const {
  return "heat transfer (Ranz-Marshall) and particle temperature";
}

}  // namespace dustlift
