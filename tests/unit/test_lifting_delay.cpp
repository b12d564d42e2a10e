// Lifting delay distance (insitu/lifting_delay.hpp) on synthetic surface profiles.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "insitu/lifting_delay.hpp"

using namespace dustlift;

namespace {

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
  EXPECT_NEAR(lifting_delay_distance(x, h, 0.29, 0.0), 0.1125, 1e-12);
  // A larger threshold (1 mm) is reached 50 mm behind the start of the rise.
  EXPECT_NEAR(lifting_delay_distance(x, h, 0.29, 0.0, 1e-3), 0.15, 1e-12);
  // The layer top is where the undisturbed surface is: here 0.2 mm lower.
  for (double& v : h) v -= 0.2e-3;
  EXPECT_NEAR(lifting_delay_distance(x, h, 0.29, -0.2e-3), 0.1125, 1e-12);
}

TEST(LiftingDelay, DustAheadOfTheShockAndColumnsWithoutDustAreIgnored) {
  const auto x = columns();
  std::vector<double> h;
  for (double xi : x) h.push_back(profile(xi));
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (x[i] > 0.3 && x[i] < 0.31) h[i] = 5e-3;                     // a heap ahead of the shock
    if (x[i] > 0.20 && x[i] < 0.21) h[i] = std::nan("");            // no dust in these columns,
    if (x[i] > 0.176 && x[i] < 0.179) h[i] = std::nan("");          // nor around the crossing

  }
  EXPECT_NEAR(lifting_delay_distance(x, h, 0.29, 0.0), 0.1125, 1e-12);
}

TEST(LiftingDelay, NoLiftNoShockOrLiftedAtTheShockFront) {
  const auto x = columns();
  const std::vector<double> flat(x.size(), 0.0);
  EXPECT_TRUE(std::isnan(lifting_delay_distance(x, flat, 0.29, 0.0)));
  std::vector<double> h;
  for (double xi : x) h.push_back(profile(xi));
  EXPECT_TRUE(std::isnan(lifting_delay_distance(x, h, std::nan(""), 0.0)));
  // Lifted everywhere behind the shock: the delay is the distance to the first column behind it.
  const std::vector<double> high(x.size(), 1e-3);
  EXPECT_NEAR(lifting_delay_distance(x, high, 0.2901, 0.0), 0.2901 - x[1159], 1e-15);
  const std::vector<double> short_h(3, 0.0);
  EXPECT_THROW(lifting_delay_distance(x, short_h, 0.29, 0.0), std::invalid_argument);
}
