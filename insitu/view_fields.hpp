#pragma once
// Fields an observer reads from a state view beyond the stored gas state.
#include <cstddef>
#include <vector>

#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"
#include "solver/sim/observer.hpp"

namespace dustlift {

/// The vorticity of what the view shows: the run's derived field (made once per step,
/// StateView::derived), or for a view made by hand, made here into `scratch`. On an MPI
/// rank's slab the derivatives at the cuts read the ghost columns, which hold the
/// neighbours' cells, so every piece holds the one-rank values.
const Field2D& vorticity_of(const StateView& view, Field2D& scratch);

/// The dust concentration rho_p alpha_p (kg/m^3) of what the view shows, made once per step
/// like the vorticity (or into `scratch` for a view made by hand); zeros without parcels.
const Field2D& dust_concentration_of(const StateView& view, Field2D& scratch);

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
