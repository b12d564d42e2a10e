// Axis::locate (bucketed) finds the same cell as a binary search of the faces, on the paper's
// stretched axis and on an axis with a cell far smaller than the rest, including points on
// faces, outside the axis and NaN.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "solver/core/grid.hpp"

using namespace dustlift;

namespace {

int reference_locate(const Axis& a, double s) {
  const auto& f = a.interior_faces();
  const auto it = std::upper_bound(f.begin(), f.end(), s);
  return std::clamp(static_cast<int>(it - f.begin()) - 1, 0, a.cells() - 1);
}

void expect_same_as_binary_search(const Axis& a) {
  std::mt19937 rng(5);
  const double lo = a.start(), hi = a.end(), span = hi - lo;
  std::uniform_real_distribution<double> u(lo - 0.1 * span, hi + 0.1 * span);
  for (int k = 0; k < 200000; ++k) {
    const double s = u(rng);
    ASSERT_EQ(a.locate(s), reference_locate(a, s)) << "s = " << s;
  }
  for (double f : a.interior_faces()) {
    ASSERT_EQ(a.locate(f), reference_locate(a, f)) << "face " << f;
    ASSERT_EQ(a.locate(std::nextafter(f, -1e9)), reference_locate(a, std::nextafter(f, -1e9)));
  }
  EXPECT_EQ(a.locate(std::numeric_limits<double>::quiet_NaN()), 0);
}

}  // namespace

TEST(AxisLocate, PaperStretchedAxisMatchesBinarySearch) {
  AxisSpec x;
  x.start = -0.4;
  x.end = 0.4;
  x.cell_size = 250e-6;
  x.uniform_start = 0.0;
  x.uniform_end = 0.4;
  x.cells_below = 300;
  expect_same_as_binary_search(Axis(build_axis_nodes(x), 2));
}

TEST(AxisLocate, OneTinyCellAmongLargeOnes) {
  // Buckets are capped at 4 n: each may then span several cells, found by the scan.
  Axis a({0.0, 1e-9, 0.3, 0.5, 0.9, 1.0}, 2);
  expect_same_as_binary_search(a);
}
