#pragma once
// Layer files (`[particles.layer] arrangement = "file"`): parcels as CSV, so a packing from
// LIGGGHTS/LAMMPS or a few hand-placed parcels can start a run. Format (docs/dem.md):
//   # comment lines and blank lines anywhere
//   x,y,diameter,vx,vy,omega,temperature      <- header: x and y required, the rest optional
//                                                (and particle_diameter: a polydisperse layer)
//   0.0010,0.0010,100e-6,1.0,0,0,300          <- one parcel per line, SI units
// Errors throw SceneError "file:line:column: what is wrong" (columns count characters from 1).
#include <array>
#include <string>
#include <vector>

#include "solver/dem/dem_config.hpp"

namespace dustlift {

/// Where the parcels of a layer file may be and how large (checked per line).
struct ParcelFileLimits {
  double x_min = 0.0, x_max = 0.0, y_min = 0.0, y_max = 0.0;  ///< m, the grid: centres must lie in it
  double min_diameter = 0.0;  ///< m, the real particle diameter (n_xy >= 1, eq. 11)
  double max_diameter = 0.0;  ///< m, the smallest grid cell (unresolved-particle model)
};

/// Parses the text of a layer file named `name` (for messages). Optional columns take their
/// value from `defaults`. Checks syntax, numbers (finite), diameter and temperature > 0,
/// centres inside the grid and diameters within the limits.
std::vector<PlacedParcel> parse_parcel_file(const std::string& text, const std::string& name,
                                            const PlacedParcel& defaults, const ParcelFileLimits& limits);

/// Reads and parses the layer file at `path` (SceneError if it cannot be read).
std::vector<PlacedParcel> read_parcel_file(const std::string& path, const PlacedParcel& defaults,
                                           const ParcelFileLimits& limits);

}  // namespace dustlift
