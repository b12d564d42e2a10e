#pragma once
// The ghost fillers of a grid's own sides, one per boundary condition (BoundaryKind): walls,
// inflow and outflow fill the ghosts from the cells next to the side or from the inflow
// state (PhysicalBoundary); a periodic side copies the opposite side's cells
// (PeriodicBoundary). The y-sides fill every column, the x-sides' ghost columns included, so
// the x-sides are filled first (the corners come from their ghosts).
#include <cstddef>
#include <memory>
#include <vector>

#include "solver/core/grid.hpp"
#include "solver/gas/gas_config.hpp"
#include "solver/gas/ghost_filler.hpp"

namespace dustlift {

/// The boundary kind of `side`.
BoundaryKind boundary_kind(const BoundaryConfig& b, GridSide side);

/// One side's cells as indices into a field of the grid: line `line` (a row of an x-side, a
/// column of a y-side) and `k` cells across (0 .. n-1 the interior, ghost(g) ghost layer g).
struct SideCells {
  SideCells(GridSide side, const Grid2D& grid);

  bool low;                      ///< the left or the bottom side
  int n;                         ///< interior cells across the side (nx for an x-side)
  int ghosts;                    ///< ghost layers
  int line_begin, line_end;      ///< rows [0, ny) of an x-side, columns [-ng, nx + ng) of a y-side
  std::ptrdiff_t origin;         ///< index of cell (0, 0)
  std::ptrdiff_t along, across;  ///< index steps from line to line and from cell to cell across

  std::size_t cell(int line, int k) const {
    return static_cast<std::size_t>(origin + line * along + k * across);
  }
  /// The index across of ghost layer g (0 next to the interior).
  int ghost(int g) const { return low ? -1 - g : n + g; }
};

/// A wall (slip: the normal velocity mirrored; no-slip: both components), an inflow (the
/// state given per line) or an outflow (the last interior cell copied). The porosity is
/// mirrored at each of them (zero normal gradient).
class PhysicalBoundary final : public GhostFiller {
 public:
  /// `inflow`: the state an Inflow side imposes, one per row of an x-side or per interior
  /// column of a y-side (the corner columns take the nearest); unused by the other kinds.
  PhysicalBoundary(GridSide side, BoundaryKind kind, const Grid2D& grid, double gas_constant,
                   std::vector<PrimitiveState> inflow);
  void fill(const PrimitiveGhosts& ghosts) override;
  void fill_porosity(Field2D& alpha) override;

 private:
  SideCells cells_;
  BoundaryKind kind_;
  double su_, sv_;  ///< signs of u and v in a ghost cell against its mirror cell
  double gas_constant_;
  std::vector<PrimitiveState> inflow_;
};

/// The opposite side's interior cells, in order: ghost layer g beyond the high end is cell
/// g, beyond the low end cell n-1-g (wrapped when the grid is thinner than the ghosts).
class PeriodicBoundary final : public GhostFiller {
 public:
  PeriodicBoundary(GridSide side, const Grid2D& grid);
  void fill(const PrimitiveGhosts& ghosts) override;
  void fill_porosity(Field2D& alpha) override;

 private:
  int source(int g) const;
  SideCells cells_;
};

/// The filler of `side` for its boundary kind (see PhysicalBoundary for `inflow`).
std::unique_ptr<GhostFiller> make_boundary_filler(GridSide side, BoundaryKind kind,
                                                  const Grid2D& grid, double gas_constant,
                                                  std::vector<PrimitiveState> inflow);

}  // namespace dustlift
