#pragma once
// The gas fields made once per step (gas_fields.hpp: GasFieldMade::OncePerStep), at most once
// per step of the view that shows them: the VTK writer, Catalyst, the near-layer and
// dust-cloud series read the same vorticity and dust concentration.
#include <string_view>
#include <vector>

#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"
#include "solver/gas/gas_solver.hpp"
#include "solver/sim/gas_fields.hpp"

namespace dustlift {

class DerivedFields {
 public:
  /// What the view shows now (its grid, gas and deposited alpha_p, at `step`; alpha_p null in
  /// a gas-only scene, `particle_density` the real particles' kg/m^3); what was made for
  /// another step or grid is forgotten.
  void show(const Grid2D* grid, const GasPrimitives& gas, const Field2D* alpha_p,
            double particle_density, long long step);
  /// Forgets what was made (the state changed without a step: a restore).
  void forget() { step_ = -1; }
  /// What the fields are made from (no sound speed: the writer that needs one adds it).
  const GasFieldInputs& inputs() const { return inputs_; }
  /// The field of gas_fields() entry `index` (one made once per step) on the interior cells.
  const Field2D& field(std::size_t index) const;
  /// The same by name.
  const Field2D& field(std::string_view name) const { return field(gas_field_index(name)); }

 private:
  /// One field of the registry as made: its storage is kept between steps.
  struct Made {
    Field2D values;
    long long step = -2;
    int nx = -1, ny = -1;
  };
  GasFieldInputs inputs_;
  long long step_ = -1;
  mutable std::vector<Made> made_;  ///< per gas_fields() entry
};

}  // namespace dustlift
