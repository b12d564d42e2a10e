#pragma once
// `dustlift info`'s expected wall time: the scene's work (gas cell-stages, parcel sub-steps,
// parcel samples) forecast over the whole run, times rates measured on this machine by a few
// steps of the scene itself with nothing skipped (a short calibration, cached per scene,
// threads, code version and CPU for a day).
#include <optional>
#include <string>
#include <vector>

#include "solver/scene/scene.hpp"

namespace dustlift {

class Simulation;

/// Wall seconds per unit of work, measured.
struct WorkRates {
  double gas_per_cell_stage = 0.0;      ///< s per gas cell-stage update
  double dem_per_parcel_substep = 0.0;  ///< s per parcel-sub-step (contacts, integration, rebuilds)
  double coupling_per_parcel_step = 0.0;  ///< s per parcel per CFD step (sample, exchange, deposit)
};

/// The whole run's work as forecast from the scene at t = 0.
struct WorkForecast {
  double steps = 0.0;            ///< CFD steps
  double cell_stages = 0.0;      ///< gas cell-stage updates
  double parcel_substeps = 0.0;  ///< parcel-sub-steps stepped
  double parcel_steps = 0.0;     ///< parcels sampled, summed over the steps
  double gas_share = 1.0;        ///< of the cell-stages of the full grid
  double parcel_share = 1.0;     ///< of the parcel-steps of all parcels
};

/// The share of the run (averaged over its steps) during which a region behind an active
/// front that starts at `x0` and moves by `advance_per_step` per step covers the positions `x`
/// (sorted or not; each counts once per step it is behind the front). Pure: tested.
double mean_share_behind(const std::vector<double>& x, double x0, double steps,
                         double advance_per_step);

/// The forecast of `sim`'s scene from its state at t = 0: steps from `estimated_steps`, shares
/// of the gas and the parcels that skipping at rest leaves active (with exact skipping, the
/// rounding noise ahead of the shock runs at about four cells per step; with run.rest_tolerance
/// the active region is taken to follow the shock, which undercounts where contacts or the
/// porous layer carry a disturbance ahead of it: a lower bound).
WorkForecast forecast_work(const Simulation& sim, double steps);

/// Rates measured by stepping a copy of the scene with nothing skipped on this machine's
/// current threads, or read from the cache. `fresh`: measure even when cached.
WorkRates measured_rates(const Scene& scene, bool fresh, std::string& how);

/// Expected wall seconds of the run.
inline double expected_wall(const WorkForecast& w, const WorkRates& r) {
  return w.cell_stages * r.gas_per_cell_stage + w.parcel_substeps * r.dem_per_parcel_substep +
         w.parcel_steps * r.coupling_per_parcel_step;
}

}  // namespace dustlift
