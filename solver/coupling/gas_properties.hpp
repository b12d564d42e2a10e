#pragma once
// The gas properties the particle models and the implicit exchange read at a temperature.
#include <cmath>

#include "solver/gas/gas_config.hpp"
#include "solver/gas/thermo.hpp"
#include "solver/gas/transport.hpp"

namespace dustlift {

/// cp(T), c(T) and gamma(T) of the configured thermodynamics, and the transport properties
/// the particle models use: the gas's own (the Gordon-Wilke model through the same table as
/// the gas solver), or for an inviscid gas the Gordon-Wilke air values (the gas itself stays
/// inviscid; the particles always need mu and lambda).
class GasProperties {
 public:
  explicit GasProperties(const GasConfig& g)
      : thermo_(g.thermo),
        transport_(g.transport),
        perfect_(g.thermo.gamma, g.thermo.gas_constant),
        air_(g.thermo.gas_constant) {}
  struct At {
    double cp, c, gamma;
  };
  At thermo(double T) const {
    if (thermo_.model == ThermoModel::CaloricallyPerfect) {
      return {perfect_.cp(T), std::sqrt(perfect_.sound_speed_squared(T)), perfect_.gamma(T)};
    }
    const double cp = air_.cp(T), R = thermo_.gas_constant;
    const double gamma = cp / (cp - R);
    return {cp, std::sqrt(gamma * R * T), gamma};
  }
  TransportProperties transport(double T, double cp) const {
    if (transport_.model == TransportModel::Inviscid ||
        transport_.model == TransportModel::GordonWilke)
      return table_(T);
    return transport_properties(transport_, T, cp);
  }

 private:
  ThermoConfig thermo_;
  TransportConfig transport_;
  CaloricallyPerfectGas perfect_;
  ThermallyPerfectAir air_;
  GordonWilkeAirTable table_;
};

}  // namespace dustlift
