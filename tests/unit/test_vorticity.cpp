// Vorticity on a stretched grid: exact for linear fields (every cell, boundaries included)
// and 2nd-order for a smooth field.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "solver/core/derivatives.hpp"
#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"

namespace dustlift {
namespace {

/// Nodes on [a, ...] with geometric growth r: strongly non-uniform on purpose.
std::vector<double> geometric_nodes(double start, double first, double r, int cells) {
  std::vector<double> nodes{start};
  double w = first;
  for (int i = 0; i < cells; ++i) {
    nodes.push_back(nodes.back() + w);
    w *= r;
  }
  return nodes;
}

/// Splits every cell into `parts` equal cells: halves the widest cell exactly.
std::vector<double> refine(const std::vector<double>& nodes, int parts) {
  std::vector<double> out{nodes.front()};
  for (std::size_t k = 0; k + 1 < nodes.size(); ++k)
    for (int p = 1; p <= parts; ++p)
      out.push_back(nodes[k] + (nodes[k + 1] - nodes[k]) * p / parts);
  return out;
}

Grid2D stretched_grid(int nx, int ny, int parts = 1) {
  return Grid2D(Axis(refine(geometric_nodes(-0.3, 0.02, 1.15, nx), parts), 2),
                Axis(refine(geometric_nodes(0.1, 0.01, 1.2, ny), parts), 2));
}

TEST(Vorticity, DerivativeWeightsExactForQuadratics) {
  const double c0 = 0.1, c1 = 0.13, c2 = 0.2;
  for (double at : {c0, c1, c2}) {
    const auto w = derivative_weights(c0, c1, c2, at);
    auto f = [](double x) { return 3.0 - 2.0 * x + 5.0 * x * x; };
    EXPECT_NEAR(w.w0 * f(c0) + w.w1 * f(c1) + w.w2 * f(c2), -2.0 + 10.0 * at, 1e-11);
  }
}

TEST(Vorticity, LinearVelocityOnStretchedGridIsExactEverywhere) {
  const Grid2D grid = stretched_grid(17, 13);
  const double a = 1.7, b = -2.3, c = 4.1, d = 0.6;
  Field2D u(grid), v(grid);
  for (int j = 0; j < grid.ny(); ++j)
    for (int i = 0; i < grid.nx(); ++i) {
      const double x = grid.x().center(i), y = grid.y().center(j);
      u(i, j) = a * x + b * y;
      v(i, j) = c * x + d * y;
    }
  const auto w = vorticity_z(grid, u, v);
  ASSERT_EQ(w.size(), grid.interior_cells());
  double worst = 0.0;
  for (double value : w) worst = std::max(worst, std::abs(value - (c - b)));
  EXPECT_LT(worst, 1e-12) << "largest deviation from c - b = " << c - b;
}

TEST(Vorticity, SmoothFieldConvergesAtSecondOrder) {
  // u = sin(3y), v = cos(2x): w = -2 sin(2x) - 3 cos(3y). Max error over all cells
  // (boundaries included) must drop ~4x each time every cell is halved.
  auto max_error = [](int parts) {
    const Grid2D grid = stretched_grid(12, 10, parts);
    Field2D u(grid), v(grid);
    for (int j = 0; j < grid.ny(); ++j)
      for (int i = 0; i < grid.nx(); ++i) {
        u(i, j) = std::sin(3.0 * grid.y().center(j));
        v(i, j) = std::cos(2.0 * grid.x().center(i));
      }
    const auto w = vorticity_z(grid, u, v);
    double e = 0.0;
    for (int j = 0; j < grid.ny(); ++j)
      for (int i = 0; i < grid.nx(); ++i) {
        const double exact =
            -2.0 * std::sin(2.0 * grid.x().center(i)) - 3.0 * std::cos(3.0 * grid.y().center(j));
        e = std::max(e, std::abs(w[static_cast<std::size_t>(i + grid.nx() * j)] - exact));
      }
    return e;
  };
  // Every refinement splits each cell of the same stretched grid in two.
  const double e1 = max_error(1), e2 = max_error(2), e3 = max_error(4);
  const double order1 = std::log2(e1 / e2), order2 = std::log2(e2 / e3);
  RecordProperty("order_fine", std::to_string(order2));
  EXPECT_GT(order2, 1.8) << "errors " << e1 << " " << e2 << " " << e3;
  EXPECT_GT(order1, 1.5) << "errors " << e1 << " " << e2 << " " << e3;
}

}  // namespace
TEST(Vorticity, RowKernelsOfAQuadraticAreExact) {
  // The row kernels (vorticity_z_rows, gradient_rows; their segments are what the coupling
  // samples) read each axis's
  // derivative weights made once (Axis::derivative_stencil): the same numbers as the weights
  // made per cell, and exact for a quadratic field on a stretched grid, walls included.
  const Grid2D grid = stretched_grid(17, 13);
  for (const Axis* a : {&grid.x(), &grid.y()}) {
    for (int k = 0; k < a->cells(); ++k) {
      const int first = k == 0 ? 0 : (k == a->cells() - 1 ? a->cells() - 3 : k - 1);
      const auto w = derivative_weights(a->center(first), a->center(first + 1),
                                        a->center(first + 2), a->center(k));
      EXPECT_EQ(a->derivative_stencil(k).first, first);
      EXPECT_EQ(a->derivative_stencil(k).w0, w.w0);
      EXPECT_EQ(a->derivative_stencil(k).w2, w.w2);
    }
  }
  Field2D f(grid), u(grid), v(grid), dfdx(grid), dfdy(grid), w_rows(grid);
  for (int j = 0; j < grid.ny(); ++j)
    for (int i = 0; i < grid.nx(); ++i) {
      const double x = grid.x().center(i), y = grid.y().center(j);
      f(i, j) = 1.0 + 2.0 * x - 3.0 * y + 0.5 * x * x - 1.5 * x * y + 2.5 * y * y;
      u(i, j) = 0.3 * x * x - 1.1 * x * y + 0.7 * y * y;  // du/dy = -1.1 x + 1.4 y
      v(i, j) = -0.4 * x * x + 0.9 * x * y + 2.0 * y;     // dv/dx = -0.8 x + 0.9 y
    }
  gradient_rows(grid, f, 0, grid.ny(), dfdx, dfdy);
  vorticity_z_rows(grid, u, v, 0, grid.ny(), w_rows);
  const auto w_whole = vorticity_z(grid, u, v);
  double worst = 0.0;
  for (int j = 0; j < grid.ny(); ++j)
    for (int i = 0; i < grid.nx(); ++i) {
      const double x = grid.x().center(i), y = grid.y().center(j);
      worst = std::max({worst, std::abs(dfdx(i, j) - (2.0 + x - 1.5 * y)),
                        std::abs(dfdy(i, j) - (-3.0 - 1.5 * x + 5.0 * y))});
      worst =
          std::max(worst, std::abs(w_rows(i, j) - ((-0.8 * x + 0.9 * y) - (-1.1 * x + 1.4 * y))));
      EXPECT_EQ(w_rows(i, j),
                w_whole[static_cast<std::size_t>(i) + static_cast<std::size_t>(grid.nx()) * j]);
    }
  EXPECT_LT(worst, 1e-9);
}

}  // namespace dustlift
