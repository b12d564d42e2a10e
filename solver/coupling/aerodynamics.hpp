#pragma once
// Gas-particle force, torque and heat models of the paper's Table 1 and eqs. (8)-(10),
// as small pure functions per REAL particle (coarse graining multiplies by n_i, eqs. 13-15).
// Garbled print forms in the paper are corrected as physics-reference.md §3 and §6 explain.
#include <cmath>

#include "solver/core/vec2.hpp"

namespace dustlift::aero {

/// Standard drag curve, Clift & Gauvin (1970); physics-reference §3.1 (the paper's print lacks
/// the 0.687 exponent and multiplies where it should divide).
double cd_standard(double re);
/// Re * C_D,std: finite as Re -> 0 (Stokes limit 24).
double re_cd_standard(double re);

/// Parmar, Haselbacher & Balachandar (2010) compressible drag C_D(M, Re); M > 1.75 holds the
/// M = 1.75 fit (not fitted beyond).
double cd_parmar(double mach, double re);
double re_cd_parmar(double mach, double re);
/// xi_1(M, Re) = C_D(M, Re) / C_D,std(Re).
double xi1_parmar(double mach, double re);

/// How the volume-fraction correction xi_2(alpha_g) is evaluated.
struct VolumeFractionCorrection {
  enum class Kind { None, Sangani, Linear };
  Kind kind = Kind::Sangani;
  /// phi = alpha_p is capped at this value before evaluation (1 = no cap).
  double phi_cap = 1.0;
};
/// Sangani, Zhang & Prosperetti (1991) as used by Ling et al. (2012):
/// xi_2 = (1 + 2 phi) / (1 - phi)^3; Linear: 1 + 5.94 phi; None: 1.
double xi2(double alpha_g, const VolumeFractionCorrection& c);

/// Local gas state interpolated to a parcel (eq. 16).
struct GasAtParcel {
  double rho = 1.0;        ///< kg/m^3 (gas density, not alpha_g rho)
  Vec2 u{};                ///< m/s
  double mu = 1.8e-5;      ///< Pa s
  double c = 340.0;        ///< m/s
  double alpha_g = 1.0;
};

/// Drag per unit slip speed of one real particle, beta in F_drag = beta u_r (Table 1):
/// beta = 3 pi mu d (Re C_D / 24) xi_2(alpha_g), C_D with Parmar's xi_1(M, Re) when
/// `compressible`, else the Clift-Gauvin curve; finite at zero slip (Stokes).
double drag_coefficient(const GasAtParcel& g, double slip, double d, bool compressible,
                        const VolumeFractionCorrection& c);

/// Drag on one real particle of diameter d moving with velocity up (Table 1):
/// F = 3 pi mu d u_r (Re/24) C_D,std xi_1 xi_2, u_r = u_g - u_p.
Vec2 drag_force(const GasAtParcel& g, Vec2 up, double d, const VolumeFractionCorrection& c);

/// Magnus lift conventions (physics-reference §3.2 and docs/coupling.md):
/// Standard (Rubinow-Keller): F = C (pi/8) rho d^3 Omega_r z x u_r with Omega_r = omega_z/2 - omega_p.
/// Paper: the paper's clockwise-positive rotation, which equals -(Standard) for the same state
/// and gives the upward lift over the layer that the paper reports.
enum class MagnusConvention { Paper, Standard };
/// Relative rotation of the gas with respect to the particle in the right-handed sense:
/// omega_z / 2 - omega_p (the fluid spins at half its vorticity).
inline double relative_rotation(double vorticity_z, double omega_p) { return 0.5 * vorticity_z - omega_p; }
/// Optional Lun & Liu (1997) Reynolds-number factor on the lift coefficient.
double lun_liu_factor(double re);
Vec2 magnus_force(double rho, double d, Vec2 u_r, double omega_rel, double c_lm, MagnusConvention conv);

/// Pressure-gradient force -V_p grad p (the paper prints +; §3.3).
inline Vec2 pressure_force(double d, Vec2 grad_p) {
  const double vp = 3.14159265358979323846 / 6.0 * d * d * d;
  return grad_p * (-vp);
}

/// Rotational friction torque (Dennis, Singh & Ingham 1980) on the z axis, relaxing the
/// particle spin towards the fluid rotation: M = (1/64) C_T d^5 rho Omega_r |Omega_r|,
/// C_T = 6.45/sqrt(Re_w) + 32.1/Re_w, Re_w = rho |Omega_r| d^2 / (4 mu). With
/// stokes_below > 0 the Stokes torque pi mu d^3 Omega_r is used for Re_w below it (7.93 is
/// where the two cross).
double rotation_torque(double rho, double mu, double d, double omega_rel, double stokes_below);

/// Ranz & Marshall (1952) Nusselt number: 2 + 0.6 Re^1/2 Pr^1/3 (the paper prints it garbled).
inline double nusselt_ranz_marshall(double re, double pr) {
  return 2.0 + 0.6 * std::sqrt(re) * std::cbrt(pr);
}
/// Heat flow into one particle (eqs. 8-9): Q = pi d^2 (Nu lambda / d) (T_g - T_p).
double heat_flow(double lambda, double nusselt, double d, double t_gas, double t_particle);

}  // namespace dustlift::aero

