#pragma once
// Magnus lift (Table 1, docs/coupling.md): per real particle
// F = C_LM (pi/8) rho d^3 Omega_r z x u_r (with the convention's sign), written as a
// coefficient M = s C_LM (pi/8) rho d^3 (s the convention's sign) times w_r z x u_r, so a DEM
// sub-step applies M of the CFD step's start to the parcel's current relative rotation and slip.
#include <numbers>

#include "solver/core/vec2.hpp"

namespace dustlift::aero {

/// Magnus lift conventions (docs/coupling.md):
/// Standard (Rubinow-Keller): F = C (pi/8) rho d^3 Omega_r z x u_r with Omega_r = omega_z/2 -
/// omega_p. Paper: the paper's clockwise-positive rotation, which equals -(Standard) for the same
/// state and gives the upward lift over the layer that the paper reports.
enum class MagnusConvention { Paper, Standard };

/// Relative rotation of the gas with respect to the particle in the right-handed sense:
/// omega_z / 2 - omega_p (the fluid spins at half its vorticity).
inline double relative_rotation(double vorticity_z, double omega_p) {
  return 0.5 * vorticity_z - omega_p;
}

/// Optional Lun & Liu (1997) Reynolds-number factor on the lift coefficient.
double lun_liu_factor(double re);

/// M = s C_LM (pi/8) rho d^3, s = +1 in the standard convention and -1 in the paper's.
inline double magnus_coefficient(double c_lm, MagnusConvention conv, double rho, double d) {
  const double sign = conv == MagnusConvention::Standard ? 1.0 : -1.0;
  return sign * (c_lm * std::numbers::pi / 8.0 * rho * d * d * d);
}

/// The lift at the relative rotation w_r and slip u_r for the coefficient M: F = M w_r z x u_r.
inline Vec2 magnus_lift(double M, double w_r, Vec2 u_r) {
  const double m = M * w_r;
  return {-m * u_r.y, m * u_r.x};
}

/// Table 1 with the |.| bars restored: 1/2 rho |u_r|^2 (pi d^2/4) C_LM (d |w_r|/|u_r|)
/// (w_r x u_r)/(|w_r||u_r|) = C_LM (pi/8) rho d^3 (w_r x u_r), signed by the convention.
Vec2 magnus_force(double rho, double d, Vec2 u_r, double omega_rel, double c_lm,
                  MagnusConvention conv);

}  // namespace dustlift::aero
