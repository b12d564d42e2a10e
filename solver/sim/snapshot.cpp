// Simulation::snapshot / restore: the state a bitwise continuation needs, by name.
// What is (and is not) in it and why: docs/reliability.md.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <type_traits>

#include "solver/parallel/slab_decomposition.hpp"
#include "solver/sim/simulation.hpp"
#include "solver/sim/slab_driver.hpp"
#include "solver/sim/time_targets.hpp"

namespace dustlift {
namespace {

/// The checkpoint's map for a column's element type (the wall mask's bits are stored as int8).
template <class E>
auto& snapshot_map(Snapshot& s) {
  if constexpr (std::is_same_v<E, double>)
    return s.f64;
  else if constexpr (std::is_same_v<E, std::int32_t>)
    return s.i32;
  else if constexpr (std::is_same_v<E, std::int64_t>)
    return s.i64;
  else
    return s.i8;
}
template <class E>
const auto& snapshot_map(const Snapshot& s) {
  return snapshot_map<E>(const_cast<Snapshot&>(s));
}

/// The dataset of a checkpointed column: a built-in one's own, "parcels/attached_<name>" for
/// an attached one.
std::string checkpoint_name(const ParcelColumnSpec& c) {
  return c.checkpoint_name.empty() ? "parcels/attached_" + c.name : c.checkpoint_name;
}

const char* const kPrimitiveNames[5] = {"rho", "u", "v", "p", "T"};

/// Checkpoint group of an observer's state.
std::string observer_prefix(const std::string& key) {
  return "insitu/" + key + "/";
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (std::size_t k = 0; k < v.size(); ++k) s += (k ? "\n" : "") + v[k];
  return s;
}

}  // namespace

Snapshot Simulation::snapshot() const {
  Snapshot s;
  s.text["scene/name"] = scene_.source_file;
  s.text["scene/text"] = scene_.source_text;
  s.text["scene/overrides"] = join(scene_.overrides);
  s.text["scene/resolved"] = scene_.resolved_toml;
  s.f64["run/time"] = {time_};
  s.f64["run/output_interval"] = {scene_.output.interval};
  s.f64["run/end_time"] = {end_target(scene_.run.end_time, scene_.output.interval)};
  s.i64["run/step"] = {step_};
  s.i64["run/next_output"] = {outputs_.next_index()};
  // Gas: every field step() reads, ghosts included (1-D, row-major (ny + 2g) x (nx + 2g)).
  s.i64["gas/shape"] = {whole_grid_.ny() + 2 * whole_grid_.ghosts(),
                        whole_grid_.nx() + 2 * whole_grid_.ghosts()};
  // A decomposed run gathers the whole grid on rank 0 and writes the same checkpoint as one
  // rank would: it restarts on any number of ranks. The other ranks' snapshots stop here.
  if (slabs_) slabs_->gather(true);
  if (slabs_ && !slabs_->comm().is_root()) return s;
  // Read through the const accessors: the writing ones mark the state as written from
  // outside, which would make the next step check every cell and scan all the resting gas and
  // sources again.
  const GasSolver& gas = slabs_ ? *slabs_->whole_gas() : *gas_;
  for (int k = 0; k < 4; ++k) {
    s.f64["gas/conserved_" + std::to_string(k)] = gas.conserved(k).raw();
    s.f64["gas/source_" + std::to_string(k)] = gas.source(k).raw();
  }
  const GasPrimitives g = gas.primitives();
  s.f64["gas/porosity"] = g.alpha_g->raw();
  const Field2D* const primitives[5] = {g.rho, g.u, g.v, g.p, g.T};
  for (int k = 0; k < 5; ++k)
    s.f64[std::string("gas/") + kPrimitiveNames[k]] = primitives[k]->raw();
  for (const auto& o : observers_) {
    if (const std::string key = o->state_key(); !key.empty())
      o->save_state(s, observer_prefix(key));
  }
  if (!parcels_) return s;

  // A decomposed run writes the gathered parcels (gathered above): the one-rank system.
  const ParcelSystem& p = slabs_ ? *slabs_->whole_parcels() : *parcels_;
  p.for_each_column([&](const ParcelColumnSpec& c, const auto& v) {
    using E = typename std::remove_reference_t<decltype(v)>::value_type;
    if (c.checkpointed) snapshot_map<E>(s)[checkpoint_name(c)].assign(v.begin(), v.end());
  });
  s.f64["parcels/nbr_delta"] = p.nbr_delta;
  s.i32["parcels/nbr_offset"] = p.nbr_offset;
  s.i32["parcels/nbr_index"] = p.nbr_index;
  s.i8["parcels/nbr_image"] = p.nbr_image;
  const ParcelInternals in = p.internals();
  s.f64["dem/time"] = {in.time};
  s.f64["dem/gravity"] = {in.gravity_x, in.gravity_y};
  s.i64["dem/needs_rebuild"] = {in.needs_rebuild ? 1 : 0};
  s.i64["dem/steps"] = {in.steps};
  s.i64["dem/rebuilds"] = {in.rebuilds};
  s.f64["coupling/alpha_p"] = slabs_ ? slabs_->whole_alpha_p()->raw() : coupling_->alpha_p().raw();
  s.i64["coupling/rows_touched"] = {slabs_ ? slabs_->whole_rows_touched()
                                           : coupling_->rows_touched()};
  s.f64["coupling/rest_reference"] = {coupling_->rest_pressure(), coupling_->rest_temperature()};
  return s;
}

namespace {

/// Each observer's state, checked as it is taken.
void restore_observers(const std::vector<std::unique_ptr<Observer>>& observers, const Snapshot& s) {
  for (const auto& o : observers) {
    const std::string key = o->state_key();
    if (key.empty()) continue;
    const std::string prefix = observer_prefix(key);
    const auto has_prefix = [&](const auto& m) {
      const auto it = m.lower_bound(prefix);
      return it != m.end() && it->first.compare(0, prefix.size(), prefix) == 0;
    };
    if (!has_prefix(s.f64) && !has_prefix(s.i64) && !has_prefix(s.text)) {
      throw SnapshotError("no state for the in-situ output '" + key +
                          "' (a checkpoint of an older dustlift, or of a run with other outputs)");
    }
    o->restore_state(s, prefix);
  }
}

/// The whole grid's gas fields, read (and their lengths checked) before anything is assigned.
using StoredGas = std::array<const std::vector<double>*, 14>;
StoredGas read_gas(const Snapshot& s, std::size_t cells) {
  StoredGas gas_fields{};
  for (int k = 0; k < 4; ++k) {
    gas_fields[k] = &snapshot_array(s.f64, "gas/conserved_" + std::to_string(k), cells);
    gas_fields[4 + k] = &snapshot_array(s.f64, "gas/source_" + std::to_string(k), cells);
  }
  gas_fields[8] = &snapshot_array(s.f64, "gas/porosity", cells);
  for (int k = 0; k < 5; ++k)
    gas_fields[9 + k] = &snapshot_array(s.f64, std::string("gas/") + kPrimitiveNames[k], cells);
  return gas_fields;
}

/// The parcel columns a checkpoint holds (`n` parcels), the neighbour lists with their
/// history and the DEM's internals, into `restored` and `in`.
void read_parcel_columns(const Snapshot& s, std::size_t n, bool has_attached,
                         ParcelSystem& restored, ParcelInternals& in) {
  in.needs_rebuild = snapshot_array(s.i64, "dem/needs_rebuild", 1)[0] != 0;
  restored.for_each_column([&](const ParcelColumnSpec& c, auto& v) {
    using E = typename std::remove_reference_t<decltype(v)>::value_type;
    if (!c.checkpointed) return;
    const std::string name = checkpoint_name(c);
    const std::size_t rows = n * static_cast<std::size_t>(c.per_parcel);
    const auto& map = snapshot_map<E>(s);
    if (c.flow == ColumnFlow::Rebuilt) {
      // Made by the next rebuild when the checkpoint lacks it (older checkpoints have no skins).
      const auto it = map.find(name);
      if (it == map.end() || it->second.size() != rows) {
        v.clear();
        in.needs_rebuild = true;
      } else {
        v.assign(it->second.begin(), it->second.end());
      }
    } else if (c.checkpoint_name.empty() && !has_attached) {
      std::fill(v.begin(), v.end(), E{});
    } else {
      const auto& stored = snapshot_array(map, name, rows);
      v.assign(stored.begin(), stored.end());
    }
  });
  restored.nbr_delta = snapshot_array(s.f64, "parcels/nbr_delta");
  restored.nbr_offset = snapshot_array(s.i32, "parcels/nbr_offset");
  restored.nbr_index = snapshot_array(s.i32, "parcels/nbr_index");
  restored.nbr_image = snapshot_array(s.i8, "parcels/nbr_image");
  in.time = snapshot_array(s.f64, "dem/time", 1)[0];
  const auto& gravity = snapshot_array(s.f64, "dem/gravity", 2);
  in.gravity_x = gravity[0];
  in.gravity_y = gravity[1];
  in.steps = snapshot_array(s.i64, "dem/steps", 1)[0];
  in.rebuilds = snapshot_array(s.i64, "dem/rebuilds", 1)[0];
}

/// Ids must be a permutation of 0..n-1 (they name the parcels in the outputs).
void check_ids(const std::vector<std::int32_t>& ids, std::size_t n) {
  std::vector<char> seen(n, 0);
  for (std::int32_t i : ids) {
    if (i < 0 || static_cast<std::size_t>(i) >= n || seen[static_cast<std::size_t>(i)]) {
      throw SnapshotError("parcels/id is not a permutation of 0.." + std::to_string(n - 1));
    }
    seen[static_cast<std::size_t>(i)] = 1;
  }
}

}  // namespace

void Simulation::restore(const Snapshot& s, const std::string& previous_output_dir) {
  const auto shape = snapshot_array(s.i64, "gas/shape", 2);
  if (shape[0] != whole_grid_.ny() + 2 * whole_grid_.ghosts() ||
      shape[1] != whole_grid_.nx() + 2 * whole_grid_.ghosts()) {
    throw SnapshotError("gas/shape " + std::to_string(shape[0]) + " x " + std::to_string(shape[1]) +
                        " does not match the scene's grid");
  }
  const bool has_parcels = s.i32.count("parcels/id") != 0;
  if (has_parcels != (parcels_ != nullptr)) {
    throw SnapshotError(has_parcels ? "the checkpoint has parcels but the scene has none"
                                    : "the scene has particles but the checkpoint has no parcels");
  }
  const double t = snapshot_array(s.f64, "run/time", 1)[0];
  const long long step = snapshot_array(s.i64, "run/step", 1)[0];
  long long next_output = snapshot_array(s.i64, "run/next_output", 1)[0];
  if (!std::isfinite(t) || t < 0.0 || step < 0 || next_output < 1)
    throw SnapshotError("run time or counters out of range");
  const std::size_t cells = whole_grid_.size_with_ghosts();
  // The observers first: their state is checked as it is taken, and a failure leaves the
  // simulation untouched (a failed restore ends the program anyway).
  restore_observers(observers_, s);
  // Read everything first, assign after: a failing restore leaves nothing half-written.
  const StoredGas gas_fields = read_gas(s, cells);
  if (parcels_) restore_parcels(s, cells);
  assign_gas(gas_fields);
  time_ = t;
  step_ = step;
  // A restart may change output.interval: the next output is then the first multiple after t.
  const auto stored_interval = s.f64.find("run/output_interval");
  const double interval = scene_.output.interval;
  if (stored_interval == s.f64.end() || stored_interval->second.size() != 1 ||
      stored_interval->second[0] != interval) {
    next_output = interval > 0.0 ? first_multiple_after(t, interval) : 1;
  }
  outputs_.set_next_index(next_output);
  derived_whole_.forget();
  derived_piece_.forget();
  restored_ = true;
  resumed_from_ = previous_output_dir;
}

void Simulation::restore_parcels(const Snapshot& s, std::size_t cells) {
  ParcelSystem& p = *parcels_;
  // A decomposed run reads the whole system on every rank and splits it again below.
  const std::size_t n = slabs_ ? total_parcels_ : p.size();
  ParcelSystem restored = p;  // validated on the copy, then swapped in
  if (slabs_) {
    restored.drop_decomposition();
    // Columns the checkpoint does not hold are made anew within each step: sized only.
    for (std::size_t k = 0; k < restored.attached_count(); ++k) restored.attached(k).assign(n, 0.0);
  }
  // Attached columns a restart needs; checkpoints from before they were kept have none,
  // which leaves them zero (the rest counts then start anew: exact skipping is unaffected).
  const bool has_attached = s.f64.count("coupling/rest_reference") != 0;
  ParcelInternals in;
  read_parcel_columns(s, n, has_attached, restored, in);
  check_ids(restored.id, n);
  try {
    restored.restore_internals(in);
  } catch (const std::invalid_argument& e) {
    throw SnapshotError(e.what());
  }
  GasParticleCoupling::CarriedState c;
  c.alpha_p = snapshot_array(s.f64, "coupling/alpha_p", cells);
  if (slabs_) {
    std::vector<double> slab;
    extract_slab(c.alpha_p, whole_grid_, slabs_->layout(), slab);
    c.alpha_p.swap(slab);
    slabs_->split(restored);
  }
  c.rows_touched = static_cast<int>(snapshot_array(s.i64, "coupling/rows_touched", 1)[0]);
  if (has_attached) {
    const auto& ref = snapshot_array(s.f64, "coupling/rest_reference", 2);
    c.rest_p = ref[0];
    c.rest_T = ref[1];
  }
  try {
    coupling_->restore_carried_state(c);
  } catch (const std::invalid_argument& e) {
    throw SnapshotError(e.what());
  }
  p = std::move(restored);
}

void Simulation::assign_gas(const std::array<const std::vector<double>*, 14>& gas_fields) {
  // A slab takes its columns and the ghost columns beyond them (its neighbours' cells).
  const auto assign = [&](Field2D& f, const std::vector<double>& whole) {
    if (slabs_) {
      extract_slab(whole, whole_grid_, slabs_->layout(), f.raw());
    } else {
      f.raw() = whole;
    }
  };
  for (int k = 0; k < 4; ++k) {
    assign(gas_->conserved(k), *gas_fields[k]);
    assign(gas_->source(k), *gas_fields[4 + k]);
  }
  assign(gas_->porosity(), *gas_fields[8]);
  for (int k = 0; k < 5; ++k) assign(gas_->primitive_field(k), *gas_fields[9 + k]);
}

}  // namespace dustlift
