// The x-slab decomposition without MPI: where the cuts go, the slab's axis, and
// the copies between a slab's fields and the whole grid's.
#include <gtest/gtest.h>

#include <numeric>
#include <stdexcept>

#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"
#include "solver/core/communicator.hpp"
#include "solver/parallel/slab_decomposition.hpp"

namespace dustlift {
namespace {

TEST(SlabDecomposition, EqualCostsGiveEqualSlabs) {
  const std::vector<double> cost(1900, 160.0);  // the paper grid's columns
  EXPECT_EQ(balanced_slabs(cost, 2, 2), (std::vector<int>{0, 950, 1900}));
  EXPECT_EQ(balanced_slabs(cost, 4, 2), (std::vector<int>{0, 475, 950, 1425, 1900}));
  EXPECT_EQ(balanced_slabs(cost, 1, 2), (std::vector<int>{0, 1900}));
}

TEST(SlabDecomposition, CutsFollowTheCost) {
  // Columns 0..99 cost 1, columns 100..199 cost 3 (parcels there): the total is 400, and
  // half of it is reached 33 1/3 columns into the costly part, so the cut is at column 133
  // (the first column whose middle lies past the half).
  std::vector<double> cost(200, 1.0);
  for (int i = 100; i < 200; ++i) cost[static_cast<std::size_t>(i)] = 3.0;
  EXPECT_EQ(balanced_slabs(cost, 2, 2), (std::vector<int>{0, 133, 200}));
  // A cost all in the last columns still leaves every slab its minimum.
  std::vector<double> spike(100, 0.0);
  spike[99] = 1000.0;
  const std::vector<int> b = balanced_slabs(spike, 4, 3);
  ASSERT_EQ(b.size(), 5u);
  for (int r = 0; r < 4; ++r)
    EXPECT_GE(b[static_cast<std::size_t>(r) + 1] - b[static_cast<std::size_t>(r)], 3) << r;
  EXPECT_THROW(balanced_slabs(std::vector<double>(5, 1.0), 3, 2), std::invalid_argument);
}

TEST(SlabDecomposition, NeighboursAndStoredColumns) {
  SlabLayout l{{0, 10, 20, 30}, 0, false};
  EXPECT_EQ(l.left(), -1);
  EXPECT_EQ(l.right(), 1);
  EXPECT_EQ(l.of_rank(2).right(), -1);
  EXPECT_EQ(l.of_rank(1).stored_begin(2), 0);
  EXPECT_EQ(l.stored_begin(2), -2);
  EXPECT_EQ(l.of_rank(2).stored_end(2), 12);
  l.periodic_x = true;
  EXPECT_EQ(l.left(), 2);
  EXPECT_EQ(l.of_rank(2).right(), 0);
  EXPECT_FALSE(l.owns_left_boundary());
  // One rank owns both ends even when periodic (its boundary conditions wrap).
  EXPECT_TRUE((SlabLayout{{0, 30}, 0, true}).owns_left_boundary());
}

TEST(SlabDecomposition, SliceKeepsEveryFaceOfTheWholeAxis) {
  // The paper's x-axis: stretched upstream, uniform after x = 0.
  AxisSpec x;
  x.start = -0.4;
  x.end = 0.4;
  x.cell_size = 250e-6;
  x.uniform_start = 0.0;
  x.uniform_end = 0.4;
  x.cells_below = 300;
  const Axis whole(build_axis_nodes(x), 2);
  for (const auto& [i0, i1] : {std::pair{0, 950}, std::pair{950, 1900}, std::pair{290, 310}}) {
    const Axis s = whole.slice(i0, i1);
    ASSERT_EQ(s.cells(), i1 - i0);
    for (int i = -2; i <= s.cells() + 2; ++i)
      ASSERT_EQ(s.face(i), whole.face(i + i0)) << i0 << " " << i;
    for (int i = -2; i < s.cells() + 2; ++i) {
      ASSERT_EQ(s.center(i), whole.center(i + i0));
      ASSERT_EQ(s.width(i), whole.width(i + i0));
    }
    for (int k = 0; k < s.cells(); ++k) {
      const auto& a = s.derivative_stencil(k);
      const auto& b = whole.derivative_stencil(k + i0);
      ASSERT_EQ(a.first + i0, b.first);
      ASSERT_EQ(a.w0, b.w0);
      ASSERT_EQ(a.w2, b.w2);
      EXPECT_EQ(s.locate(s.center(k)), k);
    }
  }
  EXPECT_THROW((void)whole.slice(10, 10), std::invalid_argument);
  EXPECT_THROW((void)whole.slice(0, 1901), std::invalid_argument);
}

TEST(SlabDecomposition, PackUnpackAndExtractRebuildTheWholeField) {
  const Grid2D whole(AxisSpec{0.0, 1.0, 12}, AxisSpec{0.0, 0.5, 3}, 2);
  Field2D field(whole);
  std::iota(field.raw().begin(), field.raw().end(), 1.0);  // every cell its own value
  for (bool periodic : {false, true}) {
    const SlabLayout layout{{0, 5, 12}, 0, periodic};
    std::vector<double> rebuilt(whole.size_with_ghosts(), -1.0);
    for (int r = 0; r < 2; ++r) {
      const SlabLayout mine = layout.of_rank(r);
      const Grid2D slab = whole.slice_x(mine.first_column(), mine.end_column());
      Field2D piece(slab);
      extract_slab(field.raw(), whole, mine, piece.raw());
      // The slab's cells, ghosts included, are the whole grid's: beyond a domain end its own
      // ghost columns (not a periodic wrap: those hold what one rank holds there).
      for (int j = -2; j < 5; ++j) {
        for (int i = -2; i < slab.nx() + 2; ++i) {
          ASSERT_EQ(piece(i, j), field(i + mine.first_column(), j))
              << periodic << " " << r << " " << i << " " << j;
        }
      }
      unpack_slab(pack_slab(piece, slab, mine), whole, mine, rebuilt);
    }
    // Gathered back, every cell and every ghost of the whole grid.
    EXPECT_EQ(rebuilt, field.raw()) << periodic;
  }
}

TEST(SlabDecomposition, ASingleRankWorldWithoutMpi) {
  const SingleRank one;
  EXPECT_EQ(one.size(), 1);
  EXPECT_EQ(one.min(3.5), 3.5);
  EXPECT_EQ(one.first_nonempty("x"), "x");
  std::vector<std::vector<double>> pieces;
  one.gather(std::vector<double>{1.0, 2.0}, pieces);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0], (std::vector<double>{1.0, 2.0}));
  std::vector<std::vector<double>> received;
  one.exchange({{3.0, 4.0}}, received);  // to itself
  ASSERT_EQ(received.size(), 1u);
  EXPECT_EQ(received[0], (std::vector<double>{3.0, 4.0}));
}

}  // namespace
}  // namespace dustlift
