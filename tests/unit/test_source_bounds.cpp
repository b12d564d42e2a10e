// The coupling vouches for where the gas's sources may be non-zero (GasSolver::
// sources_zero_beyond), and a gas step then searches for them only there: every source outside
// the vouched rows and columns must be zero after every step, and a writer through source()
// must void the vouch.
#include <gtest/gtest.h>

#include <utility>

#include "solver/scene/scene.hpp"
#include "solver/sim/simulation.hpp"
#include "support/shock_over_dust.hpp"

using namespace dustlift;

namespace {

/// Sources outside the bounds that are not zero (all four fields, every interior cell).
int sources_outside(const GasSolver& gas, const Grid2D& grid) {
  const SourceBounds b = gas.source_bounds();
  int found = 0;
  for (int k = 0; k < 4; ++k) {
    const Field2D& s = gas.source(k);
    for (int j = 0; j < grid.ny(); ++j)
      for (int i = 0; i < grid.nx(); ++i)
        if ((j >= b.rows || i >= b.columns) && s(i, j) != 0.0) ++found;
  }
  return found;
}

}  // namespace

TEST(SourceBounds, EverySourceOutsideTheCouplingsBoundsIsZero) {
  // The mini scene (a shock over a 16 mm layer) on a taller channel, so that rows above the
  // layer never hold parcels, for 60 us: the shock crosses the layer and lifts dust.
  const Scene scene = parse_scene(dustlift::testing::kShockOverDust, "mini.toml",
                                  {"run.end_time=6e-5", "grid.y.end=0.008", "grid.y.cells=20"});
  Simulation sim(scene);
  const Grid2D& grid = sim.grid();
  int steps = 0, narrower = 0, with_sources = 0;
  while (sim.time() < scene.run.end_time) {
    sim.advance(scene.run.end_time - sim.time());
    const GasSolver& gas = std::as_const(sim).gas();
    ASSERT_EQ(sources_outside(gas, grid), 0) << "step " << sim.step();
    const SourceBounds b = gas.source_bounds();
    narrower += b.rows < grid.ny() || b.columns < grid.nx() ? 1 : 0;
    for (int j = 0; j < b.rows; ++j)
      for (int i = 0; i < b.columns; ++i) with_sources += gas.source(1)(i, j) != 0.0 ? 1 : 0;
    ++steps;
  }
  EXPECT_GT(steps, 200);
  EXPECT_EQ(narrower, steps);  // the search was narrowed at every step
  EXPECT_GT(with_sources, 0);  // and the parcels did exchange momentum inside it
  // Handing the sources out voids the vouch: the next step searches the whole grid.
  sim.gas().source(1);
  EXPECT_EQ(sim.gas().source_bounds().rows, grid.ny());
  EXPECT_EQ(sim.gas().source_bounds().columns, grid.nx());
}
