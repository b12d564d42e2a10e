#pragma once
// Observers read the simulation at output times through a read-only StateView.
// insitu/ implements them (VTK writers, filters, series); the solver never
// includes insitu/ headers, VTK or HDF5.
#include <string>

#include "solver/core/grid.hpp"
#include "solver/gas/gas_solver.hpp"
#include "solver/scene/scene.hpp"

namespace dustlift {

class ParcelSystem;         // solver/dem/parcel_system.hpp
class GasParticleCoupling;  // solver/coupling/gas_particle_coupling.hpp

struct StateView {
  const Scene* scene = nullptr;
  const Grid2D* grid = nullptr;
  const GasSolver* gas = nullptr;
  GasPrimitives primitives{};
  const ParcelSystem* parcels = nullptr;  ///< null in a gas-only scene
  const GasParticleCoupling* coupling = nullptr;  ///< null in a gas-only scene
  /// Particle volume fraction as deposited (eq. 12, before the porosity cap); null in a
  /// gas-only scene. Use it rather than 1 - alpha_g, which one-way coupling leaves at 0.
  const Field2D* alpha_p = nullptr;
  double time = 0.0;                      ///< s
  long long step = 0;
  std::string output_dir;                 ///< the run's output folder
};

class Observer {
 public:
  virtual ~Observer() = default;
  /// Called once before the first step (time 0 state).
  virtual void on_start(const StateView& view) { on_output(view); }
  /// Called at each output time of the scene's cadence.
  virtual void on_output(const StateView& view) = 0;
  /// Called after every step; keep it cheap (filters that need every step use it).
  virtual void on_step(const StateView&) {}
  /// Called once after the last step (final state).
  virtual void on_finish(const StateView& view) { on_output(view); }
};

}  // namespace dustlift
