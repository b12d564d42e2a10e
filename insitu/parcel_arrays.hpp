#pragma once
// Read-only views of parcel arrays (structure of arrays) for the writers and filters.
// VTK-free. A ParcelSystem adaptor points the spans at its own arrays: no copies.
#include <cstddef>
#include <span>

namespace dustlift {

/// A 2-D vector stored as two columns. Empty: absent (not written / not averaged).
struct Vec2Columns {
  std::span<const double> x, y;
  bool present() const { return !x.empty(); }
};

/// Parcel state for the .vtp writer, each array `count` long (optional ones may be empty).
struct ParcelArraysView {
  std::size_t count = 0;
  Vec2Columns position;                      ///< m (required)
  Vec2Columns velocity;                      ///< m/s
  std::span<const double> angular_velocity;  ///< rad/s, w_z
  std::span<const double> temperature;       ///< K
  std::span<const double> diameter;          ///< m
  Vec2Columns initial_position;              ///< m
  Vec2Columns force_contact;                 ///< N
  Vec2Columns force_drag;                    ///< N
  Vec2Columns force_magnus;                  ///< N
  Vec2Columns force_pressure;                ///< N (pressure-gradient force)
  /// Throws std::invalid_argument when a present array is not `count` long.
  void check_sizes() const;
};

}  // namespace dustlift
