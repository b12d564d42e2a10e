#pragma once
// The channel cut into x-slabs, one per MPI rank: where the cuts go, and the
// copies between a slab's fields and the whole grid's (gathers for output, restarts).
#include <span>
#include <vector>

#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"

namespace dustlift {

/// Column bounds b[0] = 0 < b[1] < ... < b[parts] = columns: slab r holds columns
/// [b[r], b[r+1]). Each cut is placed where the running cost first reaches r/parts of the
/// total (cost per column, e.g. its cells plus weighted active parcels), and every slab keeps
/// at least `min_columns` columns (the stencil needs its neighbours' edge columns to be
/// interior cells). Throws std::invalid_argument when columns < parts * min_columns.
std::vector<int> balanced_slabs(std::span<const double> column_cost, int parts, int min_columns);

/// Where one rank's slab lies in the whole grid.
struct SlabLayout {
  std::vector<int> bounds;  ///< balanced_slabs' bounds, one slab per rank
  int rank = 0;
  bool periodic_x = false;  ///< the x-ends are joined: the first and last slabs are neighbours

  int ranks() const { return static_cast<int>(bounds.size()) - 1; }
  int first_column() const { return bounds[static_cast<std::size_t>(rank)]; }
  int end_column() const { return bounds[static_cast<std::size_t>(rank) + 1]; }
  int columns() const { return end_column() - first_column(); }
  /// Neighbouring ranks (-1 at a domain end that is not periodic; with one rank, -1 too:
  /// a periodic one-rank grid wraps through its own boundary conditions).
  int left() const;
  int right() const;
  bool owns_left_boundary() const { return left() < 0; }
  bool owns_right_boundary() const { return right() < 0; }
  /// The columns of the slab's field (ghosts included) that hold the whole grid's state:
  /// the interior, and the ghost columns beyond a domain end (filled by the boundary
  /// conditions, or across a periodic join by the exchange: the same values either way).
  int stored_begin(int ghosts) const { return rank == 0 ? -ghosts : 0; }
  int stored_end(int ghosts) const { return columns() + (rank + 1 == ranks() ? ghosts : 0); }
  /// The same decomposition seen from rank r.
  SlabLayout of_rank(int r) const { return {bounds, r, periodic_x}; }
};

/// The slab's part of a whole-grid field (all rows, ghost rows included; `stored_begin` to
/// `stored_end` of the slab's columns) as one array, row by row.
std::vector<double> pack_slab(const Field2D& slab, const Grid2D& slab_grid,
                              const SlabLayout& layout);
/// Puts what pack_slab gave on the rank of `layout` into the whole grid's field.
void unpack_slab(std::span<const double> piece, const Grid2D& whole, const SlabLayout& layout,
                 std::vector<double>& whole_field);
/// The slab's field, ghost columns included, copied from the whole grid's (a restart, a move
/// of the cuts): beyond a domain end its ghost columns are the whole grid's ghost columns.
void extract_slab(std::span<const double> whole_field, const Grid2D& whole,
                  const SlabLayout& layout, std::vector<double>& slab_field);

}  // namespace dustlift
