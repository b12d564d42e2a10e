#pragma once
// What the coupling needs from a domain decomposition: an MPI rank holds an x-slab of the grid
// (Grid2D::slice_x) and this fills the ghost columns of the coupling's fields that it shares
// with its neighbours (solver/parallel/slab_halo.hpp implements it). The gas solver's own
// ghosts go through GhostFiller (ghost_filler.hpp).
#include <span>

#include "solver/core/field.hpp"

namespace dustlift {

class GasHalo {
 public:
  virtual ~GasHalo() = default;
  /// Whether this slab's left (right) end is the domain's own: the boundary conditions fill
  /// the ghosts there; elsewhere exchange_columns() does.
  virtual bool owns_left_boundary() const = 0;
  virtual bool owns_right_boundary() const = 0;
  /// Collective: every field's ghost columns at the shared ends, all rows including the ghost
  /// rows, take the neighbouring slab's edge columns (its interior cells, y-ghosts filled).
  virtual void exchange_columns(std::span<Field2D* const> fields) = 0;
};

}  // namespace dustlift
