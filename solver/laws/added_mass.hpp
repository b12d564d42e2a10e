#pragma once
// Inviscid-unsteady (added-mass) force on a sphere in compressible flow (Parmar, Haselbacher
// & Balachandar 2008, Phil. Trans. R. Soc. A 366:2161):
//   F_am = C_M V_p [ D(rho_g u)/Dt - d(rho_g v)/dt ].
// Over a CFD step the gas is frozen and rho_g is the step's: with the added mass
// m_a = C_M rho_g V_p and the fluid part F_g = C_M V_p D(rho_g u)/Dt,
//   F_am = F_g - m_a dv/dt,
// and each DEM sub-step solves (m + m_a) dv/dt = F_others + F_g for dv/dt (the added mass on
// the left: stable whatever rho_g / rho_p).
#include "solver/core/vec2.hpp"

namespace dustlift::aero {

/// How the added-mass coefficient depends on the particle volume fraction phi.
enum class AddedMassVolumeFraction { Zuber, None };

/// C_M(Ma, phi) = 1/2 (1 + 1.8 Ma^2 + 7.6 Ma^4) (Parmar et al. 2008, eq. 3.4; Ma the relative
/// Mach number, held at 0.6 beyond the fit's range), times the volume-fraction correction:
/// (1 + 2 phi) / (1 - phi) (Zuber 1964), or none. Ma >= 0; phi in [0, 1).
double added_mass_coefficient(double mach, double phi, AddedMassVolumeFraction correction);

/// The published force on one real particle of diameter d accelerating at dv/dt in a gas of
/// density rho whose momentum changes at D(rho u)/Dt: C_M V_p [D(rho u)/Dt - rho dv/dt].
Vec2 added_mass_force(double c_m, double d, double rho, Vec2 d_rho_u_dt, Vec2 dv_dt);

/// The share s = alpha_g / (alpha_g + alpha_p C_M) of -grad p taken as the gas's own momentum
/// rate D(rho u)/Dt in a cloud of volume fraction alpha_p = 1 - alpha_g.
inline double gas_acceleration_share(double alpha_g, double c_m) {
  return alpha_g / (alpha_g + (1.0 - alpha_g) * c_m);
}

/// The sub-step's acceleration of one real particle of mass m under the forces F (all but
/// the added-mass force's) and the fluid part F_g: (F + F_g) / (m + m_a), with
/// `inv_total_mass` = 1 / (m + m_a).
inline Vec2 added_mass_acceleration(Vec2 forces, Vec2 fluid_part, double inv_total_mass) {
  return {(forces.x + fluid_part.x) * inv_total_mass, (forces.y + fluid_part.y) * inv_total_mass};
}

/// The added-mass force at that acceleration: F_am = F_g - m_a dv/dt.
inline Vec2 added_mass_force_at(Vec2 fluid_part, double added_mass, Vec2 acceleration) {
  return {fluid_part.x - added_mass * acceleration.x, fluid_part.y - added_mass * acceleration.y};
}

}  // namespace dustlift::aero
