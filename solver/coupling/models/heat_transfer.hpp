#pragma once
// Heat transfer (eqs. 7-10, Ranz & Marshall 1952): the published law per real particle
// Q = pi d^2 (Nu lambda / d) (T_g - T_p); its sub-step coefficient H = pi d lambda Nu with Nu at
// the step's Re and the sub-step heat flow Q = H (T_g - T_p) at the parcel's current temperature.
#include <cmath>
#include <numbers>
#include <string>

#include "solver/coupling/models/coupling_model.hpp"

namespace dustlift {

namespace aero {

/// Ranz & Marshall (1952) Nusselt number: 2 + 0.6 Re^1/2 Pr^1/3 (the paper prints it garbled).
inline double nusselt_ranz_marshall(double re, double pr) {
  return 2.0 + 0.6 * std::sqrt(re) * std::cbrt(pr);
}
/// Heat flow into one particle (eqs. 8-9): Q = pi d^2 (Nu lambda / d) (T_g - T_p).
double heat_flow(double lambda, double nusselt, double d, double t_gas, double t_particle);

}  // namespace aero

class HeatTransferModel final : public BatchedCouplingModel<HeatTransferModel> {
 public:
  static constexpr ModelTraits kTraits{.reads = {.temperature = true}, .writes = {.heat = true}};

  /// H = pi d lambda Nu = pi d^2 (Nu lambda / d).
  static double coefficient(double d, double lambda, double nusselt) {
    return std::numbers::pi * d * lambda * nusselt;
  }
  /// The sub-step heat flow into one real particle at its temperature: Q = H (T_g - T_p).
  static double heat_flow(double H, double t_gas, double t_particle) {
    return H * (t_gas - t_particle);
  }

  std::string description() const override;
  void coefficient(const ModelInput& in, SubstepCoefficients& out) const {
    const GasSample& g = in.gas;
    out.heat = coefficient(in.parcel.diameter, g.lambda,
                           aero::nusselt_ranz_marshall(in.re, g.mu * g.cp / g.lambda));
  }
};

}  // namespace dustlift
