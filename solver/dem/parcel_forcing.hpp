#pragma once
// What moves the parcels besides their contacts and gravity: a forcing another module composes
// (the coupling's gas-particle effects, solver/coupling/effects/) and hands to the parcel
// system. The DEM runs its sub-steps through it; with none set it integrates contacts and
// gravity alone.
#include <cstddef>

namespace dustlift {

class ParcelSystem;

class ParcelForcing {
 public:
  virtual ~ParcelForcing() = default;
  /// One symplectic Euler sub-step of dt of the parcels [0, n) of `parcels` under their
  /// contact forces (computed for this sub-step), gravity and this forcing, through
  /// forced_euler (forced_euler.hpp). `store`: write the force parts for the observers.
  /// Returns the largest squared displacement since the last neighbour build in units of
  /// each parcel's skin (above 1 the list must be rebuilt).
  virtual double substep(ParcelSystem& parcels, std::size_t n, double dt, bool store) const = 0;
};

}  // namespace dustlift
