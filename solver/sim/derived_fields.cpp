#include "solver/sim/derived_fields.hpp"

#include <stdexcept>
#include <string>

namespace dustlift {

void DerivedFields::show(const Grid2D* grid, const GasPrimitives& gas, const Field2D* alpha_p,
                         double particle_density, long long step) {
  if (grid != inputs_.grid || gas.u != inputs_.gas.u || gas.v != inputs_.gas.v ||
      alpha_p != inputs_.alpha_p || particle_density != inputs_.particle_density)
    step_ = -1;  // another state entirely
  if (step != step_)
    for (Made& m : made_) m.step = -2;
  inputs_.grid = grid;
  inputs_.gas = gas;
  inputs_.alpha_p = alpha_p;
  inputs_.particle_density = particle_density;
  step_ = step;
}

const Field2D& DerivedFields::field(std::size_t index) const {
  const GasField& f = gas_fields()[index];
  if (f.made != GasFieldMade::OncePerStep)
    throw std::invalid_argument("gas field " + std::string(f.name) + " is not made per step");
  if (made_.size() != gas_fields().size()) made_.resize(gas_fields().size());
  Made& m = made_[index];
  if (m.step != step_ || step_ < 0) {
    const Grid2D& grid = *inputs_.grid;
    if (m.nx != grid.nx() || m.ny != grid.ny()) {  // sized once: the storage is kept
      m.values = Field2D(grid);
      m.nx = grid.nx();
      m.ny = grid.ny();
    }
    f.make(inputs_, m.values);
    m.step = step_;
  }
  return m.values;
}

}  // namespace dustlift
