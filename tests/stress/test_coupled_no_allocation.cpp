// A coupled step (gas, sampling, implicit exchange, DEM sub-steps with rebuilds, deposits)
// allocates no memory once the run has warmed up: counted by replacing the global operator new in
// this test executable, over 60 steps of the reduced paper scene after 60 steps of warm-up (the
// shock is then over the layer, parcels move, lists are rebuilt and the DEM re-sorts).
#include <gtest/gtest.h>
#include <omp.h>

#include <cstdio>
#include <string>
#include <vector>

#include "solver/dem/parcel_system.hpp"
#include "solver/sim/simulation.hpp"
#include "support/allocation_counter.hpp"

using test_support::g_allocations;

using namespace dustlift;

namespace {

// Allocations in 60 coupled steps of the reduced paper scene after 60 steps of warm-up, with
// `extra` overrides; the steps must include neighbour rebuilds.
long allocations_in_running_steps(const std::string& extra) {
  const std::string paper = std::string(DUSTLIFT_SOURCE_DIR) + "/cases/paper/vertical_shock.toml";
  std::vector<std::string> reduced{"grid.x.start=-0.02",    "grid.x.end=0.04",
                                   "grid.x.cells_below=20", "particles.layer.x_max=0.04",
                                   "grid.y.end=0.012",      "grid.y.uniform_end=0.008",
                                   "grid.y.cells_above=8",  "initial.position=-0.001"};
  if (!extra.empty()) reduced.push_back(extra);
  omp_set_num_threads(2);
  Simulation sim(load_scene(paper, reduced));
  for (int s = 0; s < 60; ++s) sim.advance(1.0);
  const long rebuilds_before = sim.parcels()->neighbour_rebuilds();
  const long before = g_allocations.load();
  for (int s = 0; s < 60; ++s) sim.advance(1.0);
  const long allocations = g_allocations.load() - before;
  const long rebuilds = sim.parcels()->neighbour_rebuilds() - rebuilds_before;
  std::printf("60 coupled steps (%s): %ld allocations, %ld neighbour rebuilds\n",
              extra.empty() ? "default" : extra.c_str(), allocations, rebuilds);
  EXPECT_GT(rebuilds, 0) << "the measured steps include neighbour rebuilds";
  return allocations;
}

}  // namespace

// Skipping within the default tolerance: the active region still grows with the shock over
// the measured steps, so the buffers sized by what is active must not grow with it.
TEST(CoupledAllocation, StepsAllocateNothingOnceRunning) {
  EXPECT_EQ(allocations_in_running_steps(""), 0);
}

// Exact skipping: its active region has spread over the layer by step 60.
TEST(CoupledAllocation, StepsAllocateNothingOnceRunningWithExactSkipping) {
  EXPECT_EQ(allocations_in_running_steps("run.exact=true"), 0);
}
