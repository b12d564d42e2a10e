#pragma once
// Read-only views of parcel arrays (structure of arrays) for the writers and filters.
// VTK-free. A ParcelSystem adaptor points the spans at its own arrays: no copies.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace dustlift {

/// A column of parcel values. Absent (not written / not averaged): a default span, without
/// a data pointer. A present column of no parcel (a rank whose parcels all left) still has
/// one: present_column gives it, so that such a piece holds the same arrays as the others.
inline bool is_present(std::span<const double> column) {
  return column.data() != nullptr;
}
inline std::span<const double> present_column(const std::vector<double>& values) {
  static constexpr double kNoValue = 0.0;  // a data pointer for a column of no parcel
  return values.empty() ? std::span<const double>(&kNoValue, 0) : std::span<const double>(values);
}

/// A 2-D vector stored as two columns (absent as is_present says).
struct Vec2Columns {
  std::span<const double> x, y;
  bool present() const { return is_present(x); }
};

/// One point array of the parcels under its name: a scalar (y absent) or a 2-D vector.
struct ParcelPointArray {
  std::string name;
  std::span<const double> x, y;
  bool is_vector() const { return is_present(y); }
};

/// Parcel state for the .vtp writer and Catalyst: the positions, the ids and the point arrays
/// in the order they are written, each `count` long. The writer of a run builds it from the
/// parcel table's written columns; the point order is the parcel system's (it changes as the
/// DEM re-sorts); `id` names each parcel for good (ParaView: Temporal Particles To Pathlines
/// follows it over time).
struct ParcelArraysView {
  std::size_t count = 0;
  Vec2Columns position;              ///< m (required)
  std::span<const std::int32_t> id;  ///< stable parcel id
  std::vector<ParcelPointArray> arrays;
  void add(std::string name, std::span<const double> values) {
    arrays.push_back({std::move(name), values, {}});
  }
  void add(std::string name, const Vec2Columns& v) {
    arrays.push_back({std::move(name), v.x, v.y});
  }
  /// The array of that name; null when absent.
  const ParcelPointArray* find(const std::string& name) const;
  /// Throws std::invalid_argument when a present array is not `count` long.
  void check_sizes() const;
};

/// Storage for the rows of a ParcelArraysView that kept_rows copies (reused between calls).
struct ParcelArraysCopy {
  std::vector<std::vector<double>> columns;
  std::vector<std::int32_t> id;
};

/// The rows of `all` whose flag in `drop` is 0 (a rank's own parcels, its copies of other ranks'
/// parcels left out), copied into `storage` in their order, as a view with the same arrays. An
/// empty `drop` keeps every row (still a copy).
ParcelArraysView kept_rows(const ParcelArraysView& all, std::span<const std::uint8_t> drop,
                           ParcelArraysCopy& storage);

}  // namespace dustlift
