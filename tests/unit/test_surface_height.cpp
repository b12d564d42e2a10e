// Dust-surface height filter (paper section 3.2, alpha_p > 1e-4) on stretched grids.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "insitu/surface_height.hpp"
#include "solver/core/derivatives.hpp"
#include "solver/core/grid.hpp"

namespace dustlift {
namespace {

/// y nodes: 0.25 mm cells up to 4 mm, then growing by 12 % per cell (the paper's mesh form).
std::vector<double> stretched_y() {
  std::vector<double> n{0.0};
  double w = 2.5e-4;
  while (n.back() < 4e-3 - 1e-12) n.push_back(n.back() + w);
  for (int k = 0; k < 20; ++k) n.push_back(n.back() + (w *= 1.12));
  return n;
}
std::vector<double> stretched_x() {
  std::vector<double> n{0.0};
  double w = 1e-3;
  for (int k = 0; k < 40; ++k) n.push_back(n.back() + (w *= 1.03));
  return n;
}

/// Sine-shaped surface reaching into the stretched part of the y axis.
double surface(double x) { return 3e-3 + 2.5e-3 * std::sin(2.0 * std::numbers::pi * x / 0.05); }

TEST(SurfaceHeight, LinearProfileIsRecoveredToRoundOff) {
  // alpha_p = k (s - y) everywhere (negative above s: only the interpolation is tested):
  // linear in y, so the threshold crossing s - threshold/k is found to round-off.
  const Grid2D grid(Axis(stretched_x(), 2), Axis(stretched_y(), 2));
  const auto xc = interior_centers(grid.x()), yc = interior_centers(grid.y());
  const std::size_t nx = xc.size(), ny = yc.size();
  const double k = 200.0, threshold = 1e-4;
  std::vector<double> alpha(nx * ny);
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i)
      alpha[i + nx * j] = k * (surface(xc[i]) - yc[j]);
  const auto h = dust_surface_height(yc, alpha, nx, threshold);
  ASSERT_EQ(h.size(), nx);
  double worst = 0.0;
  for (std::size_t i = 0; i < nx; ++i)
    worst = std::max(worst, std::abs(h[i] - (surface(xc[i]) - threshold / k)));
  EXPECT_LT(worst, 1e-15) << "largest error " << worst << " m";
}

TEST(SurfaceHeight, SineSurfaceOfASmoothProfileWithinOneCellHeight) {
  // alpha_p(y) = threshold * exp(-(y - s(x)) / L) decreases monotonically and equals the
  // threshold exactly on the sine surface s(x); sampled at the centres of a stretched grid,
  // the recovered height must lie within one local cell height of s.
  const Grid2D grid(Axis(stretched_x(), 2), Axis(stretched_y(), 2));
  const auto xc = interior_centers(grid.x()), yc = interior_centers(grid.y());
  const std::size_t nx = xc.size(), ny = yc.size();
  const double threshold = 1e-4, L = 5e-4;
  std::vector<double> alpha(nx * ny);
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i)
      alpha[i + nx * j] = std::min(0.59, threshold * std::exp(-(yc[j] - surface(xc[i])) / L));
  const auto h = dust_surface_height(yc, alpha, nx, threshold);
  double worst_in_cells = 0.0;
  for (std::size_t i = 0; i < nx; ++i) {
    const int j = grid.y().locate(surface(xc[i]));
    const double local = std::max({grid.y().width(j), grid.y().width(j + 1), grid.y().width(j - 1)});
    worst_in_cells = std::max(worst_in_cells, std::abs(h[i] - surface(xc[i])) / local);
  }
  RecordProperty("worst_error_in_cells", std::to_string(worst_in_cells));
  EXPECT_LT(worst_in_cells, 1.0);
}

TEST(SurfaceHeight, PackedLayerWithSharpTopIsBiasedUpwardByLessThanOneAndAHalfCells) {
  // Cell averages of a packed layer (alpha_p = 0.59 below s, the straddling cell partly
  // filled, 0 above): the 1e-4 level is met just below the first empty centre, so the
  // height lies in (s - w/2, s + 1.5 w) with w the local cell height (documented bias).
  const Grid2D grid(Axis(stretched_x(), 2), Axis(stretched_y(), 2));
  const auto xc = interior_centers(grid.x()), yc = interior_centers(grid.y());
  const std::size_t nx = xc.size(), ny = yc.size();
  std::vector<double> alpha(nx * ny);
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      const double lo = grid.y().face(static_cast<int>(j)), hi = grid.y().face(static_cast<int>(j) + 1);
      alpha[i + nx * j] = 0.59 * std::clamp((surface(xc[i]) - lo) / (hi - lo), 0.0, 1.0);
    }
  const auto h = dust_surface_height(yc, alpha, nx);
  for (std::size_t i = 0; i < nx; ++i) {
    const int j = grid.y().locate(surface(xc[i]));
    const double w = std::max(grid.y().width(j), grid.y().width(j + 1));
    EXPECT_GT(h[i] - surface(xc[i]), -0.5 * w) << "column " << i;
    EXPECT_LT(h[i] - surface(xc[i]), 1.5 * w) << "column " << i;
  }
}

TEST(SurfaceHeight, EmptyColumnsGiveNaNAndAFullTopCellGivesItsCentre) {
  const std::vector<double> yc{0.5, 1.5, 2.5};
  // 3 columns: empty; particles up to the top cell; particles only in the bottom cell.
  const std::vector<double> alpha{0.0, 0.3, 0.5, 0.0, 0.3, 0.0, 0.0, 0.3, 0.0};
  const auto h = dust_surface_height(yc, alpha, 3, 1e-4);
  EXPECT_TRUE(std::isnan(h[0]));
  EXPECT_EQ(h[1], 2.5);
  EXPECT_NEAR(h[2], 0.5 + (0.5 - 1e-4) / 0.5, 1e-15);
}

TEST(SurfaceHeight, StationsInterpolateBetweenColumnCentres) {
  const std::vector<double> xc{0.0, 1.0, 3.0, 4.0}, h{1.0, 2.0, 4.0, std::nan("")};
  EXPECT_DOUBLE_EQ(height_at_station(xc, h, 2.0), 3.0);
  EXPECT_DOUBLE_EQ(height_at_station(xc, h, 0.25), 1.25);
  EXPECT_DOUBLE_EQ(height_at_station(xc, h, -1.0), 1.0);
  EXPECT_TRUE(std::isnan(height_at_station(xc, h, 3.5)));
}

}  // namespace
}  // namespace dustlift
