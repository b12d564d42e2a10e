#pragma once
// Rotational friction torque (Table 1; Dennis, Singh & Ingham 1980) on the z axis, relaxing the
// particle's spin towards the fluid rotation, per real particle:
// M = (1/64) C_T d^5 rho Omega_r |Omega_r|. A DEM sub-step applies its slope
// kappa = M(w_r0) / w_r0 at the CFD step's relative rotation w_r0 (the torque is odd in w_r; at
// w_r0 = 0 the Stokes slope pi mu d^3) to the parcel's current relative rotation.
namespace dustlift::aero {

/// The Stokes torque's slope: M = pi mu d^3 Omega_r (C_T = 16 pi / Re_w).
inline double stokes_torque_slope(double mu, double d) {
  return 3.14159265358979323846 * mu * d * d * d;
}

/// M = (1/64) C_T d^5 rho Omega_r |Omega_r|, C_T = 6.45/sqrt(Re_w) + 32.1/Re_w,
/// Re_w = rho |Omega_r| d^2 / (4 mu). With stokes_below > 0 the Stokes torque is used for Re_w
/// below it (7.93 is where the two cross).
double rotation_torque(double rho, double mu, double d, double omega_rel, double stokes_below);

/// kappa = M(w_r0) / w_r0 at the relative rotation w_r0; the Stokes slope at w_r0 = 0.
inline double torque_slope(double rho, double mu, double d, double w0, double stokes_below) {
  return w0 != 0.0 ? rotation_torque(rho, mu, d, w0, stokes_below) / w0
                   : stokes_torque_slope(mu, d);
}

/// The torque at the relative rotation w_r for the slope kappa: M = kappa w_r.
inline double linear_torque(double kappa, double w_r) {
  return kappa * w_r;
}

}  // namespace dustlift::aero
