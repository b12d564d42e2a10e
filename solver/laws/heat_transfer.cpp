#include "solver/laws/heat_transfer.hpp"

namespace dustlift::aero {

double heat_flow(double lambda, double nusselt, double d, double t_gas, double t_particle) {
  return linear_heat_flow(heat_conductance(d, lambda, nusselt), t_gas, t_particle);
}

}  // namespace dustlift::aero
