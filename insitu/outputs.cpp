#include "insitu/outputs.hpp"

#include "insitu/observers.hpp"

namespace dustlift {

std::vector<std::unique_ptr<Observer>> make_output_observers(const Scene& scene,
                                                             const std::string&) {
  std::vector<std::unique_ptr<Observer>> observers;
  if (scene.output.vtk) observers.push_back(make_vtk_gas_writer());

  // Shock position along x: the pre-shock pressure is known for shock and Riemann
  // starts (the state the shock runs into); otherwise each row's downstream cell is used.
  const InitialCondition& ic = scene.initial;
  if (ic.axis == 'x') {
    ShockPositionOptions shock;
    if (ic.kind == InitialCondition::Kind::Shock) shock.p_ambient = ic.state.p;
    if (ic.kind == InitialCondition::Kind::Riemann) shock.p_ambient = ic.right.p;
    // A Riemann start with the high pressure on the right sends its shock to -x: skip.
    const bool rightward = ic.kind != InitialCondition::Kind::Riemann || ic.left.p > ic.right.p;
    if (rightward) observers.push_back(make_shock_position_observer(shock));
  }
  if (scene.particles.enabled) observers.push_back(make_surface_height_observer());
  return observers;
}

}  // namespace dustlift
