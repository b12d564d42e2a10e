// The gas solver: SLAU2 + MUSCL, porosity-weighted fluxes (physics-reference 2.1), central
// viscous terms, SSP-RK3 (Shu-Osher), ghost-cell boundaries. See docs/gas-solver.md.
#include "solver/gas/gas_solver.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <variant>
#include <vector>

#include "solver/core/errors.hpp"
#include "solver/gas/flux_rows.hpp"
#include "solver/gas/boundary_fillers.hpp"
#include "solver/gas/ghost_filler.hpp"
#include "solver/gas/muscl.hpp"
#include "solver/gas/rest_ranges.hpp"
#include "solver/gas/shock_relations.hpp"
#include "solver/gas/slau2.hpp"
#include "solver/gas/stage_update.hpp"
#include "solver/gas/thermo.hpp"
#include "solver/gas/time_step_rows.hpp"
#include "solver/gas/transport.hpp"
#include "solver/gas/viscous_rows.hpp"

namespace dustlift {
namespace {

/// Below this many interior cells the solver does not fork threads.
constexpr std::size_t kMinCellsForThreads = 8192;

using Thermo = std::variant<CaloricallyPerfectGas, ThermallyPerfectAir>;

Thermo make_thermo(const ThermoConfig& c) {
  if (c.model == ThermoModel::CaloricallyPerfect) return CaloricallyPerfectGas(c.gamma, c.gas_constant);
  return ThermallyPerfectAir(c.gas_constant);
}

/// Which check a cell failed (0: none).
enum class CellFault { None, NotFinite, Density, Pressure };

}  // namespace

struct GasSolver::Impl {
  Grid2D grid;
  GasConfig config;
  Thermo thermo;
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
  /// Per grid row including ghost rows (index j + ng): cells [-ng, rest_to] rest at the left
  /// reference state, cells [rest_from, nx + ng) at the right one.
  std::vector<int> rest_to, rest_from;
  RestReference left_reference, right_reference;
  std::vector<SourceExtent> source_rows;  ///< per interior row, found once per step
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
  /// Per GridSide: this grid's boundary condition, the filler set in its place
  /// (set_ghost_filler; null: none) and the one used. Local fillers run in the parallel
  /// regions; the collective ones (distinct, in side order, null after the last) after them.
  std::array<std::unique_ptr<GhostFiller>, 4> boundary;
  std::array<GhostFiller*, 4> replaced{}, filler{};
  std::array<bool, 4> local{};
  std::array<GhostFiller*, 2> collective{};
  FaultReporting fault_reporting;

  Impl(const Grid2D& g, const GasConfig& c)
      : grid(g), config(c), thermo(make_thermo(c.thermo)), muscl(muscl_settings(c.scheme)),
        viscous(c.transport.model != TransportModel::Inviscid), nx(g.nx()), ny(g.ny()), ng(g.ghosts()),
        stride(g.stride()), threaded(g.interior_cells() >= kMinCellsForThreads), R(c.thermo.gas_constant),
        skip_resting(c.skip_resting_cells && !c.has_gravity()) {
    if (ng < 2) throw std::invalid_argument("GasSolver: the grid needs at least 2 ghost layers");
    if (nx < 1 || ny < 1) throw std::invalid_argument("GasSolver: the grid has no cells");
    for (int k = 0; k < Conserved::kCount; ++k) {
      U[k] = Field2D(grid);
      U0[k] = Field2D(grid);
      source[k] = Field2D(grid);
      fx[k].assign(static_cast<std::size_t>(nx + 1) * ny, 0.0);
      fy[k].assign(static_cast<std::size_t>(nx) * (ny + 1), 0.0);
    }
    fx_pressure.assign(static_cast<std::size_t>(nx + 1) * ny, 0.0);
    fy_pressure.assign(static_cast<std::size_t>(nx) * (ny + 1), 0.0);
    y_face_owner.assign(static_cast<std::size_t>(ny + 1), -1);
    x_face_owner.assign(static_cast<std::size_t>(ny), -1);
    row_lo.assign(static_cast<std::size_t>(ny), 0);
    row_hi.assign(static_cast<std::size_t>(ny), nx);
    rest_to.assign(static_cast<std::size_t>(ny + 2 * ng), -ng - 1);
    rest_from.assign(static_cast<std::size_t>(ny + 2 * ng), nx + ng);
    source_rows.assign(static_cast<std::size_t>(ny), SourceExtent{});
    saved_lo.assign(static_cast<std::size_t>(ny), 0);
    widened_lo_.assign(static_cast<std::size_t>(ny), 0);
    widened_hi_.assign(static_cast<std::size_t>(ny), 0);
    saved_hi.assign(static_cast<std::size_t>(ny), 0);
    rho = Field2D(grid, 1.0);
    u = Field2D(grid);
    v = Field2D(grid);
    p = Field2D(grid, 1.0);
    T = Field2D(grid, 300.0);
    alpha = Field2D(grid, 1.0);
    mu = Field2D(grid);
    lambda = Field2D(grid);
    build_geometry(grid.x(), inv_dx, inv_dxc, inv_dx2);
    build_geometry(grid.y(), inv_dy, inv_dyc, inv_dy2);
    fault_i.assign(static_cast<std::size_t>(ny), -1);
    fault_kind.assign(static_cast<std::size_t>(ny), CellFault::None);
    make_boundaries({});
    ensure_scratch();
  }

  void build_geometry(const Axis& a, std::vector<double>& inv_w, std::vector<double>& inv_c,
                      std::vector<double>& inv_2) {
    const int n = a.cells(), g = a.ghosts();
    inv_w.assign(static_cast<std::size_t>(n + 2 * g), 0.0);
    inv_c = inv_w;
    inv_2 = inv_w;
    for (int i = -g; i < n + g; ++i) {
      const auto k = static_cast<std::size_t>(i + g);
      inv_w[k] = 1.0 / a.width(i);
      if (i + 1 < n + g) inv_c[k] = 1.0 / (a.center(i + 1) - a.center(i));
      if (i - 1 >= -g && i + 1 < n + g) inv_2[k] = 1.0 / (a.center(i + 1) - a.center(i - 1));
    }
  }

  std::size_t at(int i, int j) const { return grid.index(i, j); }
  double geo(const std::vector<double>& v, int i) const { return v[static_cast<std::size_t>(i + ng)]; }

  // ---------------------------------------------------------------- primitives
  /// The checks of one cell after its primitives were set.
  CellFault classify(std::size_t c, double pp) const {
    if (!(std::isfinite(U[Conserved::kMass].data()[c]) && std::isfinite(U[Conserved::kMomentumX].data()[c]) &&
          std::isfinite(U[Conserved::kMomentumY].data()[c]) && std::isfinite(U[Conserved::kEnergy].data()[c]))) {
      return CellFault::NotFinite;
    }
    if (!(rho.data()[c] > 0.0)) return CellFault::Density;
    if (!(pp > 0.0) || !std::isfinite(pp)) return CellFault::Pressure;
    return CellFault::None;
  }

  /// Sets cell (i, j) to state s: the primitives exactly as given (T as the scene gave it, or
  /// p/(rho R)), the conserved variables from them. A state at rest then has exactly the same
  /// p and T in every cell whatever the porosity, so it stays at rest to the last bit.
  template <class Th>
  void set_cell_state(const Th& th, int i, int j, const PrimitiveState& s) {
    const std::size_t c = at(i, j);
    const double a = alpha.data()[c];
    const double t = temperature_of(s, R);
    U[Conserved::kMass].data()[c] = a * s.rho;
    U[Conserved::kMomentumX].data()[c] = a * s.rho * s.u;
    U[Conserved::kMomentumY].data()[c] = a * s.rho * s.v;
    U[Conserved::kEnergy].data()[c] = a * s.rho * (th.internal_energy(t) + 0.5 * (s.u * s.u + s.v * s.v));
    rho.data()[c] = s.rho;
    u.data()[c] = s.u;
    v.data()[c] = s.v;
    p.data()[c] = s.p;
    T.data()[c] = t;
  }

  // ---------------------------------------------------------------- boundaries
  /// This grid's boundary conditions, an inflow imposing inflow[side] (see PhysicalBoundary).
  void make_boundaries(std::array<std::vector<PrimitiveState>, 4> inflow) {
    for (GridSide side : kGridSides) {
      const std::size_t k = side_index(side);
      boundary[k] = make_boundary_filler(side, boundary_kind(config.boundary, side), grid, R,
                                         std::move(inflow[k]));
    }
    resolve_fillers();
  }

  void resolve_fillers() {
    collective = {};
    std::size_t n = 0;
    for (GridSide side : kGridSides) {
      const std::size_t k = side_index(side);
      filler[k] = replaced[k] != nullptr ? replaced[k] : boundary[k].get();
      local[k] = !filler[k]->collective();
      if (!local[k] && (n == 0 || collective[n - 1] != filler[k])) collective[n++] = filler[k];
    }
  }

  PrimitiveGhosts primitive_ghosts() {
    return {{&rho, &u, &v, &p, &T},
            skip_resting ? row_lo.data() : nullptr,
            skip_resting ? row_hi.data() : nullptr};
  }

  /// The ghosts of the sides filled from this grid's own cells, by every thread of a
  /// parallel region (or outside one). The x-sides first: the y-sides' corners read them.
  void fill_local_ghosts() {
    const PrimitiveGhosts ghosts = primitive_ghosts();
    for (GridSide side : {GridSide::Left, GridSide::Right}) {
      if (local[side_index(side)]) filler[side_index(side)]->fill(ghosts);
    }
#pragma omp barrier
    for (GridSide side : {GridSide::Bottom, GridSide::Top}) {
      if (local[side_index(side)]) filler[side_index(side)]->fill(ghosts);
    }
#pragma omp barrier
  }

  /// The collective fillers' ghosts (outside a parallel region, after the local ones).
  void fill_collective_ghosts() {
    for (GhostFiller* c : collective) {
      if (c != nullptr) c->fill(primitive_ghosts());
    }
  }
  bool has_collective_fillers() const { return collective[0] != nullptr; }

  /// Every ghost of the primitive fields, outside a parallel region.
  void fill_ghosts() {
#pragma omp parallel if (threaded)
    fill_local_ghosts();
    fill_collective_ghosts();
  }

  void fill_porosity_ghosts() {
    for (GridSide side : kGridSides) {
      if (local[side_index(side)]) filler[side_index(side)]->fill_porosity(alpha);
    }
    for (GhostFiller* c : collective) {
      if (c != nullptr) c->fill_porosity(alpha);
    }
  }

  // ---------------------------------------------------------------- fluxes
  double* thread_scratch_base() const {
    return scratch.data() + static_cast<std::size_t>(omp_get_thread_num()) * kScratchRows * scratch_len;
  }
  /// Scratch rows for the flux kernels (the first 8 of this thread's rows).
  FaceRowScratch thread_scratch() {
    const std::size_t len = scratch_len;
    double* b = thread_scratch_base();
    return {b, b + len, b + 2 * len, b + 3 * len, b + 4 * len, b + 5 * len, b + 6 * len, b + 7 * len};
  }
  /// Scratch rows for the stage update (the same memory: the phases are separated by barriers).
  StageScratch stage_scratch() {
    const std::size_t len = scratch_len;
    double* b = thread_scratch_base();
    return {{b, b + len, b + 2 * len, b + 3 * len}, b + 4 * len, b + 5 * len, b + 6 * len, b + 7 * len,
            b + 8 * len, b + 9 * len};
  }

  /// Sized once for the current thread count (so normally no allocation in step()).
  void ensure_scratch() const {
    scratch_len = static_cast<std::size_t>(std::max(nx, ny) + 1);
    const auto threads = static_cast<std::size_t>(threaded ? omp_get_max_threads() : 1);
    if (scratch.size() < threads * kScratchRows * scratch_len) scratch.resize(threads * kScratchRows * scratch_len);
  }

  /// The four stencil rows of a row of faces whose first face has cell c_m1 before it.
  static StencilRows stencil(const Field2D& q, std::size_t c_m1, std::size_t step) {
    const double* b = q.data() + c_m1;
    return {b - step, b, b + step, b + 2 * step};
  }

  FaceRowInput face_row_input(std::size_t c_m1, std::size_t step, int faces) const {
    return {stencil(rho, c_m1, step), stencil(u, c_m1, step), stencil(v, c_m1, step), stencil(p, c_m1, step),
            alpha.data() + c_m1, alpha.data() + c_m1 + step, faces};
  }

  /// Transport properties at temperature t (the Gordon-Wilke model through its table).
  template <class Th>
  TransportProperties transport_at(const Th& th, double t) const {
    if (config.transport.model == TransportModel::GordonWilke) return air_table(t);
    return transport_properties(config.transport, t, th.cp(t));
  }

  /// Cells of grid row j (-1..ny) whose mu and lambda the viscous faces of the active rows
  /// j-1..j+1 read: [lo, hi).
  void transport_range(int j, int& lo, int& hi) const {
    lo = nx + 1;
    hi = -1;
    for (int r = std::max(j - 1, 0); r <= std::min(j + 1, ny - 1); ++r) {
      if (row_lo[static_cast<std::size_t>(r)] >= row_hi[static_cast<std::size_t>(r)]) continue;
      lo = std::min(lo, row_lo[static_cast<std::size_t>(r)] - 1);
      hi = std::max(hi, row_hi[static_cast<std::size_t>(r)] + 1);
    }
    lo = std::max(lo, -1);
    hi = std::min(hi, nx + 1);
  }

  template <class Th>
  void compute_transport(const Th& th) {
#pragma omp for schedule(static)
    for (int j = -1; j <= ny; ++j) {
      int lo = 0, hi = 0;
      transport_range(j, lo, hi);
      if (hi <= lo) continue;
      const std::size_t c = at(lo, j);
      if (config.transport.model == TransportModel::GordonWilke) {
        air_table.apply(T.data() + c, mu.data() + c, lambda.data() + c, hi - lo);
        continue;
      }
      for (int i = lo; i < hi; ++i) {
        const std::size_t ci = at(i, j);
        const TransportProperties tp = transport_at(th, T.data()[ci]);
        mu.data()[ci] = tp.mu;
        lambda.data()[ci] = tp.lambda;
      }
    }
  }

  /// Subtracts the porosity-weighted viscous and heat fluxes of x-faces [f0, f1) of row j
  /// (face f between cells f-1 and f).
  void viscous_x_row(int j, int f0, int f1) {
    const std::size_t row = static_cast<std::size_t>(j) * static_cast<std::size_t>(nx + 1) + static_cast<std::size_t>(f0);
    const std::size_t hi = at(f0, j), lo = hi - 1, up = static_cast<std::size_t>(stride);
    const ViscousFaceCells c{u.data() + lo, u.data() + hi, v.data() + lo, v.data() + hi, T.data() + lo, T.data() + hi,
                             mu.data() + lo, mu.data() + hi, lambda.data() + lo, lambda.data() + hi,
                             alpha.data() + lo, alpha.data() + hi,
                             u.data() + lo - up, u.data() + lo + up, u.data() + hi - up, u.data() + hi + up,
                             v.data() + lo - up, v.data() + lo + up, v.data() + hi - up, v.data() + hi + up};
    viscous_x_faces(c, inv_dxc.data() + static_cast<std::size_t>(f0 - 1 + ng), geo(inv_dy2, j), fx[Conserved::kMomentumX].data() + row,
                    fx[Conserved::kMomentumY].data() + row, fx[Conserved::kEnergy].data() + row, f1 - f0);
  }

  /// Same for the y-faces [i0, i1) of face row jf (face (i, jf) between cells (i, jf-1), (i, jf)).
  void viscous_y_row(int jf, int i0, int i1) {
    const std::size_t row = static_cast<std::size_t>(jf) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i0);
    const std::size_t hi = at(i0, jf), lo = hi - static_cast<std::size_t>(stride);
    const ViscousFaceCells c{u.data() + lo, u.data() + hi, v.data() + lo, v.data() + hi, T.data() + lo, T.data() + hi,
                             mu.data() + lo, mu.data() + hi, lambda.data() + lo, lambda.data() + hi,
                             alpha.data() + lo, alpha.data() + hi,
                             u.data() + lo - 1, u.data() + lo + 1, u.data() + hi - 1, u.data() + hi + 1,
                             v.data() + lo - 1, v.data() + lo + 1, v.data() + hi - 1, v.data() + hi + 1};
    viscous_y_faces(c, geo(inv_dyc, jf - 1), inv_dx2.data() + static_cast<std::size_t>(i0 + ng), fy[Conserved::kMomentumX].data() + row,
                    fy[Conserved::kMomentumY].data() + row, fy[Conserved::kEnergy].data() + row, i1 - i0);
  }

  /// x-faces [row_lo, row_hi] of row j: those of its active cells (face f lies between
  /// cells f-1 and f). Reads the primitives of row j (and of rows j-1, j+1 when viscous).
  template <class Th>
  void x_flux_row(const Th& th, int j) {
    const std::size_t nf = static_cast<std::size_t>(nx + 1);
    const int f0 = row_lo[static_cast<std::size_t>(j)], f1 = row_hi[static_cast<std::size_t>(j)] + 1;
    if (f1 - f0 < 2) return;
    const std::size_t row = static_cast<std::size_t>(j) * nf + static_cast<std::size_t>(f0);
    inviscid_flux_row(th, muscl, face_row_input(at(f0 - 1, j), 1, f1 - f0), thread_scratch(),
                      {fx[Conserved::kMass].data() + row, fx[Conserved::kMomentumX].data() + row, fx[Conserved::kMomentumY].data() + row,
                       fx[Conserved::kEnergy].data() + row, fx_pressure.data() + row},
                      1.0, 0.0);
    if (viscous) viscous_x_row(j, f0, f1);
  }

  /// y-faces of face row jf under the active cells of the rows on either side.
  void y_face_range(int jf, int& i0, int& i1) const {
    i0 = nx;
    i1 = 0;
    for (int r = jf - 1; r <= jf; ++r) {
      if (r < 0 || r >= ny) continue;
      const auto k = static_cast<std::size_t>(r);
      if (row_lo[k] >= row_hi[k]) continue;
      i0 = std::min(i0, row_lo[k]);
      i1 = std::max(i1, row_hi[k]);
    }
  }

  /// y-faces of face row jf (between cell rows jf-1 and jf). Reads the primitives of rows
  /// jf-2 .. jf+1.
  template <class Th>
  void y_flux_row(const Th& th, int jf) {
    const auto step = static_cast<std::size_t>(stride);
    int i0 = 0, i1 = 0;
    y_face_range(jf, i0, i1);
    if (i1 <= i0) return;
    const std::size_t row = static_cast<std::size_t>(jf) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i0);
    inviscid_flux_row(th, muscl, face_row_input(at(i0, jf - 1), step, i1 - i0), thread_scratch(),
                      {fy[Conserved::kMass].data() + row, fy[Conserved::kMomentumX].data() + row, fy[Conserved::kMomentumY].data() + row,
                       fy[Conserved::kEnergy].data() + row, fy_pressure.data() + row},
                      0.0, 1.0);
    if (viscous) viscous_y_row(jf, i0, i1);
  }

  /// First interior row of thread t of `threads` in the fused flux-and-update loop.
  int row_begin(int t, int threads) const {
    return static_cast<int>(static_cast<long long>(ny) * t / threads);
  }

  /// The face rows that read cell rows of two threads' ranges must be computed before any
  /// of those rows changes: y-face rows j0-1 .. j0+1 (inviscid stencil rows jf-2 .. jf+1) and
  /// x-face rows j0-1, j0 (viscous tangential derivatives, rows j-1 .. j+1) at each range
  /// start j0. Each is given to the lowest thread whose boundary needs it; -1: computed by
  /// the thread owning its rows, in its row loop.
  void assign_boundary_faces(int threads) {
    std::fill(y_face_owner.begin(), y_face_owner.end(), -1);
    std::fill(x_face_owner.begin(), x_face_owner.end(), -1);
    for (int t = threads - 1; t >= 1; --t) {
      const int j0 = row_begin(t, threads);
      if (j0 <= 0 || j0 >= ny) continue;
      for (int k = std::max(j0 - 1, 0); k <= std::min(j0 + 1, ny); ++k) y_face_owner[static_cast<std::size_t>(k)] = t;
      for (int k = std::max(j0 - 1, 0); k <= std::min(j0, ny - 1); ++k) x_face_owner[static_cast<std::size_t>(k)] = t;
    }
    face_owners_for_threads = threads;
  }

  /// Fluxes and stage update fused row by row, so that a row's face fluxes are still in
  /// cache when the row is updated: row r is updated as soon as every face that reads its
  /// stage-input primitives is computed (y-face rows up to r+2, x-face rows up to r+1). Each
  /// face is computed once, from the same inputs as in separate passes, so the result is
  /// bitwise the same. Runs inside the stage's parallel region.
  template <class Th>
  void fluxes_and_update(const Th& th, double dt, double c_new) {
    const int threads = omp_get_num_threads(), tid = omp_get_thread_num();
#pragma omp single
    if (face_owners_for_threads != threads) assign_boundary_faces(threads);
    for (int k = 0; k <= ny; ++k)
      if (y_face_owner[static_cast<std::size_t>(k)] == tid) y_flux_row(th, k);
    for (int k = 0; k < ny; ++k)
      if (x_face_owner[static_cast<std::size_t>(k)] == tid) x_flux_row(th, k);
#pragma omp barrier
    const int j0 = row_begin(tid, threads), j1 = row_begin(tid + 1, threads);
    if (j0 >= j1) return;
    auto y_unowned = [&](int k) { return k <= ny && y_face_owner[static_cast<std::size_t>(k)] < 0; };
    auto x_unowned = [&](int k) { return k < ny && x_face_owner[static_cast<std::size_t>(k)] < 0; };
    for (int k = j0; k <= j0 + 1; ++k)
      if (y_unowned(k)) y_flux_row(th, k);
    if (x_unowned(j0)) x_flux_row(th, j0);
    for (int r = j0; r < j1; ++r) {
      if (y_unowned(r + 2)) y_flux_row(th, r + 2);
      if (x_unowned(r + 1)) x_flux_row(th, r + 1);
      update_row(th, r, dt, c_new);
    }
  }

  /// U = c_old U0 + c_new (U + dt L(U)) with c_old = 1 - c_new, written as
  /// U0 + c_new (U - U0 + dt L) (stage_update.hpp), on the active cells of row j; then the
  /// primitives of the cells whose state changed, and the checks.
  template <class Th>
  void update_row(const Th& th, int j, double dt, double c_new) {
    const std::size_t nfx = static_cast<std::size_t>(nx + 1);
    const std::size_t nfy = static_cast<std::size_t>(nx);
    const auto sx = static_cast<std::size_t>(stride);
    const int i0 = row_lo[static_cast<std::size_t>(j)], i1 = row_hi[static_cast<std::size_t>(j)];
    fault_i[static_cast<std::size_t>(j)] = -1;
    fault_kind[static_cast<std::size_t>(j)] = CellFault::None;
    if (i1 <= i0) return;
    const std::size_t c = at(i0, j);
    const std::size_t kx = static_cast<std::size_t>(j) * nfx + static_cast<std::size_t>(i0);
    const std::size_t ky = static_cast<std::size_t>(j) * nfy + static_cast<std::size_t>(i0);
    StageRow r{};
    for (int k = 0; k < Conserved::kCount; ++k) {
      r.U0[k] = U0[k].data() + c;
      r.U[k] = U[k].data() + c;
      r.source[k] = source[k].data() + c;
      r.fx[k] = fx[k].data() + kx;
      r.fy_below[k] = fy[k].data() + ky;
      r.fy_above[k] = fy[k].data() + ky + nfy;
    }
    r.fx_pressure = fx_pressure.data() + kx;
    r.fy_pressure_below = fy_pressure.data() + ky;
    r.fy_pressure_above = fy_pressure.data() + ky + nfy;
    r.alpha = alpha.data() + c;
    r.alpha_below = alpha.data() + c - sx;
    r.alpha_above = alpha.data() + c + sx;
    r.inv_dx = inv_dx.data() + static_cast<std::size_t>(i0 + ng);
    r.inv_dy = geo(inv_dy, j);
    r.gas_constant = R;
    r.gravity_x = config.gravity_x;
    r.gravity_y = config.gravity_y;
    r.rho = rho.data() + c;
    r.u = u.data() + c;
    r.v = v.data() + c;
    r.p = p.data() + c;
    r.T = T.data() + c;
    r.n = i1 - i0;
    save_step_start(j, i0, i1);
    const int bad = stage_update_row(th, r, stage_scratch(), dt, c_new);
    if (bad >= 0) record_fault(j, i0 + bad);
  }

  /// Saves U0 = U for the cells of [i0, i1) not saved yet this step. A cell outside the hull
  /// was not updated this step, so its U is still the step-start state.
  void save_step_start(int j, int i0, int i1) {
    const auto k = static_cast<std::size_t>(j);
    int lo = saved_lo[k], hi = saved_hi[k];
    auto copy = [&](int a, int b) {
      if (b <= a) return;
      const std::size_t c = at(a, j), n = static_cast<std::size_t>(b - a);
      for (int q = 0; q < Conserved::kCount; ++q) std::copy_n(U[q].data() + c, n, U0[q].data() + c);
    };
    if (lo >= hi) {
      copy(i0, i1);
      lo = i0;
      hi = i1;
    } else {
      copy(std::min(lo, i0), lo);
      copy(hi, std::max(hi, i1));
      lo = std::min(lo, i0);
      hi = std::max(hi, i1);
    }
    saved_lo[k] = lo;
    saved_hi[k] = hi;
  }

  /// Which check cell (i, j) failed, for the message.
  void record_fault(int j, int i) {
    const std::size_t c = at(i, j);
    fault_i[static_cast<std::size_t>(j)] = i;
    fault_kind[static_cast<std::size_t>(j)] = classify(c, p.data()[c]);
  }

  /// Per row (ghost rows included) the cells at each end that rest at that end's reference
  /// state; then per interior row the cells a stage must update (rest_ranges.hpp). Runs inside
  /// the stage's parallel region after the ghosts were filled.
  void compute_active_ranges() {
    if (!skip_resting) return;
#pragma omp single
    {
      left_reference = rest_reference_of(at(0, ny - 1));
      right_reference = rest_reference_of(at(nx - 1, ny - 1));
    }
    const int cells = nx + 2 * ng;
#pragma omp for schedule(static)
    for (int jr = -ng; jr < ny + ng; ++jr) {
      const std::size_t c = at(-ng, jr);
      const RowView row{u.data() + c, v.data() + c, p.data() + c, T.data() + c, cells};
      const auto k = static_cast<std::size_t>(jr + ng);
      rest_to[k] = resting_prefix(row, left_reference) - 1 - ng;
      rest_from[k] = cells - resting_suffix(row, right_reference) - ng;
    }
#pragma omp for schedule(static)
    for (int j = 0; j < ny; ++j) {
      const auto k = static_cast<std::size_t>(j);
      const ActiveRange r = active_range(rest_to.data() + j, rest_from.data() + j, 2 * ng + 1, source_rows[k], nx);
      row_lo[k] = r.lo;
      row_hi[k] = r.hi;
    }
  }

  /// Where each row has sources this step (they are held constant over the step).
  void find_source_rows() {
    if (!skip_resting) return;
#pragma omp parallel for if (threaded) schedule(static)
    for (int j = 0; j < ny; ++j) {
      const std::size_t c = at(0, j);
      const double* const rows[Conserved::kCount] = {source[Conserved::kMass].data() + c, source[Conserved::kMomentumX].data() + c,
                                                     source[Conserved::kMomentumY].data() + c, source[Conserved::kEnergy].data() + c};
      source_rows[static_cast<std::size_t>(j)] = source_extent(rows, nx);
    }
  }

  /// Ranges of the next stage from this step's first: a stage changes only cells in its
  /// ranges, so a cell further than the stencil reach (2 cells, 2 rows) from all of them
  /// still has the resting stencil it had (exact; cheaper than scanning again).
  void widen_active_ranges() {
    if (!skip_resting) return;
#pragma omp single
    {
      widened_lo_ = row_lo;
      widened_hi_ = row_hi;
      for (int j = 0; j < ny; ++j) {
        int lo = nx, hi = 0;
        for (int r = std::max(j - ng, 0); r <= std::min(j + ng, ny - 1); ++r) {
          const auto k = static_cast<std::size_t>(r);
          if (widened_lo_[k] >= widened_hi_[k]) continue;
          lo = std::min(lo, widened_lo_[k] - ng);
          hi = std::max(hi, widened_hi_[k] + ng);
        }
        // The edge cells read ghosts copied from another process's cells: where its previous
        // stage updated those (within the stencil's rows), they are updated too.
        if (has_collective_fillers()) {
          const int r0 = std::max(j - ng, 0), r1 = std::min(j + ng, ny - 1) + 1;
          const auto changed = [&](GridSide side) {
            const std::size_t k = side_index(side);
            return !local[k] && filler[k]->changed_beyond(side, r0, r1);
          };
          const bool left = changed(GridSide::Left), right = changed(GridSide::Right);
          if (left) {
            lo = std::min(lo, 0);
            hi = std::max(hi, std::min(ng, nx));
          }
          if (right) {
            lo = std::min(lo, std::max(nx - ng, 0));
            hi = std::max(hi, nx);
          }
        }
        lo = std::max(lo, 0);
        hi = std::min(hi, nx);
        row_lo[static_cast<std::size_t>(j)] = lo < hi ? lo : 0;
        row_hi[static_cast<std::size_t>(j)] = lo < hi ? hi : 0;
      }
    }
  }

  RestReference rest_reference_of(std::size_t c) const {
    return dustlift::rest_reference(u.data()[c], v.data()[c], p.data()[c], T.data()[c], rho.data()[c], config.rest_tolerance);
  }

  template <class Th>
  void stage(const Th& th, double dt, double c_new) {
    // Collective fillers need the ghosts filled outside the stage's parallel region.
    const bool collective_fill = has_collective_fillers();
    if (collective_fill) fill_ghosts();
#pragma omp parallel if (threaded)
    {
      if (!collective_fill) fill_local_ghosts();
      if (c_new == 1.0) {
        compute_active_ranges();
      } else {
        widen_active_ranges();
      }
      if (viscous) compute_transport(th);
      fluxes_and_update(th, dt, c_new);
    }
    for (int j = 0; j < ny; ++j) cell_updates += row_hi[static_cast<std::size_t>(j)] - row_lo[static_cast<std::size_t>(j)];
    throw_on_fault();
  }

  void throw_on_fault() const {
    std::string message = fault_message();
    if (fault_reporting.agree) message = fault_reporting.agree(message);
    if (!message.empty()) throw NumericalFailure(message);
  }

  /// The first faulty row's cell, described ("" when no row has one).
  std::string fault_message() const {
    for (int j = 0; j < ny; ++j) {
      const int i = fault_i[static_cast<std::size_t>(j)];
      if (i < 0) continue;
      const std::size_t c = at(i, j);
      std::ostringstream m;
      m.precision(6);
      m << "gas cell (i, j) = (" << i + fault_reporting.first_column << ", " << j << ") at x = " << grid.x().center(i)
        << " m, y = " << grid.y().center(j) << " m: ";
      switch (fault_kind[static_cast<std::size_t>(j)]) {
        case CellFault::NotFinite:
          m << "conserved variables not finite (a rho = " << U[Conserved::kMass].data()[c]
            << ", a rho u = " << U[Conserved::kMomentumX].data()[c] << ", a rho v = " << U[Conserved::kMomentumY].data()[c]
            << ", a E = " << U[Conserved::kEnergy].data()[c] << ")";
          break;
        case CellFault::Density:
          m << "density rho = " << rho.data()[c] << " kg/m^3 (a rho = " << U[Conserved::kMass].data()[c]
            << ") is not positive";
          break;
        default:
          m << "pressure p = " << p.data()[c] << " Pa is not positive (T = " << T.data()[c] << " K)";
          break;
      }
      return m.str();
    }
    return {};
  }

  template <class Th>
  void refresh(const Th& th) {
    fill_porosity_ghosts();
#pragma omp parallel if (threaded)
    {
#pragma omp for schedule(static)
      for (int j = 0; j < ny; ++j) {
        const StageScratch sc = stage_scratch();
        for (int i = 0; i < nx; ++i) sc.changed[i] = 1.0;
        (void)primitives_row(th, primitive_row(j, 0, nx), sc);
      }
      fill_local_ghosts();
    }
    fill_collective_ghosts();
  }

  PrimitiveRow primitive_row(int j, int i0, int i1) {
    const std::size_t c = at(i0, j);
    return {{U[Conserved::kMass].data() + c, U[Conserved::kMomentumX].data() + c,
             U[Conserved::kMomentumY].data() + c, U[Conserved::kEnergy].data() + c},
            alpha.data() + c,
            R,
            rho.data() + c,
            u.data() + c,
            v.data() + c,
            p.data() + c,
            T.data() + c,
            i1 - i0};
  }

  /// See GasSolver::change_porosity.
  template <class Th>
  void change_porosity(const Th& th, const Field2D& alpha_new, int j0, int j1) {
    j0 = std::max(j0, 0);
    j1 = std::min(j1, ny);
#pragma omp parallel if (threaded)
    {
      // Rows one at a time: the rows whose porosity changed (the layer's) are a few at the
      // bottom, and a static split gave them all to one thread. Rows are independent.
#pragma omp for schedule(dynamic, 1)
      for (int j = j0; j < j1; ++j) {
        const StageScratch sc = stage_scratch();
        fault_i[static_cast<std::size_t>(j)] = -1;
        int first = nx, last = -1;
        for (int i = 0; i < nx; ++i) {
          const std::size_t c = at(i, j);
          const double a_new = alpha_new.data()[c], a_old = alpha.data()[c];
          sc.changed[i] = 0.0;
          if (a_new == a_old) continue;
          // alpha rho and alpha rho u are kept; the internal energy follows the isentropic
          // compression by the volume the particles took or gave back: to first order exactly
          // the -p d(alpha_g) work of eq. (3), and unlike the linear form it cannot drive the
          // internal energy negative when alpha_g changes by a large fraction in one step.
          const double m = U[Conserved::kMass].data()[c], mx = U[Conserved::kMomentumX].data()[c], my = U[Conserved::kMomentumY].data()[c];
          const double kinetic = 0.5 * (mx * mx + my * my) / m;
          const double g = th.gamma(T.data()[c]);
          U[Conserved::kEnergy].data()[c] = kinetic + (U[Conserved::kEnergy].data()[c] - kinetic) * std::pow(a_old / a_new, g - 1.0);
          alpha.data()[c] = a_new;
          sc.changed[i] = 1.0;
          first = std::min(first, i);
          last = i;
        }
        if (last < first) continue;
        StageScratch shifted = sc;
        shifted.changed = sc.changed + first;
        const int bad = primitives_row(th, primitive_row(j, first, last + 1), shifted);
        if (bad >= 0) record_fault(j, first + bad);
      }
    }
    fill_porosity_ghosts();
    fill_ghosts();
    throw_on_fault();
  }

  /// Checks the current primitives (as left by the last step or refresh_primitives(), e.g.
  /// after the coupling changed the state) so a bad input is reported where it is, not
  /// where its NaN spread to during the first stage.
  void check_current_state() {
#pragma omp parallel for if (threaded) schedule(static)
    for (int j = 0; j < ny; ++j) {
      int first_fault = -1;
      CellFault kind = CellFault::None;
      for (int i = 0; i < nx && first_fault < 0; ++i) {
        const std::size_t c = at(i, j);
        bool finite = true;
        for (int k = 0; k < Conserved::kCount; ++k) finite = finite && std::isfinite(U[k].data()[c]);
        if (!finite) {
          kind = CellFault::NotFinite;
        } else if (!(rho.data()[c] > 0.0) || !(U[Conserved::kMass].data()[c] > 0.0)) {
          kind = CellFault::Density;
        } else if (!(p.data()[c] > 0.0)) {
          kind = CellFault::Pressure;
        }
        if (kind != CellFault::None) first_fault = i;
      }
      fault_i[static_cast<std::size_t>(j)] = first_fault;
      fault_kind[static_cast<std::size_t>(j)] = kind;
    }
    throw_on_fault();
  }

  template <class Th>
  void rk3_step(const Th& th, double dt) {
    if (externally_modified) {
      check_current_state();
      externally_modified = false;
    }
    ensure_scratch();
    fill_porosity_ghosts();
    find_source_rows();
    std::fill(saved_lo.begin(), saved_lo.end(), 0);
    std::fill(saved_hi.begin(), saved_hi.end(), 0);
    stage(th, dt, 1.0);
    stage(th, dt, 0.25);
    stage(th, dt, 2.0 / 3.0);
    fill_ghosts();
  }

  template <class Th>
  double stable_dt(const Th& th) const {
    ensure_scratch();
    double max_rate = 0.0;
    double min_viscous_dt = std::numeric_limits<double>::infinity();
    const bool table = viscous && config.transport.model == TransportModel::GordonWilke;
#pragma omp parallel for if (threaded) schedule(static) reduction(max : max_rate) reduction(min : min_viscous_dt)
    for (int j = 0; j < ny; ++j) {
      const double idy = geo(inv_dy, j);
      const std::size_t c0 = at(0, j);
      double* const sc = thread_scratch_base();
      const TimeStepRow row{u.data() + c0, v.data() + c0, T.data() + c0, rho.data() + c0,
                            inv_dx.data() + static_cast<std::size_t>(ng), idy, nx, sc, sc + scratch_len};
      time_step_row(th, table ? &air_table : nullptr, row, max_rate, min_viscous_dt);
      if (!viscous || table) continue;
      for (int i = 0; i < nx; ++i) {
        const std::size_t c = at(i, j);
        const double t = T.data()[c];
        const double idx = geo(inv_dx, i);
        const double cp = th.cp(t);
        const TransportProperties tp = transport_at(th, t);
        const double diffusivity_factor = std::max(1.0, th.gamma(t) * tp.lambda / (tp.mu * cp));
        const double h2 = std::min(1.0 / (idx * idx), 1.0 / (idy * idy));
        min_viscous_dt = std::min(min_viscous_dt, 0.25 * h2 * rho.data()[c] / (tp.mu * diffusivity_factor));
      }
    }
    return std::min(config.scheme.cfl / max_rate, min_viscous_dt);
  }

  template <class Th>
  void initialize(const Th& th, const InitialCondition& ic) {
    fill_porosity_ghosts();
    PrimitiveState below = ic.left, above = ic.right;
    if (ic.kind == InitialCondition::Kind::Shock) {
      below = normal_shock(ic.state, ic.mach, config.thermo, ic.axis).post;
      above = ic.state;
    }
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        PrimitiveState s = ic.state;
        if (ic.kind != InitialCondition::Kind::Uniform) {
          const double coord = ic.axis == 'y' ? grid.y().center(j) : grid.x().center(i);
          s = coord < ic.position ? below : above;
        }
        set_cell_state(th, i, j, s);
      }
    }
    record_inflow_states();  // also fills the ghosts
  }

  PrimitiveState state_at(int i, int j) const {
    return {rho(i, j), u(i, j), v(i, j), p(i, j), T(i, j)};
  }

  /// The boundary conditions with their inflow states: as given, else the initial state next
  /// to the boundary (e.g. the post-shock state).
  void record_inflow_states() {
    const BoundaryConfig& b = config.boundary;
    auto record = [&](int n, auto cell) {
      std::vector<PrimitiveState> out(static_cast<std::size_t>(n));
      for (int k = 0; k < n; ++k) out[static_cast<std::size_t>(k)] = b.inflow_given ? b.inflow : cell(k);
      return out;
    };
    make_boundaries({record(ny, [&](int j) { return state_at(0, j); }),
                     record(ny, [&](int j) { return state_at(nx - 1, j); }),
                     record(nx, [&](int i) { return state_at(i, 0); }),
                     record(nx, [&](int i) { return state_at(i, ny - 1); })});
    fill_ghosts();
  }
};

GasSolver::GasSolver(const Grid2D& grid, const GasConfig& config)
    : impl_(std::make_unique<Impl>(grid, config)) {
  // Until initialize(): a uniform state at rest so that every accessor is valid.
  initialize(InitialCondition{});
}
GasSolver::~GasSolver() = default;
GasSolver::GasSolver(GasSolver&&) noexcept = default;
GasSolver& GasSolver::operator=(GasSolver&&) noexcept = default;

void GasSolver::initialize(const InitialCondition& ic) {
  std::visit([&](const auto& th) { impl_->initialize(th, ic); }, impl_->thermo);
}

double GasSolver::stable_dt() const {
  return std::visit([&](const auto& th) { return impl_->stable_dt(th); }, impl_->thermo);
}

void GasSolver::step(double dt) {
  std::visit([&](const auto& th) { impl_->rk3_step(th, dt); }, impl_->thermo);
}

void GasSolver::set_ghost_filler(GridSide side, GhostFiller* filler) {
  if (filler != nullptr && filler->collective() && !is_x_side(side)) {
    throw std::invalid_argument("GasSolver::set_ghost_filler: a collective filler serves an x-side");
  }
  Impl& m = *impl_;
  m.replaced[side_index(side)] = filler;
  m.resolve_fillers();
  m.externally_modified = true;
}

void GasSolver::set_fault_reporting(FaultReporting reporting) {
  impl_->fault_reporting = std::move(reporting);
  impl_->externally_modified = true;
}

const Grid2D& GasSolver::grid() const { return impl_->grid; }
const GasConfig& GasSolver::config() const { return impl_->config; }

GasPrimitives GasSolver::primitives() const {
  return {&impl_->rho, &impl_->u, &impl_->v, &impl_->p, &impl_->T, &impl_->alpha};
}

GasTotals GasSolver::totals() const {
  GasTotals t;
  const Impl& m = *impl_;
  for (int j = 0; j < m.ny; ++j) {
    GasTotals row;
    for (int i = 0; i < m.nx; ++i) {
      const double area = m.grid.area(i, j);
      row.mass += m.U[Conserved::kMass](i, j) * area;
      row.momentum_x += m.U[Conserved::kMomentumX](i, j) * area;
      row.momentum_y += m.U[Conserved::kMomentumY](i, j) * area;
      row.energy += m.U[Conserved::kEnergy](i, j) * area;
    }
    t.mass += row.mass;
    t.momentum_x += row.momentum_x;
    t.momentum_y += row.momentum_y;
    t.energy += row.energy;
  }
  return t;
}

double GasSolver::sound_speed(int i, int j) const {
  const double t = impl_->T(i, j);
  return std::visit([&](const auto& th) { return std::sqrt(th.sound_speed_squared(t)); }, impl_->thermo);
}

Field2D& GasSolver::conserved(int k) {
  impl_->externally_modified = true;
  return impl_->U[static_cast<std::size_t>(k)];
}
const Field2D& GasSolver::conserved(int k) const { return impl_->U[static_cast<std::size_t>(k)]; }

void GasSolver::refresh_primitives() {
  std::visit([&](const auto& th) { impl_->refresh(th); }, impl_->thermo);
}

Field2D& GasSolver::porosity() {
  impl_->externally_modified = true;
  return impl_->alpha;
}

long long GasSolver::cell_updates() const { return impl_->cell_updates; }

void GasSolver::add_column_work(std::vector<double>& per_column) const {
  const Impl& m = *impl_;
  if (per_column.size() != static_cast<std::size_t>(m.nx)) throw std::invalid_argument("add_column_work: one entry per column");
  // A difference array over each row's range [lo, hi), then its running sum.
  std::vector<double> step(static_cast<std::size_t>(m.nx) + 1, 0.0);
  for (int j = 0; j < m.ny; ++j) {
    const auto k = static_cast<std::size_t>(j);
    if (m.row_lo[k] >= m.row_hi[k]) continue;
    step[static_cast<std::size_t>(m.row_lo[k])] += 1.0;
    step[static_cast<std::size_t>(m.row_hi[k])] -= 1.0;
  }
  double running = 0.0;
  for (int i = 0; i < m.nx; ++i) {
    running += step[static_cast<std::size_t>(i)];
    per_column[static_cast<std::size_t>(i)] += running;
  }
}

RestReference GasSolver::rest_reference() const {
  const Impl& m = *impl_;
  RestReference ref = m.rest_reference_of(m.at(m.nx - 1, m.ny - 1));
  // Under gravity no gas rests: the body force changes every cell's momentum.
  ref.valid = ref.valid && !m.config.has_gravity();
  return ref;
}

void GasSolver::resting_gas(RestingGas& out, const RestReference& ref) const {
  const Impl& m = *impl_;
  out.reference = ref;
  out.first_resting.resize(static_cast<std::size_t>(m.ny));
  const int cells = m.nx + 2 * m.ng;
#pragma omp parallel for if (m.threaded) schedule(static)
  for (int j = 0; j < m.ny; ++j) {
    const std::size_t c = m.at(-m.ng, j);
    const RowView row{m.u.data() + c, m.v.data() + c, m.p.data() + c, m.T.data() + c, cells};
    out.first_resting[static_cast<std::size_t>(j)] = cells - resting_suffix(row, ref) - m.ng;
  }
}

void GasSolver::initialize_porosity(const Field2D& alpha_g) {
  Impl& m = *impl_;
  for (int j = 0; j < m.ny; ++j) {
    for (int i = 0; i < m.nx; ++i) {
      const double a = alpha_g(i, j);
      const double scale = a / m.alpha(i, j);
      for (int k = 0; k < Conserved::kCount; ++k) m.U[static_cast<std::size_t>(k)](i, j) *= scale;
      m.alpha(i, j) = a;
    }
  }
  m.fill_porosity_ghosts();
}

void GasSolver::change_porosity(const Field2D& alpha_g, int j0, int j1) {
  std::visit([&](const auto& th) { impl_->change_porosity(th, alpha_g, j0, j1); }, impl_->thermo);
}

Field2D& GasSolver::source(int k) { return impl_->source[static_cast<std::size_t>(k)]; }

Field2D& GasSolver::primitive_field(int k) {
  Impl& m = *impl_;
  m.externally_modified = true;
  Field2D* fields[Primitive::kCount] = {&m.rho, &m.u, &m.v, &m.p, &m.T};
  if (k < 0 || k >= Primitive::kCount) throw std::out_of_range("GasSolver::primitive_field: k must be 0..4");
  return *fields[k];
}

}  // namespace dustlift
