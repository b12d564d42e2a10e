#pragma once
// Coarse-grained DEM parcels (paper eqs. 5–6, 11, 18; physics-reference.md §3.6–§4) as
// structure-of-arrays, with a cell-sorted Verlet neighbour list that carries the
// per-pair tangential history, axis-aligned walls, optional periodicity in x, and
// symplectic Euler sub-steps.
//
// Units: 2-D, per metre of depth. A parcel stands for n_real real particles (per metre);
// its mass and inertia are the sums over them. Every force part stored here is per REAL
// particle (the parcel's total is n_real times it): eq. (5) divided by n_i, which is how
// the paper integrates parcels (acceleration = real-particle force / real-particle mass).
//
// Determinism: every parcel gathers its own contacts in neighbour-list order (each pair is
// evaluated from both sides, bitwise symmetrically); no atomics, no reductions other than
// max. Results are identical for any OpenMP thread count.
#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "solver/core/parallel_minimum.hpp"
#include "solver/core/phase_timer.hpp"
#include "solver/dem/dem_config.hpp"

namespace dustlift {

class Communicator;

/// Wall slots of the per-parcel wall history, in this order.
enum class Wall : int { Bottom = 0, Top = 1, Left = 2, Right = 3, Count = 4 };
inline constexpr int kWallCount = static_cast<int>(Wall::Count);

/// A column of the parcel table: its name and unit (as written to checkpoints, .vtp and
/// Catalyst) and what it is for. Every column is permuted with the parcels by the cell sort.
struct ParcelColumnSpec {
  std::string name;
  std::string unit;
  bool checkpointed = false;  ///< part of the state a restart needs
  bool written = false;       ///< written to the .vtp (and published in situ)
};

/// Handle of a column attached to a ParcelSystem (see attach_column).
struct ParcelColumn {
  std::size_t index = static_cast<std::size_t>(-1);
  bool valid() const { return index != static_cast<std::size_t>(-1); }
};

/// Sub-step gas forcing of the parcels (frozen gas over one CFD step), per REAL particle:
///   F = K (u_g - v) + M (Omega_g - w) z x (u_g - v) + F_p,   M_z = kappa (Omega_g - w),
///   Q = H (T_g - T),
/// with the gas values u_g, Omega_g (half the vorticity), T_g and the coefficients K, M,
/// kappa, H (columns the coupling fills once per CFD step; each law is its model's,
/// solver/coupling/models/) and F_p the pressure_fx/fy columns. Only the effects the
/// coupling's models write are evaluated. The exchange with the gas, drag + Magnus impulse, its
/// work (with the symplectic-Euler mean velocity, exactly the kinetic energy it gives) and Q dt, is
/// summed per parcel over the sub-steps into the accumulator columns.
struct GasForcing {
  bool drag = false, magnus = false, pressure = false, torque = false, heat = false;
  ParcelColumn gas_u, gas_v, gas_rotation, gas_temperature;
  ParcelColumn drag_coefficient, magnus_coefficient, torque_coefficient, heat_coefficient;
  ParcelColumn impulse_x, impulse_y, work, heat_in;  ///< accumulators (zeroed by the coupling)
  ParcelColumn relative_rotation;                  ///< Omega_g - w of the last sub-step
  bool any() const { return drag || magnus || pressure || torque || heat; }
};

/// One parcel to add (before the first step).
struct ParcelInit {
  double x = 0.0, y = 0.0;          ///< m
  double vx = 0.0, vy = 0.0;        ///< m/s
  double omega = 0.0;               ///< rad/s, counter-clockwise positive (right-handed z)
  double diameter = 100e-6;         ///< m, parcel diameter n_xy d
  double real_diameter = 100e-6;    ///< m, real particle diameter d
  double density = 980.0;           ///< kg/m^3 of the real particles
  double n_real = 1.0;              ///< real particles per parcel (per metre of depth)
  double temperature = 300.0;       ///< K
};

/// The private state of a ParcelSystem that its next step reads, for checkpoints: with the
/// public arrays (state, force parts, contact history) it continues a run bitwise.
/// Per-parcel vectors are in the current (cell-sorted) parcel order.
struct ParcelInternals {
  std::vector<double> inv_mass_real, inv_inertia_real;  ///< 1/m and 1/I of one real particle
  std::vector<double> x_build, y_build;                 ///< positions at the last rebuild
  std::vector<double> half_skin;                        ///< how far each may move until the next
  std::vector<std::uint8_t> wall_mask;                  ///< walls within reach until the next rebuild
  bool needs_rebuild = true;
  double time = 0.0;
  long long steps = 0, rebuilds = 0;
  double gravity_x = 0.0, gravity_y = 0.0;              ///< may differ from the scene (set_gravity)
};

class ParcelSystem {
 public:
  /// Contact laws, walls, domain, gravity, skin and heat capacity come from `cfg`;
  /// the parcels are added with add_parcel (see make_paper_layer in layer_generator.hpp).
  explicit ParcelSystem(const DemConfig& cfg);

  void reserve(std::size_t n);
  /// Adds one parcel; its id is the running count. Invalidates the neighbour list.
  void add_parcel(const ParcelInit& p);
  std::size_t size() const { return x.size(); }

  /// Eq. (18): nu_DEM sqrt(min real-particle mass / max spring constant).
  double stable_time_step() const;

  /// One symplectic Euler step (v^{n+1} = v^n + dt F^n/m, x^{n+1} = x^n + dt v^{n+1}) under
  /// the contacts (recomputed), gravity and, when set, the gas forcing (set_gas_forcing).
  void step(double dt);

  /// Called before every sub-step with (system, sub-step time) so the coupling can fill
  /// the drag/Magnus/pressure/fluid-torque/heat arrays.
  using SubstepHook = std::function<void(ParcelSystem&, double)>;
  /// n = ceil(dt_total / stable_time_step()): the sub-steps advance() takes for dt_total.
  int substeps_for(double dt_total) const;
  /// Advances by dt_total in n = substeps_for(dt_total) equal sub-steps.
  /// Returns n.
  int advance(double dt_total, const SubstepHook& hook = {});

  /// Kinetic (translation + rotation) energy, J per metre of depth (sum over real particles).
  double kinetic_energy() const;
  /// Kinetic + elastic (contact springs, from the current overlaps and stored tangential
  /// elongations) + gravitational potential, J per metre of depth.
  double mechanical_energy() const;
  /// Number of parcel–parcel pairs in contact (each counted once) at the current positions.
  std::size_t contact_pair_count() const;

  double time() const { return time_; }
  long long steps() const { return steps_; }
  long long neighbour_rebuilds() const { return rebuilds_; }
  /// How often the parcel data were re-sorted (every column permuted) since construction:
  /// parcel indices are stable between two of them.
  long long data_permutations() const { return data_permutations_; }
  /// Parcel-sub-steps computed (sub-steps times the parcels stepped in each).
  long long parcel_substeps() const { return parcel_substeps_; }
  /// Wall seconds spent in the contact pass, the integration and the neighbour rebuilds.
  struct Timings {
    double contacts = 0.0, integrate = 0.0, rebuild = 0.0;
  };
  const Timings& timings() const { return timings_; }
  const DemConfig& config() const { return cfg_; }
  /// Changes the body acceleration (e.g. gravity only while a bed settles).
  void set_gravity(double gx, double gy) {
    cfg_.gravity_x = gx;
    cfg_.gravity_y = gy;
  }

  /// Forces a neighbour rebuild (and cell re-sort) before the next step.
  void invalidate_neighbours() { needs_rebuild_ = true; }
  /// Sorts the parcels by cell and builds the neighbour list now if it is due (the coupling
  /// does this before its first deposit, so that the deposit order of parcels at rest never
  /// changes afterwards: a resting layer then deposits the same alpha_p to the last bit).
  void build_neighbours_if_due() {
    if (needs_rebuild_) rebuild_neighbours();
  }

  /// Attaches a column of doubles to the parcel table (zeros for the parcels present, and for
  /// parcels added later); from then on it is permuted with the parcels.
  ParcelColumn attach_column(ParcelColumnSpec spec);
  std::vector<double>& column(ParcelColumn c) { return attached_[c.index]; }
  const std::vector<double>& column(ParcelColumn c) const { return attached_[c.index]; }
  /// The attached columns, in the order attached.
  std::size_t attached_count() const { return attached_.size(); }
  const ParcelColumnSpec& attached_spec(std::size_t k) const { return attached_specs_[k]; }
  const std::vector<double>& attached(std::size_t k) const { return attached_[k]; }
  std::vector<double>& attached(std::size_t k) { return attached_[k]; }

  /// The built-in double columns (state, properties, force parts) with their specs, and
  /// their arrays; same order for both.
  static constexpr std::size_t kBuiltinColumns = 24;
  static const std::vector<ParcelColumnSpec>& builtin_specs();
  std::array<std::vector<double>*, kBuiltinColumns> builtin_columns();
  std::array<const std::vector<double>*, kBuiltinColumns> builtin_columns() const;

  /// Sets the sub-step gas forcing (the coupling, once). Its columns must be attached here.
  void set_gas_forcing(const GasForcing& f);
  /// Marks the next advance() to store the force parts, relative rotation and heat rate of
  /// its last sub-step in their columns (the observers' view); other sub-steps skip those
  /// stores. Default: always stored.
  void store_parts_on_last_substep_only(bool on) { parts_last_only_ = on; }

  /// Limits the sub-steps to the parcels up to the last one whose `activity` column value is
  /// non-zero (the coupling marks those that may move this CFD step; those after them rest
  /// exactly and would not change a bit). Re-read at every advance and after every re-sort.
  /// An invalid handle (the default) steps every parcel.
  void set_activity_column(ParcelColumn activity) { activity_ = activity; }
  /// Parcels the current sub-steps run over: [0, active_count()).
  std::size_t active_count() const { return active_count_ < size() ? active_count_ : size(); }

  // ---- Decomposition over x-slabs of MPI ranks (issue 12, docs/parallel.md) ----
  /// Splits the parcels over the ranks: this rank keeps those whose neighbour-cell column
  /// lies between the cuts (x of the boundaries between ranks 0|1, 1|2, ...; a cut is rounded
  /// to the nearest cell face) and ghost copies of the others' parcels within contact reach
  /// of its columns (plus the ghost margin) and of every listed partner of its own. Every
  /// rank must hold the same table when this is called (each builds the same layer, or reads
  /// the same checkpoint); a system between two rebuilds keeps its lists. The results are
  /// bitwise those of one rank: every loop runs in the one-rank parcel order (`order_key`),
  /// the rebuild, sort and sub-step decisions are collective, and ghost states are
  /// refreshed every sub-step. Parcels change owner at rebuilds, with their contact
  /// history. Not for periodic x. `comm` must outlive this system.
  void set_decomposition(const Communicator& comm, std::vector<double> cuts);
  /// New cuts, applied at the next rebuild (the parcels move then).
  void set_cuts(std::vector<double> cuts);
  /// Ghosts also within this distance (m) beyond the contact reach, from the next rebuild:
  /// what the coupling's stencils need around a cut.
  void set_ghost_margin(double margin) { ghost_margin_ = margin; }
  /// Collective: the ghosts take their owners' values of these attached columns now (the
  /// coupling's samples and exchange sums, which the owners compute).
  void refresh_ghost_columns(std::span<const ParcelColumn> columns);
  /// Collective in decomposed runs: the lowest-numbered rank's non-empty text ("" when none),
  /// so that a failure one rank finds stops every rank with the same message.
  std::string first_failure(const std::string& local) const;
  /// Collective in decomposed runs: the largest value over the ranks (the value otherwise).
  double max_over_ranks(double value) const;
  /// Element by element, in place (one message for all of them).
  void max_over_ranks(std::span<double> values) const;
  bool decomposed() const { return comm_ != nullptr; }
  /// Back to a one-rank system's bookkeeping (the table is left as it is): a restart first
  /// takes the whole checkpointed system into a copy of this one, then splits it again.
  void drop_decomposition();
  /// Whether parcel i is another rank's, copied here for the contacts (decomposed runs).
  bool is_ghost(std::size_t i) const { return !ghost_.empty() && ghost_[i] != 0; }
  /// Per parcel: 1 = another rank's copy; empty when the system is not decomposed.
  std::span<const std::uint8_t> ghost_flags() const { return ghost_; }
  /// Parcels this rank owns (size() in a one-rank run).
  std::size_t owned_count() const;
  /// Appends every owned parcel's full state (all columns, wall history and its contact
  /// history as partner ids and elongations) to `out`, in parcel order: what moves with a
  /// parcel to another rank, and what a checkpoint gathers.
  /// Without the history (`with_history` false) the packed parcels carry no contact
  /// history (an observer's view: cheaper to gather and to assign).
  /// `keep`, when given, picks the parcels (by index) to pack.
  void pack_owned(std::vector<double>& out, bool with_history = true,
                  const std::function<bool(std::size_t)>& keep = {}) const;
  /// A one-rank system from packed parcels (pack_owned of every rank, any order): sorted by
  /// order key, with each parcel's contact history as its neighbour list, so that it
  /// continues as the decomposed run would (checkpoints, tests). The attached columns must
  /// be attached (same specs, same order) before.
  void assign_packed(const std::vector<std::vector<double>>& pieces);
  /// Exchange counters of the decomposition: parcels sent to another owner (and of them,
  /// those touching another parcel or a wall with a tangential elongation to carry), ghost
  /// copies sent at rebuilds, doubles and messages sent, and the seconds spent in them.
  struct DecompositionCounters {
    long long migrated = 0, migrated_with_history = 0, ghosts_sent = 0, doubles_sent = 0,
              messages = 0;
    double seconds = 0.0;
  };
  const DecompositionCounters& decomposition_counters() const { return counters_; }

  /// Checkpoint access to the private state (see ParcelInternals).
  ParcelInternals internals() const;
  /// Restores it after the public arrays have been restored; throws std::invalid_argument
  /// when a per-parcel vector does not match size() or the contact history is inconsistent.
  void restore_internals(const ParcelInternals& s);

  // ---- Per-parcel state (SoA; the order changes when parcels are re-sorted by cell) ----
  std::vector<std::int32_t> id;             ///< stable parcel id (order of add_parcel)
  /// Decomposed runs: each parcel's index in the one-rank run's parcel order (empty otherwise).
  std::vector<std::int64_t> order_key;
  std::vector<double> x, y;                 ///< m (x unwrapped between rebuilds when periodic)
  std::vector<double> vx, vy;               ///< m/s
  std::vector<double> omega;                ///< rad/s, counter-clockwise positive
  std::vector<double> temperature;          ///< K
  std::vector<double> diameter;             ///< m, parcel
  std::vector<double> radius;               ///< m, parcel (contact lever arm)
  std::vector<double> mass;                 ///< kg/m, parcel (n_real m_real)
  std::vector<double> inertia;              ///< kg m, parcel (cylinder: mass r^2 / 2)
  std::vector<double> n_real;               ///< real particles per parcel (per metre)
  std::vector<double> x_initial, y_initial; ///< m, where the parcel started (in-situ filters)

  // ---- Force parts per REAL particle (N, N m, W); observers read, coupling writes ----
  std::vector<double> contact_fx, contact_fy, contact_torque;  ///< recomputed every step
  std::vector<double> drag_fx, drag_fy;
  std::vector<double> magnus_fx, magnus_fy;
  std::vector<double> pressure_fx, pressure_fy;
  std::vector<double> fluid_torque;         ///< M_rotation (Table 1)
  std::vector<double> heat_rate;            ///< Q_i, W (eq. 7)

  // ---- Contact history (serialisable for checkpoints) ----
  /// Neighbour list in CSR form: parcel i's candidates are slots
  /// nbr_offset[i] .. nbr_offset[i+1]-1; nbr_index is the partner's current index,
  /// nbr_image its periodic image (partner x seen from i = x[j] + image * L_x) and
  /// nbr_delta the tangential spring elongation of the pair (0 when not touching).
  std::vector<std::int32_t> nbr_offset, nbr_index;
  std::vector<std::int8_t> nbr_image;
  std::vector<double> nbr_delta;
  /// Tangential elongation of each parcel against each wall: wall_delta[i * kWallCount + w].
  std::vector<double> wall_delta;

 private:
  void step_with_parts(double dt, bool store_parts);
  void rebuild_neighbours();
  /// Per-parcel skins: the base skin/2, the time a fast parcel's skin covers at its speed,
  /// and the cap (after update_cell_geometry).
  struct SkinLimits {
    double base = 0.0, time = 0.0, cap = 0.0;
  };
  SkinLimits skin_limits() const;
  /// The neighbour cells (size >= the largest cutoff, over every rank's parcels).
  void update_cell_geometry();
  void sort_by_cell(bool permute_data);
  // Decomposition (parcel_decomposition.cpp).
  /// Before a rebuild: parcels to their owners with their contact history, fresh ghosts,
  /// the table in order-key order and the carried history in old_offset_/old_partner_id_/
  /// old_delta_. Returns whether there was a list before (on every rank alike).
  bool redistribute();
  /// set_decomposition's split of a table every rank holds alike.
  void split_replicated();
  /// Each rank's first cell column (first_column_) from the cuts.
  void update_first_columns();
  /// Collective: how many cell columns beyond a rank's own its ghosts reach.
  int ghost_reach_columns() const;
  /// After the rebuild's sort: the exchange lists follow the parcels, and a permuting sort
  /// gives the owned parcels their new order keys and sends them to the ghosts.
  void after_distributed_sort(bool permuted);
  /// Every sub-step: the owners' positions, velocities and spins to their ghosts.
  void refresh_ghost_kinematics();
  /// The owners' values of these per-parcel arrays to their ghosts (one message per neighbour).
  void refresh_ghosts(std::span<std::vector<double>* const> columns);
  /// new table row k = old row source[k], for every per-parcel array a rebuild keeps.
  void reorder_parcels(const std::vector<std::int32_t>& source);
  /// The exchange lists after a reorder (old_of_new[k]: the old index of row k).
  void follow_rows(const std::vector<std::int32_t>& old_of_new);
  /// Sorts the table by order key; returns the rows' old indices in their new order.
  std::vector<std::int32_t> sort_table_by_key();
  void pack_parcel(std::size_t i, bool with_history, std::vector<double>& out) const;
  /// Appends a packed parcel; returns the next row; its history goes to hist_* scratch.
  const double* append_packed(const double* row, bool ghost);
  int owner_of_column(int cx) const;
  int cell_column(double px) const;
  void compute_contacts(double dt);
  void integrate(double dt, bool store_parts);
  void integrate_forced(double dt, bool store_parts);
  double wall_position(int w) const;
  /// Calls f for every per-parcel double column the cell sort permutes.
  void for_each_permuted_column(const std::function<void(std::vector<double>&)>& f);

  DemConfig cfg_;
  double length_x_ = 0.0;           ///< periodic length
  double skin_ = 0.0;               ///< m, absolute
  bool needs_rebuild_ = true;
  double time_ = 0.0;
  long long steps_ = 0;
  long long rebuilds_ = 0;
  long long data_permutations_ = 0;
  long long parcel_substeps_ = 0;

  // Derived per parcel, permuted along with the state.
  std::vector<double> inv_mass_real_, inv_inertia_real_;
  std::vector<double> x_build_, y_build_;   ///< positions at the last rebuild
  std::vector<std::uint8_t> wall_mask_;     ///< bit w: wall w within reach until the next rebuild

  // Attached columns (coupling state, filters' state), permuted with the parcels.
  std::vector<ParcelColumnSpec> attached_specs_;
  std::vector<std::vector<double>> attached_;
  GasForcing forcing_;
  bool parts_last_only_ = false;
  ParcelColumn activity_;
  std::size_t active_count_ = static_cast<std::size_t>(-1);
  void update_active_count();
  Timings timings_;

  // Cell grid of the last rebuild.
  int cells_x_ = 1, cells_y_ = 1;
  bool x_major_ = true;  ///< cells numbered along y first (x is the long axis)
  /// The cells stored: columns [box_x0_, box_x0_ + box_nx_) x rows [box_y0_, box_y0_ + box_ny_)
  /// of the domain's cells, those the parcels occupied at the last sort.
  int box_x0_ = 0, box_y0_ = 0, box_nx_ = 1, box_ny_ = 1;
  bool in_box(int cx, int cy) const {
    return cx >= box_x0_ && cx < box_x0_ + box_nx_ && cy >= box_y0_ && cy < box_y0_ + box_ny_;
  }
  /// Index of domain cell (cx, cy) inside the box, numbered in the domain's order.
  int cell_index(int cx, int cy) const {
    return x_major_ ? (cx - box_x0_) * box_ny_ + (cy - box_y0_) : (cy - box_y0_) * box_nx_ + (cx - box_x0_);
  }
  double cell_dx_ = 1.0, cell_dy_ = 1.0;
  std::vector<std::int32_t> cell_of_, cell_start_, order_;
  std::vector<std::int32_t> cell_y_;     ///< sort scratch: each parcel's cell row
  std::vector<std::int32_t> members_;    ///< parcels of each cell: members_[cell_start_[c] ..]
  std::vector<std::int32_t> cursor_;     ///< counting-sort fill positions, one per cell
  std::vector<std::int32_t> old_index_;  ///< index before the last rebuild, per parcel

  // Per-parcel skins of the last rebuild (half_skin_: how far the parcel may move) and the
  // fast parcels' pairs (see rebuild_neighbours).
  struct FastPair {
    std::int32_t i, j;
    std::int8_t image;
  };
  std::vector<double> half_skin_, inv_skin2_;
  std::vector<std::int32_t> fast_, fast_start_, extra_start_;
  std::vector<FastPair> fast_pairs_, extra_pairs_;
  std::vector<std::vector<FastPair>> fast_pairs_by_thread_;
  struct ListedPartner {
    std::int32_t j;
    std::int8_t image;
  };
  std::vector<std::vector<ListedPartner>> list_by_range_;  ///< rebuild scratch, one per range of parcels (one per thread)
  double radius_max_ = 0.0, cutoff_ = 0.0;

  // Rebuild scratch (kept to avoid reallocation).
  std::vector<double> scratch_d_, scratch_wall_;
  std::vector<std::int32_t> scratch_i_;
  std::vector<std::int32_t> old_offset_, old_partner_id_;
  std::vector<double> old_delta_;

  // Decomposition state.
  const Communicator* comm_ = nullptr;
  std::vector<double> cuts_;
  std::vector<int> first_column_;    ///< of each rank's cell columns, plus the end
  double ghost_margin_ = 0.0;        ///< m, ghosts beyond the contact reach (set_ghost_margin)
  std::vector<std::uint8_t> ghost_;  ///< per parcel: 1 = another rank's copy
  std::vector<std::vector<std::int32_t>> send_ghosts_;  ///< per rank: owned parcels it copies
  std::vector<std::vector<std::int32_t>> recv_ghosts_;  ///< per rank: its ghosts here, same order
  std::vector<std::vector<double>> send_buf_, recv_buf_;
  std::vector<std::int32_t> hist_offset_, hist_partner_;  ///< carried history, per table row
  std::vector<double> hist_delta_;
  std::vector<std::int64_t> scratch_key_;
  std::vector<std::uint8_t> scratch_u8_;
  DecompositionCounters counters_;
};

}  // namespace dustlift
