#pragma once
// Every per-parcel array of the DEM as one table of typed columns. Each column says what it
// holds (name, unit) and how it follows the parcels: whether the cell sort permutes it,
// whether it travels with a parcel to another rank (and into a gather), whether a checkpoint
// keeps it, and whether the outputs write it. The cell sort, the moves between ranks, the
// checkpoint, the .vtp writer and Catalyst all iterate this one list, so a new per-parcel
// field is one line in builtin_columns() (or one attach_column call from the module that
// owns it).
//
// Units: 2-D, per metre of depth (see parcel_system.hpp).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "solver/laws/force_part.hpp"

namespace dustlift {

/// Wall slots of the per-parcel wall history, in this order.
enum class Wall : int { Bottom = 0, Top = 1, Left = 2, Right = 3, Count = 4 };
inline constexpr int kWallCount = static_cast<int>(Wall::Count);

/// How a column follows the parcels.
enum class ColumnFlow {
  /// Parcel state: permuted by the cell sort, moved with its parcel to another rank,
  /// gathered, one row per parcel always.
  Carried,
  /// Made by every neighbour rebuild right after its sort (so the sort leaves it alone);
  /// moved with its parcel, and empty until the first rebuild.
  Rebuilt,
  /// A cache of other columns, remade wherever they change; never moved.
  Cache,
  /// Exists only when the parcels are split over ranks (empty otherwise); permuted by the
  /// sort, set by the decomposition itself when parcels move.
  Ranks,
};

/// A column of the parcel table: its name and unit (as written to checkpoints, .vtp and
/// Catalyst) and what it is for. The first four fields are what a module attaching a column
/// sets; the rest describe the built-in columns.
struct ParcelColumnSpec {
  std::string name;
  std::string unit;
  bool checkpointed = false;  ///< part of the state a restart needs
  bool written = false;       ///< written to the .vtp (and published in situ)
  ColumnFlow flow = ColumnFlow::Carried;
  int per_parcel = 1;                ///< values per parcel (the wall history: one per wall)
  std::string checkpoint_name = {};  ///< dataset of a checkpointed built-in column
  /// A written column's point array and component (two columns make one 2-D vector);
  /// "position" is the points themselves.
  std::string written_as = {};
  int component = 0;
  ForcePart part = ForcePart::None;  ///< written only when this part is computed
};

/// Handle of a column attached to a ParcelTable (see attach_column).
struct ParcelColumn {
  std::size_t index = static_cast<std::size_t>(-1);
  bool valid() const { return index != static_cast<std::size_t>(-1); }
};

/// The per-parcel arrays (structure of arrays; the order changes when the parcels are
/// re-sorted by cell) and the columns other modules attach.
class ParcelTable {
 public:
  // ---- Parcel state and properties ----
  std::vector<std::int32_t> id;       ///< stable parcel id (order of adding)
  std::vector<double> x, y;           ///< m (x unwrapped between rebuilds when periodic)
  std::vector<double> vx, vy;         ///< m/s
  std::vector<double> omega;          ///< rad/s, counter-clockwise positive
  std::vector<double> temperature;    ///< K
  std::vector<double> diameter;       ///< m, parcel
  std::vector<double> real_diameter;  ///< m, the real particles the parcel stands for
  /// The layer's size class the parcel belongs to (0 for a monodisperse layer). Held as a
  /// double because every written parcel array is one; always a small whole number.
  std::vector<double> size_class;
  std::vector<double> radius;                ///< m, parcel (contact lever arm)
  std::vector<double> mass;                  ///< kg/m, parcel (n_real m_real)
  std::vector<double> inertia;               ///< kg m, parcel (cylinder: mass r^2 / 2)
  std::vector<double> n_real;                ///< real particles per parcel (per metre)
  std::vector<double> x_initial, y_initial;  ///< m, where the parcel started (in-situ filters)
  std::vector<double> inv_mass_real, inv_inertia_real;  ///< 1/m and 1/I of one real particle

  // ---- Contact forces per REAL particle (N, N m), recomputed every sub-step. The parts of
  // other effects (drag, lift, ...) are columns their effect attaches (ForcePart tags them).
  std::vector<double> contact_fx, contact_fy, contact_torque;

  // ---- Contact bookkeeping ----
  /// Tangential elongation of each parcel against each wall: wall_delta[i * kWallCount + w].
  std::vector<double> wall_delta;
  std::vector<double> x_build, y_build;  ///< positions at the last neighbour rebuild
  std::vector<double> half_skin;         ///< how far each may move until the next rebuild
  std::vector<double> inv_skin2;         ///< 1 / half_skin^2 (0: never asks for a rebuild)
  std::vector<std::uint8_t> wall_mask;   ///< bit w: wall w within reach until the next rebuild

  // ---- Parcels split over ranks (empty otherwise) ----
  /// Each parcel's index in the one-rank run's parcel order.
  std::vector<std::int64_t> order_key;
  /// 1: another rank's parcel, copied here for the contacts and the coupling's stencils.
  std::vector<std::uint8_t> rank_copy;

  /// The number of parcels.
  std::size_t size() const { return x.size(); }

  /// A built-in column: its spec and the member holding it.
  using Member =
      std::variant<std::vector<double> ParcelTable::*, std::vector<std::int32_t> ParcelTable::*,
                   std::vector<std::int64_t> ParcelTable::*,
                   std::vector<std::uint8_t> ParcelTable::*>;
  struct BuiltinColumn {
    ParcelColumnSpec spec;
    Member member;
  };
  /// The built-in columns, in the order the outputs write them.
  static const std::vector<BuiltinColumn>& builtin_columns();
  /// Whether a column is one of the parcel state's doubles (position, velocity, spin,
  /// temperature, properties, force parts): what a run's result is compared by.
  static bool is_state(const ParcelColumnSpec& c) {
    return c.checkpoint_name.rfind("parcels/", 0) == 0 && c.per_parcel == 1 && c.name != "id";
  }

  /// Calls f(spec, values) for every column: the built-in ones (values a std::vector of their
  /// element type), then the attached ones (std::vector<double>), in order.
  template <class F>
  void for_each_column(F&& f) {
    for (const BuiltinColumn& c : builtin_columns())
      std::visit([&](auto m) { f(c.spec, this->*m); }, c.member);
    for (std::size_t k = 0; k < attached_.size(); ++k) f(attached_specs_[k], attached_[k]);
  }
  template <class F>
  void for_each_column(F&& f) const {
    for (const BuiltinColumn& c : builtin_columns())
      std::visit([&](auto m) { f(c.spec, this->*m); }, c.member);
    for (std::size_t k = 0; k < attached_.size(); ++k) f(attached_specs_[k], attached_[k]);
  }

  /// Calls f(spec, mine, theirs) for every column of this table and the same column of
  /// `other` (a table with the same attached columns), e.g. to compare two runs.
  template <class F>
  void for_each_column_pair(const ParcelTable& other, F&& f) const {
    for (const BuiltinColumn& c : builtin_columns())
      std::visit([&](auto m) { f(c.spec, this->*m, other.*m); }, c.member);
    for (std::size_t k = 0; k < attached_.size() && k < other.attached_.size(); ++k)
      f(attached_specs_[k], attached_[k], other.attached_[k]);
  }

  /// Attaches a column of doubles (zeros for the parcels present, and for parcels added
  /// later); from then on it is permuted and moved with the parcels.
  ParcelColumn attach_column(ParcelColumnSpec spec);
  std::vector<double>& column(ParcelColumn c) { return attached_[c.index]; }
  const std::vector<double>& column(ParcelColumn c) const { return attached_[c.index]; }
  /// The attached column of that name (an invalid handle when there is none).
  ParcelColumn find_column(std::string_view name) const;
  /// The attached column tagged with force part `part` and component `component` (an invalid
  /// handle when no effect computes that part).
  ParcelColumn find_part(ForcePart part, int component) const;
  /// The attached columns, in the order attached.
  std::size_t attached_count() const { return attached_.size(); }
  const ParcelColumnSpec& attached_spec(std::size_t k) const { return attached_specs_[k]; }
  const std::vector<double>& attached(std::size_t k) const { return attached_[k]; }
  std::vector<double>& attached(std::size_t k) { return attached_[k]; }

  /// Whether parcel i is another rank's copy.
  bool is_rank_copy(std::size_t i) const { return !rank_copy.empty() && rank_copy[i] != 0; }

  // ---- Whole-table operations (the cell sort, moves between ranks, gathers) ----
  /// A new row with every carried column zero (the caller sets its values); the rebuilt
  /// columns are emptied (the next rebuild makes them for every parcel).
  void append_zero_row();
  /// Row k of every column of the given flows becomes old row order[k] (a permutation or a
  /// selection of rows); empty Ranks columns stay empty.
  void permute_rows(const std::vector<std::int32_t>& order, bool carried, bool rebuilt);
  /// Values of one parcel packed as doubles: its order key (its index when there is none)
  /// and id, then every moved column (carried and rebuilt; a rebuilt column not yet made
  /// packs zeros).
  void pack_row(std::size_t i, std::vector<double>& out) const;
  /// Appends a row packed by pack_row (of a table with the same attached columns); returns
  /// the value after it. Sets rank_copy when the table holds rank copies.
  const double* append_packed_row(const double* row, bool copy);
  /// Doubles pack_row writes per parcel.
  std::size_t packed_row_size() const;

 private:
  std::vector<ParcelColumnSpec> attached_specs_;
  std::vector<std::vector<double>> attached_;
  // Scratch of permute_rows, one per element type and one for the wide columns (kept to
  // avoid reallocation: a buffer swapped into a column keeps its size class).
  std::vector<double> scratch_f64_, scratch_wide_;
  std::vector<std::int32_t> scratch_i32_;
  std::vector<std::int64_t> scratch_i64_;
  std::vector<std::uint8_t> scratch_u8_;
};

}  // namespace dustlift
