// The deposits of a CFD step (eqs. 12-15): alpha_p at the parcels' new positions, the exchange
// terms as the gas's sources, the porosity update, and the exchange totals.
#include <algorithm>
#include <limits>

#include "solver/coupling/gas_particle_coupling.hpp"

namespace dustlift {

void GasParticleCoupling::deposit_alpha(const ParcelSystem& parcels) {
  int j0 = 0, j1 = 0;
  row_range(parcels, j0, j1);
  const int clear_to = std::max(rows_touched_, j1);
  rows_touched_ = j1;
  cleared_to_ = clear_to;
  // Only columns [0, C] can change: those the parcels stepped this step reached before and
  // after it, and those the last deposit changed (their sources go back to zero). Beyond C
  // every cell's parcels rested and kept their order, so its sums are the ones it holds. A
  // re-sort, or no stencils yet, makes everything anew.
  const std::size_t stepped = stepped_.count;
  int reach = grid_.nx() - 1;
  if (!stencils_.need_all(parcels) && stepped < parcels.size()) {
    double x_after = -std::numeric_limits<double>::infinity();
    const double* x = parcels.x.data();
#pragma omp parallel for schedule(static) reduction(max : x_after) if (stepped >= kParallelMinimum)
    for (std::size_t k = 0; k < stepped; ++k) x_after = std::max(x_after, x[k]);
    reach = stepped == 0 ? 0 : stencils_.column_bound(grid_, std::max(stepped_.x_max, x_after));
  }
  const int c = std::min(std::max(reach, last_reach_), grid_.nx() - 1);
  last_reach_ = reach;
  deposit_columns_ = c;
  const std::size_t reaching = stencils_.parcels_reaching(grid_, parcels, c);
  clear_rows(grid_, alpha_p_.data(), clear_to, c + 1);
  stencils_.update(grid_, slab(), parcels, reaching);
  stencils_.plan(grid_, reaching);
  // Each cell sums its parcels in parcel order whatever the thread count (ParallelDeposit).
  const double* n_real = parcels.n_real.data();
  // Each parcel's own solid volume: its class's V_p (computed once, as particle_volume_ is, so
  // a one-class layer deposits the same bits).
  const double* size_class = parcels.size_class.data();
  const double* class_volume = class_volume_.empty() ? nullptr : class_volume_.data();
  const double one_volume = particle_volume_;
  stencils_.run([&](std::size_t k, int m) {
    const DepositStencil& d = stencils_[k];
    const int i = d.i[static_cast<std::size_t>(m)], j = d.j[static_cast<std::size_t>(m)];
    if (i > c) return;
    const double v_p = class_volume == nullptr
                           ? one_volume
                           : class_volume[static_cast<std::size_t>(size_class[k])];
    const double volume = n_real[k] * v_p;  // eq. (12), per metre of depth
    alpha_p_(i, j) += d.fraction[static_cast<std::size_t>(m)] * volume / grid_.area(i, j);
  });
  Field2D* const deposited[] = {&alpha_p_};
  fill_ghosts(grid_, slab(), deposited, 0, clear_to);
}

void GasParticleCoupling::deposit_exchange(GasSolver& gas, const ParcelSystem& ps, double dt) {
  deposit_alpha(ps);  // also makes the stencils at the new positions
  last_dt_ = dt;
  if (!cfg_.two_way) return;
  const double* jx = ps.column(col_.impulse_x).data();
  const double* jy = ps.column(col_.impulse_y).data();
  const double* work = ps.column(col_.work).data();
  const double* heat = ps.column(col_.heat).data();
  // Columns beyond deposit_columns_ had no source last step and have none now (only stepped
  // parcels exchange anything).
  const int columns = deposit_columns_ + 1;
  clear_rows(grid_, exchange_.data(), rows_touched_, columns);
  const double* n_real = ps.n_real.data();
  stencils_.run([&](std::size_t k, int m) {
    const double energy = work[k] + heat[k];
    // A parcel that exchanged nothing adds nothing (skipping it keeps -0 out of the sums).
    if (jx[k] == 0.0 && jy[k] == 0.0 && energy == 0.0) return;
    const DepositStencil& d = stencils_[k];
    const int i = d.i[static_cast<std::size_t>(m)], j = d.j[static_cast<std::size_t>(m)];
    if (i >= columns) return;
    const double w = d.fraction[static_cast<std::size_t>(m)] * n_real[k] / (grid_.area(i, j) * dt);
    ExchangeCell& e = exchange_[grid_.index(i, j)];
    e.x += w * jx[k];
    e.y += w * jy[k];
    e.energy += w * energy;
  });
  const int rows = rows_touched_;
  const int nx = columns;
  Field2D& sx = gas.source(1);
  Field2D& sy = gas.source(2);
  Field2D& se = gas.source(3);
  // Rows [rows, cleared) held parcels before and none now: their sources go back to zero;
  // rows above them never held any. Every cell on its own: any split over threads.
#pragma omp parallel for schedule(static) if (static_cast <std::size_t>(cleared_to_) * nx >= \
                                              kParallelMinimum)
  for (int j = 0; j < cleared_to_; ++j) {
    for (int i = 0; i < nx; ++i) {
      alpha_g_(i, j) = 1.0 - std::min(alpha_p_(i, j), cfg_.max_volume_fraction);
      if (j >= rows) {
        sx(i, j) = sy(i, j) = se(i, j) = 0.0;
        continue;
      }
      const ExchangeCell& e = exchange_[grid_.index(i, j)];
      sx(i, j) = -e.x;
      sy(i, j) = -e.y;
      se(i, j) = -e.energy;
    }
  }
  // Rows from `rows` on and columns from `nx` on hold no source now (see above): the gas step
  // need not look there.
  gas.sources_zero_beyond(rows, nx);
  gas.change_porosity(alpha_g_, 0, cleared_to_);
}

ExchangeTotals GasParticleCoupling::last_exchange(const ParcelSystem& ps) const {
  ExchangeTotals e;
  e.substeps = last_substeps_;
  const double* jx = ps.column(col_.impulse_x).data();
  const double* jy = ps.column(col_.impulse_y).data();
  const double* work = ps.column(col_.work).data();
  const double* heat = ps.column(col_.heat).data();
  for (std::size_t k = 0; k < ps.size(); ++k) {
    const double nr = ps.n_real[k];
    e.parcel_impulse_x += nr * jx[k];
    e.parcel_impulse_y += nr * jy[k];
    e.parcel_work += nr * work[k];
    e.parcel_heat += nr * heat[k];
  }
  if (!cfg_.two_way) return e;
  for (int j = 0; j < rows_touched_; ++j) {
    for (int i = 0; i < grid_.nx(); ++i) {
      const double area_dt = grid_.area(i, j) * last_dt_;
      const ExchangeCell& cell = exchange_[grid_.index(i, j)];
      e.gas_impulse_x += cell.x * area_dt;
      e.gas_impulse_y += cell.y * area_dt;
      e.gas_energy += cell.energy * area_dt;
    }
  }
  return e;
}

}  // namespace dustlift
