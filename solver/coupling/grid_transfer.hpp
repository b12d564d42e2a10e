#pragma once
// Moving quantities between the Eulerian grid and parcels.
//  - Interpolation (eq. 16, Fig. 2): a parcel lies in the quad of the four nearest cell
//    centres; the quad is split along its diagonal and the parcel's triangle gives area
//    (barycentric) weights c1..c4 that sum to one (one of them is zero). Linear fields are
//    reproduced exactly. Ghost cells take part, so wall boundary conditions shape the values
//    interpolated in the half cell next to a wall.
//  - Deposition (eqs. 12-15): a parcel's contribution goes to the cell holding its centre
//    (the paper's rule), or is spread over the cells overlapped by a square "domain of
//    influence" of side `influence_width` centred on the parcel (Table 2). Both conserve
//    the deposited sum exactly.
#include <array>
#include <cstddef>

#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"

namespace dustlift {

/// Four cells and weights (c1: (i, j), c2: (i+1, j), c3: (i, j+1), c4: (i+1, j+1)).
struct InterpolationStencil {
  int i = 0, j = 0;
  std::array<double, 4> weight{};
  /// The interpolated value; a uniform stencil gives its value exactly (weighted sums of
  /// equal values can be off in the last bit, and a gas at rest must look exactly at rest).
  double apply(const Field2D& f) const {
    const double a = f(i, j), b = f(i + 1, j), c = f(i, j + 1), d = f(i + 1, j + 1);
    if (a == b && a == c && a == d) return a;
    return weight[0] * a + weight[1] * b + weight[2] * c + weight[3] * d;
  }
};

enum class InterpolationRule { Triangle, Bilinear };

/// Stencil of point (x, y); points beyond the outermost interior centres use the ghost
/// layer (ghosts >= 1), points outside the grid are clamped to it.
InterpolationStencil interpolation_stencil(const Grid2D& g, double x, double y,
                                           InterpolationRule rule = InterpolationRule::Triangle);

/// Up to four (cell, fraction) pairs of a deposit; fractions sum to one.
struct DepositStencil {
  int count = 0;
  std::array<int, 4> i{}, j{};
  std::array<double, 4> fraction{};
};

/// influence_width <= 0: the cell holding (x, y) takes everything (eq. 12 literally).
/// Otherwise a square of that side is split by area over the interior cells it overlaps
/// (clipped at the domain edges so nothing is lost).
DepositStencil deposit_stencil(const Grid2D& g, double x, double y, double influence_width);

}  // namespace dustlift
