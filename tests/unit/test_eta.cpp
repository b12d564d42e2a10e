// The progress line's wall-time estimate against a run whose cost per simulated time grows, as a
// shock sweeping a dust layer's makes it (solver/sim/eta.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "solver/sim/eta.hpp"

namespace dustlift {
namespace {

TEST(Eta, TheLastIntervalsRateFollowsAGrowingCost) {
  // wall(t) = t^2 (the cost rate grows linearly): at t = 0.25 of 1, 0.9375 is left.
  const auto wall = [](double t) { return t * t; };
  const double t = 0.25, end = 1.0, left = wall(end) - wall(t);
  const double average = remaining_wall_seconds(t, end, wall(t), 0.0, 0.0);
  const double recent = remaining_wall_seconds(t, end, wall(t), 0.2, wall(0.2));
  EXPECT_DOUBLE_EQ(average, 0.1875);  // 0.0625 * 0.75 / 0.25: five times too short
  EXPECT_DOUBLE_EQ(recent, 0.3375);   // (0.0625 - 0.04) / 0.05 * 0.75
  EXPECT_LT(std::abs(recent - left), std::abs(average - left));
  // A steady cost: both are exact.
  EXPECT_DOUBLE_EQ(remaining_wall_seconds(0.5, 1.0, 2.0, 0.25, 1.0), 2.0);
  EXPECT_EQ(remaining_wall_seconds(0.5, 1.0, 2.0, 0.5, 1.0), 0.0);
  EXPECT_EQ(remaining_wall_seconds(1.0, 1.0, 2.0, 0.5, 1.0), 0.0);
}

}  // namespace
}  // namespace dustlift
