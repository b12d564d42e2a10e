#pragma once
// The CFD-DEM coupling of the paper (eqs. 2-3 sources, 5-16, Fig. 3), per CFD step:
//  1. sample the gas at every parcel (eq. 16) together with the derived fields the enabled
//     forces need (vorticity for Magnus/torque, grad p for the pressure force);
//  2. sub-cycle the DEM over the CFD step (eq. 18), evaluating drag, Magnus, pressure force,
//     friction torque and heat transfer per sub-step with the parcel's current velocity,
//     spin and temperature in the frozen sampled gas;
//  3. deposit alpha_p (eq. 12) and the exchange terms f_p, s_p, q_p (eqs. 13-15) as their
//     averages over the sub-steps, so the gas loses exactly the momentum and energy the
//     parcels receive; update the porosity with the p d(alpha_g)/dt work term of eq. (3).
// The gas step that follows uses the new porosity and the sources (two-way coupling).
#include <vector>

#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"
#include "solver/coupling/coupling_config.hpp"
#include "solver/dem/dem_config.hpp"
#include "solver/gas/gas_config.hpp"

namespace dustlift {

class GasSolver;
class ParcelSystem;

/// What the parcels received from the gas through the exchange terms in the last step
/// (sums over parcels of n_i x per-particle quantities; J/m and N s/m per metre of depth),
/// and what was deposited into the gas sources (integrated over cells and the step).
struct ExchangeTotals {
  double parcel_impulse_x = 0, parcel_impulse_y = 0, parcel_work = 0, parcel_heat = 0;
  double gas_impulse_x = 0, gas_impulse_y = 0, gas_energy = 0;
  int substeps = 0;
};

class GasParticleCoupling {
 public:
  GasParticleCoupling(const Grid2D& grid, const CouplingConfig& config, const GasConfig& gas,
                      const DemConfig& dem);

  /// Deposits the initial alpha_p and, with two-way coupling, gives the gas its porosity
  /// (conserved variables rescaled so the primitive state stays the initial condition).
  void initialize(GasSolver& gas, ParcelSystem& parcels);

  /// Steps 1-3 above for a CFD step dt. Throws NumericalFailure naming the parcel and
  /// variable if a parcel state becomes non-finite.
  void advance(GasSolver& gas, ParcelSystem& parcels, double dt);

  const ExchangeTotals& last_exchange() const { return exchange_; }
  /// Deposited particle volume fraction (eq. 12), before the cap.
  const Field2D& alpha_p() const { return alpha_p_; }
  /// Magnus inputs by parcel id, from the last step: gas rotation omega_z/2 (right-handed)
  /// and the relative rotation omega_z/2 - omega_p used by the Magnus force and torque.
  const std::vector<double>& gas_rotation_by_id() const { return gas_rotation_; }
  const std::vector<double>& relative_rotation_by_id() const { return relative_rotation_; }
  /// Gas pressure sampled at each parcel (by id) at the start of the last step.
  const std::vector<double>& gas_pressure_by_id() const { return sampled_p_; }

  bool needs_vorticity() const;

  /// What one advance() leaves for the next (for checkpoints): the deposited alpha_p
  /// (ghosts included; sampled at the start of the next step) and the rows it touched
  /// (cleared at the next deposit). Everything else is rebuilt within each step.
  struct CarriedState {
    std::vector<double> alpha_p;
    int rows_touched = 0;
  };
  CarriedState carried_state() const { return {alpha_p_.raw(), rows_touched_}; }
  /// Throws std::invalid_argument when the field size or row count does not fit the grid.
  void restore_carried_state(const CarriedState& s);

 private:
  struct Sample {
    double rho, u, v, p, T, mu, lambda, c, cp, alpha_g, vorticity, dpdx, dpdy;
    // Per-CFD-step model coefficients (per real particle), zero for effects that are off:
    double drag_coef = 0.0;    ///< F_drag = drag_coef u_r (includes stiff_exchange_relief)
    double magnus_coef = 0.0;  ///< C_LM (pi/8) rho d^3
    double pressure_fx = 0.0, pressure_fy = 0.0;  ///< -V_p grad p
    double torque_coef = 0.0;  ///< M_rotation = torque_coef w_rel
    double heat_coef = 0.0;    ///< Q = heat_coef (T_g - T_p) (includes the relief)
  };
  /// Drag and heat exchange are stiff in a packed layer: the gas in a cell holds far less
  /// momentum and heat than its particles (mass loading ~ 700 at alpha_p = 0.59), so its
  /// relaxation time can be shorter than a CFD step. With explicit, frozen-gas exchange the
  /// gas would overshoot. Each cell's exchange is therefore scaled by the backward-Euler
  /// factor 1 / (1 + dt K (1/C_gas + 1/C_particles)) of the two-body relaxation it drives
  /// (K: sum of the cell's drag or heat coefficients; C: momentum or heat capacities), which
  /// tends to 1 when the exchange is slow and to the exact equilibrium transfer when it is
  /// fast. Conservation is unaffected: the gas receives exactly what the parcels get.
  void stiff_exchange_relief(const GasSolver& gas, const ParcelSystem& parcels, double dt);
  void deposit_alpha(const ParcelSystem& parcels);
  void sample_gas(const GasSolver& gas, const ParcelSystem& parcels, double dt);
  void substep_forces(ParcelSystem& parcels, double dt_sub, bool first);
  void finish_work(const ParcelSystem& parcels);
  void deposit_exchange(GasSolver& gas, const ParcelSystem& parcels, double dt);
  void check_parcels(const ParcelSystem& parcels) const;
  void row_range(const ParcelSystem& parcels, int& j0, int& j1) const;

  Grid2D grid_;
  CouplingConfig cfg_;
  GasConfig gas_cfg_;
  DemConfig dem_cfg_;
  double particle_volume_ = 0.0;  ///< V_p of one real particle

  Field2D alpha_p_, vorticity_, dpdx_, dpdy_;
  Field2D src_x_, src_y_, src_e_;
  Field2D cell_drag_, cell_heat_, cell_mass_, cell_heat_capacity_;  ///< stiff_exchange_relief sums
  std::vector<Sample> samples_;  ///< by parcel id
  std::vector<double> impulse_x_, impulse_y_, work_, heat_;   ///< by id, per real particle
  std::vector<double> force_x_prev_, force_y_prev_, vx_prev_, vy_prev_;  ///< by id
  std::vector<double> gas_rotation_, relative_rotation_, sampled_p_;
  double dt_sub_prev_ = 0.0;
  int rows_touched_ = 0;  ///< deposit rows [0, rows_touched_) to clear next time
  ExchangeTotals exchange_;
};

}  // namespace dustlift
