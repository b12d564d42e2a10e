#include "solver/coupling/effects/rotation_torque.hpp"

#include "solver/coupling/coupling_config.hpp"

namespace dustlift {

RotationTorqueEffect::RotationTorqueEffect(const CouplingConfig& c)
    : stokes_below_(c.torque_stokes_below) {}

std::string RotationTorqueEffect::description() const {
  return "rotational friction torque (Dennis, Singh & Ingham 1980)";
}

void RotationTorqueEffect::attach(ParcelTable& t) {
  namespace c = effect_columns;
  coefficient_ = c::coefficient(t, "torque_coefficient", "N m s");
  torque_ =
      c::part(t, "fluid_torque", "N m", ForcePart::FluidTorque, "", 0, "parcels/fluid_torque");
}

}  // namespace dustlift
