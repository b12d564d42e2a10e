#include "solver/sim/derived_fields.hpp"

#include "solver/core/derivatives.hpp"

namespace dustlift {

void DerivedFields::show(const Grid2D* grid, const GasPrimitives& gas, const Field2D* alpha_p,
                         double particle_density, long long step) {
  if (grid != grid_ || gas.u != gas_.u || gas.v != gas_.v || alpha_p != alpha_p_ ||
      particle_density != particle_density_)
    step_ = -1;  // another state entirely
  if (step != step_) vorticity_step_ = concentration_step_ = -2;
  grid_ = grid;
  gas_ = gas;
  alpha_p_ = alpha_p;
  particle_density_ = particle_density;
  step_ = step;
}

namespace {
/// Sizes `f` to the grid once (a field keeps its storage between steps).
void fit(Field2D& f, int& nx, int& ny, const Grid2D& grid) {
  if (nx != grid.nx() || ny != grid.ny()) {
    f = Field2D(grid);
    nx = grid.nx();
    ny = grid.ny();
  }
}
}  // namespace

const Field2D& DerivedFields::vorticity() const {
  if (vorticity_step_ != step_ || step_ < 0) {
    fit(vorticity_, vorticity_nx_, vorticity_ny_, *grid_);
    vorticity_z_rows(*grid_, *gas_.u, *gas_.v, 0, grid_->ny(), vorticity_);
    vorticity_step_ = step_;
  }
  return vorticity_;
}

void fill_dust_concentration(const Grid2D& grid, const Field2D* alpha_p, double particle_density,
                             Field2D& out) {
  for (int j = 0; j < grid.ny(); ++j)
    for (int i = 0; i < grid.nx(); ++i)
      out(i, j) = alpha_p != nullptr ? particle_density * (*alpha_p)(i, j) : 0.0;
}

const Field2D& DerivedFields::dust_concentration() const {
  if (concentration_step_ != step_ || step_ < 0) {
    fit(concentration_, concentration_nx_, concentration_ny_, *grid_);
    fill_dust_concentration(*grid_, alpha_p_, particle_density_, concentration_);
    concentration_step_ = step_;
  }
  return concentration_;
}

}  // namespace dustlift
