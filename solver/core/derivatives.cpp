#include "solver/core/derivatives.hpp"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace dustlift {

ThreePointWeights derivative_weights(double c0, double c1, double c2, double at) {
  // d/dx of the Lagrange basis polynomials l_k(x) = prod_{m != k} (x - c_m)/(c_k - c_m).
  const double w0 = ((at - c1) + (at - c2)) / ((c0 - c1) * (c0 - c2));
  const double w1 = ((at - c0) + (at - c2)) / ((c1 - c0) * (c1 - c2));
  const double w2 = ((at - c0) + (at - c1)) / ((c2 - c0) * (c2 - c1));
  return {w0, w1, w2};
}

std::vector<double> interior_centers(const Axis& axis) {
  std::vector<double> c(static_cast<std::size_t>(axis.cells()));
  for (int i = 0; i < axis.cells(); ++i) c[static_cast<std::size_t>(i)] = axis.center(i);
  return c;
}

std::vector<double> vorticity_z(const Grid2D& grid, const Field2D& u, const Field2D& v) {
  Field2D w(grid);
  vorticity_z_rows(grid, u, v, 0, grid.ny(), w);
  std::vector<double> out(grid.interior_cells());
  for (int j = 0; j < grid.ny(); ++j)
    for (int i = 0; i < grid.nx(); ++i)
      out[static_cast<std::size_t>(i) + static_cast<std::size_t>(grid.nx()) * j] = w(i, j);
  return out;
}

namespace {

/// d f / d s along an axis at interior index k, f read through `at(m)` for interior m.
template <class At>
double axis_derivative(const Axis& a, int k, At at) {
  const int n = a.cells();
  if (n < 2) return 0.0;
  if (n == 2) return (at(1) - at(0)) / (a.center(1) - a.center(0));
  // The weights of the axis's centres, made once (Axis::derivative_stencil).
  const Axis::DerivativeStencil& w = a.derivative_stencil(k);
  // The weights sum to zero: written as differences, a uniform field gives exactly 0.
  const double f1 = at(w.first + 1);
  return w.w0 * (at(w.first) - f1) + w.w2 * (at(w.first + 2) - f1);
}

}  // namespace

void vorticity_z_segment(const Grid2D& g, const Field2D& u, const Field2D& v, int j, int i0, int i1,
                         Field2D& out) {
  for (int i = i0; i < i1; ++i) {
    const double dvdx = axis_derivative(g.x(), i, [&](int m) { return v(m, j); });
    const double dudy = axis_derivative(g.y(), j, [&](int m) { return u(i, m); });
    out(i, j) = dvdx - dudy;
  }
}

void gradient_segment(const Grid2D& g, const Field2D& f, int j, int i0, int i1, Field2D& dfdx,
                      Field2D& dfdy) {
  for (int i = i0; i < i1; ++i) {
    dfdx(i, j) = axis_derivative(g.x(), i, [&](int m) { return f(m, j); });
    dfdy(i, j) = axis_derivative(g.y(), j, [&](int m) { return f(i, m); });
  }
}

void vorticity_z_rows(const Grid2D& g, const Field2D& u, const Field2D& v, int j0, int j1,
                      Field2D& out) {
  j0 = std::max(j0, 0);
  j1 = std::min(j1, g.ny());
#pragma omp parallel for schedule(static) if ((j1 - j0) * g.nx() >= 32768)
  for (int j = j0; j < j1; ++j) vorticity_z_segment(g, u, v, j, 0, g.nx(), out);
}

void gradient_rows(const Grid2D& g, const Field2D& f, int j0, int j1, Field2D& dfdx,
                   Field2D& dfdy) {
  j0 = std::max(j0, 0);
  j1 = std::min(j1, g.ny());
#pragma omp parallel for schedule(static) if ((j1 - j0) * g.nx() >= 32768)
  for (int j = j0; j < j1; ++j) gradient_segment(g, f, j, 0, g.nx(), dfdx, dfdy);
}

}  // namespace dustlift
