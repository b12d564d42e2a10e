#pragma once
// What the gas solver needs from a domain decomposition (issue 12): an MPI rank holds an
// x-slab of the grid (Grid2D::slice_x) and this fills the ghost columns it shares with its
// neighbours. The interface keeps MPI out of the gas solver (solver/parallel/ implements it).
#include <span>
#include <string>

#include "solver/core/field.hpp"

namespace dustlift {

class GasHalo {
 public:
  virtual ~GasHalo() = default;
  /// Whether this slab's left (right) end is the domain's own: the boundary conditions fill
  /// the ghosts there; elsewhere exchange_columns() does.
  virtual bool owns_left_boundary() const = 0;
  virtual bool owns_right_boundary() const = 0;
  /// Index in the whole grid of the slab's column 0 (for messages that name a cell).
  virtual int first_column() const = 0;
  /// Collective: every field's ghost columns at the shared ends, all rows including the ghost
  /// rows, take the neighbouring slab's edge columns (its interior cells, y-ghosts filled).
  virtual void exchange_columns(std::span<Field2D* const> fields) = 0;
  /// Collective: the failure of the lowest-numbered rank that reports one, "" when none does,
  /// so that a blow-up on one rank stops every rank with the same message.
  virtual std::string first_failure(const std::string& local) = 0;
};

}  // namespace dustlift
