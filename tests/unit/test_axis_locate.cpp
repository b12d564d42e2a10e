// Axis::locate (bucketed) finds the same cell as a binary search of the faces, on the paper's
// stretched axis and on an axis with a cell far smaller than the rest, including points on
// faces, outside the axis and NaN; and so does the bounded locate of vector loops where it
// reports itself exact.
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

/// AxisView::locate_bounded (the vector loops' locate) where it says it is exact; returns how
/// many points it was not.
int check_bounded(const Axis& a, double s) {
  bool exact = false;
  const int i = a.view().locate_bounded(s, exact);
  if (exact) {
    EXPECT_EQ(i, reference_locate(a, s)) << "bounded, s = " << s;
  }
  return exact ? 0 : 1;
}

/// Returns the points (of about 200,000 finite ones) where locate_bounded was not exact.
int expect_same_as_binary_search(const Axis& a) {
  std::mt19937 rng(5);
  const double lo = a.start(), hi = a.end(), span = hi - lo;
  std::uniform_real_distribution<double> u(lo - 0.1 * span, hi + 0.1 * span);
  int inexact = 0;
  for (int k = 0; k < 200000; ++k) {
    const double s = u(rng);
    EXPECT_EQ(a.locate(s), reference_locate(a, s)) << "s = " << s;
    inexact += check_bounded(a, s);
  }
  for (double f : a.interior_faces()) {
    EXPECT_EQ(a.locate(f), reference_locate(a, f)) << "face " << f;
    EXPECT_EQ(a.locate(std::nextafter(f, -1e9)), reference_locate(a, std::nextafter(f, -1e9)));
    inexact += check_bounded(a, f) + check_bounded(a, std::nextafter(f, -1e9));
  }
  for (double far : {-1e300, 1e300, -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()}) {
    EXPECT_EQ(a.locate(far), reference_locate(a, far));
    inexact += check_bounded(a, far);
  }
  EXPECT_EQ(a.locate(std::numeric_limits<double>::quiet_NaN()), 0);
  bool exact = true;
  a.view().locate_bounded(std::numeric_limits<double>::quiet_NaN(), exact);
  EXPECT_FALSE(exact);  // the caller falls back to locate()
  return inexact;
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
  // Buckets no wider than the smallest cell: the bounded locate is exact everywhere.
  EXPECT_EQ(expect_same_as_binary_search(Axis(build_axis_nodes(x), 2)), 0);
}

TEST(AxisLocate, OneTinyCellAmongLargeOnes) {
  // Buckets are capped at 4 n: each may then span several cells, found by the scan.
  Axis a({0.0, 1e-9, 0.3, 0.5, 0.9, 1.0}, 2);
  expect_same_as_binary_search(a);
}

TEST(AxisLocate, SeveralTinyCellsInOneBucket) {
  // The bounded locate of vector loops then cannot reach the cell in its few steps: it must
  // say so (the callers fall back to locate), and be right wherever it does not.
  Axis a({0.0, 1e-9, 2e-9, 3e-9, 4e-9, 0.5, 1.0}, 2);
  EXPECT_GT(expect_same_as_binary_search(a), 0);
}
