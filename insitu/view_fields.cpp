#include "insitu/view_fields.hpp"

#include "solver/core/derivatives.hpp"
#include "solver/sim/derived_fields.hpp"

namespace dustlift {

const Field2D& vorticity_of(const StateView& view, Field2D& scratch) {
  if (view.derived != nullptr) return view.derived->vorticity();
  const Grid2D& g = *view.grid;
  if (scratch.size() != g.size_with_ghosts()) scratch = Field2D(g);
  vorticity_z_rows(g, *view.primitives.u, *view.primitives.v, 0, g.ny(), scratch);
  return scratch;
}

const Field2D& dust_concentration_of(const StateView& view, Field2D& scratch) {
  if (view.derived != nullptr) return view.derived->dust_concentration();
  const Grid2D& g = *view.grid;
  if (scratch.size() != g.size_with_ghosts()) scratch = Field2D(g);
  const double rho_p =
      view.scene != nullptr && view.scene->particles.enabled ? view.scene->particles.density : 0.0;
  fill_dust_concentration(g, view.alpha_p, rho_p, scratch);
  return scratch;
}

}  // namespace dustlift
