#pragma once
// The CFD-DEM coupling of the paper (eqs. 2-3 sources, 5-16, Fig. 3), per CFD step:
//  1. sample the gas at every parcel (eq. 16) together with the derived fields the active
//     effects read (effects/effect_list.hpp), and let the effects turn it into the coefficients
//     of their sub-step laws (gas_sampling.cpp);
//  2. sub-cycle the DEM over the CFD step (eq. 18): each sub-step applies the effects' laws to
//     the parcel's current slip, spin and temperature in the frozen sampled gas (the effects'
//     functors fused into the DEM's forced Euler step) and sums the exchange per parcel; drag
//     and heat exchange
//     are first scaled by implicit exchange factors where they are stiff
//     (implicit_exchange.cpp);
//  3. deposit alpha_p (eq. 12) and the exchange terms f_p, s_p, q_p (eqs. 13-15) as their
//     averages over the sub-steps, so the gas loses exactly the momentum and energy the
//     parcels receive; move the gas to the new porosity (GasSolver::change_porosity)
//     (coupling_deposits.cpp).
// Parcels resting exactly are left out of all three (resting_parcels.hpp). Every per-parcel
// quantity lives in columns of the ParcelSystem (parcel order); one deposit stencil per parcel
// per step serves every deposit (deposit_stencils.hpp).
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"
#include "solver/coupling/coupling_config.hpp"
#include "solver/coupling/coupling_slab.hpp"
#include "solver/coupling/deposit_stencils.hpp"
#include "solver/coupling/effects/effect_list.hpp"
#include "solver/coupling/gas_halo.hpp"
#include "solver/coupling/resting_parcels.hpp"
#include "solver/dem/dem_config.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/gas/gas_config.hpp"
#include "solver/gas/gas_solver.hpp"

namespace dustlift {

class Communicator;
class GasProperties;

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

  /// On an MPI rank (docs/parallel.md): this coupling's grid is the rank's slab of `whole`,
  /// starting at its column `first_column`; the parcels are split over the ranks
  /// (ParcelSystem::set_decomposition), `halo` fills the slab's ghost columns and `comm` gives
  /// the collectives. Stencils are then made on the whole grid (a slab would clamp them at its
  /// cut), deposits go to the slab's own cells, the fields the parcels read are exchanged at
  /// the cuts, and resting parcels are not skipped (skipping changes no bit; it is not split
  /// yet). Call before initialize(); `whole`, `halo` and `comm` must outlive this coupling.
  void set_slab(const Grid2D& whole, int first_column, GasHalo& halo, const Communicator& comm);
  /// After a move of the cuts: this rank's new slab (its grid, first column and halo). The
  /// fields start empty: restore_carried_state gives alpha_p; the rest is made each step.
  void move_to_slab(const Grid2D& slab, int first_column, GasHalo& halo);

  /// Steps 1-3 above for a CFD step dt. Throws NumericalFailure naming the parcel and
  /// variable if a parcel state becomes non-finite.
  void advance(GasSolver& gas, ParcelSystem& parcels, double dt);

  /// The exchange totals of the last advance() of `parcels` (summed on demand, in parcel and
  /// cell order: a diagnostic, kept out of the step).
  ExchangeTotals last_exchange(const ParcelSystem& parcels) const;
  /// Wall seconds spent sampling the gas (with the models), making the implicit exchange
  /// factors, and depositing alpha_p and the exchange terms (with the porosity update).
  struct Timings {
    double sample = 0.0, implicit_exchange = 0.0, deposit = 0.0;
  };
  const Timings& timings() const { return timings_; }
  /// Skip parcels resting exactly (resting_parcels.hpp); on by default.
  void set_skip_resting(bool on) { skip_resting_ = on; }
  /// Parcels stepped in the last CFD step (the others rested exactly).
  std::size_t last_active_parcels() const { return stepped_.count; }
  /// Deposited particle volume fraction (eq. 12), before the cap.
  const Field2D& alpha_p() const { return alpha_p_; }
  /// Parcel columns (see initialize): gas rotation omega_z/2 at the parcel (right-handed),
  /// the relative rotation omega_z/2 - omega_p of the last sub-step (Magnus and torque input)
  /// and the gas pressure sampled at the start of the last step.
  ParcelColumn gas_rotation_column() const { return col_.gas_rotation; }
  ParcelColumn relative_rotation_column() const { return col_.relative_rotation; }
  /// 1 for the parcels stepped in the last CFD step, 0 for those left resting.
  ParcelColumn stepped_column() const { return col_.stepped; }
  ParcelColumn gas_pressure_column() const { return col_.gas_p; }

  /// One line per active effect, for `dustlift info`.
  std::vector<std::string> model_descriptions() const { return effects_.descriptions(); }
  /// The active effects (what they read, their validity).
  const CouplingEffects& effects() const { return effects_; }
  /// What the flow asks of the effects' laws now: the densest deposited alpha_p, and the
  /// Reynolds and Mach numbers of the largest particle at rest in the fastest gas (collective on
  /// several ranks).
  FlowEnvelope flow_envelope(const GasSolver& gas) const;

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
  double rest_pressure() const { return resting_.reference_pressure(); }
  double rest_temperature() const { return resting_.reference_temperature(); }
  /// Throws std::invalid_argument when the field size or row count does not fit the grid.
  void restore_carried_state(const CarriedState& s);

 private:
  struct Columns {
    ParcelColumn gas_u, gas_v, gas_rotation, gas_T, gas_p;
    ParcelColumn impulse_x, impulse_y, work, heat;
    ParcelColumn relative_rotation;
    ParcelColumn rest_steps;  ///< consecutive steps begun exactly at rest in resting gas
    ParcelColumn stepped;     ///< 1: stepped this CFD step (ParcelSystem::set_stepped_column)
  };
  /// The rows holding parcels (of every rank on a slab: collective), with two rows of margin
  /// for the interpolation quad and the 3-point derivative stencils.
  void row_range(const ParcelSystem& parcels, int& j0, int& j1) const;
  /// (Re)makes the grid-sized fields for grid_ (those of the derived fields the models read).
  void make_fields();
  /// A slab's implicit exchange factors (with two-way coupling).
  void make_slab_fields();

  // gas_sampling.cpp
  void sample_gas(const GasSolver& gas, ParcelSystem& parcels);
  /// Parcels sampled together: each field is interpolated at a batch's stencils in one vector
  /// loop, and each effect runs over the whole batch.
  static constexpr std::size_t kSampleBatch = 64;
  /// The rows [j0, j1) and columns [0, i1) the sampled parcels' quads read.
  void sampled_rows(const ParcelSystem& parcels, int& j0, int& j1, int& i1) const;
  /// The derived fields the effects read, where the sampled parcels read them (on a slab:
  /// everywhere, with the cut's ghosts, and the rank copies' sampling positions).
  void derived_fields_for_sampling(const GasPrimitives& gas, ParcelSystem& parcels);
  /// What a batch interpolates, in this order (value[field][parcel]); a field no effect reads
  /// is zero.
  enum SampledField {
    kRho,
    kU,
    kV,
    kP,
    kT,
    kAlphaP,
    kVorticity,
    kDpdx,
    kDpdy,
    kDxRhoU,
    kDyRhoU,
    kDxRhoV,
    kDyRhoV,
    kSampledFields
  };
  void interpolate_sampled(const InterpolationBatch<kSampleBatch>& quads, const GasPrimitives& gas,
                           std::size_t count, double (*value)[kSampleBatch]) const;
  /// The gas at parcels [k0, k0 + count) and the effects' coefficients from it.
  void sample_batch(const GasPrimitives& gas, ParcelSystem& parcels, std::size_t k0,
                    std::size_t count, const StepContext& step) const;
  /// The vorticity and pressure gradient (what the models read) at the cells the sampled
  /// parcels' quads can read, in rows [j0, j1) and columns [0, i1).
  void derivatives_near_parcels(const GasPrimitives& gas, int j0, int j1, int i1);
  /// coupling.finite_size: the batch's samples of grad p and of the gas momentum and its
  /// gradient replaced by their averages over each particle's sphere (sphere_average.hpp).
  void average_over_particles(const double* x, const double* y, const double* d, std::size_t n,
                              ModelInput* in) const;
  /// rho u and rho v in the interior cells of rows [j0, j1), columns [0, i1).
  void momentum_fields(const GasPrimitives& gas, int j0, int j1, int i1);
  /// Every derived field the effects read in cells [i0, i1) of row j.
  void derived_segment(const GasPrimitives& gas, int j, int i0, int i1);
  /// The derived fields the effects read (their slab exchange list).
  std::vector<Field2D*> derived_fields();

  // implicit_exchange.cpp
  /// Drag and heat exchange are stiff in a packed layer: the gas in a cell holds far less
  /// momentum and heat than its particles (mass loading ~ 700 at alpha_p = 0.59), so its
  /// relaxation time can be shorter than a CFD step. With explicit, frozen-gas exchange the
  /// gas would overshoot. Each cell's exchange is therefore scaled by the implicit
  /// (backward-Euler) exchange factor 1 / (1 + dt K (1/C_gas + 1/C_particles)) of the
  /// two-body relaxation it drives (K: sum of the cell's drag or heat coefficients; C:
  /// momentum or heat capacities), which tends to 1 when the exchange is slow and to the exact
  /// equilibrium transfer when it is fast. Conservation is unaffected: the gas receives
  /// exactly what the parcels get.
  void apply_implicit_exchange(const GasSolver& gas, ParcelSystem& parcels, double dt);
  /// Its steps: every parcel's coefficients and capacities summed into the cells of columns
  /// [0, c] it reaches; each such cell's factors (rows [0, j1), columns [0, nx)); on a slab,
  /// the neighbours' factors in the ghost cells; each stepped parcel's coefficients scaled
  /// by its stencil's average factors.
  void sum_implicit_cells(const ParcelSystem& parcels, int c, const double* K_raw,
                          const double* H_raw);
  void implicit_factors(const GasSolver& gas, double dt, int j1, int nx);
  void share_implicit_factors(int j1);
  void scale_by_implicit_factors(const ParcelSystem& parcels, std::size_t active, double* K,
                                 double* H) const;

  // coupling_deposits.cpp
  /// The alpha_p deposit after the step planned by RestingParcels (the parcels
  /// [0, stepped_.count) moved, the farthest of them from stepped_.x_max): columns beyond what
  /// they reach keep their sums.
  void deposit_alpha(const ParcelSystem& parcels);
  void deposit_exchange(GasSolver& gas, const ParcelSystem& parcels, double dt);
  void check_parcels(const ParcelSystem& parcels) const;

  Grid2D grid_;
  std::optional<CouplingSlab> slab_;  ///< none: one rank holds the whole grid
  CouplingSlab* slab() { return slab_ ? &*slab_ : nullptr; }
  const CouplingSlab* slab() const { return slab_ ? &*slab_ : nullptr; }
  CouplingConfig cfg_;
  DemConfig dem_cfg_;
  double particle_volume_ = 0.0;  ///< V_p of one real particle
  /// V_p of each size class, same expression (a polydisperse layer; empty: one class).
  std::vector<double> class_volume_;
  CouplingEffects effects_;
  std::vector<ParcelColumn> stiff_sampled_;  ///< the sampled stiff coefficients (rank copies')
  std::vector<Field2D*> derived_;            ///< derived_fields(), kept (no allocation per step)
  double largest_diameter_ = 0.0;  ///< m, of the real particles (the finite-size averages' reach)
  std::unique_ptr<GasProperties> props_;
  Columns col_;

  Field2D alpha_p_, alpha_g_, vorticity_, dpdx_, dpdy_;
  /// The gas momentum rho u, rho v (cells the derivatives read) and its gradient, for the
  /// resolved added mass.
  Field2D rho_u_, rho_v_, dx_rho_u_, dy_rho_u_, dx_rho_v_, dy_rho_v_;
  /// Deposited exchange per cell (N/m^3, W/m^3; indexed as the grid's fields), side by side.
  struct ExchangeCell {
    double x = 0.0, y = 0.0, energy = 0.0;
  };
  std::vector<ExchangeCell> exchange_;
  /// apply_implicit_exchange's sums per cell (indexed as the grid's fields), side by side: a
  /// parcel's deposit adds to all four, and then drag and heat become the cell's factors.
  struct ImplicitExchangeCell {
    double drag = 0.0, heat = 0.0, mass = 0.0, heat_capacity = 0.0;
  };
  std::vector<ImplicitExchangeCell> implicit_;
  DepositStencils stencils_;  ///< parcel order, at the positions after the last DEM step
  RestingParcels resting_;
  SteppedParcels stepped_;  ///< this step's stepped parcels
  int last_reach_ =
      std::numeric_limits<int>::max();  ///< last column the last step's stepped parcels reached
  int deposit_columns_ = 0;  ///< the last deposit recomputed columns [0, deposit_columns_]
  int rows_touched_ = 0;     ///< deposit rows [0, rows_touched_) to clear next time
  int cleared_to_ = 0;       ///< rows the last deposit cleared (they may have changed)
  int last_substeps_ = 0;    ///< DEM sub-steps of the last advance()
  double last_dt_ = 0.0;     ///< its CFD step (the sources are rates over it)
  Timings timings_;
  bool skip_resting_ = true;
  std::vector<std::uint8_t> near_scratch_;  ///< per thread, derivatives_near_parcels
};

}  // namespace dustlift
