#pragma once
// The rotational friction torque (Table 1; Dennis, Singh & Ingham 1980) as an effect:
// M = kappa w_r per real particle with kappa the torque's slope at the CFD step's relative
// rotation (laws/rotation_torque.hpp). The gas does not feel it (the paper has no counterpart).
#include <string>

#include "solver/coupling/coupling_config.hpp"
#include "solver/coupling/effects/effect.hpp"
#include "solver/dem/forced_euler.hpp"
#include "solver/laws/magnus.hpp"
#include "solver/laws/rotation_torque.hpp"

namespace dustlift {

class RotationTorqueEffect final : public BatchedEffect<RotationTorqueEffect> {
 public:
  /// Where its functor runs in the DEM's forced sub-step (Table 1's order; effect_list.cpp).
  static constexpr int kPosition = 5;
  static bool active(const CouplingConfig& c) { return c.rotation_torque; }
  explicit RotationTorqueEffect(const CouplingConfig& c);
  std::string description() const override;
  GasReads reads() const override { return {.rotation = true}; }
  void attach(ParcelTable& t) override;

  struct Columns {
    double* kappa;
  };
  Columns columns(ParcelTable& t) const { return {t.column(coefficient_).data()}; }
  void coefficient(const ModelInput& in, std::size_t k, Columns& out) const {
    const GasSample& g = in.gas;
    const double w0 = aero::relative_rotation(g.vorticity, in.parcel.omega);
    out.kappa[k] = aero::torque_slope(g.rho, g.mu, in.parcel.diameter, w0, stokes_below_);
  }

  /// The sub-step: M = kappa (Omega_g - w).
  struct Substep : SubstepRoles, StoresValue {
    static constexpr bool kTorque = true;
    const double *rotation, *kappa;
    double force(std::size_t i, SubstepParcel& p) const {
      const double m = aero::linear_torque(kappa[i], rotation[i] - p.omega);
      p.torque += m;
      return m;
    }
  };
  Substep substep(ParcelTable& t, const FrozenGas& g) const {
    return {{}, {t.column(torque_).data()}, g.rotation, t.column(coefficient_).data()};
  }

 private:
  double stokes_below_;
  ParcelColumn coefficient_, torque_;
};

}  // namespace dustlift
