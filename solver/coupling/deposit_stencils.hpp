#pragma once
// One deposit stencil per parcel (eq. 12; parcel order) at the positions after the last DEM
// step, made once and reused by every deposit of a CFD step (alpha_p, the exchange terms) and
// by the next step's implicit exchange, with the parallel scatter planned over them.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "solver/core/grid.hpp"
#include "solver/core/parallel_minimum.hpp"
#include "solver/coupling/grid_transfer.hpp"
#include "solver/coupling/parallel_deposit.hpp"

namespace dustlift {

class ParcelSystem;
struct CouplingSlab;

class DepositStencils {
 public:
  /// `width`: the side of a parcel's deposit square (CouplingConfig::influence_width).
  explicit DepositStencils(double width) : width_(width) {}

  /// Whether every stencil must be made anew: none yet, or a re-sort permuted the parcels.
  bool need_all(const ParcelSystem& parcels) const;
  /// Stencils at the current positions of parcels [0, count), unless there was no DEM step
  /// since they were made; all of them when need_all(). The caller's count must cover every
  /// parcel stepped since: the others did not move. On a slab they are made on the whole grid
  /// and given in the slab's columns.
  void update(const Grid2D& grid, const CouplingSlab* slab, const ParcelSystem& parcels,
              std::size_t count);
  /// Plans the scatter over parcels [0, count) of the current stencils (or keeps a plan of as
  /// many).
  void plan(const Grid2D& grid, std::size_t count);
  /// The parcels were replaced (or the grid changed): make every stencil anew.
  void invalidate() { dem_steps_ = -1; }
  /// The plan no longer fits the grid.
  void drop_plan() { planned_ = 0; }

  /// The last grid column a stencil of a parcel at x <= this x can reach (+1 margin).
  int column_bound(const Grid2D& grid, double x) const;
  /// 1 + the last parcel index whose stencil may reach a column <= `column` (all parcels
  /// from the first up to it: a superset of the parcels reaching those columns).
  std::size_t parcels_reaching(const Grid2D& grid, const ParcelSystem& parcels, int column) const;

  const DepositStencil& operator[](std::size_t k) const { return stencils_[k]; }
  /// add(k, m) for entry m of every planned parcel k's stencil: each cell's entries in parcel
  /// order whatever the thread count (ParallelDeposit).
  template <class Add>
  void run(Add&& add) const {
    scatter_.run(stencils_, add);
  }

 private:
  double width_;
  std::vector<DepositStencil> stencils_;
  ParallelDeposit scatter_;
  long long dem_steps_ = -1;     ///< ParcelSystem::steps() when they were made
  long long permutations_ = -1;  ///< ParcelSystem::data_permutations() then
  std::size_t planned_ = 0;      ///< scatter_ is planned over [0, planned_) (0: no plan)
};

/// Resets columns [0, columns) of rows [0, rows) of the interior of a per-cell array
/// (indexed as the grid's fields) to T{}.
template <class T>
void clear_rows(const Grid2D& g, T* cells, int rows, int columns) {
  const int nx = std::min(columns, g.nx()), n_rows = std::min(rows, g.ny());
  if (nx <= 0) return;
#pragma omp parallel for schedule(static) if (static_cast<std::size_t>(n_rows) * nx >= kParallelMinimum)
  for (int j = 0; j < n_rows; ++j) std::fill_n(cells + g.index(0, j), nx, T{});
}

}  // namespace dustlift
