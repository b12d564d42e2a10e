#pragma once
// Rankine-Hugoniot jump of a normal shock (docs/gas-solver.md), for either thermodynamic
// model: closed form for the calorically perfect gas; for thermally perfect air the shock-frame
// conservation of mass, momentum and total enthalpy with h(T) is solved numerically.
#include "solver/gas/gas_config.hpp"

namespace dustlift {

/// The state behind a shock and its speed.
struct ShockJump {
  PrimitiveState post;      ///< lab-frame state behind the shock
  double shock_speed;       ///< m/s along +axis in the lab frame
  double pre_temperature;   ///< K
  double post_temperature;  ///< K
};

/// A normal shock of Mach `mach` (relative to the pre-shock sound speed c1 = sqrt(gamma(T1) R T1))
/// moving towards +axis ('x' or 'y') into `pre`. Tangential velocity passes unchanged.
/// Throws std::invalid_argument for mach <= 1 or when the numeric solve fails.
ShockJump normal_shock(const PrimitiveState& pre, double mach, const ThermoConfig& thermo, char axis = 'x');

}  // namespace dustlift
