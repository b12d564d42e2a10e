#pragma once
// Rotational friction torque (Table 1; Dennis, Singh & Ingham 1980) on the z axis, relaxing the
// particle's spin towards the fluid rotation: the published law per real particle
// M = (1/64) C_T d^5 rho Omega_r |Omega_r|; its sub-step coefficient kappa = M(w_r0) / w_r0,
// the slope at the step's relative rotation w_r0 (the torque is odd in w_r; at w_r0 = 0 the
// Stokes slope pi mu d^3), and the sub-step torque M = kappa w_r at the parcel's current
// relative rotation.
#include <string>

#include "solver/coupling/models/coupling_model.hpp"
#include "solver/coupling/models/magnus.hpp"

namespace dustlift {

struct CouplingConfig;

namespace aero {

/// The Stokes torque's slope: M = pi mu d^3 Omega_r (C_T = 16 pi / Re_w).
inline double stokes_torque_slope(double mu, double d) {
  return 3.14159265358979323846 * mu * d * d * d;
}

/// M = (1/64) C_T d^5 rho Omega_r |Omega_r|, C_T = 6.45/sqrt(Re_w) + 32.1/Re_w,
/// Re_w = rho |Omega_r| d^2 / (4 mu). With stokes_below > 0 the Stokes torque is used for Re_w
/// below it (7.93 is where the two cross).
double rotation_torque(double rho, double mu, double d, double omega_rel, double stokes_below);

}  // namespace aero

class RotationTorqueModel final : public BatchedCouplingModel<RotationTorqueModel> {
 public:
  static constexpr ModelTraits kTraits{.reads = {.rotation = true}, .writes = {.torque = true}};

  /// kappa = M(w_r0) / w_r0 at the step's relative rotation w_r0; the Stokes slope at w_r0 = 0.
  static double coefficient(double rho, double mu, double d, double w0, double stokes_below) {
    return w0 != 0.0 ? aero::rotation_torque(rho, mu, d, w0, stokes_below) / w0
                     : aero::stokes_torque_slope(mu, d);
  }
  /// The sub-step torque per real particle at the relative rotation w_r: M = kappa w_r.
  static double torque(double kappa, double w_r) { return kappa * w_r; }

  explicit RotationTorqueModel(const CouplingConfig& c);
  std::string description() const override;
  void coefficient(const ModelInput& in, SubstepCoefficients& out) const {
    const GasSample& g = in.gas;
    const double w0 = aero::relative_rotation(g.vorticity, in.parcel.omega);
    out.torque = coefficient(g.rho, g.mu, in.parcel.diameter, w0, stokes_below_);
  }

 private:
  double stokes_below_;
};

}  // namespace dustlift
