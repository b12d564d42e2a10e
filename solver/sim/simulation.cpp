#include "solver/sim/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "solver/core/errors.hpp"
#include "solver/dem/layer_generator.hpp"
#include "solver/parallel/slab_halo.hpp"
#include "solver/scene/table_reader.hpp"
#include "solver/sim/time_targets.hpp"

namespace dustlift {

namespace {
/// Every field of a gas solver's state that a gather or a move of the slab cuts carries, in
/// one order: conserved, primitives, porosity, and (with_sources) the sources.
std::vector<Field2D*> gas_state_fields(GasSolver& g, bool with_sources) {
  std::vector<Field2D*> f;
  for (int k = 0; k < 4; ++k) f.push_back(&g.conserved(k));
  for (int k = 0; k < 5; ++k) f.push_back(&g.primitive_field(k));
  f.push_back(&g.porosity());
  if (with_sources) {
    for (int k = 0; k < 4; ++k) f.push_back(&g.source(k));
  }
  return f;
}

/// The run's counters and decisions (time, steps, rebuilds, a pending rebuild, gravity), which
/// every rank's parcel system has alike, onto a system assembled from packed parcels.
void take_run_state(ParcelSystem& assembled, const ParcelSystem& here) {
  ParcelInternals in = assembled.internals();
  const ParcelInternals run = here.internals();
  in.time = run.time;
  in.steps = run.steps;
  in.rebuilds = run.rebuilds;
  in.needs_rebuild = run.needs_rebuild;
  in.gravity_x = run.gravity_x;
  in.gravity_y = run.gravity_y;
  assembled.restore_internals(in);
}

std::string fmt_number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
}  // namespace

Simulation::Simulation(const Scene& scene, const Communicator* comm)
    : scene_(scene), whole_grid_(scene.grid.x, scene.grid.y, kGhostLayers), comm_(comm) {
  GasConfig& gas_config = gas_config_;
  gas_config = scene_.gas;
  gas_config.skip_resting_cells = scene_.run.skip_at_rest;
  gas_config.rest_tolerance = scene_.run.rest_tolerance;
  decomposed_ = comm_ != nullptr && comm_->size() > 1;
  layout_.bounds = {0, whole_grid_.nx()};
  layout_.periodic_x = scene_.gas.boundary.left == BoundaryKind::Periodic;
  if (!decomposed_) {
    grid_ = whole_grid_;
    gas_ = std::make_unique<GasSolver>(grid_, gas_config);
  } else {
    if (scene_.particles.enabled && layout_.periodic_x) {
      throw SceneError(scene_.source_file + ": key 'boundary.left' = \"periodic\" with [particles] needs one MPI rank "
                       "(a periodic channel's parcels are not split over ranks yet)");
    }
    if (scene_.run.rest_tolerance > 0.0) {
      // The rest references are each slab's own: exact skipping does not depend on them, a
      // tolerance would (docs/parallel.md).
      throw SceneError(scene_.source_file + ": key 'run.rest_tolerance' > 0 needs one MPI rank (it makes the "
                       "results depend on the decomposition); set it to 0");
    }
    // Cost of a column: its cells (the parcels' weight joins when particles do).
    const std::vector<double> cost(static_cast<std::size_t>(whole_grid_.nx()), static_cast<double>(whole_grid_.ny()));
    layout_.bounds = balanced_slabs(cost, comm_->size(), kMinSlabColumns);
    layout_.rank = comm_->rank();
    build_slab_gas();
    if (comm_->is_root()) whole_gas_ = std::make_unique<GasSolver>(whole_grid_, gas_config);
  }
  gas_->initialize(scene_.initial);
  if (scene_.particles.enabled) {
    // On several ranks every rank makes the whole layer and keeps its part (and ghosts).
    parcels_ = std::make_unique<ParcelSystem>(make_layer_system(scene_.particles));
    if (layer_settles(scene_.particles.layer)) bed_description_ = describe_bed(*parcels_, scene_.particles.layer);
    coupling_ = std::make_unique<GasParticleCoupling>(grid_, scene_.coupling, scene_.gas, scene_.particles);
    if (decomposed_) {
      // Ghosts also as far as a deposit square reaches beyond the cut.
      total_parcels_ = parcels_->size();
      parcels_->set_ghost_margin(std::max(scene_.coupling.influence_width, scene_.particles.parcel_diameter));
      parcels_->set_decomposition(*comm_, parcel_cuts());
      coupling_->set_slab(whole_grid_, layout_.first_column(), *halo_, *comm_);
    }
    if (!decomposed_) total_parcels_ = parcels_->size();
    coupling_->set_skip_resting(scene_.run.skip_at_rest);
    coupling_->initialize(*gas_, *parcels_);
  }
}

Simulation::~Simulation() = default;

void Simulation::build_slab_gas() {
  if (halo_) {
    retired_halo_doubles_ += halo_->doubles_sent();
    retired_halo_messages_ += halo_->messages_sent();
    retired_halo_seconds_ += halo_->seconds();
  }
  if (gas_) retired_cell_updates_ += gas_->cell_updates();
  grid_ = whole_grid_.slice_x(layout_.first_column(), layout_.end_column());
  gas_ = std::make_unique<GasSolver>(grid_, gas_config_);
  halo_ = std::make_unique<SlabHalo>(*comm_, layout_, grid_);
  gas_->set_halo(halo_.get());
}

long long Simulation::cell_updates() const { return retired_cell_updates_ + gas_->cell_updates(); }

bool Simulation::rebalance() {
  if (!decomposed_) return false;
  const ScopedTimer timer(timings_.balance);
  // Work per column of the whole grid: the cells the last stage updated, plus a twentieth
  // of every cell for the scans that find the resting ones (an estimate; docs/parallel.md).
  std::vector<double> work(static_cast<std::size_t>(grid_.nx()), 0.05 * static_cast<double>(grid_.ny()));
  gas_->add_column_work(work);
  if (parcels_) {
    // A parcel stepped in the last step costs about 2.4 cell updates (paper scene on 2 ranks:
    // 5.2e-8 s per parcel-sub-step x 11.4 sub-steps against 8.2e-8 s per cell-stage x 3
    // stages); one left resting only its check, taken as a tenth of that.
    constexpr double kParcelWeight = 2.4, kRestingParcelWeight = 0.24;
    const ParcelSystem& p = *parcels_;
    const std::vector<double>& stepped = p.column(coupling_->stepped_column());
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.is_ghost(i)) continue;
      const int column =
          std::clamp(whole_grid_.x().locate(p.x[i]) - layout_.first_column(), 0, grid_.nx() - 1);
      work[static_cast<std::size_t>(column)] +=
          stepped[i] != 0.0 ? kParcelWeight : kRestingParcelWeight;
    }
  }
  std::vector<std::vector<double>> pieces;
  comm_->gather(work, pieces);
  std::vector<double> whole_work;
  if (comm_->is_root()) {
    for (const auto& p : pieces) whole_work.insert(whole_work.end(), p.begin(), p.end());
  }
  comm_->broadcast(whole_work);  // every rank computes the same cuts from the same numbers
  const std::vector<int> bounds = balanced_slabs(whole_work, comm_->size(), kMinSlabColumns);
  auto largest = [&](const std::vector<int>& b) {
    double most = 0.0;
    for (std::size_t r = 0; r + 1 < b.size(); ++r) {
      double sum = 0.0;
      for (int i = b[r]; i < b[r + 1]; ++i) sum += whole_work[static_cast<std::size_t>(i)];
      most = std::max(most, sum);
    }
    return most;
  };
  if (!(largest(bounds) < 0.95 * largest(layout_.bounds))) return false;
  // The parcels and alpha_p, whole, on every rank: each splits them again at the new cuts
  // (keeping the contact lists: the move changes no bit).
  std::vector<double> parcels_whole, alpha_whole;
  if (parcels_) {
    gather_gas(true);
    if (comm_->is_root()) {
      whole_parcels_->pack_owned(parcels_whole);
      alpha_whole = whole_alpha_p_->raw();
      alpha_whole.push_back(static_cast<double>(whole_rows_touched_));
    }
    comm_->broadcast(parcels_whole);
    comm_->broadcast(alpha_whole);
  }
  // The state moves exactly: every rank sends each rank the columns of its new slab, ghost
  // columns included, that it holds now (its interior, and the ghost columns beyond a domain
  // end), every field and row. Only ranks whose columns overlap exchange anything.
  const int ng = kGhostLayers;
  const auto rows = static_cast<std::size_t>(whole_grid_.ny() + 2 * ng);
  SlabLayout moved = layout_;
  moved.bounds = bounds;
  // Whole-grid columns [first, end) a layout's rank stores.
  auto stored = [&](const SlabLayout& l) {
    return std::pair{l.first_column() + l.stored_begin(ng), l.first_column() + l.stored_end(ng)};
  };
  // Whole-grid columns [first, end) a layout's rank needs after the move: its stored columns
  // and the ghost columns at its cuts, which are other ranks' cells now (the coupling samples
  // them before the next step's exchanges fill them).
  auto needed = [&](const SlabLayout& l) {
    return std::pair{std::max(l.first_column() - ng, -ng), std::min(l.end_column() + ng, whole_grid_.nx() + ng)};
  };
  auto overlap = [](std::pair<int, int> a, std::pair<int, int> b) {
    return std::pair{std::max(a.first, b.first), std::min(a.second, b.second)};
  };
  const int ranks = comm_->size();
  std::vector<std::vector<double>> send(static_cast<std::size_t>(ranks)), receive(static_cast<std::size_t>(ranks));
  {
    const std::vector<Field2D*> old_fields = gas_state_fields(*gas_, true);
    const std::pair<int, int> mine = stored(layout_);
    for (int q = 0; q < ranks; ++q) {
      const auto [a, b] = overlap(mine, needed(moved.of_rank(q)));
      if (a >= b) continue;
      std::vector<double>& out = send[static_cast<std::size_t>(q)];
      out.reserve(old_fields.size() * rows * static_cast<std::size_t>(b - a));
      for (const Field2D* f : old_fields) {
        for (int j = -ng; j < whole_grid_.ny() + ng; ++j) {
          const double* row = f->data() + grid_.index(a - layout_.first_column(), j);
          out.insert(out.end(), row, row + (b - a));
        }
      }
    }
    const std::pair<int, int> wanted = needed(moved);
    for (int q = 0; q < ranks; ++q) {
      const auto [a, b] = overlap(stored(layout_.of_rank(q)), wanted);
      if (a < b) receive[static_cast<std::size_t>(q)].resize(old_fields.size() * rows * static_cast<std::size_t>(b - a));
    }
  }
  comm_->exchange(send, receive);
  const SlabLayout before = layout_;
  layout_ = moved;
  build_slab_gas();
  gas_->initialize(scene_.initial);  // the inflow states, as at the start; then the state
  const std::vector<Field2D*> new_fields = gas_state_fields(*gas_, true);
  const std::pair<int, int> wanted = needed(layout_);
  for (int q = 0; q < ranks; ++q) {
    const auto [a, b] = overlap(stored(before.of_rank(q)), wanted);
    if (a >= b) continue;
    const std::vector<double>& in = receive[static_cast<std::size_t>(q)];
    std::size_t k = 0;
    for (Field2D* f : new_fields) {
      for (int j = -ng; j < whole_grid_.ny() + ng; ++j) {
        std::copy_n(in.begin() + static_cast<std::ptrdiff_t>(k), b - a,
                    f->data() + grid_.index(a - layout_.first_column(), j));
        k += static_cast<std::size_t>(b - a);
      }
    }
  }
  if (parcels_) {
    ParcelSystem split = *parcels_;
    split.drop_decomposition();
    split.assign_packed({parcels_whole});
    take_run_state(split, *parcels_);
    split.set_decomposition(*comm_, parcel_cuts());
    *parcels_ = std::move(split);
    coupling_->move_to_slab(grid_, layout_.first_column(), *halo_);
    GasParticleCoupling::CarriedState c;
    c.rows_touched = static_cast<int>(alpha_whole.back());
    alpha_whole.pop_back();
    extract_slab(alpha_whole, whole_grid_, layout_, c.alpha_p);
    c.rest_p = coupling_->rest_pressure();
    c.rest_T = coupling_->rest_temperature();
    coupling_->restore_carried_state(c);
  }
  ++rebalances_;
  return true;
}

std::vector<double> Simulation::parcel_cuts() const {
  std::vector<double> cuts;
  for (int q = 1; q < comm_->size(); ++q) cuts.push_back(whole_grid_.x().face(layout_.bounds[static_cast<std::size_t>(q)]));
  return cuts;
}

void Simulation::gather_parcels(bool with_lists, bool band_only) const {
  if (!decomposed_ || !parcels_) return;
  std::vector<double> mine;
  const ParcelSystem& p = *parcels_;
  const auto in_a_band = [&](std::size_t i) {
    for (const BandConfig& b : scene_.output.bands) {
      if (p.x_initial[i] >= b.x_min && p.x_initial[i] <= b.x_max && p.y_initial[i] >= b.y_min &&
          p.y_initial[i] <= b.y_max) {
        return true;
      }
    }
    return false;
  };
  parcels_->pack_owned(mine, with_lists, band_only ? std::function<bool(std::size_t)>(in_a_band) : nullptr);
  std::vector<std::vector<double>> pieces;
  comm_->gather(mine, pieces);
  const int rows = static_cast<int>(-comm_->min(-static_cast<double>(coupling_->rows_touched())));
  if (!comm_->is_root()) return;
  if (!whole_parcels_) {
    whole_parcels_ = std::make_unique<ParcelSystem>(scene_.particles);
    for (std::size_t k = 0; k < parcels_->attached_count(); ++k) whole_parcels_->attach_column(parcels_->attached_spec(k));
  }
  whole_parcels_->assign_packed(pieces);
  whole_rows_touched_ = rows;
  if (!with_lists) return;
  take_run_state(*whole_parcels_, *parcels_);
}

void Simulation::gather_gas(bool with_sources, unsigned reads) const {
  if (!decomposed_) return;
  if (with_sources) reads = Observer::kReadsEverything;
  const bool all_gas = (reads & Observer::kReadsGas) != 0;
  const bool alpha = coupling_ && (reads & (Observer::kReadsGas | Observer::kReadsAlphaP)) != 0;
  constexpr int kPressure = 3;  // primitive_field: rho, u, v, p, T
  std::vector<Field2D*> fields;
  if (all_gas) {
    fields = gas_state_fields(*gas_, with_sources);
  } else if ((reads & Observer::kReadsPressure) != 0) {
    fields.push_back(&gas_->primitive_field(kPressure));
  }
  // alpha_p goes with the gas (read only: pack_slab copies it).
  if (alpha) fields.push_back(const_cast<Field2D*>(&coupling_->alpha_p()));
  // One message per rank: the fields' slab parts one after another.
  std::vector<double> piece;
  for (const Field2D* f : fields) {
    const std::vector<double> part = pack_slab(*f, grid_, layout_);
    piece.insert(piece.end(), part.begin(), part.end());
  }
  std::vector<std::vector<double>> pieces;
  comm_->gather(piece, pieces);
  if ((reads & (Observer::kReadsParcels | Observer::kReadsBandParcels)) != 0) {
    gather_parcels(with_sources, (reads & Observer::kReadsParcels) == 0);
  }
  if (!comm_->is_root()) return;
  std::vector<Field2D*> targets;
  if (all_gas) {
    targets = gas_state_fields(*whole_gas_, with_sources);
  } else if ((reads & Observer::kReadsPressure) != 0) {
    targets.push_back(&whole_gas_->primitive_field(kPressure));
  }
  if (alpha) {
    if (!whole_alpha_p_) whole_alpha_p_ = std::make_unique<Field2D>(whole_grid_);
    targets.push_back(whole_alpha_p_.get());
  }
  for (int r = 0; r < comm_->size(); ++r) {
    const SlabLayout of_r = layout_.of_rank(r);
    const std::size_t part = static_cast<std::size_t>(of_r.stored_end(kGhostLayers) - of_r.stored_begin(kGhostLayers)) *
                             static_cast<std::size_t>(whole_grid_.ny() + 2 * kGhostLayers);
    const std::vector<double>& all = pieces[static_cast<std::size_t>(r)];
    for (std::size_t f = 0; f < targets.size(); ++f) {
      unpack_slab(std::span<const double>(all).subspan(f * part, part), whole_grid_, of_r, targets[f]->raw());
    }
  }
}

void Simulation::add_observer(std::unique_ptr<Observer> observer) {
  observers_.push_back(std::move(observer));
}

void Simulation::set_progress_callback(std::function<void(const Progress&)> callback) {
  progress_ = std::move(callback);
}

StateView Simulation::view(const std::string& output_dir) const {
  StateView v;
  v.scene = &scene_;
  const bool whole = whole_gas_ != nullptr;
  v.grid = whole ? &whole_grid_ : &grid_;
  v.gas = whole ? whole_gas_.get() : gas_.get();
  v.primitives = v.gas->primitives();
  // Rank 0 of a decomposed run shows the gathered parcels (the column handles are the same).
  v.parcels = whole && whole_parcels_ ? whole_parcels_.get() : parcels_.get();
  v.coupling = coupling_.get();
  v.alpha_p = whole && whole_alpha_p_ ? whole_alpha_p_.get() : coupling_ ? &coupling_->alpha_p() : nullptr;
  v.time = time_;
  v.step = step_;
  v.output_dir = output_dir;
  v.provenance = &provenance_;
  v.log = log_ ? &log_ : nullptr;
  return v;
}

StateView Simulation::piece_view(const std::string& output_dir) const {
  if (!decomposed_) return view(output_dir);
  StateView v = view(output_dir);
  // The slab itself (rank 0's view() shows the gathered whole).
  v.grid = &grid_;
  v.gas = gas_.get();
  v.primitives = gas_->primitives();
  v.parcels = parcels_.get();
  v.alpha_p = coupling_ ? &coupling_->alpha_p() : nullptr;
  piece_.comm = comm_;
  piece_.rank = layout_.rank;
  piece_.column_bounds = layout_.bounds;
  piece_.parcel_ghosts = parcels_ ? parcels_->ghost_flags() : std::span<const std::uint8_t>();
  v.piece = &piece_;
  return v;
}

std::vector<std::string> Simulation::enabled_effects() const {
  std::vector<std::string> e;
  const auto& g = scene_.gas;
  e.push_back(g.thermo.model == ThermoModel::ThermallyPerfect
                  ? "gas: thermally perfect air (NASA polynomials, O2:N2 = 1:3.76)"
                  : "gas: calorically perfect (gamma = " + fmt_number(g.thermo.gamma) + ")");
  switch (g.transport.model) {
    case TransportModel::Inviscid: e.push_back("viscosity: off (Euler)"); break;
    case TransportModel::Constant: e.push_back("viscosity + heat conduction: constant mu, Pr"); break;
    case TransportModel::Sutherland: e.push_back("viscosity + heat conduction: Sutherland"); break;
    case TransportModel::GordonWilke: e.push_back("viscosity + heat conduction: Gordon fits + Wilke rule"); break;
  }
  const char* rec = g.scheme.reconstruction == Reconstruction::FirstOrder ? "1st order"
                    : g.scheme.reconstruction == Reconstruction::Muscl2   ? "MUSCL 2nd order"
                                                                          : "MUSCL 3rd order (kappa = 1/3)";
  e.push_back(std::string("convection: SLAU2 + ") + rec + ", SSP-RK3");
  if (g.has_gravity())
    e.push_back("gravity on the gas: [" + fmt_number(g.gravity_x) + ", " + fmt_number(g.gravity_y) +
                "] m/s^2 (no cell skipped at rest)");
  else if (!scene_.run.skip_at_rest)
    e.push_back("skipping at rest: off (every cell and parcel computed every step)");
  else if (scene_.run.rest_tolerance > 0.0)
    e.push_back("skipping at rest: within a relative " + fmt_number(scene_.run.rest_tolerance) +
                " of the resting state (also skips the rounding noise ahead of a shock; results change at that level)");
  else
    e.push_back("skipping at rest: exact (bitwise the same results as without)");
  if (!scene_.particles.enabled) {
    e.push_back("particles: none (gas only)");
    return e;
  }
  const auto& d = scene_.particles;
  const auto& c = scene_.coupling;
  std::ostringstream s;
  s << "particles: " << (parcels_ ? parcels_->size() : 0) << " DEM parcels of " << d.parcel_diameter * 1e6
    << " um holding " << d.real_per_parcel << " real particles of " << d.particle_diameter * 1e6
    << " um per metre; spring-dashpot contacts (k_n " << d.contact.k_n << " N/m, k_t " << d.contact.k_t
    << " N/m, h " << d.contact.damping << " N s/m)";
  e.push_back(s.str());
  e.push_back(c.two_way ? "coupling: two-way (porosity, exchange terms f_p, s_p, q_p)" : "coupling: one-way (gas does not feel the particles)");
  if (coupling_) {
    for (const std::string& m : coupling_->model_descriptions()) e.push_back(m);
  }
  if (d.gravity_x != 0.0 || d.gravity_y != 0.0) {
    e.push_back("gravity on the parcels: (" + fmt_number(d.gravity_x) + ", " + fmt_number(d.gravity_y) + ") m/s^2");
  }
  return e;
}

std::string Simulation::work_summary() const {
  std::ostringstream s;
  const double full = 3.0 * static_cast<double>(whole_grid_.interior_cells()) * static_cast<double>(step_ - first_step_);
  const long long updates = decomposed_ ? comm_->sum(cell_updates() - first_cell_updates_) : cell_updates() - first_cell_updates_;
  s << "work: gas " << updates << " cell-stage updates ("
    << (full > 0.0 ? 100.0 * static_cast<double>(updates) / full : 0.0) << " % of the full grid)";
  if (decomposed_) {
    s << " on " << comm_->size() << " ranks, x-slabs of";
    for (int r = 0; r < layout_.ranks(); ++r) s << (r ? ", " : " ") << layout_.of_rank(r).columns();
    s << " columns at the end (" << rebalances_ << " moves of the cuts)";
    const long long steps = std::max<long long>(step_ - first_step_, 1);
    const long long doubles = comm_->sum(retired_halo_doubles_ + halo_->doubles_sent());
    const long long messages = comm_->sum(retired_halo_messages_ + halo_->messages_sent());
    s << "; halo exchange per rank and step: " << static_cast<double>(doubles) * 8.0 / comm_->size() / steps
      << " bytes in " << static_cast<double>(messages) / comm_->size() / steps << " messages";
    if (parcels_) {
      // Ghost refreshes every sub-step, migrations and ghost copies at rebuilds, the
      // coupling's refreshes; counted since the start of the run.
      const ParcelSystem::DecompositionCounters& c = parcels_->decomposition_counters();
      const long long all_steps = std::max<long long>(step_, 1);
      s << "; parcel exchange per rank and step: "
        << static_cast<double>(comm_->sum(c.doubles_sent)) * 8.0 / comm_->size() / all_steps << " bytes in "
        << static_cast<double>(comm_->sum(c.messages)) / comm_->size() / all_steps << " messages, "
        << comm_->sum(c.migrated) << " parcels handed over";
    }
  }
  if (parcels_) {
    const long long substeps = parcels_->steps() - first_dem_steps_;
    const long long stepped = parcels_->parcel_substeps() - first_parcel_substeps_;
    // On several ranks summed over the ranks, ghost copies included (they are integrated,
    // then overwritten by their owners' states).
    const long long stepped_all = decomposed_ ? comm_->sum(stepped) : stepped;
    const double parcels = static_cast<double>(total_parcels_);
    s << "; DEM " << substeps << " sub-steps of " << total_parcels_ << " parcels, " << stepped_all
      << " parcel-sub-steps ("
      << (substeps > 0 ? 100.0 * static_cast<double>(stepped_all) / (static_cast<double>(substeps) * parcels) : 0.0)
      << " %), " << parcels_->neighbour_rebuilds() - first_rebuilds_ << " neighbour rebuilds";
  }
  s.precision(3);
  s << "\ntime: gas " << timings_.gas << " s";
  if (parcels_) {
    const auto& c = coupling_->timings();
    const auto& d = parcels_->timings();
    s << ", coupling sample " << c.sample << " s, relief " << c.implicit_exchange << " s, deposit " << c.deposit
      << " s, DEM contacts " << d.contacts << " s, integration " << d.integrate << " s, rebuilds " << d.rebuild
      << " s";
  }
  s << ", observers " << timings_.observers << " s, checkpoints " << timings_.checkpoints << " s";
  if (decomposed_) {
    s << ", moving slab cuts " << timings_.balance << " s";
    // Per rank: the gas time, and the part of it spent in (or waiting at) the halo exchange.
    const double mine[3] = {timings_.gas, retired_halo_seconds_ + halo_->seconds(),
                            parcels_ ? parcels_->decomposition_counters().seconds : 0.0};
    std::vector<std::vector<double>> all;
    comm_->gather(mine, all);
    if (comm_->is_root()) {
      s << "\ntime per rank: gas";
      for (const auto& r : all) s << " " << r[0];
      s << " s, of which in the halo exchange";
      for (const auto& r : all) s << " " << r[1];
      s << " s";
      if (parcels_) {
        s << "; in the parcel exchange";
        for (const auto& r : all) s << " " << r[2];
        s << " s";
      }
    }
  }
  return s.str();
}

double Simulation::advance(double dt_max) {
  double dt = std::min(decomposed_ ? comm_->min(gas_->stable_dt()) : gas_->stable_dt(), dt_max);
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
  if (decomposed_ && scene_.run.rebalance_steps > 0 && step_ % scene_.run.rebalance_steps == 0) rebalance();
  return dt;
}

void Simulation::set_checkpoint_writer(std::function<void(const Simulation&)> writer) {
  checkpoint_ = std::move(writer);
}

void Simulation::set_stop_request(std::function<bool()> stop_requested) {
  stop_requested_ = std::move(stop_requested);
}

RunEnd Simulation::run(const std::string& output_dir) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const double time0 = time_;
  auto last_report = t0, last_checkpoint = t0;
  const double interval = scene_.output.interval;
  const double end = end_target(scene_.run.end_time, interval);
  const double checkpoint_interval = scene_.output.checkpoint_interval;
  const double checkpoint_wall = scene_.output.checkpoint_wall_interval;
  // First checkpoint multiple strictly after the start (a restart does not rewrite its own).
  long long next_checkpoint = checkpoint_interval > 0.0 ? first_multiple_after(time_, checkpoint_interval) : 1;
  long long last_checkpoint_step = restored_ ? step_ : -1;
  auto write_checkpoint = [&] {
    const ScopedTimer t(timings_.checkpoints);
    checkpoint_(*this);
    last_checkpoint = clock::now();
    last_checkpoint_step = step_;
  };

  first_step_ = step_;
  first_cell_updates_ = cell_updates();
  first_dem_steps_ = parcels_ ? parcels_->steps() : 0;
  first_rebuilds_ = parcels_ ? parcels_->neighbour_rebuilds() : 0;
  first_parcel_substeps_ = parcels_ ? parcels_->parcel_substeps() : 0;
  // Observers of the whole state live on rank 0; every rank takes part in gathering what
  // they see. Those that write pieces run on every rank with its slab and need no gather.
  bool whole_observers = false;
  unsigned output_reads = 0;  // what they read at outputs (Observer::output_reads)
  for (const auto& o : observers_) {
    if (o->writes_pieces()) continue;
    whole_observers = true;
    output_reads |= o->output_reads();
  }
  const bool gather = decomposed_ && comm_->any(whole_observers);
  // Observers live on rank 0 (the others' is 0): a max is rank 0's value everywhere.
  if (gather) output_reads = static_cast<unsigned>(-comm_->min(-static_cast<double>(output_reads)));
  if (gather) gather_gas(false, output_reads);
  {
    const StateView v = view(output_dir), piece = piece_view(output_dir);
    for (auto& o : observers_) {
      if (restored_) {
        o->on_resume(view_for(*o, v, piece), resumed_from_);
      } else {
        o->on_start(view_for(*o, v, piece));
      }
    }
  }
  RunEnd how = RunEnd::Completed;
  double dt = 0.0;
  while (time_ < end) {
    if (scene_.run.max_steps > 0 && step_ >= scene_.run.max_steps) {
      how = RunEnd::StepLimit;
      break;
    }
    double target = end;
    if (interval > 0.0) target = std::min(target, multiple_time(next_output_, interval));
    const double remaining = target - time_;
    dt = advance(remaining);
    if (dt == remaining) time_ = target;  // exactly on the target, not a rounding short of it
    {
      const ScopedTimer t(timings_.observers);
      const bool output_due = interval > 0.0 && time_ >= multiple_time(next_output_, interval);
      if (gather) {
        bool read = output_due;
        unsigned reads = output_due ? output_reads : 0u;
        const StateView now = view(output_dir);
        for (auto& o : observers_) {
          if (o->writes_pieces() || !o->reads_step(now)) continue;
          read = true;
          reads |= o->step_reads();
        }
        if (comm_->any(read)) {
          // Observers live on rank 0 (the others' is 0): a max is rank 0's value everywhere.
          reads = static_cast<unsigned>(-comm_->min(-static_cast<double>(reads)));
          gather_gas(false, reads);
        }
      }
      const StateView v = view(output_dir), piece = piece_view(output_dir);
      for (auto& o : observers_) o->on_step(view_for(*o, v, piece));
      if (interval > 0.0 && time_ >= multiple_time(next_output_, interval)) {
        for (auto& o : observers_) o->on_output(view_for(*o, v, piece));
        next_output_ = first_multiple_after(time_, interval);
      }
    }
    const bool at_end = !(time_ < end);
    const bool stop = any_rank(stop_requested_ && stop_requested_());
    const auto now = clock::now();
    if (checkpoint_ && !at_end && !stop) {
      const bool by_time = checkpoint_interval > 0.0 && time_ >= multiple_time(next_checkpoint, checkpoint_interval);
      const bool by_wall =
          any_rank(checkpoint_wall > 0.0 && std::chrono::duration<double>(now - last_checkpoint).count() >= checkpoint_wall);
      if (by_time || by_wall) write_checkpoint();
      if (checkpoint_interval > 0.0) next_checkpoint = first_multiple_after(time_, checkpoint_interval);
    }
    if (progress_ && std::chrono::duration<double>(now - last_report).count() >= scene_.run.progress_interval) {
      last_report = now;
      Progress p;
      p.time = time_;
      p.end_time = end;
      p.dt = dt;
      p.step = step_;
      p.wall_seconds = std::chrono::duration<double>(now - t0).count();
      p.eta_seconds = time_ > time0 ? p.wall_seconds * (end - time_) / (time_ - time0) : 0.0;
      progress_(p);
    }
    if (stop && !at_end) {
      how = RunEnd::Interrupted;
      break;
    }
  }
  if (how != RunEnd::Interrupted) {
    const ScopedTimer t(timings_.observers);
    if (gather) gather_gas(false, output_reads);
    const StateView v = view(output_dir), piece = piece_view(output_dir);
    for (auto& o : observers_) o->on_finish(view_for(*o, v, piece));
  }
  if (checkpoint_ && last_checkpoint_step != step_) write_checkpoint();
  restored_ = false;
  return how;
}

}  // namespace dustlift
