#pragma once
// Fields made from the state for the observers, at most once per step of the view that shows
// them: the VTK writer, Catalyst and the near-layer series read the same vorticity.
#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"
#include "solver/gas/gas_solver.hpp"

namespace dustlift {

class DerivedFields {
 public:
  /// What the view shows now (its grid and gas, at `step`); what was made for another step
  /// or grid is forgotten.
  void show(const Grid2D* grid, const GasPrimitives& gas, long long step);
  /// Forgets what was made (the state changed without a step: a restore).
  void forget() { step_ = -1; }
  /// w_z = dv/dx - du/dy on the interior cells (derivatives.hpp). On an MPI rank's slab the
  /// derivatives at its cuts read the ghost columns, which hold the neighbours' cells: the
  /// values are the whole grid's.
  const Field2D& vorticity() const;

 private:
  const Grid2D* grid_ = nullptr;
  GasPrimitives gas_{};
  long long step_ = -1;
  mutable Field2D vorticity_;
  mutable long long vorticity_step_ = -2;
  mutable int vorticity_nx_ = -1, vorticity_ny_ = -1;
};

}  // namespace dustlift
