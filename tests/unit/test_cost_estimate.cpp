// `dustlift info`'s cost estimate (solver/app/cost_estimate.hpp): the share of a run a front
// leaves active, against hand-computed values, and the forecast work of a shock over a dust
// layer against the work a run of it counts, with exact skipping and within a tolerance.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/app/cost_estimate.hpp"
#include "solver/app/info.hpp"
#include "solver/dem/parcel_system.hpp"
#include "solver/scene/scene.hpp"
#include "solver/sim/simulation.hpp"
#include "support/shock_over_dust.hpp"

using namespace dustlift;

TEST(CostEstimate, TheShareBehindAFrontIsTheMeanOfEachPointsRemainingSteps) {
  // Front from 0 at 1 per step over 4 steps: the points at 0, 1, 2, 3 are behind it for 4, 3,
  // 2 and 1 of the 4 steps; one at -1 for all of them, one at 5 for none.
  EXPECT_DOUBLE_EQ(mean_share_behind({0.0, 1.0, 2.0, 3.0}, 0.0, 4.0, 1.0), 0.625);
  EXPECT_DOUBLE_EQ(mean_share_behind({-1.0, 5.0}, 0.0, 4.0, 1.0), 0.5);
  // A front that does not move leaves active only what is behind it from the start.
  EXPECT_DOUBLE_EQ(mean_share_behind({-1.0, 0.5, 2.0, -3.0}, 0.0, 10.0, 0.0), 0.5);
  EXPECT_DOUBLE_EQ(mean_share_behind({}, 0.0, 10.0, 1.0), 1.0);
  // The expected wall time adds each work times its rate.
  WorkForecast w;
  w.cell_stages = 1e6;
  w.parcel_substeps = 2e6;
  w.parcel_steps = 3e4;
  WorkRates r{20e-9, 10e-9, 100e-9};
  EXPECT_DOUBLE_EQ(expected_wall(w, r), 0.02 + 0.02 + 0.003);
}

namespace {

/// The forecast and the work a run of the scene counts to its end.
struct Work {
  WorkForecast forecast;
  double steps = 0.0, cell_stages = 0.0, parcel_substeps = 0.0;
};

Work forecast_and_run(const std::vector<std::string>& overrides) {
  const Scene scene = parse_scene(dustlift::testing::kShockOverDust, "mini.toml", overrides);
  Simulation sim(scene);
  Work w;
  w.forecast = forecast_work(sim, estimated_steps(sim));
  while (sim.time() < scene.run.end_time) sim.advance(scene.run.end_time - sim.time());
  w.steps = static_cast<double>(sim.step());
  w.cell_stages = static_cast<double>(sim.gas().cell_updates());
  w.parcel_substeps = static_cast<double>(sim.parcels()->parcel_substeps());
  return w;
}

}  // namespace

TEST(CostEstimate, TheForecastWorkOfAShockOverDustIsTheRunsWithinAThird) {
  // The mini scene: a Mach 1.44 shock from x = 0.5 mm over a 16 mm layer for 20 us (10 mm),
  // with exact skipping (run.exact): the rounding noise runs ahead of the shock at about four
  // cells per step, so almost everything is stepped (this checks that forecast).
  const Work w = forecast_and_run({"run.exact=true"});
  EXPECT_NEAR(w.forecast.steps / w.steps, 1.0, 0.34);
  EXPECT_NEAR(w.forecast.cell_stages / w.cell_stages, 1.0, 0.34);
  EXPECT_NEAR(w.forecast.parcel_substeps / w.parcel_substeps, 1.0, 0.34);
  EXPECT_GT(w.forecast.parcel_share, 0.8);
  // Without skipping everything is stepped, and the forecast says so.
  const Work all = forecast_and_run({"run.skip_at_rest=false"});
  EXPECT_EQ(all.forecast.gas_share, 1.0);
  EXPECT_EQ(all.forecast.parcel_share, 1.0);
  EXPECT_NEAR(all.forecast.cell_stages / all.cell_stages, 1.0, 0.34);
  EXPECT_NEAR(all.forecast.parcel_substeps / all.parcel_substeps, 1.0, 0.34);
}
