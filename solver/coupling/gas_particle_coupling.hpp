#pragma once
// The CFD-DEM coupling of the paper (eqs. 2-3 sources, 5-16, Fig. 3), per CFD step:
//  1. sample the gas at every parcel (eq. 16) together with the derived fields the enabled
//     models need (vorticity for Magnus/torque, grad p for the pressure force), and let the
//     active models (coupling_models.hpp) turn it into the coefficients of the sub-step law;
//  2. sub-cycle the DEM over the CFD step (eq. 18): each sub-step applies the laws to the
//     parcel's current slip, spin and temperature in the frozen sampled gas (GasForcing,
//     fused into the DEM integrator) and sums the exchange per parcel;
//  3. deposit alpha_p (eq. 12) and the exchange terms f_p, s_p, q_p (eqs. 13-15) as their
//     averages over the sub-steps, so the gas loses exactly the momentum and energy the
//     parcels receive; move the gas to the new porosity (GasSolver::change_porosity).
// Every per-parcel quantity lives in columns of the ParcelSystem (parcel order); one deposit
// stencil per parcel per step serves every deposit.
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"
#include "solver/coupling/coupling_config.hpp"
#include "solver/coupling/coupling_models.hpp"
#include "solver/coupling/grid_transfer.hpp"
#include "solver/coupling/parallel_deposit.hpp"
#include "solver/dem/dem_config.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/gas/gas_config.hpp"
#include "solver/gas/gas_halo.hpp"
#include "solver/gas/gas_solver.hpp"

namespace dustlift {


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
  ~GasParticleCoupling();

  /// Attaches the coupling's columns to `parcels`, deposits the initial alpha_p and, with
  /// two-way coupling, gives the gas its porosity (the primitive state stays the initial one).
  void initialize(GasSolver& gas, ParcelSystem& parcels);

  /// On an MPI rank (issue 12, docs/parallel.md): this coupling's grid is the rank's slab of
  /// `whole`, starting at its column `first_column`; the parcels are split over the ranks
  /// (ParcelSystem::set_decomposition) and `halo` fills the slab's ghost columns. Stencils
  /// are then made on the whole grid (a slab would clamp them at its cut), deposits go to the
  /// slab's own cells, the fields the parcels read are exchanged at the cuts, and resting
  /// parcels are not skipped (skipping changes no bit; it is not split yet). Call before
  /// initialize(); `whole` and `halo` must outlive this coupling.
  void set_slab(const Grid2D& whole, int first_column, GasHalo& halo);
  /// After a move of the cuts: this rank's new slab (its grid, first column and halo). The
  /// fields start empty: restore_carried_state gives alpha_p; the rest is made each step.
  void move_to_slab(const Grid2D& slab, int first_column, GasHalo& halo);

  /// Steps 1-3 above for a CFD step dt. Throws NumericalFailure naming the parcel and
  /// variable if a parcel state becomes non-finite.
  void advance(GasSolver& gas, ParcelSystem& parcels, double dt);

  /// The exchange totals of the last advance() of `parcels` (summed on demand, in parcel and
  /// cell order: a diagnostic, kept out of the step).
  ExchangeTotals last_exchange(const ParcelSystem& parcels) const;
  /// Wall seconds spent sampling the gas (with the models), in the stiff-exchange relief,
  /// and depositing alpha_p and the exchange terms (with the porosity update).
  struct Timings {
    double sample = 0.0, relief = 0.0, deposit = 0.0;
  };
  const Timings& timings() const { return timings_; }
  /// Skip parcels resting exactly (see plan_active_parcels); on by default.
  void set_skip_resting(bool on) { skip_resting_ = on; }
  /// Parcels stepped in the last CFD step (the others rested exactly).
  std::size_t last_active_parcels() const { return last_active_; }
  /// Deposited particle volume fraction (eq. 12), before the cap.
  const Field2D& alpha_p() const { return alpha_p_; }
  /// Parcel columns (see initialize): gas rotation omega_z/2 at the parcel (right-handed),
  /// the relative rotation omega_z/2 - omega_p of the last sub-step (Magnus and torque input)
  /// and the gas pressure sampled at the start of the last step.
  ParcelColumn gas_rotation_column() const { return col_.gas_rotation; }
  ParcelColumn relative_rotation_column() const { return col_.relative_rotation; }
  /// 1 for the parcels stepped in the last CFD step, 0 for those left resting.
  ParcelColumn stepped_column() const { return col_.active; }
  ParcelColumn gas_pressure_column() const { return col_.gas_p; }

  /// The force parts the active models write (the outputs leave the others out: a column of
  /// zeros would read as a computed zero force).
  const ForceParts& force_parts() const { return models_.writes(); }
  /// One line per active model, for `dustlift info`.
  std::vector<std::string> model_descriptions() const { return models_.descriptions(); }

  /// What one advance() leaves for the next (checkpoints read it through alpha_p(),
  /// rows_touched(), rest_pressure() and rest_temperature()): the deposited alpha_p
  /// (ghosts included; sampled at the start of the next step) and the rows it touched
  /// (cleared at the next deposit). Everything else is rebuilt within each step.
  /// Also the resting reference the parcels' rest counts refer to (their counts and the
  /// samples of resting parcels are parcel columns attached as checkpointed; a checkpoint
  /// without them gives reference 0 and counts 0, which starts the counts anew).
  struct CarriedState {
    std::vector<double> alpha_p;
    int rows_touched = 0;
    double rest_p = 0.0, rest_T = 0.0;
  };
  int rows_touched() const { return rows_touched_; }
  double rest_pressure() const { return rest_p_; }
  double rest_temperature() const { return rest_T_; }
  /// Throws std::invalid_argument when the field size or row count does not fit the grid.
  void restore_carried_state(const CarriedState& s);

 private:
  struct Columns {
    ParcelColumn gas_u, gas_v, gas_rotation, gas_T, gas_p;
    ParcelColumn drag_raw, heat_raw;  ///< as sampled (the relief sums read these)
    ParcelColumn drag, magnus, torque, heat_coef;  ///< as the sub-steps use them
    ParcelColumn impulse_x, impulse_y, work, heat;
    ParcelColumn relative_rotation;
    ParcelColumn rest_steps;  ///< consecutive steps begun exactly at rest in resting gas
    ParcelColumn active;      ///< 1: stepped this CFD step (ParcelSystem::set_activity_column)
  };
  /// Exact skipping of resting parcels: a parcel that began this step and the last one at
  /// rest (v = w = 0, no contact force, T = T_gas) in gas resting at one state (its whole
  /// interpolation and derivative stencil) would not change a bit, nor would anything it
  /// feeds, as long as nothing that moves can reach it within the step. The parcels after the
  /// last one that may move (or lies within reach of one) are left out of sampling and
  /// sub-steps. With run.rest_tolerance "at rest" is within the tolerance (rest_ranges.hpp:
  /// parcel_still). Returns how many parcels, from the first, are stepped.
  std::size_t plan_active_parcels(const GasSolver& gas, ParcelSystem& parcels, double dt);
  /// On a slab: resting_ for the whole grid, agreed over the ranks (collective): the whole
  /// grid's reference state, and first_resting per row in the whole grid's columns, as one
  /// rank finds them.
  void resting_on_slab(const GasSolver& gas, const ParcelSystem& parcels);
  /// Drag and heat exchange are stiff in a packed layer: the gas in a cell holds far less
  /// momentum and heat than its particles (mass loading ~ 700 at alpha_p = 0.59), so its
  /// relaxation time can be shorter than a CFD step. With explicit, frozen-gas exchange the
  /// gas would overshoot. Each cell's exchange is therefore scaled by the backward-Euler
  /// factor 1 / (1 + dt K (1/C_gas + 1/C_particles)) of the two-body relaxation it drives
  /// (K: sum of the cell's drag or heat coefficients; C: momentum or heat capacities), which
  /// tends to 1 when the exchange is slow and to the exact equilibrium transfer when it is
  /// fast. Conservation is unaffected: the gas receives exactly what the parcels get.
  void stiff_exchange_relief(const GasSolver& gas, ParcelSystem& parcels, double dt, std::size_t active);
  void sample_gas(const GasSolver& gas, ParcelSystem& parcels, std::size_t active);
  /// Deposit stencils at the current positions (one per parcel, parcel order) of parcels
  /// [0, count), unless there was no DEM step since they were made; all of them when a re-sort
  /// permuted the parcels or there are none yet (stencils_need_all). The caller's count must
  /// cover every parcel stepped since: the others did not move.
  void update_stencils(const ParcelSystem& parcels, std::size_t count);
  bool stencils_need_all(const ParcelSystem& parcels) const;
  /// Plans scatter_ over parcels [0, count) of the current stencils (or keeps a plan of as many).
  void plan_scatter(std::size_t count);
  /// The last grid column a deposit stencil of a parcel at x <= this x can reach (+1 margin).
  int deposit_column_bound(double x) const;
  /// 1 + the last parcel index whose stencil may reach a column <= `column` (all parcels
  /// from the first up to it: a superset of the parcels reaching those columns).
  std::size_t parcels_reaching(const ParcelSystem& parcels, int column) const;
  /// The alpha_p deposit after the step planned by plan_active_parcels (the parcels
  /// [0, last_active_) moved, the farthest of them from active_x_max_): columns beyond what
  /// they reach keep their sums.
  void deposit_alpha(const ParcelSystem& parcels);
  void deposit_exchange(GasSolver& gas, const ParcelSystem& parcels, double dt);
  void check_parcels(const ParcelSystem& parcels) const;
  /// The vorticity and pressure gradient (what the models need) at the cells the sampled
  /// parcels' quads can read, in rows [j0, j1) and columns [0, i1).
  void derivatives_near_parcels(const GasPrimitives& gas, int j0, int j1, int i1);
  void row_range(const ParcelSystem& parcels, int& j0, int& j1) const;

  /// The ghost columns of these fields at the cuts from the neighbours (a slab; else nothing),
  /// after the domain ends' and the ghost rows' copies.
  void fill_ghosts(std::span<Field2D* const> fields, int j0, int j1);

  Grid2D grid_;
  const Grid2D* whole_ = nullptr;  ///< the grid stencils are located on (grid_ unless a slab)
  int first_column_ = 0;           ///< of the slab in the whole grid
  GasHalo* halo_ = nullptr;
  Field2D relief_drag_, relief_heat_;  ///< a slab's relief factors, exchanged at the cuts
  std::vector<double> sample_x_;       ///< a slab's parcel x for sampling (ghosts kept inside)
  std::vector<Field2D*> derived_fields_;  ///< a slab's vorticity and grad p, exchanged at the cuts
  CouplingConfig cfg_;
  GasConfig gas_cfg_;
  DemConfig dem_cfg_;
  double particle_volume_ = 0.0;  ///< V_p of one real particle
  CouplingModels models_;
  class GasProperties;
  std::unique_ptr<GasProperties> props_;
  GasForcing forcing_;
  Columns col_;

  Field2D alpha_p_, alpha_g_, vorticity_, dpdx_, dpdy_;
  /// Deposited exchange per cell (N/m^3, W/m^3; indexed as the grid's fields), side by side.
  struct ExchangeCell {
    double x = 0.0, y = 0.0, energy = 0.0;
  };
  std::vector<ExchangeCell> exchange_;
  /// stiff_exchange_relief's sums per cell (indexed as the grid's fields), side by side: a
  /// parcel's deposit adds to all four, and the relief then replaces drag and heat by the
  /// cell's factors.
  struct ReliefCell {
    double drag = 0.0, heat = 0.0, mass = 0.0, heat_capacity = 0.0;
  };
  std::vector<ReliefCell> relief_;
  std::vector<DepositStencil> stencils_;  ///< parcel order, at the positions after the last DEM step
  ParallelDeposit scatter_;               ///< planned with the stencils
  long long stencil_dem_steps_ = -1;      ///< ParcelSystem::steps() when they were made
  long long stencil_permutations_ = -1;   ///< ParcelSystem::data_permutations() then
  int last_reach_ = std::numeric_limits<int>::max();  ///< last column the last step's stepped parcels reached
  int deposit_columns_ = 0;               ///< the last deposit recomputed columns [0, deposit_columns_]
  std::size_t planned_parcels_ = 0;       ///< scatter_ is planned over [0, planned_parcels_) (0: no plan)
  double active_x_max_ = 0.0, active_y_min_ = 0.0, active_y_max_ = 0.0;  ///< of this step's stepped parcels
  int rows_touched_ = 0;  ///< deposit rows [0, rows_touched_) to clear next time
  int cleared_to_ = 0;    ///< rows the last deposit cleared (they may have changed)
  int last_substeps_ = 0;        ///< DEM sub-steps of the last advance()
  double last_dt_ = 0.0;         ///< its CFD step (the sources are rates over it)
  Timings timings_;
  bool skip_resting_ = true;
  GasSolver::RestingGas resting_;
  double rest_p_ = 0.0, rest_T_ = 0.0;  ///< the reference the rest_steps counts refer to
  std::vector<std::uint8_t> near_scratch_;  ///< per thread, derivatives_near_parcels
  std::vector<double> rest_rows_;           ///< resting_on_slab's per-row exchange
  std::vector<double>
      rest_x_threshold_;  ///< per row: the gas over parcels at x >= it rests (plan_active_parcels)
  std::size_t last_active_ = 0;
};

}  // namespace dustlift
