// Grid <-> parcel transfer: eq. (16) interpolation reproduces linear fields exactly, weights
// sum to one; deposition conserves the deposited quantity exactly.
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <random>
#include <vector>

#include "solver/coupling/grid_transfer.hpp"

using namespace dustlift;

namespace {

Grid2D stretched_grid() {
  AxisSpec x{-0.01, 0.02, 0, 1e-3, 0.0, 0.01, 5, 4};
  AxisSpec y{-0.002, 0.006, 0, 5e-4, -0.002, 0.003, 0, 3};
  return Grid2D(x, y, 2);
}

}  // namespace

TEST(Interpolation, LinearFieldIsExactOnStretchedGrid) {
  const Grid2D g = stretched_grid();
  Field2D f(g);
  auto linear = [](double x, double y) { return 3.0 + 2.0 * x - 5.0 * y; };
  for (int j = -2; j < g.ny() + 2; ++j)
    for (int i = -2; i < g.nx() + 2; ++i) f(i, j) = linear(g.x().center(i), g.y().center(j));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(g.x().start(), g.x().end()), uy(g.y().start(), g.y().end());
  for (auto rule : {InterpolationRule::Triangle, InterpolationRule::Bilinear}) {
    for (int k = 0; k < 2000; ++k) {
      const double x = ux(rng), y = uy(rng);
      const auto st = interpolation_stencil(g, x, y, rule);
      EXPECT_NEAR(st.weight[0] + st.weight[1] + st.weight[2] + st.weight[3], 1.0, 1e-14);
      for (double w : st.weight) EXPECT_GE(w, 0.0);
      EXPECT_NEAR(st.apply(f), linear(x, y), 1e-12);
    }
  }
}

TEST(Interpolation, TriangleRuleUsesThreeCells) {
  const Grid2D g = stretched_grid();
  const double x = 0.5 * (g.x().center(3) + g.x().center(4)) + 1e-5;
  const double y = 0.5 * (g.y().center(2) + g.y().center(3));
  const auto st = interpolation_stencil(g, x, y);
  int zeros = 0;
  for (double w : st.weight) zeros += (w == 0.0);
  EXPECT_EQ(zeros, 1);
  EXPECT_EQ(st.i, 3);
  EXPECT_EQ(st.j, 2);
}

TEST(Interpolation, AtCellCentreReturnsTheCellValue) {
  const Grid2D g = stretched_grid();
  Field2D f(g);
  for (int j = -2; j < g.ny() + 2; ++j)
    for (int i = -2; i < g.nx() + 2; ++i) f(i, j) = 100.0 * i + j;
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i)
      EXPECT_NEAR(interpolation_stencil(g, g.x().center(i), g.y().center(j)).apply(f), 100.0 * i + j, 1e-9);
}

TEST(Interpolation, BatchGivesTheBitsOfOneStencilAtATime) {
  // The coupling samples nine fields per parcel through InterpolationBatch (vector loops);
  // every value must be the one InterpolationStencil::apply gives, bit for bit, including the
  // exact value of a uniform quad (a field at rest must stay exactly at rest).
  const Grid2D g = stretched_grid();
  Field2D f(g);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> value(-3.0, 7.0);
  for (int j = -2; j < g.ny() + 2; ++j)
    for (int i = -2; i < g.nx() + 2; ++i) f(i, j) = i < 4 ? 0.1 : value(rng);  // uniform on the left
  std::uniform_real_distribution<double> ux(g.x().start(), g.x().end()), uy(g.y().start(), g.y().end());
  constexpr std::size_t kBatch = 64;
  InterpolationBatch<kBatch> batch(g);
  int uniform = 0;
  for (int round = 0; round < 40; ++round) {
    batch.clear();
    std::vector<InterpolationStencil> one;
    const std::size_t count = round % 2 == 0 ? kBatch : 1 + static_cast<std::size_t>(round);
    for (std::size_t q = 0; q < count; ++q) {
      one.push_back(interpolation_stencil(g, ux(rng), uy(rng), round % 3 == 0 ? InterpolationRule::Bilinear
                                                                                : InterpolationRule::Triangle));
      batch.push(one.back());
    }
    ASSERT_EQ(batch.size(), count);
    std::array<double, kBatch> out{};
    batch.apply(f, out.data());
    for (std::size_t q = 0; q < count; ++q) {
      const double expected = one[q].apply(f);
      EXPECT_EQ(std::memcmp(&out[q], &expected, sizeof(double)), 0) << out[q] << " vs " << expected;
      if (one[q].i + 1 < 4) {
        EXPECT_EQ(out[q], 0.1);  // exactly, whatever the weights
        ++uniform;
      }
    }
  }
  EXPECT_GT(uniform, 20);
}

TEST(Interpolation, PointBatchMakesTheStencilsOfInterpolationStencil) {
  // InterpolationBatch::push_points locates a batch in one vector loop (AxisView::
  // locate_bounded, falling back to Axis::locate where that is not exact: the second grid has
  // a cell far smaller than its buckets). Its stencils must be interpolation_stencil's: the
  // values of a field of cell labels and of a random field come out bit for bit the same.
  for (const Grid2D& g : {stretched_grid(), Grid2D(Axis({0.0, 1e-9, 2e-9, 3e-9, 4e-9, 0.5, 1.0}, 2), Axis({0.0, 0.2, 0.7, 1.0}, 2))}) {
    Field2D label(g), noise(g);
    std::mt19937 rng(13);
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    for (int j = -2; j < g.ny() + 2; ++j)
      for (int i = -2; i < g.nx() + 2; ++i) {
        label(i, j) = 1000.0 * i + j;
        noise(i, j) = value(rng);
      }
    const double lx = g.x().end() - g.x().start(), ly = g.y().end() - g.y().start();
    std::uniform_real_distribution<double> ux(g.x().start() - 0.1 * lx, g.x().end() + 0.1 * lx),
        uy(g.y().start() - 0.1 * ly, g.y().end() + 0.1 * ly);
    constexpr std::size_t kBatch = 64;
    for (auto rule : {InterpolationRule::Triangle, InterpolationRule::Bilinear}) {
      for (int round = 0; round < 50; ++round) {
        std::array<double, kBatch> x{}, y{};
        for (std::size_t q = 0; q < kBatch; ++q) {
          x[q] = ux(rng);
          y[q] = uy(rng);
        }
        if (round == 0) x[3] = g.x().face(1);  // on a face
        InterpolationBatch<kBatch> batch(g);
        batch.push_points(x.data(), y.data(), 40, rule);  // two calls fill one batch
        batch.push_points(x.data() + 40, y.data() + 40, kBatch - 40, rule);
        for (const Field2D* f : {&label, &noise}) {
          std::array<double, kBatch> out{};
          batch.apply(*f, out.data());
          for (std::size_t q = 0; q < kBatch; ++q) {
            const double expected = interpolation_stencil(g, x[q], y[q], rule).apply(*f);
            ASSERT_EQ(std::memcmp(&out[q], &expected, sizeof(double)), 0)
                << "point (" << x[q] << ", " << y[q] << "): " << out[q] << " vs " << expected;
          }
        }
      }
    }
  }
}

TEST(Deposition, BatchMakesTheStencilsOfDepositStencil) {
  // deposit_stencils (vector loops, the coupling's) against deposit_stencil one point at a
  // time, bit for bit, on a stretched grid and on one whose buckets hold several cells.
  for (const Grid2D& g : {stretched_grid(), Grid2D(Axis({0.0, 1e-9, 2e-9, 3e-9, 4e-9, 0.5, 1.0}, 2), Axis({0.0, 0.2, 0.7, 1.0}, 2))}) {
    std::mt19937 rng(17);
    const double lx = g.x().end() - g.x().start(), ly = g.y().end() - g.y().start();
    std::uniform_real_distribution<double> ux(g.x().start() - 0.05 * lx, g.x().end() + 0.05 * lx),
        uy(g.y().start() - 0.05 * ly, g.y().end() + 0.05 * ly);
    const std::size_t n = 1000;  // several blocks of 256
    std::vector<double> x(n), y(n);
    for (std::size_t k = 0; k < n; ++k) {
      x[k] = ux(rng);
      y[k] = uy(rng);
    }
    for (double width : {0.0, 1e-4, 4e-4, 0.05}) {
      std::vector<DepositStencil> batch(n);
      deposit_stencils(g, x.data(), y.data(), width, batch.data(), n);
      for (std::size_t k = 0; k < n; ++k) {
        const DepositStencil one = deposit_stencil(g, x[k], y[k], width);
        ASSERT_EQ(batch[k].count, one.count) << "point " << k << ", width " << width;
        for (int m = 0; m < one.count; ++m) {
          EXPECT_EQ(batch[k].i[m], one.i[m]);
          EXPECT_EQ(batch[k].j[m], one.j[m]);
          EXPECT_EQ(std::memcmp(&batch[k].fraction[m], &one.fraction[m], sizeof(double)), 0);
        }
      }
    }
  }
}

TEST(Deposition, ConservesTheDepositedSum) {
  const Grid2D g = stretched_grid();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ux(g.x().start(), g.x().end()), uy(g.y().start(), g.y().end());
  for (double width : {0.0, 1e-4, 4e-4}) {
    Field2D sum(g);
    double total = 0.0;
    for (int k = 0; k < 5000; ++k) {
      const double x = ux(rng), y = uy(rng), q = 1.0 + (k % 7);
      const auto d = deposit_stencil(g, x, y, width);
      ASSERT_GE(d.count, 1);
      double fsum = 0.0;
      for (int m = 0; m < d.count; ++m) {
        ASSERT_GE(d.i[m], 0);
        ASSERT_LT(d.i[m], g.nx());
        ASSERT_GE(d.j[m], 0);
        ASSERT_LT(d.j[m], g.ny());
        sum(d.i[m], d.j[m]) += q * d.fraction[m];
        fsum += d.fraction[m];
      }
      EXPECT_NEAR(fsum, 1.0, 1e-14);
      total += q;
    }
    double deposited = 0.0;
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) deposited += sum(i, j);
    EXPECT_NEAR(deposited, total, 1e-10 * total) << "width " << width;
  }
}

TEST(Deposition, SquareOverlapSplitsByArea) {
  // Uniform 1 mm cells; a 0.4 mm square centred on a vertical face at x = 1 mm, inside row 0.
  const Grid2D g(AxisSpec{0.0, 0.004, 4}, AxisSpec{0.0, 0.004, 4}, 2);
  const auto d = deposit_stencil(g, 0.001, 0.0005, 4e-4);
  double left = 0, right = 0;
  for (int m = 0; m < d.count; ++m) (d.i[m] == 0 ? left : right) += d.fraction[m];
  EXPECT_NEAR(left, 0.5, 1e-12);
  EXPECT_NEAR(right, 0.5, 1e-12);
  const auto c = deposit_stencil(g, 0.0013, 0.0013, 0.0);
  EXPECT_EQ(c.count, 1);
  EXPECT_EQ(c.i[0], 1);
  EXPECT_EQ(c.j[0], 1);
}
