// Lifting delay distance (insitu/lifting_delay.hpp) on synthetic surface profiles, and as the
// sweep summary reports it (summarise_run on series written by the series writer).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "insitu/lifting_delay.hpp"
#include "insitu/series_table.hpp"
#include "solver/app/run_summary.hpp"
#include "tests/support/scratch_dir.hpp"

using namespace dustlift;

namespace {

/// The layer's downstream end (particles.layer.x_max).
constexpr double kLayerEnd = 0.4;

/// Column centres every 0.25 mm from 0 to 400 mm.
std::vector<double> columns() {
  std::vector<double> x;
  for (int i = 0; i < 1600; ++i) x.push_back((i + 0.5) * 0.25e-3);
  return x;
}

/// A profile of the paper's kind at 0.6 ms: undisturbed (0) ahead of the shock at 290 mm,
/// pressed down by 0.1 mm just behind it, rising linearly from x = 190 mm at 2 mm per 100 mm.
double profile(double x) {
  if (x > 0.29) return 0.0;
  if (x > 0.25) return -0.1e-3;
  if (x > 0.19) return 0.0;
  return 0.02 * (0.19 - x);
}

}  // namespace

TEST(LiftingDelay, DistanceFromTheShockToWhereTheSurfaceRisesAboveTheThreshold) {
  const auto x = columns();
  std::vector<double> h;
  for (double xi : x) h.push_back(profile(xi));
  // 0.25 mm above the top is reached 12.5 mm behind x = 190 mm: delay 290 - 177.5 mm.
  EXPECT_NEAR(lifting_delay_distance(x, h, 0.29, 0.0, kLayerEnd), 0.1125, 1e-12);
  // A larger threshold (1 mm) is reached 50 mm behind the start of the rise.
  EXPECT_NEAR(lifting_delay_distance(x, h, 0.29, 0.0, kLayerEnd, 1e-3), 0.15, 1e-12);
  // The layer top is where the undisturbed surface is: here 0.2 mm lower.
  for (double& v : h) v -= 0.2e-3;
  EXPECT_NEAR(lifting_delay_distance(x, h, 0.29, -0.2e-3, kLayerEnd), 0.1125, 1e-12);
}

TEST(LiftingDelay, DustAheadOfTheShockAndColumnsWithoutDustAreIgnored) {
  const auto x = columns();
  std::vector<double> h;
  for (double xi : x) h.push_back(profile(xi));
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (x[i] > 0.3 && x[i] < 0.31) h[i] = 5e-3;             // a heap ahead of the shock
    if (x[i] > 0.20 && x[i] < 0.21) h[i] = std::nan("");    // no dust in these columns,
    if (x[i] > 0.176 && x[i] < 0.179) h[i] = std::nan("");  // nor around the crossing
  }
  EXPECT_NEAR(lifting_delay_distance(x, h, 0.29, 0.0, kLayerEnd), 0.1125, 1e-12);
}

TEST(LiftingDelay, NoLiftNoShockOrLiftedAtTheShockFront) {
  const auto x = columns();
  const std::vector<double> flat(x.size(), 0.0);
  EXPECT_TRUE(std::isnan(lifting_delay_distance(x, flat, 0.29, 0.0, kLayerEnd)));
  std::vector<double> h;
  for (double xi : x) h.push_back(profile(xi));
  EXPECT_TRUE(std::isnan(lifting_delay_distance(x, h, std::nan(""), 0.0, kLayerEnd)));
  // Lifted everywhere behind the shock: the delay is the distance to the first column behind it.
  const std::vector<double> high(x.size(), 1e-3);
  EXPECT_NEAR(lifting_delay_distance(x, high, 0.2901, 0.0, kLayerEnd), 0.2901 - x[1159], 1e-15);
  const std::vector<double> short_h(3, 0.0);
  EXPECT_THROW(lifting_delay_distance(x, short_h, 0.29, 0.0, kLayerEnd), std::invalid_argument);
}

TEST(LiftingDelay, NoDelayOnceTheShockHasLeftTheLayer) {
  // The layer ends at x_max; the same lifted profile gives a delay while the shock is over
  // the layer (up to x_max itself) and none once the shock is beyond it.
  const auto x = columns();
  std::vector<double> h;
  for (double xi : x) h.push_back(profile(xi));
  const double x_max = 0.29;
  EXPECT_NEAR(lifting_delay_distance(x, h, 0.29, 0.0, x_max), 0.1125, 1e-12);
  EXPECT_TRUE(std::isnan(lifting_delay_distance(x, h, 0.2901, 0.0, x_max)));
  EXPECT_TRUE(std::isnan(lifting_delay_distance(x, h, 0.35, 0.0, x_max, 1e-3)));
}

TEST(LiftingDelay, TheSweepSummaryLeavesItEmptyOnceTheShockHasLeftTheLayer) {
  // A run folder with the surface series (flat at t = 0, the lifted profile at 0.6 ms) and
  // the shock at 290 mm then: the summary reports the delay for a layer reaching 400 mm, and
  // none (NaN, "nan" in summary.csv) for one that ends at 250 mm.
  const auto dir = dustlift::testing::scratch_dir("lifting_delay_summary");
  SeriesSink sink(dir.string());
  SeriesTable shock("shock_position", {{"time", "s"}, {"x", "m"}});
  SeriesTable surface("surface_height", {{"time", "s"}, {"x", "m"}, {"height", "m"}});
  shock.append_row(std::vector{0.0, 0.0});
  shock.append_row(std::vector{0.6e-3, 0.29});
  for (double xi : columns()) surface.append_row(std::vector{0.0, xi, 0.0});
  for (double xi : columns()) surface.append_row(std::vector{0.6e-3, xi, profile(xi)});
  sink.write(shock);
  sink.write(surface);
  Scene scene;
  scene.particles.layer.x_min = 0.0;
  scene.particles.layer.y_max = 0.0;
  scene.particles.layer.x_max = 0.4;
  EXPECT_NEAR(summarise_run(dir.string(), scene, {}, kDefaultLiftThreshold).lifting_delay, 0.1125,
              1e-12);
  scene.particles.layer.x_max = 0.25;
  const RunResults beyond = summarise_run(dir.string(), scene, {}, kDefaultLiftThreshold);
  EXPECT_TRUE(std::isnan(beyond.lifting_delay)) << beyond.lifting_delay;
  EXPECT_DOUBLE_EQ(beyond.shock_x, 0.29) << "the shock position is still reported";
}
