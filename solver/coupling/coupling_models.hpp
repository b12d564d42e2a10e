#pragma once
// The gas-particle effects of the paper's Table 1 and eqs. (7)-(10) as a list of models built
// once from the scene (an effect that is off is not in the list and costs nothing). Once per
// CFD step each model turns the gas sampled at a parcel into the coefficient of its sub-step
// law (GasForcing in solver/dem/parcel_system.hpp), calling the tested aero:: kernel:
//   drag      K      F_drag = K u_r               (Clift-Gauvin x Parmar xi_1 x Sangani xi_2)
//   Magnus    M      F_Magnus = s M w_r z x u_r   (C_LM (pi/8) rho d^3, optional Lun-Liu factor)
//   pressure  F_p    -V_p grad p
//   torque    kappa  M_rotation = kappa w_r       (Dennis et al., slope at the step's w_r)
//   heat      H      Q = H (T_g - T_p)            (Ranz-Marshall)
// Per REAL particle; the parcel's share is n_i times it (eqs. 13-15).
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "solver/coupling/coupling_config.hpp"

namespace dustlift {

/// Gas interpolated to a parcel (eq. 16) with the derived fields the models need.
struct GasSample {
  double rho = 1.0, u = 0.0, v = 0.0, p = 0.0, T = 300.0;
  double mu = 1.8e-5, lambda = 0.026, c = 340.0, cp = 1005.0;
  double alpha_g = 1.0;
  double vorticity = 0.0;  ///< omega_z = dv/dx - du/dy
  double dpdx = 0.0, dpdy = 0.0;
};

/// The parcel seen by the models at the start of the CFD step.
struct ParcelAtSample {
  double vx = 0.0, vy = 0.0, omega = 0.0;  ///< m/s, rad/s (counter-clockwise)
  double diameter = 100e-6;                 ///< m, of a real particle
};

/// The sub-step coefficients of one parcel (zero for effects that are off).
struct SubstepCoefficients {
  double drag = 0.0;                        ///< K, N s/m
  double magnus = 0.0;                      ///< M, N s^2/m^2 ... per (rad/s)(m/s)
  double pressure_fx = 0.0, pressure_fy = 0.0;  ///< N
  double torque = 0.0;                      ///< kappa, N m s
  double heat = 0.0;                        ///< H, W/K
};

/// What the models read of one parcel: its gas, itself, slip = |u_g - v_p| and
/// re = rho slip d / mu.
struct ModelInput {
  GasSample gas;
  ParcelAtSample parcel;
  double slip = 0.0, re = 0.0;
};

class CouplingModel {
 public:
  virtual ~CouplingModel() = default;
  /// One line for `dustlift info`.
  virtual std::string description() const = 0;
  /// Adds this model's coefficient for each of n parcels: one virtual call per batch, the
  /// per-parcel formula (coefficient() of the model) inlined in its loop.
  virtual void coefficients(const ModelInput* in, SubstepCoefficients* out, std::size_t n) const = 0;
};

/// The batch loop over a model's per-parcel `coefficient(const ModelInput&, SubstepCoefficients&)`.
template <class Model>
class BatchedCouplingModel : public CouplingModel {
 public:
  void coefficients(const ModelInput* in, SubstepCoefficients* out, std::size_t n) const final {
    const Model& m = static_cast<const Model&>(*this);
    for (std::size_t k = 0; k < n; ++k) m.coefficient(in[k], out[k]);
  }
};

/// The active models, in Table 1's order.
std::vector<std::unique_ptr<CouplingModel>> build_coupling_models(const CouplingConfig& c);

}  // namespace dustlift
