#include "solver/coupling/effects/added_mass.hpp"

#include <numbers>

#include "solver/coupling/coupling_config.hpp"

namespace dustlift {

AddedMassEffect::AddedMassEffect(const CouplingConfig& c)
    : correction_(c.added_mass_volume_fraction) {}

std::string AddedMassEffect::description() const {
  return std::string(
             "added mass (inviscid unsteady): C_M = 1/2 (1 + 1.8 Ma^2 + 7.6 Ma^4) (Parmar et al. "
             "2008)") +
         (correction_ == aero::AddedMassVolumeFraction::Zuber
              ? " x (1 + 2 alpha_p)/(1 - alpha_p) (Zuber 1964)"
              : "") +
         ", added to the parcel's inertia";
}

void AddedMassEffect::attach(ParcelTable& t) {
  namespace c = effect_columns;
  added_mass_ = c::coefficient(t, "added_mass", "kg");
  fluid_x_ = c::coefficient(t, "added_mass_gas_x", "N");
  fluid_y_ = c::coefficient(t, "added_mass_gas_y", "N");
  inv_total_mass_ = c::coefficient(t, "inv_total_mass", "1/kg");
  fx_ = c::part(t, "added_mass_fx", "N", ForcePart::AddedMass, "force_added_mass", 0, "");
  fy_ = c::part(t, "added_mass_fy", "N", ForcePart::AddedMass, "force_added_mass", 1, "");
}

void AddedMassEffect::coefficient(const ModelInput& in, std::size_t k, Columns& out) const {
  const GasSample& g = in.gas;
  const double d = in.parcel.diameter;
  const double c_m = aero::added_mass_coefficient(in.slip / g.c, 1.0 - g.alpha_g, correction_);
  const double cv = c_m * (std::numbers::pi / 6.0 * d * d * d);  // C_M V_p
  const double gas = cv * aero::gas_acceleration_share(g.alpha_g, c_m);
  out.added_mass[k] = cv * g.rho;
  out.fluid_x[k] = -gas * g.dpdx;
  out.fluid_y[k] = -gas * g.dpdy;
  out.inv_total_mass[k] = 1.0 / (in.parcel.mass + out.added_mass[k]);
}

}  // namespace dustlift
