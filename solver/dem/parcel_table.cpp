// The parcel table's column list and its whole-table operations.
#include "solver/dem/parcel_table.hpp"

#include <stdexcept>
#include <utility>

#include "solver/dem/permute.hpp"

namespace dustlift {
namespace {

using T = ParcelTable;

/// A checkpointed carried column of parcel state.
ParcelTable::BuiltinColumn state(const char* name, const char* unit, std::vector<double> T::*member,
                                 const char* written_as = "", int component = 0,
                                 ForcePart part = ForcePart::None) {
  ParcelColumnSpec s{name, unit, true, *written_as != '\0'};
  s.checkpoint_name = std::string("parcels/") + name;
  s.written_as = written_as;
  s.component = component;
  s.part = part;
  return {std::move(s), member};
}

/// A column of the DEM's own bookkeeping: `checkpoint` names its dataset ("" = not kept).
template <class V>
ParcelTable::BuiltinColumn bookkeeping(const char* name, const char* unit, ColumnFlow flow,
                                       V T::*member, const char* checkpoint, int per_parcel = 1) {
  ParcelColumnSpec s{name, unit, *checkpoint != '\0', false};
  s.flow = flow;
  s.per_parcel = per_parcel;
  s.checkpoint_name = checkpoint;
  return {std::move(s), member};
}

}  // namespace

const std::vector<ParcelTable::BuiltinColumn>& ParcelTable::builtin_columns() {
  // Force parts, torques and heat are per REAL particle. The written columns are in the
  // order the .vtp lists its point arrays.
  using F = ColumnFlow;
  static const std::vector<BuiltinColumn> columns = {
      state("x", "m", &T::x, "position", 0),
      state("y", "m", &T::y, "position", 1),
      state("vx", "m/s", &T::vx, "velocity", 0),
      state("vy", "m/s", &T::vy, "velocity", 1),
      state("omega", "rad/s", &T::omega, "angular_velocity"),
      state("temperature", "K", &T::temperature, "temperature"),
      state("diameter", "m", &T::diameter, "diameter"),
      state("real_diameter", "m", &T::real_diameter, "particle_diameter"),
      state("size_class", "1", &T::size_class, "size_class"),
      state("radius", "m", &T::radius),
      state("mass", "kg/m", &T::mass),
      state("inertia", "kg m", &T::inertia),
      state("n_real", "1/m", &T::n_real),
      state("x_initial", "m", &T::x_initial, "initial_position", 0),
      state("y_initial", "m", &T::y_initial, "initial_position", 1),
      state("contact_fx", "N", &T::contact_fx, "force_contact", 0, ForcePart::Contact),
      state("contact_fy", "N", &T::contact_fy, "force_contact", 1, ForcePart::Contact),
      state("contact_torque", "N m", &T::contact_torque),
      bookkeeping("id", "1", F::Carried, &T::id, "parcels/id"),
      bookkeeping("inv_mass_real", "1/kg", F::Carried, &T::inv_mass_real, "dem/inv_mass_real"),
      bookkeeping("inv_inertia_real", "1/(kg m^2)", F::Carried, &T::inv_inertia_real,
                  "dem/inv_inertia_real"),
      bookkeeping("wall_delta", "m", F::Carried, &T::wall_delta, "parcels/wall_delta", kWallCount),
      bookkeeping("x_build", "m", F::Carried, &T::x_build, "dem/x_build"),
      bookkeeping("y_build", "m", F::Carried, &T::y_build, "dem/y_build"),
      bookkeeping("half_skin", "m", F::Rebuilt, &T::half_skin, "dem/half_skin"),
      bookkeeping("wall_mask", "1", F::Rebuilt, &T::wall_mask, "dem/wall_mask"),
      bookkeeping("inv_skin2", "1/m^2", F::Cache, &T::inv_skin2, ""),
      bookkeeping("order_key", "1", F::Ranks, &T::order_key, ""),
      bookkeeping("rank_copy", "1", F::Ranks, &T::rank_copy, ""),
  };
  return columns;
}

ParcelColumn ParcelTable::attach_column(ParcelColumnSpec spec) {
  spec.flow = ColumnFlow::Carried;
  attached_specs_.push_back(std::move(spec));
  attached_.emplace_back(size(), 0.0);
  attached_.back().reserve(x.capacity());
  return ParcelColumn{attached_.size() - 1};
}

ParcelColumn ParcelTable::find_column(std::string_view name) const {
  for (std::size_t k = 0; k < attached_specs_.size(); ++k)
    if (attached_specs_[k].name == name) return ParcelColumn{k};
  return {};
}

ParcelColumn ParcelTable::find_part(ForcePart part, int component) const {
  for (std::size_t k = 0; k < attached_specs_.size(); ++k) {
    const ParcelColumnSpec& s = attached_specs_[k];
    if (s.part == part && s.component == component) return ParcelColumn{k};
  }
  return {};
}

void ParcelTable::append_zero_row() {
  for_each_column([](const ParcelColumnSpec& s, auto& v) {
    using V = std::remove_reference_t<decltype(v)>;
    if (s.flow == ColumnFlow::Carried)
      v.insert(v.end(), static_cast<std::size_t>(s.per_parcel), typename V::value_type{});
    if (s.flow == ColumnFlow::Rebuilt) v.clear();
  });
}

void ParcelTable::permute_rows(const std::vector<std::int32_t>& order, bool carried, bool rebuilt) {
  const auto scratch_for = [this](auto& v) -> auto& {
    using E = typename std::remove_reference_t<decltype(v)>::value_type;
    if constexpr (std::is_same_v<E, double>)
      return scratch_f64_;
    else if constexpr (std::is_same_v<E, std::int32_t>)
      return scratch_i32_;
    else if constexpr (std::is_same_v<E, std::int64_t>)
      return scratch_i64_;
    else
      return scratch_u8_;
  };
  for_each_column([&](const ParcelColumnSpec& s, auto& v) {
    const bool moves = (carried && s.flow == ColumnFlow::Carried) ||
                       (rebuilt && s.flow == ColumnFlow::Rebuilt) ||
                       (carried && s.flow == ColumnFlow::Ranks && !v.empty());
    if (!moves) return;
    if (s.per_parcel == 1) {
      permute(v, order, scratch_for(v));
    } else {
      if constexpr (std::is_same_v<typename std::remove_reference_t<decltype(v)>::value_type,
                                   double>) {
        permute_strided(v, order, static_cast<std::size_t>(s.per_parcel), scratch_wide_);
      } else {
        throw std::logic_error("ParcelTable: a wide column must hold doubles");
      }
    }
  });
}

std::size_t ParcelTable::packed_row_size() const {
  std::size_t n = 2;  // order key, id
  for_each_column([&](const ParcelColumnSpec& s, const auto&) {
    if ((s.flow == ColumnFlow::Carried || s.flow == ColumnFlow::Rebuilt) && s.name != "id")
      n += static_cast<std::size_t>(s.per_parcel);
  });
  return n;
}

void ParcelTable::pack_row(std::size_t i, std::vector<double>& out) const {
  out.push_back(
      static_cast<double>(order_key.empty() ? static_cast<std::int64_t>(i) : order_key[i]));
  out.push_back(static_cast<double>(id[i]));
  const std::size_t n = size();
  for_each_column([&](const ParcelColumnSpec& s, const auto& v) {
    if ((s.flow != ColumnFlow::Carried && s.flow != ColumnFlow::Rebuilt) || s.name == "id") return;
    const auto width = static_cast<std::size_t>(s.per_parcel);
    const bool made = v.size() == n * width;  // a rebuilt column before the first rebuild: zeros
    for (std::size_t c = 0; c < width; ++c)
      out.push_back(made ? static_cast<double>(v[i * width + c]) : 0.0);
  });
}

const double* ParcelTable::append_packed_row(const double* row, bool copy) {
  order_key.push_back(static_cast<std::int64_t>(*row++));
  id.push_back(static_cast<std::int32_t>(*row++));
  for_each_column([&](const ParcelColumnSpec& s, auto& v) {
    if ((s.flow != ColumnFlow::Carried && s.flow != ColumnFlow::Rebuilt) || s.name == "id") return;
    using E = typename std::remove_reference_t<decltype(v)>::value_type;
    for (int c = 0; c < s.per_parcel; ++c) v.push_back(static_cast<E>(*row++));
  });
  rank_copy.push_back(copy ? 1 : 0);
  return row;
}

}  // namespace dustlift
