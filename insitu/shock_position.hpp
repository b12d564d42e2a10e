#pragma once
// Shock position from the pressure jump: the rightmost x where p exceeds
// p_ambient (1 + threshold), refined by linear interpolation of p between that cell
// centre and the next one downstream (a shock moving towards +x into gas at rest).
#include <span>

#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"

namespace dustlift {

/// On one row: x_centers (n) and p (n). `p_ambient` <= 0 takes the row's last
/// (downstream) value. NaN when no cell exceeds the level, or when the last cell does (the
/// shock has left the domain: no undisturbed gas ahead of it).
double shock_position_on_row(std::span<const double> x_centers, std::span<const double> p,
                             double p_ambient, double threshold);

/// Max of shock_position_on_row over the rows whose centre y >= y_min (pressure nx*ny,
/// x fastest). NaN when no row has a shock.
double shock_position(std::span<const double> x_centers, std::span<const double> y_centers,
                      std::span<const double> pressure, double p_ambient, double threshold,
                      double y_min);

/// The same, read in place from a cell field with ghosts on `grid` (whose interior centres
/// x_centers and y_centers are): the observers that follow the shock every step then copy
/// no field.
double shock_position(const Grid2D& grid, const Field2D& pressure,
                      std::span<const double> x_centers, std::span<const double> y_centers,
                      double p_ambient, double threshold, double y_min);

}  // namespace dustlift
