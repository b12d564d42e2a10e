// A run on several MPI ranks: the slabs, rank 0's gathered copy of the whole state, and the
// moves of the cuts (docs/parallel.md).
#include "solver/sim/slab_driver.hpp"

#include <algorithm>
#include <sstream>

#include "solver/sim/simulation.hpp"

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
  assembled.restore_internals(here.internals());
}

}  // namespace

SlabDriver::SlabDriver(Simulation& sim, const Communicator& comm) : sim_(sim), comm_(&comm) {
  const Grid2D& whole = sim_.whole_grid();
  // Cost of a column: its cells (the parcels' weight joins when particles do).
  const std::vector<double> cost(static_cast<std::size_t>(whole.nx()),
                                 static_cast<double>(whole.ny()));
  layout_.bounds = balanced_slabs(cost, comm_->size(), kMinSlabColumns);
  layout_.rank = comm_->rank();
  layout_.periodic_x = sim_.slab().periodic_x;  // the one-rank slab: this driver is not yet set
  build_slab_gas();
  if (comm_->is_root()) whole_gas_ = std::make_unique<GasSolver>(whole, sim_.gas_config());
}

SlabDriver::~SlabDriver() = default;

void SlabDriver::split_parcels() {
  parcel_slabs_ = std::make_unique<ParcelSlabs>(*comm_);
  // Copies also as far as a deposit square reaches beyond the cut.
  parcel_slabs_->set_copy_margin(
      std::max(sim_.scene().coupling.influence_width, sim_.scene().particles.parcel_diameter));
  parcel_slabs_->split(*sim_.parcels(), parcel_cuts());
  sim_.coupling()->set_slab(sim_.whole_grid(), layout_.first_column(), *halo_, *comm_);
}

long long SlabDriver::cell_updates() const {
  return retired_cell_updates_ + sim_.gas().cell_updates();
}

const RunPiece& SlabDriver::piece() const {
  piece_.comm = comm_;
  piece_.rank = layout_.rank;
  piece_.column_bounds = layout_.bounds;
  piece_.parcel_copies = sim_.parcels() ? std::span<const std::uint8_t>(sim_.parcels()->rank_copy)
                                        : std::span<const std::uint8_t>();
  return piece_;
}

std::string SlabDriver::exchange_summary(long long steps) const {
  std::ostringstream s;
  const Communicator& comm = *comm_;
  s << " on " << comm.size() << " ranks, x-slabs of";
  for (int r = 0; r < layout_.ranks(); ++r) s << (r ? ", " : " ") << layout_.of_rank(r).columns();
  s << " columns at the end (" << rebalances_ << " moves of the cuts)";
  const long long doubles = comm.sum(retired_halo_doubles_ + halo_->doubles_sent());
  const long long messages = comm.sum(retired_halo_messages_ + halo_->messages_sent());
  s << "; halo exchange per rank and step: "
    << static_cast<double>(doubles) * 8.0 / comm.size() / steps << " bytes in "
    << static_cast<double>(messages) / comm.size() / steps << " messages";
  if (parcel_slabs_) {
    // Copy refreshes every sub-step, migrations and copies at rebuilds, the coupling's
    // refreshes; counted since the start of the run.
    const ParcelSlabs::Counters& c = parcel_slabs_->counters();
    const long long all_steps = std::max<long long>(sim_.step(), 1);
    s << "; parcel exchange per rank and step: "
      << static_cast<double>(comm.sum(c.doubles_sent)) * 8.0 / comm.size() / all_steps
      << " bytes in " << static_cast<double>(comm.sum(c.messages)) / comm.size() / all_steps
      << " messages, " << comm.sum(c.migrated) << " parcels handed over";
  }
  return s.str();
}

std::string SlabDriver::time_per_rank(double gas_seconds) const {
  // Per rank: the gas time, and the part of it spent in (or waiting at) the halo exchange.
  const double mine[3] = {gas_seconds, retired_halo_seconds_ + halo_->seconds(),
                          parcel_slabs_ ? parcel_slabs_->counters().seconds : 0.0};
  std::vector<std::vector<double>> all;
  comm_->gather(mine, all);
  if (!comm_->is_root()) return {};
  std::ostringstream s;
  s.precision(3);
  s << "\ntime per rank: gas";
  for (const auto& r : all) s << " " << r[0];
  s << " s, of which in the halo exchange";
  for (const auto& r : all) s << " " << r[1];
  s << " s";
  if (parcel_slabs_) {
    s << "; in the parcel exchange";
    for (const auto& r : all) s << " " << r[2];
    s << " s";
  }
  return s.str();
}

void SlabDriver::build_slab_gas() {
  if (halo_) {
    retired_halo_doubles_ += halo_->doubles_sent();
    retired_halo_messages_ += halo_->messages_sent();
    retired_halo_seconds_ += halo_->seconds();
  }
  retired_cell_updates_ += sim_.replace_slab(layout_.first_column(), layout_.end_column());
  halo_ = std::make_unique<SlabHalo>(*comm_, layout_, sim_.grid());
  halo_->attach(sim_.gas());
}

namespace {

/// The largest summed work of a slab between `bounds`.
double largest_slab(const std::vector<double>& work, const std::vector<int>& bounds) {
  double most = 0.0;
  for (std::size_t r = 0; r + 1 < bounds.size(); ++r) {
    double sum = 0.0;
    for (int i = bounds[r]; i < bounds[r + 1]; ++i) sum += work[static_cast<std::size_t>(i)];
    most = std::max(most, sum);
  }
  return most;
}

using Columns = std::pair<int, int>;  ///< whole-grid columns [first, end)
/// The columns a layout's rank stores.
Columns stored_columns(const SlabLayout& l, int ng) {
  return {l.first_column() + l.stored_begin(ng), l.first_column() + l.stored_end(ng)};
}
/// The columns a layout's rank needs after a move: its stored columns and the ghost columns
/// at its cuts, which are other ranks' cells now (the coupling samples them before the next
/// step's exchanges fill them).
Columns needed_columns(const SlabLayout& l, int ng, int whole_nx) {
  return {std::max(l.first_column() - ng, -ng), std::min(l.end_column() + ng, whole_nx + ng)};
}
Columns overlap(Columns a, Columns b) {
  return {std::max(a.first, b.first), std::min(a.second, b.second)};
}

}  // namespace

bool SlabDriver::rebalance() {
  const ScopedTimer timer(balance_seconds_);
  const std::vector<double> whole_work = whole_column_work();
  const std::vector<int> bounds = balanced_slabs(whole_work, comm_->size(), kMinSlabColumns);
  if (!(largest_slab(whole_work, bounds) < 0.95 * largest_slab(whole_work, layout_.bounds)))
    return false;
  // The parcels and alpha_p, whole, on every rank: each splits them again at the new cuts
  // (keeping the contact lists: the move changes no bit).
  std::vector<double> parcels_whole, alpha_whole;
  if (sim_.parcels()) broadcast_whole_parcels(parcels_whole, alpha_whole);
  move_gas(bounds);
  if (sim_.parcels()) resplit_parcels(parcels_whole, alpha_whole);
  ++rebalances_;
  return true;
}

std::vector<double> SlabDriver::whole_column_work() const {
  // Work per column of the whole grid: the cells the last stage updated, plus a twentieth
  // of every cell for the scans that find the resting ones (an estimate; docs/parallel.md).
  std::vector<double> work(static_cast<std::size_t>(sim_.grid().nx()),
                           0.05 * static_cast<double>(sim_.grid().ny()));
  sim_.gas().add_column_work(work);
  if (sim_.parcels()) {
    // A parcel stepped in the last step costs about 2.4 cell updates (paper scene on 2 ranks:
    // 5.2e-8 s per parcel-sub-step x 11.4 sub-steps against 8.2e-8 s per cell-stage x 3
    // stages); one left resting only its check, taken as a tenth of that.
    constexpr double kParcelWeight = 2.4, kRestingParcelWeight = 0.24;
    const ParcelSystem& p = *sim_.parcels();
    const std::vector<double>& stepped = p.column(sim_.coupling()->stepped_column());
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.is_rank_copy(i)) continue;
      const int column = std::clamp(sim_.whole_grid().x().locate(p.x[i]) - layout_.first_column(),
                                    0, sim_.grid().nx() - 1);
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
  return whole_work;
}

void SlabDriver::broadcast_whole_parcels(std::vector<double>& parcels_whole,
                                         std::vector<double>& alpha_whole) const {
  gather(true);
  if (comm_->is_root()) {
    whole_parcels_->pack_owned(parcels_whole);
    alpha_whole = whole_alpha_p_->raw();
    alpha_whole.push_back(static_cast<double>(whole_rows_touched_));
  }
  comm_->broadcast(parcels_whole);
  comm_->broadcast(alpha_whole);
}

void SlabDriver::move_gas(const std::vector<int>& bounds) {
  // The state moves exactly: every rank sends each rank the columns of its new slab, ghost
  // columns included, that it holds now (its interior, and the ghost columns beyond a domain
  // end), every field and row. Only ranks whose columns overlap exchange anything.
  const int ng = kGhostLayers;
  const auto rows = static_cast<std::size_t>(sim_.whole_grid().ny() + 2 * ng);
  SlabLayout moved = layout_;
  moved.bounds = bounds;
  const auto stored = [&](const SlabLayout& l) { return stored_columns(l, ng); };
  const auto needed = [&](const SlabLayout& l) {
    return needed_columns(l, ng, sim_.whole_grid().nx());
  };
  const int ranks = comm_->size();
  std::vector<std::vector<double>> send(static_cast<std::size_t>(ranks)),
      receive(static_cast<std::size_t>(ranks));
  {
    const std::vector<Field2D*> old_fields = gas_state_fields(sim_.gas(), true);
    const std::pair<int, int> mine = stored(layout_);
    for (int q = 0; q < ranks; ++q) {
      const auto [a, b] = overlap(mine, needed(moved.of_rank(q)));
      if (a >= b) continue;
      std::vector<double>& out = send[static_cast<std::size_t>(q)];
      out.reserve(old_fields.size() * rows * static_cast<std::size_t>(b - a));
      for (const Field2D* f : old_fields) {
        for (int j = -ng; j < sim_.whole_grid().ny() + ng; ++j) {
          const double* row = f->data() + sim_.grid().index(a - layout_.first_column(), j);
          out.insert(out.end(), row, row + (b - a));
        }
      }
    }
    const std::pair<int, int> wanted = needed(moved);
    for (int q = 0; q < ranks; ++q) {
      const auto [a, b] = overlap(stored(layout_.of_rank(q)), wanted);
      if (a < b)
        receive[static_cast<std::size_t>(q)].resize(old_fields.size() * rows *
                                                    static_cast<std::size_t>(b - a));
    }
  }
  comm_->exchange(send, receive);
  const SlabLayout before = layout_;
  layout_ = moved;
  build_slab_gas();
  sim_.gas().initialize(
      sim_.scene().initial);  // the inflow states, as at the start; then the state
  const std::vector<Field2D*> new_fields = gas_state_fields(sim_.gas(), true);
  const std::pair<int, int> wanted = needed(layout_);
  for (int q = 0; q < ranks; ++q) {
    const auto [a, b] = overlap(stored(before.of_rank(q)), wanted);
    if (a >= b) continue;
    const std::vector<double>& in = receive[static_cast<std::size_t>(q)];
    std::size_t k = 0;
    for (Field2D* f : new_fields) {
      for (int j = -ng; j < sim_.whole_grid().ny() + ng; ++j) {
        std::copy_n(in.begin() + static_cast<std::ptrdiff_t>(k), b - a,
                    f->data() + sim_.grid().index(a - layout_.first_column(), j));
        k += static_cast<std::size_t>(b - a);
      }
    }
  }
}

void SlabDriver::resplit_parcels(std::vector<double>& parcels_whole,
                                 std::vector<double>& alpha_whole) {
  ParcelSystem split = *sim_.parcels();
  split.drop_decomposition();
  split.assign_packed({parcels_whole});
  take_run_state(split, *sim_.parcels());
  parcel_slabs_->split(split, parcel_cuts());
  *sim_.parcels() = std::move(split);
  sim_.coupling()->move_to_slab(sim_.grid(), layout_.first_column(), *halo_);
  GasParticleCoupling::CarriedState c;
  c.rows_touched = static_cast<int>(alpha_whole.back());
  alpha_whole.pop_back();
  extract_slab(alpha_whole, sim_.whole_grid(), layout_, c.alpha_p);
  c.rest_p = sim_.coupling()->rest_pressure();
  c.rest_T = sim_.coupling()->rest_temperature();
  sim_.coupling()->restore_carried_state(c);
}

std::vector<double> SlabDriver::parcel_cuts() const {
  std::vector<double> cuts;
  for (int q = 1; q < comm_->size(); ++q)
    cuts.push_back(sim_.whole_grid().x().face(layout_.bounds[static_cast<std::size_t>(q)]));
  return cuts;
}

void SlabDriver::gather_parcels(bool with_lists, bool band_only) const {
  if (!sim_.parcels()) return;
  std::vector<double> mine;
  const ParcelSystem& p = *sim_.parcels();
  const auto in_a_band = [&](std::size_t i) {
    for (const BandConfig& b : sim_.scene().output.bands) {
      if (p.x_initial[i] >= b.x_min && p.x_initial[i] <= b.x_max && p.y_initial[i] >= b.y_min &&
          p.y_initial[i] <= b.y_max) {
        return true;
      }
    }
    return false;
  };
  sim_.parcels()->pack_owned(mine, with_lists,
                             band_only ? std::function<bool(std::size_t)>(in_a_band) : nullptr);
  std::vector<std::vector<double>> pieces;
  comm_->gather(mine, pieces);
  const int rows =
      static_cast<int>(-comm_->min(-static_cast<double>(sim_.coupling()->rows_touched())));
  if (!comm_->is_root()) return;
  if (!whole_parcels_) {
    whole_parcels_ = std::make_unique<ParcelSystem>(sim_.scene().particles);
    for (std::size_t k = 0; k < sim_.parcels()->attached_count(); ++k)
      whole_parcels_->attach_column(sim_.parcels()->attached_spec(k));
  }
  whole_parcels_->assign_packed(pieces);
  whole_rows_touched_ = rows;
  if (!with_lists) return;
  take_run_state(*whole_parcels_, *sim_.parcels());
}

void SlabDriver::gather(bool with_sources, unsigned reads) const {
  if (with_sources) reads = Observer::kReadsEverything;
  const bool all_gas = (reads & Observer::kReadsGas) != 0;
  const bool alpha =
      sim_.coupling() && (reads & (Observer::kReadsGas | Observer::kReadsAlphaP)) != 0;
  constexpr int kPressure = Primitive::kPressure;
  std::vector<Field2D*> fields;
  if (all_gas) {
    fields = gas_state_fields(sim_.gas(), with_sources);
  } else if ((reads & Observer::kReadsPressure) != 0) {
    fields.push_back(&sim_.gas().primitive_field(kPressure));
  }
  // alpha_p goes with the gas (read only: pack_slab copies it).
  if (alpha) fields.push_back(const_cast<Field2D*>(&sim_.coupling()->alpha_p()));
  // One message per rank: the fields' slab parts one after another.
  std::vector<double> piece;
  for (const Field2D* f : fields) {
    const std::vector<double> part = pack_slab(*f, sim_.grid(), layout_);
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
    if (!whole_alpha_p_) whole_alpha_p_ = std::make_unique<Field2D>(sim_.whole_grid());
    targets.push_back(whole_alpha_p_.get());
  }
  for (int r = 0; r < comm_->size(); ++r) {
    const SlabLayout of_r = layout_.of_rank(r);
    const std::size_t part =
        static_cast<std::size_t>(of_r.stored_end(kGhostLayers) - of_r.stored_begin(kGhostLayers)) *
        static_cast<std::size_t>(sim_.whole_grid().ny() + 2 * kGhostLayers);
    const std::vector<double>& all = pieces[static_cast<std::size_t>(r)];
    for (std::size_t f = 0; f < targets.size(); ++f) {
      unpack_slab(std::span<const double>(all).subspan(f * part, part), sim_.whole_grid(), of_r,
                  targets[f]->raw());
    }
  }
}

}  // namespace dustlift
