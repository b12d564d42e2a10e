#include "solver/coupling/models/added_mass.hpp"

#include <algorithm>
#include <numbers>

#include "solver/coupling/coupling_config.hpp"

namespace dustlift::aero {

double added_mass_coefficient(double mach, double phi, AddedMassVolumeFraction correction) {
  // Parmar et al. (2008) fitted Ma <= 0.6; beyond it the coefficient is held (as Ling et al.
  // 2012 and the codes that followed them do).
  const double m = std::min(mach, 0.6);
  const double m2 = m * m;
  const double c_m = 0.5 * (1.0 + 1.8 * m2 + 7.6 * m2 * m2);
  if (correction == AddedMassVolumeFraction::None) return c_m;
  return c_m * (1.0 + 2.0 * phi) / (1.0 - phi);
}

Vec2 added_mass_force(double c_m, double d, double rho, Vec2 d_rho_u_dt, Vec2 dv_dt) {
  const double vp = std::numbers::pi / 6.0 * d * d * d;
  return {c_m * vp * (d_rho_u_dt.x - rho * dv_dt.x), c_m * vp * (d_rho_u_dt.y - rho * dv_dt.y)};
}

}  // namespace dustlift::aero

namespace dustlift {

AddedMassModel::AddedMassModel(const CouplingConfig& c)
    : correction_(c.added_mass_volume_fraction) {}

std::string AddedMassModel::description() const {
  return std::string(
             "added mass (inviscid unsteady): C_M = 1/2 (1 + 1.8 Ma^2 + 7.6 Ma^4) (Parmar et al. "
             "2008)") +
         (correction_ == aero::AddedMassVolumeFraction::Zuber
              ? " x (1 + 2 alpha_p)/(1 - alpha_p) (Zuber 1964)"
              : "") +
         ", added to the parcel's inertia";
}

void AddedMassModel::coefficient(const ModelInput& in, SubstepCoefficients& out) const {
  const GasSample& g = in.gas;
  const double d = in.parcel.diameter;
  const double c_m = aero::added_mass_coefficient(in.slip / g.c, 1.0 - g.alpha_g, correction_);
  const double cv = c_m * (std::numbers::pi / 6.0 * d * d * d);  // C_M V_p
  const double gas = cv * aero::gas_acceleration_share(g.alpha_g, c_m);
  out.added_mass = cv * g.rho;
  out.added_mass_fx = -gas * g.dpdx;
  out.added_mass_fy = -gas * g.dpdy;
  out.inv_total_mass = 1.0 / (in.parcel.mass + out.added_mass);
}

}  // namespace dustlift
