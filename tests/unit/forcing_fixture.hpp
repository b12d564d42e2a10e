#pragma once
// A parcel system driven by the coupling's effects without a gas: the test sets the sampled
// gas and the effects' coefficients in their columns by name, as the coupling would.
#include <initializer_list>
#include <string>

#include "solver/coupling/coupling_config.hpp"
#include "solver/coupling/effects/effect_list.hpp"
#include "solver/dem/parcel_system.hpp"

namespace dustlift::forcing_fixture {

/// Every effect off.
inline CouplingConfig no_effects() {
  CouplingConfig c;
  c.drag = c.magnus = c.pressure_force = c.added_mass = c.rotation_torque = c.heat_transfer = false;
  return c;
}

struct Forcing {
  CouplingEffects effects;
  CouplingEffects::SubstepColumns columns;
  Forcing(ParcelSystem& s, const CouplingConfig& c) : effects(c) {
    auto a = [&](const char* name) { return s.attach_column({name, "", false, false}); };
    columns = {a("gas_u"),     a("gas_v"), a("gas_rotation"), a("gas_temperature"),  a("impulse_x"),
               a("impulse_y"), a("work"),  a("heat"),         a("relative_rotation")};
    effects.attach(s);
    s.set_forcing(effects.forcing(columns));
  }
};

/// Parcel k's value of the attached column `name` (which must exist).
inline double& column(ParcelSystem& s, const char* name, std::size_t k = 0) {
  const ParcelColumn c = s.find_column(name);
  if (!c.valid()) throw std::logic_error(std::string("no column ") + name);
  return s.column(c)[k];
}

}  // namespace dustlift::forcing_fixture
