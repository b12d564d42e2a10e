#include "solver/coupling/coupling_models.hpp"

#include "solver/coupling/models/added_mass.hpp"
#include "solver/coupling/models/drag.hpp"
#include "solver/coupling/models/heat_transfer.hpp"
#include "solver/coupling/models/magnus.hpp"
#include "solver/coupling/models/pressure_force.hpp"
#include "solver/coupling/models/rotation_torque.hpp"

namespace dustlift {

CouplingModels::CouplingModels(const CouplingConfig& c) {
  if (c.drag) models_.push_back(std::make_unique<DragModel>(c));
  if (c.magnus) models_.push_back(std::make_unique<MagnusModel>(c));
  if (c.pressure_force) models_.push_back(std::make_unique<PressureForceModel>());
  if (c.added_mass) models_.push_back(std::make_unique<AddedMassModel>(c));
  if (c.rotation_torque) models_.push_back(std::make_unique<RotationTorqueModel>(c));
  if (c.heat_transfer) models_.push_back(std::make_unique<HeatTransferModel>());
  for (const auto& m : models_) {
    const ModelTraits t = m->traits();
    reads_ |= t.reads;
    writes_ |= t.writes;
  }
}

std::vector<std::string> CouplingModels::descriptions() const {
  std::vector<std::string> d;
  for (const auto& m : models_) d.push_back(m->description());
  return d;
}

}  // namespace dustlift
