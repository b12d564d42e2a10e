#pragma once
// GasSolver's state and the declarations of its parts, shared by the files that implement
// them, one job each (private to solver/gas): gas_solver.cpp (construction, the state and its
// access) and gas_solver_ghosts.cpp (ghost filling), _fluxes.cpp (convective and viscous face
// fluxes), _stage.cpp (the fused flux-and-update stage, SSP-RK3), _resting.cpp (skipping the
// cells whose update would change no bit), _faults.cpp (checks and their messages),
// _porosity.cpp (porosity changes) and _time_step.cpp (the stable time step).
#include <omp.h>

#include <algorithm>
#include <array>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "solver/gas/flux_rows.hpp"
#include "solver/gas/gas_solver.hpp"
#include "solver/gas/ghost_filler.hpp"
#include "solver/gas/muscl.hpp"
#include "solver/gas/rest_ranges.hpp"
#include "solver/gas/stage_update.hpp"
#include "solver/gas/thermo.hpp"
#include "solver/gas/transport.hpp"

namespace dustlift {

/// Below this many interior cells the solver does not fork threads.
inline constexpr std::size_t kMinCellsForThreads = 8192;

using GasThermo = std::variant<CaloricallyPerfectGas, ThermallyPerfectAir>;

/// Which check a cell failed (0: none).
enum class CellFault { None, NotFinite, Density, Pressure };

struct GasSolver::Impl {
  Grid2D grid;
  GasConfig config;
  GasThermo thermo;
  MusclSettings muscl;
  GordonWilkeAirTable air_table;
  bool viscous;
  int nx, ny, ng, stride;
  /// Small grids run on one thread: the fork/join barriers would cost more than the work.
  bool threaded;
  double R;

  std::array<Field2D, Conserved::kCount> U, U0, source;
  Field2D rho, u, v, p, T, alpha, mu, lambda;
  /// Porosity-weighted convective face fluxes: x-faces (nx+1) per row, y-face rows (ny+1) of
  /// nx; and the face pressures p~ (unweighted) on the same faces.
  std::array<std::vector<double>, Conserved::kCount> fx, fy;
  std::vector<double> fx_pressure, fy_pressure;
  /// Per y-face row (ny+1) and x-face row (ny): the thread that computes it before the fused
  /// loop, or -1 (fluxes_and_update); set for face_owners_for_threads threads.
  std::vector<int> y_face_owner, x_face_owner;
  int face_owners_for_threads = 0;
  /// Cells a stage updates, per interior row: [row_lo[j], row_hi[j]). Outside, the whole
  /// stencil rests at one state and has no source, so the update would change no bit
  /// (skip_resting; docs/gas-solver.md). Without skipping every row is [0, nx).
  bool skip_resting;
  std::vector<int> row_lo, row_hi;
  /// The ranges below are in the whole grid's columns (rest_agreement: on a slab they are
  /// agreed over the slabs; row_lo, row_hi are this grid's part of whole_lo, whole_hi).
  RestAgreement rest_agreement;
  /// Per interior row, the whole grid's cells [whole_lo, whole_hi) a stage updates.
  std::vector<int> whole_lo, whole_hi;
  /// Per grid row including ghost rows (index j + ng): the whole grid's cells [-ng, rest_to]
  /// rest at the left reference state, cells [rest_from, columns + ng) at the right one.
  std::vector<int> rest_to, rest_from;
  RestReference left_reference, right_reference;
  std::vector<SourceExtent> source_rows;  ///< per interior row (whole columns), once per step
  /// The sources are zero outside interior rows [0, source_row_bound) and columns
  /// [0, source_column_bound): the whole grid until their writer says less
  /// (GasSolver::sources_zero_beyond), and again whenever source() hands them out.
  int source_row_bound = 0, source_column_bound = 0;
  std::vector<double> agreed_;  ///< scratch of agree_rest_rows
  /// Per interior row, the cells whose step-start state is saved in U0 this step (a hull of
  /// the ranges updated so far; a cell enters it before its first update of the step).
  std::vector<int> saved_lo, saved_hi;
  std::vector<int> widened_lo_, widened_hi_;  ///< scratch of widen_active_ranges
  /// Geometry per index (ghosts included, offset ng): 1/width, 1/(c_{i+1}-c_i),
  /// 1/(c_{i+1}-c_{i-1}).
  std::vector<double> inv_dx, inv_dy, inv_dxc, inv_dyc, inv_dx2, inv_dy2;
  /// Per-thread scratch rows of the flux and stage kernels (kScratchRows arrays of scratch_len).
  /// Mutable: stable_dt (const) uses it too.
  mutable std::vector<double> scratch;
  mutable std::size_t scratch_len = 0;
  /// Per row: first faulty interior cell index (or -1) and its fault.
  std::vector<int> fault_i;
  std::vector<CellFault> fault_kind;
  static constexpr std::size_t kScratchRows = 10;
  long long cell_updates = 0;  ///< cell-stage updates done since construction
  /// The state was written from outside (initialize, a checkpoint, a test): check it before
  /// the next step. The solver's own updates check every cell they change.
  bool externally_modified = true;
  /// Per row (ghost rows included, index j + ng) the trailing cells that rested at
  /// `reference` when last scanned, and the cells [0, dirty_to) of the row (counted from its
  /// first ghost) that may have changed since: a scan of a row whose resting cells did not
  /// change reads only its ghosts and the cells that did, not the resting gas again, which
  /// every step read twice (the stage's ranges, the coupling's resting parcels) over most of
  /// the grid. Any write from outside makes it invalid (every row scanned whole).
  struct RestSuffixCache {
    bool valid = false;
    RestReference reference;
    std::vector<int> suffix, dirty_to;
  };
  mutable RestSuffixCache suffix_cache;
  /// The state was written from outside the step (see externally_modified).
  void state_written() {
    externally_modified = true;
    suffix_cache.valid = false;
  }
  /// Cells [0, end) of interior row j (this grid's columns) may have changed.
  void cells_changed(int j, int end) {
    int& d = suffix_cache.dirty_to[static_cast<std::size_t>(j + ng)];
    d = std::max(d, end + ng);
  }
  /// Before the rows' resting_suffix_of calls (outside their parallel loop): a reference other
  /// than the cached one voids every row's counts.
  void begin_suffix_scans(const RestReference& ref) const;
  /// Trailing cells of row jr (ghost rows included) resting at the reference passed to
  /// begin_suffix_scans; the same count resting_suffix(row, ref) gives.
  int resting_suffix_of(int jr, const RowView& row, const RestReference& ref) const;
  /// Per GridSide: this grid's boundary condition, the filler set in its place
  /// (set_ghost_filler; null: none) and the one used. Local fillers run in the parallel
  /// regions; the collective ones (distinct, in side order, null after the last) after them.
  std::array<std::unique_ptr<GhostFiller>, 4> boundary;
  std::array<GhostFiller*, 4> replaced{}, filler{};
  std::array<bool, 4> local{};
  std::array<GhostFiller*, 2> collective{};
  FaultReporting fault_reporting;

  Impl(const Grid2D& g, const GasConfig& c);
  void build_geometry(const Axis& a, std::vector<double>& inv_w, std::vector<double>& inv_c,
                      std::vector<double>& inv_2);

  std::size_t at(int i, int j) const { return grid.index(i, j); }
  double geo(const std::vector<double>& v, int i) const {
    return v[static_cast<std::size_t>(i + ng)];
  }
  /// The smallest min(dx^2, dy^2) of any interior cell (a bound of the viscous limit).
  double smallest_h2() const {
    double largest_inverse = 0.0;
    for (int i = 0; i < nx; ++i) largest_inverse = std::max(largest_inverse, geo(inv_dx, i));
    for (int j = 0; j < ny; ++j) largest_inverse = std::max(largest_inverse, geo(inv_dy, j));
    return 1.0 / (largest_inverse * largest_inverse);
  }

  // The state (gas_solver.cpp).
  template <class Th>
  void initialize(const Th& th, const InitialCondition& ic);
  template <class Th>
  void set_cell_state(const Th& th, int i, int j, const PrimitiveState& s);
  PrimitiveState state_at(int i, int j) const {
    return {rho(i, j), u(i, j), v(i, j), p(i, j), T(i, j)};
  }
  template <class Th>
  void refresh(const Th& th);
  /// The primitives from cell index c on.
  RowPrimitives row_primitives(std::size_t c) {
    return {rho.data() + c, u.data() + c, v.data() + c, p.data() + c, T.data() + c};
  }
  /// The conserved state, porosity and primitives of cells [i0, i1) of row j.
  PrimitiveRow primitive_row(int j, int i0, int i1) {
    const std::size_t c = at(i0, j);
    return {{U[Conserved::kMass].data() + c, U[Conserved::kMomentumX].data() + c,
             U[Conserved::kMomentumY].data() + c, U[Conserved::kEnergy].data() + c},
            alpha.data() + c,
            R,
            row_primitives(c),
            i1 - i0};
  }

  // Ghost cells (gas_solver_ghosts.cpp).
  void make_boundaries(std::array<std::vector<PrimitiveState>, 4> inflow);
  void record_inflow_states();
  void resolve_fillers();
  PrimitiveGhosts primitive_ghosts();
  void fill_local_ghosts();
  void fill_collective_ghosts();
  bool has_collective_fillers() const { return collective[0] != nullptr; }
  void fill_ghosts();
  void fill_porosity_ghosts();

  // Per-thread scratch.
  double* thread_scratch_base() const {
    return scratch.data() +
           static_cast<std::size_t>(omp_get_thread_num()) * kScratchRows * scratch_len;
  }
  /// Scratch rows for the flux kernels (the first 8 of this thread's rows).
  FaceRowScratch thread_scratch() {
    const std::size_t len = scratch_len;
    double* b = thread_scratch_base();
    return {b,           b + len,     b + 2 * len, b + 3 * len,
            b + 4 * len, b + 5 * len, b + 6 * len, b + 7 * len};
  }
  /// Scratch rows for the stage update (the same memory: the phases are separated by barriers).
  StageScratch stage_scratch() {
    const std::size_t len = scratch_len;
    double* b = thread_scratch_base();
    return {{b, b + len, b + 2 * len, b + 3 * len},
            b + 4 * len,
            b + 5 * len,
            b + 6 * len,
            b + 7 * len,
            b + 8 * len,
            b + 9 * len};
  }
  /// Sized once for the current thread count (so normally no allocation in step()).
  void ensure_scratch() const {
    scratch_len = static_cast<std::size_t>(std::max(nx, ny) + 1);
    const auto threads = static_cast<std::size_t>(threaded ? omp_get_max_threads() : 1);
    if (scratch.size() < threads * kScratchRows * scratch_len) {
      scratch.resize(threads * kScratchRows * scratch_len);
    }
  }

  // Face fluxes (gas_solver_fluxes.cpp).
  static StencilRows stencil(const Field2D& q, std::size_t c_m1, std::size_t step);
  FaceRowInput face_row_input(std::size_t c_m1, std::size_t step, int faces) const;
  /// Transport properties at temperature t (the Gordon-Wilke model through its table).
  template <class Th>
  TransportProperties transport_at(const Th& th, double t) const {
    if (config.transport.model == TransportModel::GordonWilke) return air_table(t);
    return transport_properties(config.transport, t, th.cp(t));
  }
  void transport_range(int j, int& lo, int& hi) const;
  template <class Th>
  void compute_transport(const Th& th);
  void viscous_x_row(int j, int f0, int f1);
  void viscous_y_row(int jf, int i0, int i1);
  template <class Th>
  void x_flux_row(const Th& th, int j);
  void y_face_range(int jf, int& i0, int& i1) const;
  template <class Th>
  void y_flux_row(const Th& th, int jf);

  // The stage and the step (gas_solver_stage.cpp).
  int row_begin(int t, int threads) const;
  void assign_boundary_faces(int threads);
  template <class Th>
  void fluxes_and_update(const Th& th, double dt, double c_new);
  template <class Th>
  void update_row(const Th& th, int j, double dt, double c_new);
  void save_step_start(int j, int i0, int i1);
  template <class Th>
  void stage(const Th& th, double dt, double c_new);
  template <class Th>
  void rk3_step(const Th& th, double dt);

  // Resting cells (gas_solver_resting.cpp; on a slab gas_solver_rest_agreement.cpp).
  bool agrees_over_slabs() const { return static_cast<bool>(rest_agreement.min_each); }
  void scan_rest_rows();
  void agree_rest_rows();
  void compute_active_ranges();
  void find_source_rows();
  void widen_active_ranges();
  void set_row_range(std::size_t k, int lo, int hi);
  RestReference rest_reference_of(std::size_t c) const;

  // Checks (gas_solver_faults.cpp).
  CellFault classify(std::size_t c, double pp) const;
  void record_fault(int j, int i);
  void check_current_state();
  void throw_on_fault() const;
  std::string fault_message() const;

  // Porosity (gas_solver_porosity.cpp) and time step (gas_solver_time_step.cpp).
  template <class Th>
  void change_porosity(const Th& th, const Field2D& alpha_new, int j0, int j1);
  template <class Th>
  double stable_dt(const Th& th) const;
};

}  // namespace dustlift
