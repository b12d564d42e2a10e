#pragma once
// Read-only views of parcel arrays (structure of arrays) for the writers and filters.
// VTK-free. A ParcelSystem adaptor points the spans at its own arrays: no copies.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace dustlift {

/// A 2-D vector stored as two columns. Empty: absent (not written / not averaged).
struct Vec2Columns {
  std::span<const double> x, y;
  bool present() const { return !x.empty(); }
};

/// A further per-parcel array, written under its name (e.g. a written column of the table).
struct NamedParcelColumn {
  std::string name;
  std::span<const double> values;
};

/// Parcel state for the .vtp writer, each array `count` long (optional ones may be empty).
/// The point order is the parcel system's (it changes as the DEM re-sorts); `id` names each
/// parcel for good (ParaView: Temporal Particles To Pathlines follows it over time).
struct ParcelArraysView {
  std::size_t count = 0;
  Vec2Columns position;                      ///< m (required)
  std::span<const std::int32_t> id;          ///< stable parcel id
  Vec2Columns velocity;                      ///< m/s
  std::span<const double> angular_velocity;  ///< rad/s, w_z
  std::span<const double> temperature;       ///< K
  std::span<const double> diameter;          ///< m
  Vec2Columns initial_position;              ///< m
  Vec2Columns force_contact;                 ///< N
  Vec2Columns force_drag;                    ///< N
  Vec2Columns force_magnus;                  ///< N
  Vec2Columns force_pressure;                ///< N (pressure-gradient force)
  std::vector<NamedParcelColumn> extra;      ///< further scalar point arrays
  /// Throws std::invalid_argument when a present array is not `count` long.
  void check_sizes() const;
};

}  // namespace dustlift
