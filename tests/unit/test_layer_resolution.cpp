// The check that enough cells span a dust layer's depth (solver/sim/layer_resolution.hpp):
// the count against hand-computed values on uniform and stretched axes, and the warning given
// exactly below two cells.
#include <gtest/gtest.h>

#include "solver/core/grid.hpp"
#include "solver/sim/layer_resolution.hpp"

using namespace dustlift;

namespace {

Grid2D grid_with_y(double start, double end, double cell, double uniform_end, std::size_t above) {
  AxisSpec x;
  x.start = 0.0;
  x.end = 0.01;
  x.cells = 10;
  AxisSpec y;
  y.start = start;
  y.end = end;
  y.cell_size = cell;
  y.uniform_start = start;
  y.uniform_end = uniform_end;
  y.cells_above = above;
  return Grid2D(x, y, 2);
}

}  // namespace

TEST(LayerResolution, CountsTheCellsAcrossTheLayer) {
  // A 0.5 mm layer on 0.5, 0.25 and 0.125 mm cells: 1, 2 and 4 cells.
  for (double cell : {0.5e-3, 0.25e-3, 0.125e-3}) {
    const Grid2D g = grid_with_y(-0.5e-3, 0.01, cell, 0.01, 0);
    EXPECT_NEAR(cells_across(g.y(), -0.5e-3, 0.0), 0.5e-3 / cell, 1e-9) << cell;
  }
  // The widest overlapped cell sets the count: on a stretched axis, a layer reaching into the
  // stretched cells counts by the widest of them (wider than 0.25 mm).
  const Grid2D s = grid_with_y(0.0, 0.02, 0.25e-3, 0.002, 8);
  EXPECT_NEAR(cells_across(s.y(), 0.0, 0.001), 4.0, 1e-9);
  EXPECT_LT(cells_across(s.y(), 0.0, 0.004), 0.004 / 0.25e-3);
  // An empty or inverted interval spans nothing.
  EXPECT_EQ(cells_across(s.y(), 0.001, 0.001), 0.0);
  EXPECT_EQ(cells_across(s.y(), 0.002, 0.001), 0.0);
}

TEST(LayerResolution, WarnsBelowTwoCellsOnly) {
  const Grid2D coarse = grid_with_y(-0.5e-3, 0.01, 0.5e-3, 0.01, 0);
  const std::string w = layer_resolution_warning(coarse.y(), -0.5e-3, 0.0);
  ASSERT_FALSE(w.empty());
  EXPECT_NE(w.find("1 cell(s) of 0.5 mm span the 0.5 mm layer"), std::string::npos) << w;
  EXPECT_NE(w.find("until 2 or more span it"), std::string::npos) << w;
  const Grid2D two = grid_with_y(-0.5e-3, 0.01, 0.25e-3, 0.01, 0);
  EXPECT_TRUE(layer_resolution_warning(two.y(), -0.5e-3, 0.0).empty());
  // 1.9 cells: 0.475 mm layer on 0.25 mm cells.
  EXPECT_FALSE(layer_resolution_warning(two.y(), -0.475e-3, 0.0).empty());
}
