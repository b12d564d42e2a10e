#pragma once
// Fields made from the state for the observers, at most once per step of the view that shows
// them: the VTK writer, Catalyst, the near-layer and dust-cloud series read the same vorticity
// and dust concentration.
#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"
#include "solver/gas/gas_solver.hpp"

namespace dustlift {

/// Dust concentration c = rho_p alpha_p (kg/m^3) on the interior cells of `grid` into `out`
/// (a field of that grid); zeros when `alpha_p` is null (a gas-only scene).
void fill_dust_concentration(const Grid2D& grid, const Field2D* alpha_p, double particle_density,
                             Field2D& out);

class DerivedFields {
 public:
  /// What the view shows now (its grid, gas and deposited alpha_p, at `step`; alpha_p null in
  /// a gas-only scene, `particle_density` the real particles' kg/m^3); what was made for
  /// another step or grid is forgotten.
  void show(const Grid2D* grid, const GasPrimitives& gas, const Field2D* alpha_p,
            double particle_density, long long step);
  /// Forgets what was made (the state changed without a step: a restore).
  void forget() { step_ = -1; }
  /// w_z = dv/dx - du/dy on the interior cells (derivatives.hpp). On an MPI rank's slab the
  /// derivatives at its cuts read the ghost columns, which hold the neighbours' cells: the
  /// values are the whole grid's.
  const Field2D& vorticity() const;
  /// Dust concentration c = rho_p alpha_p (kg of real particles per m^3 of space) on the
  /// interior cells, from the deposit the coupling made (eq. 12); zero in a gas-only scene.
  const Field2D& dust_concentration() const;

 private:
  const Grid2D* grid_ = nullptr;
  GasPrimitives gas_{};
  const Field2D* alpha_p_ = nullptr;
  double particle_density_ = 0.0;
  long long step_ = -1;
  mutable Field2D vorticity_;
  mutable long long vorticity_step_ = -2;
  mutable int vorticity_nx_ = -1, vorticity_ny_ = -1;
  mutable Field2D concentration_;
  mutable long long concentration_step_ = -2;
  mutable int concentration_nx_ = -1, concentration_ny_ = -1;
};

}  // namespace dustlift
