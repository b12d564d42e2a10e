#pragma once
// Exact skipping of resting parcels: a parcel that began this step and the last one at rest
// (v = w = 0, no contact force, T = T_gas) in gas resting at one state (its whole interpolation
// and derivative stencil) would not change a bit, nor would anything it feeds, as long as
// nothing that moves can reach it within the step. The parcels after the last one that may
// move (or lies within reach of one) are left out of sampling and sub-steps. With
// run.rest_tolerance "at rest" is within the tolerance (parcel_still).
#include <cmath>
#include <cstddef>
#include <vector>

#include "solver/core/grid.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/gas/gas_solver.hpp"

namespace dustlift {

struct CouplingSlab;

/// A parcel's motion and the contact loads on it (per real particle).
struct ParcelMotion {
  double vx, vy, omega, radius;
  double fx, fy, torque;  ///< contact force and torque
  double mass_real, inertia_real;
};

/// Whether a parcel counts as still: its speed, the surface speed of its spin, and the speed
/// its contact force and torque would add within dt, each at most du (m/s). du = 0: all of
/// them exactly zero (the comparisons are written so that no product can underflow to zero).
inline bool parcel_still(const ParcelMotion& m, double du, double dt) {
  return std::abs(m.vx) <= du && std::abs(m.vy) <= du && std::abs(m.omega) <= du / m.radius &&
         std::abs(m.fx) <= du * m.mass_real / dt && std::abs(m.fy) <= du * m.mass_real / dt &&
         std::abs(m.torque) <= du * m.inertia_real / (m.radius * dt);
}

/// The parcels a CFD step steps, [0, count), and where they are.
struct SteppedParcels {
  std::size_t count = 0;
  double x_max = 0.0, y_min = 0.0, y_max = 0.0;
};

class RestingParcels {
 public:
  /// The parcel columns it keeps: the consecutive steps each parcel began exactly at rest in
  /// resting gas, and 1 for the parcels stepped this step (ParcelSystem::set_stepped_column).
  struct Columns {
    ParcelColumn rest_steps, active;
  };

  /// Plans this step (and marks the active column). With `skip` off every parcel is stepped.
  /// On a slab every rank takes part (collective), parcels or not.
  SteppedParcels plan(const GasSolver& gas, ParcelSystem& parcels, double dt, const Grid2D& grid,
                      const CouplingSlab* slab, const Columns& columns, double influence_width,
                      bool skip);

  /// The resting reference the parcels' rest counts refer to (checkpointed with them).
  double reference_pressure() const { return rest_p_; }
  double reference_temperature() const { return rest_T_; }
  void restore_reference(double p, double T) {
    rest_p_ = p;
    rest_T_ = T;
  }

 private:
  /// On a slab: resting_ for the whole grid, agreed over the ranks (collective): the whole
  /// grid's reference state, and first_resting per row in the whole grid's columns, as one
  /// rank finds them.
  void agree_over_slabs(const GasSolver& gas, const Grid2D& grid, const CouplingSlab& slab);
  /// plan's steps. The x beyond which the gas over a parcel rests, per row (rest_x_threshold_);
  /// returns the largest over the rows.
  double update_row_thresholds(const Grid2D& grid, const Axis& ax);
  /// The front (the largest x of a parcel not at rest two steps running), the largest speed
  /// and the largest diameter.
  struct RestFront {
    double front, v_max, d_max;
  };
  /// Counts each parcel's steps at rest on (rest_steps); returns the front.
  RestFront count_rest_steps(const ParcelSystem& ps, double dt, const Grid2D& grid,
                             double* rest_steps, double all_rows) const;
  /// The parcels up to the last one a push from the front may reach within the step.
  static std::size_t last_within_reach(const ParcelSystem& ps, double dt, const Axis& ax,
                                       const double* rest_steps, const RestFront& f,
                                       double influence_width);
  /// Marks parcels [0, limit) active; where they are.
  static SteppedParcels mark_active(const ParcelSystem& ps, const Grid2D& grid, double* active,
                                    std::size_t limit);

  GasSolver::RestingGas resting_;
  double rest_p_ = 0.0, rest_T_ = 0.0;    ///< the reference the rest_steps counts refer to
  std::vector<double> rest_rows_;         ///< agree_over_slabs' per-row exchange
  std::vector<double> rest_x_threshold_;  ///< per row: the gas over parcels at x >= it rests
};

}  // namespace dustlift
