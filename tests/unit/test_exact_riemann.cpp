// Exact Riemann solver against Toro's Sod values (docs/gas-solver.md) and its own invariants.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/gas/exact_riemann.hpp"

using namespace dustlift;

TEST(ExactRiemann, SodStarStateAndWavePositions) {
  const ExactRiemannSolver s({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4);
  EXPECT_NEAR(s.star_pressure(), 0.303130, 1e-6);
  EXPECT_NEAR(s.star_velocity(), 0.927453, 1e-6);
  EXPECT_NEAR(s.star_density_left(), 0.426319, 1e-6);
  EXPECT_NEAR(s.star_density_right(), 0.265574, 1e-6);
  const double t = 0.2, x0 = 0.5;
  auto at = [&](double x) { return s.sample((x - x0) / t); };
  EXPECT_EQ(at(0.263).rho, 1.0);             // ahead of the rarefaction head (0.26336)
  EXPECT_LT(at(0.265).rho, 1.0);
  EXPECT_NEAR(at(0.487).rho, 0.426319, 1e-6);  // behind the tail (0.48595)
  EXPECT_NEAR(at(0.684).rho, 0.426319, 1e-6);  // left of the contact (0.68549)
  EXPECT_NEAR(at(0.687).rho, 0.265574, 1e-6);
  EXPECT_NEAR(at(0.850).rho, 0.265574, 1e-6);  // behind the shock (0.85043)
  EXPECT_EQ(at(0.851).rho, 0.125);
}

TEST(ExactRiemann, FanIsIsentropicAndContinuous) {
  const ExactRiemannSolver s({1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 1.4);
  for (double xi = -1.18; xi < -0.08; xi += 0.01) {
    const RiemannState q = s.sample(xi);
    EXPECT_NEAR(q.p / std::pow(q.rho, 1.4), 1.0, 1e-12);
    // Characteristic u - c = xi inside the fan.
    EXPECT_NEAR(q.u - std::sqrt(1.4 * q.p / q.rho), xi, 1e-12);
  }
}

TEST(ExactRiemann, LaxProblemSatisfiesStarConditions) {
  const ExactRiemannSolver s({0.445, 0.698, 3.528}, {0.5, 0.0, 0.571}, 1.4);
  // Independent bisection of f_L(p) + f_R(p) + du = 0 (Toro eq. 4.5) gives these.
  EXPECT_NEAR(s.star_pressure(), 2.466098, 1e-6);
  EXPECT_NEAR(s.star_velocity(), 1.528723, 1e-6);
  // Shock on the right: Rankine-Hugoniot mass flux agrees on both sides of it.
  const double rr = s.star_density_right();
  const double shock_speed = (rr * s.star_velocity() - 0.5 * 0.0) / (rr - 0.5);
  const RiemannState behind = s.sample(shock_speed - 1e-9), ahead = s.sample(shock_speed + 1e-9);
  EXPECT_NEAR(behind.rho, rr, 1e-12);
  EXPECT_EQ(ahead.rho, 0.5);
}
