#pragma once
// Fields an observer reads from a state view beyond the stored gas state.
#include <cstddef>
#include <string_view>
#include <vector>

#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"
#include "solver/sim/observer.hpp"

namespace dustlift {

/// The gas field `name` made once per step (gas_fields.hpp) for what the view shows: the
/// run's DerivedFields (StateView::derived), shared by every observer that reads it. Throws
/// std::invalid_argument for a view without them.
const Field2D& derived_field(const StateView& view, std::string_view name);

/// Copies the interior cells of `f` into `out` (x fastest: index i + nx j, the series' and
/// filters' layout); `transform` maps each value.
template <class Transform>
void interior_values(const Grid2D& grid, const Field2D& f, std::vector<double>& out,
                     Transform transform) {
  out.resize(grid.interior_cells());
  for (int j = 0; j < grid.ny(); ++j)
    for (int i = 0; i < grid.nx(); ++i)
      out[static_cast<std::size_t>(i) + static_cast<std::size_t>(grid.nx()) * j] =
          transform(f(i, j));
}
inline void interior_values(const Grid2D& grid, const Field2D& f, std::vector<double>& out) {
  interior_values(grid, f, out, [](double v) { return v; });
}

}  // namespace dustlift
