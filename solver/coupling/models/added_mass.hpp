#pragma once
// Inviscid-unsteady (added-mass) force on a sphere in compressible flow (Parmar, Haselbacher
// & Balachandar 2008, Phil. Trans. R. Soc. A 366:2161; the form Ling et al. 2012, Phys. Fluids
// 24:113301, use for a shock over a particle curtain):
//   F_am = C_M V_p [ D(rho_g u)/Dt - d(rho_g v)/dt ].
// Over a CFD step the gas is frozen and rho_g is the step's. D(rho_g u)/Dt is the gas's own
// acceleration: for a dilute cloud the undisturbed flow's -grad p; in a dense one the gas
// carries the added mass of the particles it accelerates past, and for particles much heavier
// than the gas (their acceleration negligible beside the gas's) its momentum balance
// (alpha_g + alpha_p C_M) rho_g a_g = -alpha_g grad p gives
//   D(rho_g u)/Dt = -s grad p,   s = alpha_g / (alpha_g + alpha_p C_M),
// which tends to -grad p as alpha_p -> 0 and keeps the gas's net force, -alpha_g grad p minus
// the reaction alpha_p C_M s grad p, pointing down the gradient however dense the cell (the
// undisturbed form alone would reverse it once alpha_p C_M > alpha_g, and a 0.125 mm grid of
// the particle curtain then blew up). With the added mass m_a = C_M rho_g V_p,
//   F_am = F_g - m_a dv/dt,   F_g = C_M V_p s (-grad p),
// and each sub-step solves (m + m_a) dv/dt = F_others + F_g for dv/dt (the added mass on the
// left: stable whatever rho_g / rho_p). The force is exchanged with the gas like drag.
// Coefficient:
//   C_M = 1/2 (1 + 1.8 Ma^2 + 7.6 Ma^4)            (Parmar et al. 2008, eq. 3.4; Ma the
//                                                  relative Mach number, held at 0.6 beyond
//                                                  the fit's range)
//       x (1 + 2 phi) / (1 - phi)                   (Zuber 1964, the volume-fraction
//                                                  correction; or none)
#include <string>

#include "solver/core/vec2.hpp"
#include "solver/coupling/models/coupling_model.hpp"

namespace dustlift {

struct CouplingConfig;

namespace aero {

/// How the added-mass coefficient depends on the particle volume fraction phi.
enum class AddedMassVolumeFraction { Zuber, None };

/// C_M(Ma, phi) above (Ma >= 0; phi in [0, 1)).
double added_mass_coefficient(double mach, double phi, AddedMassVolumeFraction correction);

/// The published force on one real particle of diameter d accelerating at dv/dt in a gas of
/// density rho whose momentum changes at D(rho u)/Dt: C_M V_p [D(rho u)/Dt - rho dv/dt].
Vec2 added_mass_force(double c_m, double d, double rho, Vec2 d_rho_u_dt, Vec2 dv_dt);

/// The share s = alpha_g / (alpha_g + alpha_p C_M) of -grad p that is the gas's own momentum
/// rate D(rho u)/Dt in a cloud of volume fraction alpha_p = 1 - alpha_g (see above).
inline double gas_acceleration_share(double alpha_g, double c_m) {
  return alpha_g / (alpha_g + (1.0 - alpha_g) * c_m);
}

}  // namespace aero

class AddedMassModel final : public BatchedCouplingModel<AddedMassModel> {
 public:
  static constexpr ModelTraits kTraits{.reads = {.pressure_gradient = true},
                                       .writes = {.added_mass = true}};

  /// The sub-step's acceleration of one real particle of mass m under the forces F (all but
  /// the added-mass force's) and the added-mass coefficients m_a and F_g = C_M V_p (-grad p):
  /// (F + F_g) / (m + m_a), with `inv_total_mass` = 1 / (m + m_a).
  static Vec2 acceleration(Vec2 forces, Vec2 gas_part, double inv_total_mass) {
    return {(forces.x + gas_part.x) * inv_total_mass, (forces.y + gas_part.y) * inv_total_mass};
  }
  /// The added-mass force at that acceleration: F_am = F_g - m_a dv/dt.
  static Vec2 force(Vec2 gas_part, double added_mass, Vec2 acceleration) {
    return {gas_part.x - added_mass * acceleration.x, gas_part.y - added_mass * acceleration.y};
  }

  explicit AddedMassModel(const CouplingConfig& c);
  std::string description() const override;
  /// m_a = C_M rho_g V_p, F_g = C_M V_p s (-grad p) and 1 / (m + m_a) at the step's gas and
  /// slip (Ma = slip / c, phi = 1 - alpha_g).
  void coefficient(const ModelInput& in, SubstepCoefficients& out) const;

 private:
  aero::AddedMassVolumeFraction correction_;
};

}  // namespace dustlift
