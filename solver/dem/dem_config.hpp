#pragma once
// Settings of the DEM parcel system, as resolved from a scene (SI units).
// Owned by the DEM module; parsed in solver/scene/parse_particles.cpp.

namespace dustlift {

struct DemConfig {
  bool enabled = false;  ///< false: a gas-only scene, no parcel code runs
};

}  // namespace dustlift
