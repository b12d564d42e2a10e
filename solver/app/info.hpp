#pragma once
// `dustlift info SCENE`: what a run of the scene will do before it is started.
#include "solver/scene/scene.hpp"
#include "solver/sim/simulation.hpp"

namespace dustlift {

/// Steps to the end time, from the initial state: the time step (eq. 17) if the fastest
/// signal present anywhere at t = 0 (|u| + c of the post-shock gas, say) reached the
/// smallest cells, which it does as a shock runs in from a coarse inflow region. The t = 0
/// step itself can be far too long: there the fast gas may sit only in stretched cells.
double estimated_steps(const Simulation& sim);

/// How `info` estimates the run's cost.
enum class CostEstimate {
  Off,     ///< --no-estimate
  Cached,  ///< rates from the cache when measured within a day, else measured now
  Fresh,   ///< --calibrate: measured now
};

/// Prints the resolved scene, effects on, grid, parcels, memory, step and cost estimates.
void print_info(const Scene& scene, const Simulation& sim, CostEstimate cost);

}  // namespace dustlift
