#pragma once
// Inviscid-unsteady (added-mass) force on a sphere in compressible flow (Parmar, Haselbacher
// & Balachandar 2008, Phil. Trans. R. Soc. A 366:2161):
//   F_am = C_M V_p [ D(rho_g u)/Dt - d(rho_g v)/dt ].
// Over a CFD step the gas is frozen and rho_g is the step's: with the added mass
// m_a = C_M rho_g V_p and the fluid part F_g = C_M V_p [D(rho_g u)/Dt - v d(rho_g)/dt|_p],
//   F_am = F_g - m_a dv/dt,
// and each DEM sub-step solves (m + m_a) dv/dt = F_others + F_g for dv/dt (the added mass on
// the left: stable whatever rho_g / rho_p).
#include "solver/core/vec2.hpp"

namespace dustlift::aero {

/// How the added-mass coefficient depends on the particle volume fraction phi: Beguin,
/// Pelletier & Etienne (2016, Eur. J. Mech. B/Fluids 56:28), 1 + 0.68 phi^2 (what ppiclF and MFC
/// use); Zuber (1964), (1 + 2 phi) / (1 - phi); or none.
enum class AddedMassVolumeFraction { Beguin, Zuber, None };

/// What the fluid part of the force takes for the gas's momentum rate D(rho u)/Dt: the resolved
/// gas's, or -grad p (Ling et al. 2012's approximation for a dilute cloud).
enum class FluidAcceleration { Resolved, PressureGradient };

/// C_M(Ma, phi) = 1/2 (1 + 1.8 Ma^2 + 7.6 Ma^4) (Parmar et al. 2008, eq. 3.4; Ma the relative
/// Mach number, held at 0.6 beyond the fit's range), times the volume-fraction correction.
/// Ma >= 0; phi in [0, 1).
double added_mass_coefficient(double mach, double phi, AddedMassVolumeFraction correction);

/// The published force on one real particle of diameter d accelerating at dv/dt in a gas of
/// density rho whose momentum changes at D(rho u)/Dt: C_M V_p [D(rho u)/Dt - rho dv/dt].
Vec2 added_mass_force(double c_m, double d, double rho, Vec2 d_rho_u_dt, Vec2 dv_dt);

/// The gradient of the gas momentum rho u (x row) and rho v (y row) at a point.
struct MomentumGradient {
  double dx_rho_u = 0.0, dy_rho_u = 0.0, dx_rho_v = 0.0, dy_rho_v = 0.0;
};

/// The gas's momentum rate following the gas, D(rho u)/Dt = d(rho u)/dt|_p + (u - v) . grad(rho u),
/// from its rate along the particle's path d(rho u)/dt|_p and the relative velocity u - v.
inline Vec2 momentum_rate_following_gas(Vec2 along_path, Vec2 relative, const MomentumGradient& g) {
  return {along_path.x + relative.x * g.dx_rho_u + relative.y * g.dy_rho_u,
          along_path.y + relative.x * g.dx_rho_v + relative.y * g.dy_rho_v};
}

/// The implicit virtual-mass weight of the previous step's rate in a cloud that the gas feels:
/// with the reaction of the particles' added-mass forces on the gas, the gas's momentum rate
/// solves alpha_g A = G - alpha_p C_M (A - rho a_p), whose value over a step follows from the
/// rate the gas showed with last step's reaction: A = (1 - w) A_measured + w A_previous,
/// w = alpha_p C_M / (alpha_g + alpha_p C_M) (alpha_p = 1 - alpha_g; docs/coupling.md).
inline double virtual_mass_weight(double alpha_g, double c_m) {
  const double a = (1.0 - alpha_g) * c_m;
  return a / (alpha_g + a);
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
