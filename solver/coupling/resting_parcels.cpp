#include "solver/coupling/resting_parcels.hpp"

#include <algorithm>
#include <limits>

#include "solver/coupling/coupling_slab.hpp"
#include "solver/coupling/gas_halo.hpp"

namespace dustlift {

void RestingParcels::agree_over_slabs(const GasSolver& gas, const Grid2D& grid,
                                      const CouplingSlab& slab) {
  // The whole grid's reference: the last cell of the last slab (-inf elsewhere, so that a max
  // over the ranks gives the last rank's values).
  constexpr double kNone = -std::numeric_limits<double>::infinity();
  const bool last = slab.halo->owns_right_boundary();
  double reference[kRestReferenceValues];
  pack_rest_reference(gas.rest_reference(), last, kNone, reference);
  slab.max_each(reference);
  gas.resting_gas(resting_, unpack_rest_reference(reference));
  // Per row, the first whole-grid column from which the row rests to the domain's end: the
  // largest of the ranks' own (a slab's scan runs to its ghost columns, the neighbour's first
  // cells; one whose interior rests from its first column on defers to the ranks before it,
  // and the first rank counts its boundary ghosts as one rank does).
  const int ny = grid.ny();
  rest_rows_.resize(static_cast<std::size_t>(ny));
  const bool first = slab.halo->owns_left_boundary();
  for (int j = 0; j < ny; ++j) {
    const int local = resting_.first_resting[static_cast<std::size_t>(j)];
    rest_rows_[static_cast<std::size_t>(j)] =
        !first && local <= 0 ? kNone : static_cast<double>(slab.first_column + local);
  }
  slab.max_each(rest_rows_);
  for (int j = 0; j < ny; ++j) {
    resting_.first_resting[static_cast<std::size_t>(j)] =
        static_cast<int>(rest_rows_[static_cast<std::size_t>(j)]);
  }
}

SteppedParcels RestingParcels::plan(const GasSolver& gas, ParcelSystem& ps, double dt,
                                    const Grid2D& grid, const CouplingSlab* slab,
                                    const Columns& columns, double influence_width, bool skip) {
  const std::size_t n = ps.size();
  double* rest_steps = ps.column(columns.rest_steps).data();
  double* active = ps.column(columns.active).data();
  std::size_t limit = n;
  // On a slab every rank takes part (its collectives), parcels or not.
  if (skip && (n > 0 || slab != nullptr)) {
    if (slab == nullptr) {
      gas.resting_gas(resting_);
    } else {
      agree_over_slabs(gas, grid, *slab);
    }
    // The counts hold for one reference state: a new one starts them again.
    const RestReference& ref = resting_.reference;
    if (!ref.valid || ref.p != rest_p_ || ref.T != rest_T_) {
      std::fill(rest_steps, rest_steps + n, 0.0);
      rest_p_ = ref.p;
      rest_T_ = ref.T;
    }
    const Axis& ax = slab != nullptr ? slab->whole->x() : grid.x();
    const double all_rows = update_row_thresholds(grid, ax);
    RestFront f = count_rest_steps(ps, dt, grid, rest_steps, all_rows);
    if (slab != nullptr) {
      // A push from a moving parcel of any rank may reach this rank's parcels: the front and
      // the speeds of all ranks.
      double maxima[3] = {f.front, f.v_max, f.d_max};
      slab->max_each(maxima);
      f = {maxima[0], maxima[1], maxima[2]};
    }
    limit = f.front == -std::numeric_limits<double>::infinity()
                ? 0  // everything rests
                : last_within_reach(ps, dt, ax, rest_steps, f, influence_width);
  }
  return mark_active(ps, grid, active, limit);
}

double RestingParcels::update_row_thresholds(const Grid2D& grid, const Axis& ax) {
  // The gas over a parcel's interpolation quad and derivative stencils (two cells each way)
  // rests when every row j-2..j+2 (j its row) rests from column i-2 on (i its column), that
  // is, when x >= face(first_resting + 2) of each of those rows: one threshold per row
  // window, and one for all rows (returned), so that most resting parcels need no locate at
  // all. On a slab first_resting is in the whole grid's columns (agree_over_slabs).
  const int* first_resting = resting_.first_resting.data();
  const int ny = grid.ny();
  const int nx = ax.cells();
  auto row_threshold = [&](int r) {
    const int column = first_resting[r] + 2;  // locate(x) >= column <=> x >= face(column)
    if (column <= 0) return -std::numeric_limits<double>::infinity();
    if (column >= nx) return std::numeric_limits<double>::infinity();
    return ax.face(column);
  };
  rest_x_threshold_.resize(static_cast<std::size_t>(ny));
  double all_rows = -std::numeric_limits<double>::infinity();
  for (int j = 0; j < ny; ++j) {
    double t = -std::numeric_limits<double>::infinity();
    for (int r = std::max(j - 2, 0); r <= std::min(j + 2, ny - 1); ++r)
      t = std::max(t, row_threshold(r));
    rest_x_threshold_[static_cast<std::size_t>(j)] = t;
    all_rows = std::max(all_rows, t);
  }
  return all_rows;
}

RestingParcels::RestFront RestingParcels::count_rest_steps(const ParcelSystem& ps, double dt,
                                                           const Grid2D& grid, double* rest_steps,
                                                           double all_rows) const {
  const std::size_t n = ps.size();
  const RestReference& ref = resting_.reference;
  const double* threshold = rest_x_threshold_.data();
  const bool valid = ref.valid;
  const double T_ref = ref.T, dT = ref.dT, du = ref.du;
  double front = -std::numeric_limits<double>::infinity(), v_max = 0.0, d_max = 0.0;
#pragma omp parallel for schedule(static) \
    reduction(max                         \
              : front, v_max, d_max) if (n >= kParallelMinimum)
  for (std::size_t k = 0; k < n; ++k) {
    bool rests = valid && std::abs(ps.temperature[k] - T_ref) <= dT;
    if (rests) {
      const ParcelMotion motion{ps.vx[k],
                                ps.vy[k],
                                ps.omega[k],
                                ps.radius[k],
                                ps.contact_fx[k],
                                ps.contact_fy[k],
                                ps.contact_torque[k],
                                ps.mass[k] / ps.n_real[k],
                                ps.inertia[k] / ps.n_real[k]};
      rests = parcel_still(motion, du, dt);
    }
    if (rests && !(ps.x[k] >= all_rows)) rests = ps.x[k] >= threshold[grid.y().locate(ps.y[k])];
    rest_steps[k] = rests ? rest_steps[k] + 1.0 : 0.0;
    // Two steps: the last step was then a full step at rest, so its stored force parts and
    // samples are exactly what this step would give.
    if (rest_steps[k] < 2.0) front = std::max(front, ps.x[k]);
    v_max = std::max(v_max, std::sqrt(ps.vx[k] * ps.vx[k] + ps.vy[k] * ps.vy[k]));
    d_max = std::max(d_max, ps.diameter[k]);
  }
  return {front, v_max, d_max};
}

std::size_t RestingParcels::last_within_reach(const ParcelSystem& ps, double dt, const Axis& ax,
                                              const double* rest_steps, const RestFront& f,
                                              double influence_width) {
  // Within one CFD step a push travels one contact per sub-step, parcels move v dt, and a
  // parcel's samples read the alpha_p and gas of cells within two cells of it.
  const std::size_t n = ps.size();
  const int nx = ax.cells();
  const int i_front = ax.locate(f.front);
  double cell = 0.0;
  for (int i = std::max(i_front - 4, 0); i <= std::min(i_front + 12, nx - 1); ++i) {
    cell = std::max(cell, ax.width(i));
  }
  const double reach =
      (ps.substeps_for(dt) + 2) * f.d_max + 2.0 * f.v_max * dt + 4.0 * cell + influence_width;
  const double cut = f.front + reach;
  std::size_t last = 0;
#pragma omp parallel for schedule(static) reduction(max : last) if (n >= kParallelMinimum)
  for (std::size_t k = 0; k < n; ++k) {
    if (rest_steps[k] < 2.0 || ps.x[k] <= cut) last = std::max(last, k + 1);
  }
  return last;
}

SteppedParcels RestingParcels::mark_active(const ParcelSystem& ps, const Grid2D& grid,
                                           double* active, std::size_t limit) {
  // Where the stepped parcels are: the passes of this step need only the cells they reach.
  const std::size_t n = ps.size();
  double x_max = -std::numeric_limits<double>::infinity(), y_min = grid.y().end(),
         y_max = grid.y().start();
  const double* px = ps.x.data();
  const double* py = ps.y.data();
#pragma omp parallel for schedule(static) reduction(max             \
                                                    : x_max, y_max) \
    reduction(min                                                   \
              : y_min) if (n >= kParallelMinimum)
  for (std::size_t k = 0; k < n; ++k) {
    active[k] = k < limit ? 1.0 : 0.0;
    if (k < limit) {
      x_max = std::max(x_max, px[k]);
      y_min = std::min(y_min, py[k]);
      y_max = std::max(y_max, py[k]);
    }
  }
  return SteppedParcels{limit, x_max, y_min, y_max};
}

}  // namespace dustlift
