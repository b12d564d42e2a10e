#pragma once
// Derivatives of cell-centred fields on a rectilinear (possibly stretched) grid: the
// out-of-plane vorticity w_z = dv/dx - du/dy (Magnus lift, output) and gradients (pressure
// force). 2nd order: 3-point Lagrange weights, central inside and one-sided at the edges.
#include <span>
#include <vector>

#include "solver/core/field.hpp"
#include "solver/core/grid.hpp"

namespace dustlift {

/// Derivative weights at centre k from the three centres (c0, c1, c2) of a quadratic
/// Lagrange fit; exact for any quadratic, so 2nd order on a stretched axis.
struct ThreePointWeights {
  double w0, w1, w2;
};
/// Weights for f'(at) given f at c0 < c1 < c2 (at is one of them).
ThreePointWeights derivative_weights(double c0, double c1, double c2, double at);

/// w_z = dv/dx - du/dy on the interior cells of Field2D u, v as nx*ny values, x fastest:
/// vorticity_z_rows over every row. Central 3-point differences inside, one-sided 3-point at
/// the boundaries (both 2nd order, exact for linear and quadratic fields); an axis with 2
/// cells uses the 2-point slope, an axis with 1 cell contributes no derivative.
std::vector<double> vorticity_z(const Grid2D& grid, const Field2D& u, const Field2D& v);

/// w_z and grad f on interior rows j0..j1-1 only (interior columns), written into Field2D
/// outputs (other cells untouched).
void vorticity_z_rows(const Grid2D& grid, const Field2D& u, const Field2D& v, int j0, int j1,
                      Field2D& out);
void gradient_rows(const Grid2D& grid, const Field2D& f, int j0, int j1, Field2D& dfdx,
                   Field2D& dfdy);

/// The row functions of the two above: interior cells [i0, i1) of row j only (the coupling
/// calls them on the cells its parcels read).
void vorticity_z_segment(const Grid2D& grid, const Field2D& u, const Field2D& v, int j, int i0,
                         int i1, Field2D& out);
void gradient_segment(const Grid2D& grid, const Field2D& f, int j, int i0, int i1, Field2D& dfdx,
                      Field2D& dfdy);

/// Interior cell centres of an axis.
std::vector<double> interior_centers(const Axis& axis);

}  // namespace dustlift
