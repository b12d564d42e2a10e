// Shock position filter: a synthetic step, the exact Sod solution sampled on a grid, and the
// rows read in place from a field with ghosts.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "insitu/shock_position.hpp"
#include "insitu/view_fields.hpp"
#include "solver/core/derivatives.hpp"
#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"

namespace dustlift {
namespace {

/// Exact Riemann solution of an ideal gas (Toro, ch. 4), pressure only, for left/right
/// states at rest or moving; enough to sample p(x, t) and the right shock speed.
struct GasState {
  double rho, u, p;
};

struct ExactRiemann {
  GasState left, right;
  double gamma = 1.4;
  double p_star = 0, u_star = 0;

  double wave_function(double p, const GasState& s) const {  // f_K(p) and its derivative
    const double a = std::sqrt(gamma * s.p / s.rho);
    if (p > s.p) {
      const double A = 2.0 / ((gamma + 1.0) * s.rho), B = (gamma - 1.0) / (gamma + 1.0) * s.p;
      return (p - s.p) * std::sqrt(A / (p + B));
    }
    return 2.0 * a / (gamma - 1.0) * (std::pow(p / s.p, (gamma - 1.0) / (2.0 * gamma)) - 1.0);
  }
  void solve() {
    // Bisection on f_L(p) + f_R(p) + du = 0 (monotone in p): robust and exact enough.
    double lo = 1e-12, hi = 100.0 * std::max(left.p, right.p);
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      const double f = wave_function(mid, left) + wave_function(mid, right) + right.u - left.u;
      (f > 0.0 ? hi : lo) = mid;
    }
    p_star = 0.5 * (lo + hi);
    u_star = 0.5 * (left.u + right.u) +
             0.5 * (wave_function(p_star, right) - wave_function(p_star, left));
  }
  /// Right-running shock speed (p_star > right.p assumed).
  double right_shock_speed() const {
    const double a = std::sqrt(gamma * right.p / right.rho);
    return right.u + a * std::sqrt((gamma + 1.0) / (2.0 * gamma) * p_star / right.p +
                                   (gamma - 1.0) / (2.0 * gamma));
  }
  /// Pressure at x/t = s (left rarefaction assumed, as in Sod).
  double pressure(double s) const {
    const double aL = std::sqrt(gamma * left.p / left.rho);
    const double a_star_l = aL * std::pow(p_star / left.p, (gamma - 1.0) / (2.0 * gamma));
    if (s >= u_star) return s < right_shock_speed() ? p_star : right.p;
    if (s <= left.u - aL) return left.p;
    if (s >= u_star - a_star_l) return p_star;
    const double c = 2.0 / (gamma + 1.0) + (gamma - 1.0) / ((gamma + 1.0) * aL) * (left.u - s);
    return left.p * std::pow(c, 2.0 * gamma / (gamma - 1.0));
  }
};

TEST(ShockPosition, SyntheticStepIsLocatedBetweenCentres) {
  // Stretched row; p = 2 up to x_s, 1 beyond; the level 1.05 crossing by linear
  // interpolation lies between the last high centre and the first low one.
  std::vector<double> xc;
  double x = 0.0, w = 0.01;
  for (int i = 0; i < 60; ++i) { xc.push_back(x + 0.5 * w); x += w; w *= 1.02; }
  for (double xs : {0.1234, 0.3, 0.61}) {
    std::vector<double> p(xc.size());
    for (std::size_t i = 0; i < xc.size(); ++i) p[i] = xc[i] < xs ? 2.0 : 1.0;
    const double found = shock_position_on_row(xc, p, 1.0, 0.05);
    std::size_t last = 0;
    while (xc[last + 1] < xs) ++last;
    EXPECT_NEAR(found, xc[last] + 0.95 * (xc[last + 1] - xc[last]), 1e-14);
    EXPECT_LT(std::abs(found - xs), xc[last + 1] - xc[last]);
    // Ambient from the downstream cell gives the same answer.
    EXPECT_EQ(shock_position_on_row(xc, p, 0.0, 0.05), found);
  }
  std::vector<double> calm(xc.size(), 1.0);
  EXPECT_TRUE(std::isnan(shock_position_on_row(xc, calm, 1.0, 0.05)));
}

TEST(ShockPosition, ExactSodSolutionOnAGridGivesTheShockWithinOneCell) {
  ExactRiemann sod{{1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}};
  sod.solve();
  EXPECT_NEAR(sod.p_star, 0.30313, 1e-5);           // Toro, Table 4.3 test 1
  EXPECT_NEAR(sod.right_shock_speed(), 1.75216, 1e-5);
  const int nx = 400, ny = 3;
  const double dx = 1.0 / nx, x0 = 0.5;
  std::vector<double> xc(nx), yc{0.1, 0.2, 0.3};
  for (int i = 0; i < nx; ++i) xc[static_cast<std::size_t>(i)] = (i + 0.5) * dx;
  for (double t : {0.05, 0.1, 0.2}) {
    std::vector<double> p(static_cast<std::size_t>(nx * ny));
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        p[static_cast<std::size_t>(i + nx * j)] = sod.pressure((xc[static_cast<std::size_t>(i)] - x0) / t);
    const double exact = x0 + sod.right_shock_speed() * t;
    const double found = shock_position(xc, yc, p, 0.1, 0.05, 0.0);
    EXPECT_LT(std::abs(found - exact), dx) << "t = " << t;
  }
}

TEST(ShockPosition, RowsBelowYMinAreIgnoredAndTheFurthestRowWins) {
  const std::vector<double> xc{0.5, 1.5, 2.5, 3.5}, yc{0.5, 1.5, 2.5};
  // Row 0: raised to the end (its shock has left), row 1: at 1.5..2.5, row 2: at 0.5..1.5.
  const std::vector<double> p{3, 3, 3, 3, 3, 3, 1, 1, 3, 1, 1, 1};
  EXPECT_DOUBLE_EQ(shock_position(xc, yc, p, 1.0, 0.05, 1.0), 1.5 + 0.975);
  EXPECT_DOUBLE_EQ(shock_position(xc, yc, p, 1.0, 0.05, 0.0), 1.5 + 0.975);
  EXPECT_DOUBLE_EQ(shock_position(xc, yc, p, 1.0, 0.05, 2.0), 0.5 + 0.975);
}

TEST(ShockPosition, AShockThatLeftTheDomainIsNotReportedAtTheLastCell) {
  const std::vector<double> xc{0.5, 1.5, 2.5, 3.5};
  EXPECT_DOUBLE_EQ(shock_position_on_row(xc, std::vector<double>{3, 3, 3, 1}, 1.0, 0.05), 2.5 + 0.975);
  EXPECT_TRUE(std::isnan(shock_position_on_row(xc, std::vector<double>{3, 3, 3, 3}, 1.0, 0.05)));
  EXPECT_TRUE(std::isnan(shock_position(xc, std::vector<double>{0.5}, std::vector<double>{3, 3, 3, 3}, 1.0, 0.05, 0.0)));
}

TEST(ShockPosition, ReadInPlaceFromAFieldWithGhostsAsFromItsInteriorCopy) {
  // The rows the every-step observers read in place: the same positions as from the interior
  // copy, and the ghosts (raised everywhere, so a row read with them would end raised and
  // report nothing) never read.
  const Grid2D grid(Axis({0.0, 1.0, 2.0, 3.0, 4.0, 5.0}, 2), Axis({0.0, 1.0, 2.0, 3.0}, 2));
  Field2D p(grid, 9.0);
  const double rows[3][5] = {{3, 3, 1, 1, 1}, {3, 3, 3, 2, 1}, {3, 1, 1, 1, 1}};
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 5; ++i) p(i, j) = rows[j][i];
  std::vector<double> copy;
  interior_values(grid, p, copy);
  const std::vector<double> xc = interior_centers(grid.x()), yc = interior_centers(grid.y());
  for (double y_min : {0.0, 1.0, 2.0, 5.0}) {
    const double from_copy = shock_position(xc, yc, copy, 1.0, 0.05, y_min);
    const double in_place = shock_position(grid, p, xc, yc, 1.0, 0.05, y_min);
    if (std::isnan(from_copy)) {
      EXPECT_TRUE(std::isnan(in_place)) << y_min;
    } else {
      EXPECT_EQ(in_place, from_copy) << y_min;
    }
  }
  // Row 1 leads: raised to centre 3.5, 2 there and 1 at 4.5 (level 1.05).
  EXPECT_DOUBLE_EQ(shock_position(grid, p, xc, yc, 1.0, 0.05, 0.0), 3.5 + 0.95 / 1.0);
  EXPECT_DOUBLE_EQ(shock_position(grid, p, xc, yc, 1.0, 0.05, 2.0), 0.5 + 1.95 / 2.0);
  EXPECT_THROW(shock_position(grid, p, yc, yc, 1.0, 0.05, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace dustlift
