#pragma once
// Fields an observer reads from a state view beyond the stored gas state.
#include "solver/core/field.hpp"
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

}  // namespace dustlift
