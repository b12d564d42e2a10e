#pragma once
// Compressible Navier-Stokes solver with porosity (paper eqs. 1-4, 17):
// conservative variables (a rho, a rho u, a rho v, a E) with a = alpha_g, SLAU2 fluxes
// fed by MUSCL reconstruction of primitives, 2nd-order central viscous terms, SSP-RK3.
//
// Contract used by sim/, coupling/ and insitu/ (keep it stable):
//  - construct from a grid (ghosts >= 2) and a GasConfig; initialize() from an InitialCondition;
//  - stable_dt() gives eq. (17) with the scheme's CFL (and a viscous limit when viscous);
//  - step(dt) advances one SSP-RK3 step and refreshes the primitive fields;
//  - primitives() exposes read-only rho, u, v, p, T, alpha_g on the interior+ghost layout.
#include <array>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"
#include "solver/gas/gas_components.hpp"
#include "solver/gas/gas_config.hpp"
#include "solver/gas/ghost_filler.hpp"
#include "solver/gas/rest_ranges.hpp"

namespace dustlift {

/// Read-only primitive gas fields (interior cells valid; ghosts as last filled).
struct GasPrimitives {
  const Field2D* rho = nullptr;
  const Field2D* u = nullptr;
  const Field2D* v = nullptr;
  const Field2D* p = nullptr;
  const Field2D* T = nullptr;
  const Field2D* alpha_g = nullptr;  ///< porosity, 1 where no particles
};

/// How a solver holding one part of a larger grid reports a cell that failed its checks (the
/// default: its grid is the whole, on its own).
struct FaultReporting {
  int first_column = 0;  ///< index in the whole grid of column 0 (messages name cells by it)
  /// Collective over the parts, at the end of every check: given this part's message ("" when
  /// its cells passed), the message every part throws ("" when none failed). Empty: no parts.
  std::function<std::string(const std::string&)> agree;
};

/// Where the grid is one x-slab of a larger grid (a decomposed run): what makes its skipping
/// within run.rest_tolerance decide, in every stage, to update the cells a solver on the whole
/// grid would (the whole grid's resting references, per row its resting ends and sources):
/// skipping within a tolerance changes the bits of what it skips, so the slabs must skip what
/// one grid skips. Exact skipping ignores it (any resting stencil changes no bit). The
/// default: the grid is the whole, no collective.
struct RestAgreement {
  int first_column = 0;   ///< of this grid in the whole one
  int whole_columns = 0;  ///< of the whole grid
  /// Collective over the slabs: each slab's `values` become the element-by-element minimum
  /// (every slab passes as many, in the same order).
  std::function<void(std::span<double>)> min_each;
};

/// Integrals over the interior: mass (kg/m), x/y momentum, total energy (J/m).
struct GasTotals {
  double mass = 0, momentum_x = 0, momentum_y = 0, energy = 0;
};

/// Interior rows [0, rows) and columns [0, columns) outside which a gas's sources are zero.
struct SourceBounds {
  int rows = 0, columns = 0;
};

class GasSolver {
 public:
  GasSolver(const Grid2D& grid, const GasConfig& config);
  ~GasSolver();
  GasSolver(GasSolver&&) noexcept;
  GasSolver& operator=(GasSolver&&) noexcept;

  /// The ghosts beyond `side` come from `filler` instead of the side's boundary condition
  /// (null: the boundary condition again), e.g. the neighbouring part's cells where this grid
  /// is one part of a larger one (solver/parallel/slab_halo.hpp; stable_dt() then stays local:
  /// the caller reduces it over the parts). `filler` must outlive its use; set it before
  /// initialize().
  void set_ghost_filler(GridSide side, GhostFiller* filler);
  /// How failed checks are reported (FaultReporting); set it before initialize().
  void set_fault_reporting(FaultReporting reporting);
  /// How the skipping of resting cells agrees with the other slabs (RestAgreement); set it
  /// before initialize().
  void set_rest_agreement(RestAgreement agreement);

  void initialize(const InitialCondition& ic);
  double stable_dt() const;
  void step(double dt);

  const Grid2D& grid() const;
  const GasConfig& config() const;
  GasPrimitives primitives() const;
  GasTotals totals() const;

  /// The gas resting at the right-hand reference state (the cell (nx-1, ny-1) when it is at
  /// rest): for each interior row j, first_resting[j] is the first cell index from which every
  /// cell of the row up to the last ghost rests at it (nx + ghosts when none does). The
  /// coupling skips parcels in such gas exactly (docs/coupling.md).
  struct RestingGas {
    RestReference reference;  ///< the state and its tolerances (run.rest_tolerance)
    std::vector<int> first_resting;
  };
  void resting_gas(RestingGas& out) const { resting_gas(out, rest_reference()); }
  /// The reference alone, without the scan: the cell (nx-1, ny-1)'s (invalid under gravity).
  RestReference rest_reference() const;
  /// The scan at `reference` instead of this grid's last cell: a slab of a decomposed run
  /// rests at the whole grid's reference.
  void resting_gas(RestingGas& out, const RestReference& reference) const;

  /// Adds to per_column[i] (one entry per interior column) the cells of column i the last
  /// stage updated: the work a decomposed run balances (everything without skipping).
  void add_column_work(std::vector<double>& per_column) const;

  /// Cell-stage updates done since construction (3 per cell and step without skipping;
  /// fewer where resting cells were skipped). For benchmarks and tests.
  long long cell_updates() const;

  /// Sound speed at cell (i, j) of the current state (for Mach number output).
  double sound_speed(int i, int j) const;

  /// Conservative state access (k a Conserved component: a rho, a rho u, a rho v, a E) for
  /// checkpoints and tests. After writing, call refresh_primitives().
  Field2D& conserved(int k);
  const Field2D& conserved(int k) const;
  void refresh_primitives();

  /// Porosity alpha_g per cell (1 by default). Read-only use by the coupling: it changes
  /// the porosity through initialize_porosity() or change_porosity().
  Field2D& porosity();

  /// Gives the initial state its porosity: every interior cell takes alpha_g(i, j), its
  /// conserved variables rescaled so that the primitive state stays exactly what it was.
  void initialize_porosity(const Field2D& alpha_g);

  /// The particles moved (eqs. 1-3 with a time-dependent alpha_g): cells of interior rows
  /// [j0, j1) whose porosity differs from alpha_g(i, j) take it with their alpha rho and
  /// alpha rho u kept and the internal energy changed by the isentropic compression (the
  /// -p d(alpha_g)/dt work of eq. 3); only those cells' primitives are recomputed.
  void change_porosity(const Field2D& alpha_g, int j0, int j1);

  /// External volumetric sources added to d(conserved(k))/dt (per m^3, e.g. -f_p, -s_p - q_p
  /// of eqs. 2-3); zero by default, held constant over one step(). k as in conserved().
  Field2D& source(int k);
  const Field2D& source(int k) const;
  /// The writer of the sources vouches that after its writes they are zero outside interior
  /// rows [0, rows) and columns [0, columns): a step then looks for them only there (a search
  /// of the whole grid every step read four fields mostly of zeros). Holds until source() is
  /// next called.
  void sources_zero_beyond(int rows, int columns);
  /// Rows and columns the step searches for sources (the whole grid unless vouched otherwise).
  SourceBounds source_bounds() const;

  /// Checkpoint restore only: primitive field k (a Primitive component: rho, u, v, p, T),
  /// ghosts included.
  /// The thermally perfect inversion e -> T starts its Newton iteration from the stored T,
  /// so recomputing the primitives from conserved(k) would change their last bits; a bitwise
  /// continuation writes them back as saved (with conserved, porosity and source) and does
  /// not call refresh_primitives().
  Field2D& primitive_field(int k);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dustlift
