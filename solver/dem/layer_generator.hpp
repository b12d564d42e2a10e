#pragma once
// Dust layer generator: fills the layer rectangle with parcels at a target areal
// fraction, reproducibly from a seed and without initial overlaps (jittered lattice:
// the paper's 0.589 is looser than a jammed 2-D packing, so the layer is not in contact).
#include <cstdint>
#include <vector>

#include "solver/dem/dem_config.hpp"
#include "solver/dem/parcel_system.hpp"

namespace dustlift {

/// A rectangular lattice for the layer: rows x cols sites, pitch >= parcel diameter.
struct LayerLattice {
  std::int64_t n_parcels = 0;    ///< round(fraction * area / disc area)
  int rows = 0, cols = 0;
  double pitch_x = 0.0, pitch_y = 0.0;  ///< m
};

/// Chooses the lattice (the row count that maximises the smaller pitch).
/// Throws std::invalid_argument if the fraction cannot be placed without overlap
/// (above about pi/4 for a square-ish lattice) or the layer is thinner than a parcel.
LayerLattice plan_layer_lattice(const LayerConfig& layer, double parcel_d);

/// Parcel centres of the layer (x, y), in lattice order (row-major from the bottom left).
struct LayerPositions {
  LayerLattice lattice;
  std::vector<double> x, y;
};
LayerPositions generate_layer(const LayerConfig& layer, double parcel_d);

/// Builds the ParcelSystem of a scene: the generated layer at rest, real particles per
/// parcel from the config or derived (alpha_p area / (N V_p)), and settles it under
/// gravity when layer.settle is set.
ParcelSystem make_layer_system(const DemConfig& cfg);

/// Lets a bed settle under gravity g (m/s^2, downwards) until its kinetic energy per
/// parcel falls below `ke_per_parcel` J/m or `max_time` s has passed; then zeroes the
/// velocities. Returns the simulated time used.
double settle_under_gravity(ParcelSystem& system, double g, double ke_per_parcel, double max_time);

/// Uniform double in [0, 1) from a 64-bit state (splitmix64): portable, unlike the
/// standard distributions, so a seed gives the same layer on every platform.
double uniform_from_seed(std::uint64_t& state);

}  // namespace dustlift
