#pragma once
// Dust-surface height (paper section 3.2): per grid column, the height where the particle
// volume fraction alpha_p (deposited on the grid, eq. 12) falls below a threshold (1e-4 in
// the paper), reconstructed to sub-cell precision. Pure functions on plain arrays.
//
// Reconstruction (a VOF-style local height function): in the highest cell j of the column
// whose alpha_p exceeds the threshold, the dust is taken to fill the bottom fraction
// f = alpha_j / alpha_ref of the cell at the packing alpha_ref = max(alpha_j, alpha_{j-1})
// of the cell below, so h = face_j + f (face_{j+1} - face_j): a full top cell puts the
// surface at its top face, a half-filled one at mid-cell. For an undisturbed layer this is
// the layer top to well within 0.1 cell (interpolating alpha_p between cell centres instead
// put it near the first empty centre, half a cell too high). In a dilute cloud whose top
// cell holds about as much as the one below, f ~ 1 and the surface is that cell's top face;
// a faint cell on a packed one (alpha_j << alpha_{j-1}) reads near its bottom face: the
// height is resolved to one cell there, as the grid resolves the cloud.
#include <span>
#include <vector>

namespace dustlift {

/// Heights (m) of the nx columns. `alpha_p` holds nx*ny values, x fastest; `y_faces` the
/// ny+1 cell faces (increasing; the grid may be stretched). A column with no cell above the
/// threshold gets NaN. Zero is the y origin of the grid (the initial layer top in the paper
/// scene, whose floor is at y = -2 mm).
std::vector<double> dust_surface_height(std::span<const double> y_faces,
                                        std::span<const double> alpha_p, std::size_t nx,
                                        double threshold = 1e-4);

/// Surface height at station x by linear interpolation between the two neighbouring
/// column centres (the nearest column outside the range). NaN when a needed column is NaN.
double height_at_station(std::span<const double> x_centers, std::span<const double> heights,
                         double station_x);

}  // namespace dustlift
