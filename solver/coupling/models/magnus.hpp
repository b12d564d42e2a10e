#pragma once
// Magnus lift (Table 1, docs/coupling.md and docs/coupling.md): the published law per
// real particle, F = C_LM (pi/8) rho d^3 Omega_r z x u_r (with the convention's sign); its
// sub-step coefficient M = s C_LM (pi/8) rho d^3 (s the convention's sign, C_LM with the
// optional Lun-Liu factor at the step's Re) and the sub-step force F = M w_r z x u_r at the
// parcel's current relative rotation and slip.
#include <numbers>
#include <string>

#include "solver/core/vec2.hpp"
#include "solver/coupling/models/coupling_model.hpp"

namespace dustlift {

struct CouplingConfig;

namespace aero {

/// Magnus lift conventions (docs/coupling.md and docs/coupling.md):
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
/// Table 1 with the |.| bars restored: 1/2 rho |u_r|^2 (pi d^2/4) C_LM (d |w_r|/|u_r|)
/// (w_r x u_r)/(|w_r||u_r|) = C_LM (pi/8) rho d^3 (w_r x u_r), signed by the convention.
Vec2 magnus_force(double rho, double d, Vec2 u_r, double omega_rel, double c_lm,
                  MagnusConvention conv);

}  // namespace aero

class MagnusModel final : public BatchedCouplingModel<MagnusModel> {
 public:
  static constexpr ModelTraits kTraits{.reads = {.rotation = true}, .writes = {.magnus = true}};

  /// M = s C_LM (pi/8) rho d^3, s = +1 in the standard convention and -1 in the paper's.
  static double coefficient(double c_lm, aero::MagnusConvention conv, double rho, double d) {
    const double sign = conv == aero::MagnusConvention::Standard ? 1.0 : -1.0;
    return sign * (c_lm * std::numbers::pi / 8.0 * rho * d * d * d);
  }
  /// The sub-step force per real particle at the relative rotation w_r and slip u_r:
  /// F = M w_r z x u_r.
  static Vec2 force(double M, double w_r, Vec2 u_r) {
    const double m = M * w_r;
    return {-m * u_r.y, m * u_r.x};
  }

  explicit MagnusModel(const CouplingConfig& c);
  std::string description() const override;
  void coefficient(const ModelInput& in, SubstepCoefficients& out) const {
    const double c_lm = c_lm_ * (lun_liu_ ? aero::lun_liu_factor(in.re) : 1.0);
    out.magnus = coefficient(c_lm, convention_, in.gas.rho, in.parcel.diameter);
  }

 private:
  double c_lm_;
  bool lun_liu_;
  aero::MagnusConvention convention_;
};

}  // namespace dustlift
