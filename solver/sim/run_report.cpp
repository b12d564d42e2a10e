// Simulation: what a run switches on and what it did, for the log and `dustlift info`.
#include <algorithm>
#include <sstream>

#include "solver/dem/coarse_graining.hpp"
#include "solver/dem/contact_summary.hpp"
#include "solver/gas/shock_relations.hpp"
#include "solver/laws/contact.hpp"
#include "solver/sim/layer_resolution.hpp"
#include "solver/sim/simulation.hpp"
#include "solver/sim/slab_driver.hpp"

namespace dustlift {
namespace {

std::string fmt_number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

/// The gas's lines: its model, transport, scheme, skipping at rest and the initial shock.
void gas_effects(const Scene& scene, std::vector<std::string>& e) {
  const auto& g = scene.gas;
  e.push_back(g.thermo.model == ThermoModel::ThermallyPerfect
                  ? "gas: thermally perfect air (NASA polynomials, O2:N2 = 1:3.76)"
                  : "gas: calorically perfect (gamma = " + fmt_number(g.thermo.gamma) + ")");
  switch (g.transport.model) {
    case TransportModel::Inviscid:
      e.push_back("viscosity: off (Euler)");
      break;
    case TransportModel::Constant:
      e.push_back("viscosity + heat conduction: constant mu, Pr");
      break;
    case TransportModel::Sutherland:
      e.push_back("viscosity + heat conduction: Sutherland");
      break;
    case TransportModel::GordonWilke:
      e.push_back("viscosity + heat conduction: Gordon fits + Wilke rule");
      break;
  }
  const char* rec = g.scheme.reconstruction == Reconstruction::FirstOrder ? "1st order"
                    : g.scheme.reconstruction == Reconstruction::Muscl2
                        ? "MUSCL 2nd order"
                        : "MUSCL 3rd order (kappa = 1/3)";
  e.push_back(std::string("convection: SLAU2 + ") + rec + ", SSP-RK3");
  if (g.has_gravity())
    e.push_back("gravity on the gas: [" + fmt_number(g.gravity_x) + ", " + fmt_number(g.gravity_y) +
                "] m/s^2 (no cell skipped at rest)");
  else if (!scene.run.skip_at_rest)
    e.push_back("skipping at rest: off (every cell and parcel computed every step)");
  else if (scene.run.rest_tolerance > 0.0)
    e.push_back("skipping at rest: within a relative " + fmt_number(scene.run.rest_tolerance) +
                " of the resting state (also skips the rounding noise ahead of a shock; results "
                "change at that level; run.exact = true skips only what rests exactly)");
  else
    e.push_back("skipping at rest: exact (bitwise the same results as without)");
  const InitialCondition& ic = scene.initial;
  if (ic.kind == InitialCondition::Kind::Shock) {
    // The Rankine-Hugoniot state the inflow holds: what the run's shock should settle to.
    const ShockJump j = normal_shock(ic.state, ic.mach, g.thermo, ic.axis);
    std::ostringstream s;
    s.precision(4);
    s << "shock: Mach " << ic.mach << " along +" << ic.axis << " at " << j.shock_speed
      << " m/s into " << ic.state.p * 1e-3 << " kPa, " << j.pre_temperature << " K; behind it "
      << j.post.p * 1e-3 << " kPa, " << j.post_temperature << " K, " << j.post.rho
      << " kg/m^3, gas at " << (ic.axis == 'x' ? j.post.u : j.post.v) << " m/s";
    e.push_back(s.str());
  }
}

/// The particles' line: parcels, real particles and the contact law.
std::string particles_line(const DemConfig& d, std::size_t parcels) {
  std::ostringstream s;
  s << "particles: " << parcels << " DEM parcels of "
    << (has_class_parcels(d.size_classes) ? "up to " : "") << d.parcel_diameter * 1e6
    << " um holding ";
  if (d.size_classes.empty()) {
    s << d.real_per_parcel << " real particles of " << d.particle_diameter * 1e6 << " um per metre";
  } else {
    s << "real particles of " << d.size_classes.size() << " size classes from "
      << d.size_classes.front().diameter * 1e6 << " to " << d.size_classes.back().diameter * 1e6
      << " um (mass median " << d.particle_diameter * 1e6 << " um), "
      << (has_class_parcels(d.size_classes) ? "each class in parcels of its own size"
                                            : "the same solid volume each");
  }
  s << "; spring-dashpot contacts (" << describe_contact_law(d) << ")";
  return s.str();
}

}  // namespace

std::vector<std::string> Simulation::enabled_effects() const {
  std::vector<std::string> e;
  gas_effects(scene_, e);
  if (!scene_.particles.enabled) {
    e.push_back("particles: none (gas only)");
    return e;
  }
  const auto& d = scene_.particles;
  const auto& c = scene_.coupling;
  e.push_back(particles_line(d, parcels_ ? parcels_->size() : 0));
  if (d.layer_parcels.empty()) {
    const std::string w = layer_resolution_warning(whole_grid_.y(), d.layer.y_min, d.layer.y_max);
    if (!w.empty()) e.push_back(w);
  }
  for (std::string& line : contact_descriptions(d)) e.push_back(std::move(line));
  e.push_back(c.two_way ? "coupling: two-way (porosity, exchange terms f_p, s_p, q_p)"
                        : "coupling: one-way (gas does not feel the particles)");
  if (coupling_) {
    for (const std::string& m : coupling_->model_descriptions()) e.push_back(m);
    // Where this scene takes a law beyond the range it was fitted in.
    for (const std::string& m : coupling_->effects().validity(coupling_->flow_envelope(*gas_)))
      e.push_back("out of range: " + m);
  }
  if (d.gravity_x != 0.0 || d.gravity_y != 0.0) {
    e.push_back("gravity on the parcels: (" + fmt_number(d.gravity_x) + ", " +
                fmt_number(d.gravity_y) + ") m/s^2");
  }
  return e;
}

std::string Simulation::work_summary() const {
  std::ostringstream s;
  const double full = 3.0 * static_cast<double>(whole_grid_.interior_cells()) *
                      static_cast<double>(step_ - first_step_);
  const long long updates = slabs_
                                ? slabs_->comm().sum(slabs_->cell_updates() - first_cell_updates_)
                                : gas_->cell_updates() - first_cell_updates_;
  s << "work: gas " << updates << " cell-stage updates ("
    << (full > 0.0 ? 100.0 * static_cast<double>(updates) / full : 0.0) << " % of the full grid)";
  if (slabs_) s << slabs_->exchange_summary(std::max<long long>(step_ - first_step_, 1));
  if (parcels_) {
    const long long substeps = parcels_->steps() - first_dem_steps_;
    const long long stepped = parcels_->parcel_substeps() - first_parcel_substeps_;
    // On several ranks summed over the ranks, rank copies included (they are integrated,
    // then overwritten by their owners' states).
    const long long stepped_all = slabs_ ? slabs_->comm().sum(stepped) : stepped;
    const double parcels = static_cast<double>(total_parcels_);
    s << "; DEM " << substeps << " sub-steps of " << total_parcels_ << " parcels, " << stepped_all
      << " parcel-sub-steps ("
      << (substeps > 0
              ? 100.0 * static_cast<double>(stepped_all) / (static_cast<double>(substeps) * parcels)
              : 0.0)
      << " %), " << parcels_->neighbour_rebuilds() - first_rebuilds_ << " neighbour rebuilds";
    // Lists kept from the build before (unmoved neighbourhoods) against those rebuilt.
    const long long rebuilds = parcels_->neighbour_rebuilds() - first_rebuilds_;
    if (rebuilds > 0 && !slabs_) {
      const double listed = static_cast<double>(rebuilds) * static_cast<double>(parcels_->size());
      s << " (" << 100.0 * static_cast<double>(parcels_->kept_lists() - first_kept_lists_) / listed
        << " % of the parcels' lists kept)";
    }
  }
  s.precision(3);
  s << "\ntime: gas " << timings_.gas << " s";
  if (parcels_) {
    const auto& c = coupling_->timings();
    const auto& d = parcels_->timings();
    s << ", coupling sample " << c.sample << " s, implicit exchange " << c.implicit_exchange
      << " s, deposit " << c.deposit << " s, DEM contacts " << d.contacts << " s, integration "
      << d.integrate << " s, rebuilds " << d.rebuild << " s";
  }
  s << ", observers " << timings_.observers << " s, checkpoints " << timings_.checkpoints << " s";
  if (slabs_) {
    s << ", moving slab cuts " << timings_.balance << " s";
    s << slabs_->time_per_rank(timings_.gas);
  }
  return s.str();
}

}  // namespace dustlift
