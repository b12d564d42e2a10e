#pragma once
// The default width of the dust cloud's concentration filter (docs/dust-cloud.md): one parcel
// alone in a filter cell is a tenth of the explosible band's lower limit, where the channel
// above the layer is tall enough for such cells.
#include "solver/dem/dem_config.hpp"

namespace dustlift {

/// The share of the lower limit one parcel alone in a default-sized filter cell makes.
inline constexpr double kFilterQuantumShare = 0.1;

/// kg/m (per metre of span): the mass of the heaviest parcel the scene's layer makes (as the
/// layer generator fills it: real particles per parcel times the real particle's mass).
double largest_parcel_mass(const DemConfig& dem);

/// m: sqrt(parcel_mass / (kFilterQuantumShare lower)), at most `room` (the channel's height
/// above the layer top) when there is any.
double default_cloud_filter_width(double parcel_mass, double lower, double room);

}  // namespace dustlift
