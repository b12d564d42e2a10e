// Simulation: set-up from the scene, one step, and what the observers see.
#include "solver/sim/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "solver/core/errors.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/scene/table_reader.hpp"
#include "solver/sim/slab_driver.hpp"

namespace dustlift {

Simulation::Simulation(const Scene& scene, const Communicator* comm)
    : scene_(scene),
      whole_grid_(scene.grid.x, scene.grid.y, kGhostLayers),
      outputs_(Cadence::simulated(scene.output.interval)) {
  gas_config_ = scene_.gas;
  gas_config_.skip_resting_cells = scene_.run.skip_at_rest;
  gas_config_.rest_tolerance = scene_.run.rest_tolerance;
  one_slab_.bounds = {0, whole_grid_.nx()};
  one_slab_.periodic_x = scene_.gas.boundary.left == BoundaryKind::Periodic;
  if (comm == nullptr || comm->size() <= 1) {
    grid_ = whole_grid_;
    gas_ = std::make_unique<GasSolver>(grid_, gas_config_);
  } else {
    if (scene_.particles.enabled && one_slab_.periodic_x) {
      throw SceneError(scene_.source_file +
                       ": key 'boundary.left' = \"periodic\" with [particles] needs one MPI rank "
                       "(a periodic channel's parcels are not split over ranks yet)");
    }
    slabs_ = std::make_unique<SlabDriver>(*this, *comm);
  }
  gas_->initialize(scene_.initial);
  if (scene_.particles.enabled) {
    // On several ranks every rank makes the whole layer and keeps its part (and copies).
    parcels_ = std::make_unique<ParcelSystem>(make_layer_system(scene_.particles));
    if (layer_settles(scene_.particles.layer))
      bed_description_ = describe_bed(*parcels_, scene_.particles.layer);
    coupling_ =
        std::make_unique<GasParticleCoupling>(grid_, scene_.coupling, scene_.gas, scene_.particles);
    total_parcels_ = parcels_->size();
    if (slabs_) slabs_->split_parcels();
    coupling_->set_skip_resting(scene_.run.skip_at_rest);
    coupling_->initialize(*gas_, *parcels_);
  }
}

Simulation::~Simulation() = default;

long long Simulation::replace_slab(int first_column, int end_column) {
  const long long retired = gas_ ? gas_->cell_updates() : 0;
  grid_ = whole_grid_.slice_x(first_column, end_column);
  gas_ = std::make_unique<GasSolver>(grid_, gas_config_);  // holds grid_: made after it
  return retired;
}

const SlabLayout& Simulation::slab() const {
  return slabs_ ? slabs_->layout() : one_slab_;
}

const GasSolver* Simulation::whole_gas() const {
  return slabs_ ? slabs_->whole_gas() : nullptr;
}

bool Simulation::rebalance() {
  if (!slabs_) return false;
  const ScopedTimer timer(timings_.balance);
  return slabs_->rebalance();
}

long long Simulation::rebalances() const {
  return slabs_ ? slabs_->rebalances() : 0;
}

bool Simulation::any_rank(bool value) const {
  return slabs_ ? slabs_->comm().any(value) : value;
}

void Simulation::add_observer(std::unique_ptr<Observer> observer) {
  observers_.push_back(std::move(observer));
}

void Simulation::set_progress_callback(std::function<void(const Progress&)> callback) {
  progress_ = std::move(callback);
}

void Simulation::set_stop_request(std::function<bool()> stop_requested) {
  stop_requested_ = std::move(stop_requested);
}

StateView Simulation::view(const std::string& output_dir) const {
  StateView v;
  v.scene = &scene_;
  const GasSolver* whole_gas = slabs_ ? slabs_->whole_gas() : nullptr;
  const bool whole = whole_gas != nullptr;
  v.grid = whole ? &whole_grid_ : &grid_;
  v.gas = whole ? whole_gas : gas_.get();
  v.primitives = v.gas->primitives();
  // Rank 0 of a decomposed run shows the gathered parcels (the column handles are the same).
  v.parcels = whole && slabs_->whole_parcels() ? slabs_->whole_parcels() : parcels_.get();
  v.coupling = coupling_.get();
  v.alpha_p = whole && slabs_->whole_alpha_p() ? slabs_->whole_alpha_p()
              : coupling_                      ? &coupling_->alpha_p()
                                               : nullptr;
  v.time = time_;
  v.step = step_;
  v.output_dir = output_dir;
  v.provenance = &provenance_;
  v.log = log_ ? &log_ : nullptr;
  derived_whole_.show(v.grid, v.primitives, v.alpha_p, particle_density(), step_);
  v.derived = &derived_whole_;
  return v;
}

StateView Simulation::piece_view(const std::string& output_dir) const {
  if (!slabs_) return view(output_dir);
  StateView v = view(output_dir);
  // The slab itself (rank 0's view() shows the gathered whole).
  v.grid = &grid_;
  v.gas = gas_.get();
  v.primitives = gas_->primitives();
  v.parcels = parcels_.get();
  v.alpha_p = coupling_ ? &coupling_->alpha_p() : nullptr;
  v.piece = &slabs_->piece();
  derived_piece_.show(v.grid, v.primitives, v.alpha_p, particle_density(), step_);
  v.derived = &derived_piece_;
  return v;
}

double Simulation::advance(double dt_max) {
  double dt = std::min(slabs_ ? slabs_->comm().min(gas_->stable_dt()) : gas_->stable_dt(), dt_max);
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    std::ostringstream s;
    s << "step " << step_ << ", t = " << time_ << " s: time step " << dt << " s is not positive";
    throw NumericalFailure(s.str());
  }
  try {
    if (parcels_) coupling_->advance(*gas_, *parcels_, dt);
    const ScopedTimer t(timings_.gas);
    gas_->step(dt);
  } catch (const NumericalFailure& f) {
    std::ostringstream s;
    s << "step " << step_ + 1 << ", t = " << time_ + dt << " s: " << f.what();
    throw NumericalFailure(s.str());
  }
  time_ += dt;
  ++step_;
  if (slabs_ && scene_.run.rebalance_steps > 0 && step_ % scene_.run.rebalance_steps == 0)
    rebalance();
  return dt;
}

}  // namespace dustlift
