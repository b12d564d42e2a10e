#include "solver/laws/added_mass.hpp"

#include <algorithm>
#include <numbers>

namespace dustlift::aero {

double added_mass_coefficient(double mach, double phi, AddedMassVolumeFraction correction) {
  // Parmar et al. (2008) fitted Ma <= 0.6; beyond it the coefficient is held (as Ling et al.
  // 2012 and the codes that followed them do).
  const double m = std::min(mach, 0.6);
  const double m2 = m * m;
  const double c_m = 0.5 * (1.0 + 1.8 * m2 + 7.6 * m2 * m2);
  switch (correction) {
    case AddedMassVolumeFraction::None:
      return c_m;
    case AddedMassVolumeFraction::Beguin:
      return c_m * (1.0 + 0.68 * phi * phi);
    case AddedMassVolumeFraction::Zuber:
      break;
  }
  return c_m * (1.0 + 2.0 * phi) / (1.0 - phi);
}

Vec2 added_mass_force(double c_m, double d, double rho, Vec2 d_rho_u_dt, Vec2 dv_dt) {
  const double vp = std::numbers::pi / 6.0 * d * d * d;
  return {c_m * vp * (d_rho_u_dt.x - rho * dv_dt.x), c_m * vp * (d_rho_u_dt.y - rho * dv_dt.y)};
}

}  // namespace dustlift::aero
