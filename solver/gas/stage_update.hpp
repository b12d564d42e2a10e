#pragma once
// One SSP-RK3 stage update of a row segment of cells (GasSolver::step), in passes over
// contiguous arrays so that the compiler vectorises them:
//   L(U) = -div F + S with the porosity pressure term in well-balanced form
//          -(a_{i+1/2} (p~_{i+1/2} - p_i) - a_{i-1/2} (p~_{i-1/2} - p_i)) / dx
//   (= -(a p~)_{i+1/2} + (a p~)_{i-1/2} + p_i (a_{i+1/2} - a_{i-1/2}), i.e. a grad p written as
//   div(a p) - p grad a, docs/gas-solver.md), and
//   U <- U0 + c (U - U0 + dt L(U))   (Shu-Osher stage with c_old = 1 - c),
// which leaves a cell whose L is exactly zero bitwise unchanged: a gas at rest with uniform
// p and T over any porosity stays exactly at rest, and a cell whose conserved state did not
// change keeps its primitives (the T(e) Newton solve is not a fixed point to the last bit).
#include <cstddef>

#include "solver/gas/gas_components.hpp"

namespace dustlift {

class CaloricallyPerfectGas;
class ThermallyPerfectAir;

/// The primitives of a row segment: read (p for the pressure term, T as the Newton guess) and
/// overwritten with those of the new state where it changed.
struct RowPrimitives {
  double* rho;
  double* u;
  double* v;
  double* p;
  double* T;
};

/// Pointers into the solver's arrays at the first cell of the segment (cell index i0):
/// every per-cell pointer may be indexed [0, n), the x-face arrays [0, n] (face k lies on the
/// left of cell k), the y-face arrays [0, n) for the faces below and above the row. Arrays of
/// pointers are indexed by Conserved component.
struct StageRow {
  const double* U0[Conserved::kCount];  ///< conserved state at the start of the step
  double* U[Conserved::kCount];         ///< conserved state of this stage (read, then overwritten)
  const double* source[Conserved::kCount];    ///< external sources (coupling), per m^3
  const double* fx[Conserved::kCount];        ///< porosity-weighted convective x-face fluxes
  const double* fx_pressure;                  ///< x-face pressure p~ (unweighted)
  const double* fy_below[Conserved::kCount];  ///< y-faces below the row
  const double* fy_above[Conserved::kCount];  ///< y-faces above the row
  const double* fy_pressure_below;
  const double* fy_pressure_above;
  const double* alpha;        ///< porosity of the row; alpha[-1] and alpha[n] are read too
  const double* alpha_below;  ///< porosity of the row below
  const double* alpha_above;  ///< porosity of the row above
  const double* inv_dx;       ///< 1 / cell width per cell
  double inv_dy;              ///< 1 / cell height of the row
  double gas_constant;
  double gravity_x = 0.0;  ///< m/s^2, body force on the gas (GasConfig::gravity_x)
  double gravity_y = 0.0;
  RowPrimitives prim;
  int n;
};

/// Per-thread scratch of at least n doubles per array.
struct StageScratch {
  double* rhs[Conserved::kCount];
  double* rho;
  double* u;
  double* v;
  double* e;
  double* T;
  double* changed;  ///< 1.0 where the conserved state changed, else 0.0
};

/// Applies the stage to the row segment. Returns the index (0-based within the segment) of
/// the first cell whose new state is not finite or has rho <= 0 or p <= 0, or -1.
template <class Thermo>
int stage_update_row(const Thermo& thermo, const StageRow& row, const StageScratch& scratch,
                     double dt, double c_new);

extern template int stage_update_row<CaloricallyPerfectGas>(const CaloricallyPerfectGas&,
                                                            const StageRow&, const StageScratch&,
                                                            double, double);
extern template int stage_update_row<ThermallyPerfectAir>(const ThermallyPerfectAir&,
                                                          const StageRow&, const StageScratch&,
                                                          double, double);

/// Primitives of a row segment from its conserved state (a rho, a rho u, a rho v, a E) and
/// porosity a, T(e) warm-started at the current T; cells flagged unchanged[i] != 0 keep theirs.
/// Returns the first faulty cell (as stage_update_row) or -1.
struct PrimitiveRow {
  const double* U[Conserved::kCount];
  const double* alpha;
  double gas_constant;
  RowPrimitives prim;
  int n;
};
template <class Thermo>
int primitives_row(const Thermo& thermo, const PrimitiveRow& row, const StageScratch& scratch);

extern template int primitives_row<CaloricallyPerfectGas>(const CaloricallyPerfectGas&,
                                                          const PrimitiveRow&, const StageScratch&);
extern template int primitives_row<ThermallyPerfectAir>(const ThermallyPerfectAir&,
                                                        const PrimitiveRow&, const StageScratch&);

}  // namespace dustlift
