#include "solver/parallel/slab_decomposition.hpp"

#include <stdexcept>
#include <string>

namespace dustlift {

std::vector<int> balanced_slabs(std::span<const double> column_cost, int parts, int min_columns) {
  const int n = static_cast<int>(column_cost.size());
  if (parts < 1) throw std::invalid_argument("slab decomposition: needs at least one part");
  if (min_columns < 1) min_columns = 1;
  if (n < parts * min_columns) {
    throw std::invalid_argument("slab decomposition: " + std::to_string(n) +
                                " columns cannot give " + std::to_string(parts) + " ranks " +
                                std::to_string(min_columns) + " columns each; use fewer ranks");
  }
  double total = 0.0;
  for (double c : column_cost) total += c;
  std::vector<int> bounds(static_cast<std::size_t>(parts) + 1, 0);
  bounds.back() = n;
  double running = 0.0;
  int i = 0;
  for (int r = 1; r < parts; ++r) {
    const double target = total * static_cast<double>(r) / static_cast<double>(parts);
    // At least min_columns after the previous cut, and room for the slabs still to come.
    const int lowest = bounds[static_cast<std::size_t>(r) - 1] + min_columns;
    const int highest = n - (parts - r) * min_columns;
    while (i < highest &&
           (i < lowest || running + column_cost[static_cast<std::size_t>(i)] * 0.5 < target)) {
      running += column_cost[static_cast<std::size_t>(i)];
      ++i;
    }
    bounds[static_cast<std::size_t>(r)] = i;
  }
  return bounds;
}

int SlabLayout::left() const {
  if (ranks() == 1) return -1;
  if (rank > 0) return rank - 1;
  return periodic_x ? ranks() - 1 : -1;
}

int SlabLayout::right() const {
  if (ranks() == 1) return -1;
  if (rank + 1 < ranks()) return rank + 1;
  return periodic_x ? 0 : -1;
}

std::vector<double> pack_slab(const Field2D& slab, const Grid2D& slab_grid,
                              const SlabLayout& layout) {
  const int ng = slab_grid.ghosts();
  const int i0 = layout.stored_begin(ng), i1 = layout.stored_end(ng);
  std::vector<double> piece;
  piece.reserve(static_cast<std::size_t>(i1 - i0) *
                static_cast<std::size_t>(slab_grid.ny() + 2 * ng));
  for (int j = -ng; j < slab_grid.ny() + ng; ++j) {
    const double* row = slab.data() + slab_grid.index(0, j);
    piece.insert(piece.end(), row + i0, row + i1);
  }
  return piece;
}

void unpack_slab(std::span<const double> piece, const Grid2D& whole, const SlabLayout& layout,
                 std::vector<double>& whole_field) {
  const int ng = whole.ghosts();
  const int i0 = layout.stored_begin(ng), i1 = layout.stored_end(ng);
  const auto width = static_cast<std::size_t>(i1 - i0);
  if (piece.size() != width * static_cast<std::size_t>(whole.ny() + 2 * ng) ||
      whole_field.size() != whole.size_with_ghosts()) {
    throw std::invalid_argument("unpack_slab: the piece does not fit the slab");
  }
  std::size_t k = 0;
  for (int j = -ng; j < whole.ny() + ng; ++j, k += width) {
    std::copy(piece.begin() + static_cast<std::ptrdiff_t>(k),
              piece.begin() + static_cast<std::ptrdiff_t>(k + width),
              whole_field.begin() +
                  static_cast<std::ptrdiff_t>(whole.index(layout.first_column() + i0, j)));
  }
}

void extract_slab(std::span<const double> whole_field, const Grid2D& whole,
                  const SlabLayout& layout, std::vector<double>& slab_field) {
  const int ng = whole.ghosts();
  const int width = layout.columns() + 2 * ng;
  slab_field.resize(static_cast<std::size_t>(width) *
                    static_cast<std::size_t>(whole.ny() + 2 * ng));
  // Columns beyond the domain's ends are the whole grid's own ghost columns, periodic or not:
  // they hold what one rank holds there (for the primitives the periodic copy, for the
  // conserved variables, which no stencil reads there, what they were left at), so a gather
  // gives back the one-rank arrays bit for bit.
  std::size_t k = 0;
  for (int j = -ng; j < whole.ny() + ng; ++j) {
    for (int i = -ng; i < layout.columns() + ng; ++i, ++k) {
      const int g = layout.first_column() + i;
      slab_field[k] = whole_field[whole.index(g, j)];
    }
  }
}

}  // namespace dustlift
