#include "solver/sim/derived_fields.hpp"

#include "solver/core/derivatives.hpp"

namespace dustlift {

void DerivedFields::show(const Grid2D* grid, const GasPrimitives& gas, long long step) {
  if (grid != grid_ || gas.u != gas_.u || gas.v != gas_.v) step_ = -1;  // another state entirely
  if (step != step_) vorticity_step_ = -2;
  grid_ = grid;
  gas_ = gas;
  step_ = step;
}

const Field2D& DerivedFields::vorticity() const {
  if (vorticity_step_ != step_ || step_ < 0) {
    if (vorticity_nx_ != grid_->nx() || vorticity_ny_ != grid_->ny()) {
      vorticity_ = Field2D(*grid_);
      vorticity_nx_ = grid_->nx();
      vorticity_ny_ = grid_->ny();
    }
    vorticity_z_rows(*grid_, *gas_.u, *gas_.v, 0, grid_->ny(), vorticity_);
    vorticity_step_ = step_;
  }
  return vorticity_;
}

}  // namespace dustlift
