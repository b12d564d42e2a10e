#pragma once
// Where the gas solver's ghost cells get their values: one filler per side of the grid. A
// side's own boundary condition (boundary_fillers.hpp: a wall, inflow or outflow, or the
// periodic copy of the opposite side) fills it from this grid's cells; where the grid is one
// part of a larger one, the filler copies the neighbouring part's cells instead (another
// process's: solver/parallel/slab_halo.hpp). The solver knows only this interface.
#include <array>
#include <cstddef>

#include "solver/core/field.hpp"
#include "solver/gas/gas_components.hpp"

namespace dustlift {

enum class GridSide { Left, Right, Bottom, Top };
inline constexpr std::array<GridSide, 4> kGridSides = {GridSide::Left, GridSide::Right,
                                                       GridSide::Bottom, GridSide::Top};
constexpr std::size_t side_index(GridSide s) {
  return static_cast<std::size_t>(s);
}
constexpr bool is_x_side(GridSide s) {
  return s == GridSide::Left || s == GridSide::Right;
}

/// One fill of the primitive state's ghosts.
struct PrimitiveGhosts {
  std::array<Field2D*, Primitive::kCount> fields;  ///< rho, u, v, p, T
  /// Per interior row j, the cells [updated_lo[j], updated_hi[j]) the solver's last stage
  /// updated (none when lo >= hi); null when it does not skip resting cells or agrees its
  /// ranges with the other parts (RestAgreement).
  const int* updated_lo = nullptr;
  const int* updated_hi = nullptr;
};

class GhostFiller {
 public:
  virtual ~GhostFiller() = default;

  /// False: the ghosts come from this grid's own cells; fill() is called by every thread of
  /// a parallel region (or outside one), shares its rows or columns out with `omp for
  /// nowait`, and the solver waits for all sides before it reads a ghost. True: they come
  /// from another process, so every process calls fill() at the same points, outside any
  /// parallel region, after its local sides; it sets every row, the ghost rows included (the
  /// corners are then the other process's). A collective filler serves the x-sides only and
  /// is called once per fill when it serves both.
  virtual bool collective() const { return false; }

  /// Sets the primitive state's ghost cells beyond the side(s) this filler serves.
  virtual void fill(const PrimitiveGhosts& ghosts) = 0;
  /// Sets the porosity's (alpha_g) ghost cells.
  virtual void fill_porosity(Field2D& alpha) = 0;

  /// After a fill of the primitives, for an x-side: whether the cells that the ghosts of rows
  /// [j0, j1) were copied from were updated by their own solver's last stage (another
  /// process's filler sends those ranges with the fill). Ghosts from this grid's own cells:
  /// false (the solver tracks its own updates).
  virtual bool changed_beyond(GridSide /*side*/, int /*j0*/, int /*j1*/) const { return false; }
};

}  // namespace dustlift
