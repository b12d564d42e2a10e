#include "solver/laws/magnus.hpp"

#include <cmath>

namespace dustlift::aero {

double lun_liu_factor(double re) {
  return re <= 1.0 ? 1.0 : 0.178 + 0.822 * std::pow(re, -0.522);
}

Vec2 magnus_force(double rho, double d, Vec2 u_r, double omega_rel, double c_lm,
                  MagnusConvention conv) {
  return magnus_lift(magnus_coefficient(c_lm, conv, rho, d), omega_rel, u_r);
}

}  // namespace dustlift::aero
