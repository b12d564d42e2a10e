// GasSolver remembers each row's resting cells between scans and reads again only what changed
// since (RestSuffixCache, gas_solver_resting.cpp): every count must be the one a fresh walk of
// the row gives, through steps, porosity changes and writes from outside.
#include <gtest/gtest.h>

#include <utility>

#include "solver/gas/rest_ranges.hpp"
#include "solver/scene/scene.hpp"
#include "solver/sim/simulation.hpp"
#include "support/shock_over_dust.hpp"

using namespace dustlift;

namespace {

/// Per interior row the first resting column (as GasSolver::RestingGas counts it) from a walk
/// of the row's current values, ghosts included.
std::vector<int> walked_first_resting(const GasSolver& gas, const Grid2D& grid,
                                      const RestReference& ref) {
  const GasPrimitives g = gas.primitives();
  const int ng = grid.ghosts(), cells = grid.nx() + 2 * ng;
  std::vector<int> first(static_cast<std::size_t>(grid.ny()));
  for (int j = 0; j < grid.ny(); ++j) {
    const std::size_t c = grid.index(-ng, j);
    const RowView row{g.u->data() + c, g.v->data() + c, g.p->data() + c, g.T->data() + c, cells};
    first[static_cast<std::size_t>(j)] = cells - resting_suffix(row, ref) - ng;
  }
  return first;
}

}  // namespace

TEST(RestingRowsCache, CountsAreThoseOfAFreshWalkThroughACoupledRun) {
  // The mini scene (a shock over a 16 mm layer: stages, porosity changes, exchange) for 40 us,
  // skipping within the default tolerance; after every step the coupling's query (cached)
  // against a walk of every row.
  const Scene scene = parse_scene(dustlift::testing::kShockOverDust, "mini.toml",
                                  {"run.end_time=4e-5", "grid.x.end=0.03", "grid.x.cells=68"});
  Simulation sim(scene);
  const Grid2D& grid = sim.grid();
  int steps = 0, partly_resting = 0;
  GasSolver::RestingGas cached;
  while (sim.time() < scene.run.end_time) {
    sim.advance(scene.run.end_time - sim.time());
    const GasSolver& gas = std::as_const(sim).gas();
    gas.resting_gas(cached);
    ASSERT_EQ(cached.first_resting, walked_first_resting(gas, grid, cached.reference))
        << "step " << sim.step();
    partly_resting += cached.first_resting[0] > 0 && cached.first_resting[0] < grid.nx() ? 1 : 0;
    ++steps;
  }
  EXPECT_GT(steps, 100);
  EXPECT_GT(partly_resting, steps / 2);  // the shock was inside the channel, gas ahead at rest

  // Particles arriving in the resting gas ahead of the shock change its porosity there (the
  // gas is compressed): seen at the next query.
  GasSolver& gas = sim.gas();
  const int j = grid.ny() / 2;
  Field2D porosity = *std::as_const(gas).primitives().alpha_g;
  porosity(grid.nx() - 5, j) = 0.9;
  gas.change_porosity(porosity, j, j + 1);
  gas.resting_gas(cached);
  EXPECT_EQ(cached.first_resting, walked_first_resting(std::as_const(gas), grid, cached.reference));
  EXPECT_GE(cached.first_resting[static_cast<std::size_t>(j)], grid.nx() - 4);

  // A write from outside, into the resting gas: seen at the next query.
  const int i = grid.nx() - 3;
  gas.conserved(3)(i, j) *= 1.001;  // a little more energy: warmer there
  gas.refresh_primitives();
  gas.resting_gas(cached);
  const std::vector<int> walked = walked_first_resting(std::as_const(gas), grid, cached.reference);
  EXPECT_EQ(cached.first_resting, walked);
  EXPECT_GE(walked[static_cast<std::size_t>(j)], i + 1);  // the warmed cell no longer rests
}
