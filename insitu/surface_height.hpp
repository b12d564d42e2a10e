#pragma once
// Dust-surface height (paper section 3.2): per grid column, the highest y where the
// particle volume fraction alpha_p exceeds a threshold (1e-4 in the paper), located by
// linear interpolation of alpha_p between cell centres. Pure functions on plain arrays.
#include <span>
#include <vector>

namespace dustlift {

/// Heights (m) of the nx columns. `alpha_p` holds nx*ny values, x fastest; `y_centers`
/// the ny cell-centre heights (increasing). A column with no cell above the threshold gets
/// NaN. If the top cell itself exceeds the threshold the height is its centre (the
/// surface is not resolved above the last centre).
std::vector<double> dust_surface_height(std::span<const double> y_centers,
                                        std::span<const double> alpha_p, std::size_t nx,
                                        double threshold = 1e-4);

/// Surface height at station x by linear interpolation between the two neighbouring
/// column centres (the nearest column outside the range). NaN when a needed column is NaN.
double height_at_station(std::span<const double> x_centers, std::span<const double> heights,
                         double station_x);

}  // namespace dustlift
