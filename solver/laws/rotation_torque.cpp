#include "solver/laws/rotation_torque.hpp"

#include <cmath>

namespace dustlift::aero {

double rotation_torque(double rho, double mu, double d, double omega_rel, double stokes_below) {
  const double w = std::abs(omega_rel);
  if (w == 0.0) return 0.0;
  const double re_w = rho * w * d * d / (4.0 * mu);
  if (re_w < stokes_below)
    return stokes_torque_slope(mu, d) * omega_rel;  // Stokes: C_T = 16 pi / Re_w
  if (re_w < 1e-100) {
    // The same fit with Re_w = rho w d^2 / (4 mu) divided out: C_T d^5 rho w / 64 =
    // 32.1 * 4/64 mu d^3 + 6.45 * 2/64 d^4 sqrt(mu rho w). Below here Re_w of a subnormal w
    // underflows to 0 and the form below would give inf * 0 = NaN.
    return (2.00625 * mu * d * d * d + 0.2015625 * d * d * d * d * std::sqrt(mu * rho * w)) *
           omega_rel;
  }
  const double ct = 6.45 / std::sqrt(re_w) + 32.1 / re_w;
  return ct * (d * d * d * d * d) * rho * omega_rel * w / 64.0;
}

}  // namespace dustlift::aero
