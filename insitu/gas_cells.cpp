#include "insitu/gas_cells.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "solver/core/derivatives.hpp"

namespace dustlift {

void GasCellArrays::resize(std::size_t nx, std::size_t ny) {
  for (auto* a : {&density, &velocity_x, &velocity_y, &pressure, &temperature, &mach, &alpha_p,
                  &vorticity})
    a->resize(nx * ny);
}

namespace {
std::vector<double> midpoints(const std::vector<double>& nodes) {
  std::vector<double> c(nodes.empty() ? 0 : nodes.size() - 1);
  for (std::size_t i = 0; i < c.size(); ++i) c[i] = 0.5 * (nodes[i] + nodes[i + 1]);
  return c;
}
}  // namespace

std::vector<double> GasCellArrays::x_centers() const { return midpoints(x_nodes); }
std::vector<double> GasCellArrays::y_centers() const { return midpoints(y_nodes); }

void GasCellArrays::check_sizes() const {
  const std::pair<const char*, const std::vector<double>*> arrays[] = {
      {"density", &density},         {"velocity_x", &velocity_x}, {"velocity_y", &velocity_y},
      {"pressure", &pressure},       {"temperature", &temperature}, {"mach", &mach},
      {"alpha_p", &alpha_p},         {"vorticity", &vorticity}};
  for (const auto& [name, a] : arrays)
    if (a->size() != cells())
      throw std::invalid_argument(std::string("GasCellArrays: ") + name + " has " +
                                  std::to_string(a->size()) + " values, expected nx*ny = " +
                                  std::to_string(cells()));
}

void gather_gas_cells(const Grid2D& grid, const GasPrimitives& gas, const Field2D* alpha_p,
                      const std::function<double(int, int)>& sound_speed, GasCellArrays& out,
                      int ghosts_left, int ghosts_right) {
  if (ghosts_left < 0 || ghosts_right < 0 || ghosts_left > 1 || ghosts_right > 1 ||
      std::max(ghosts_left, ghosts_right) > grid.ghosts())
    throw std::invalid_argument("gather_gas_cells: ghosts_left/right must be 0 or 1");
  if (!gas.rho || !gas.u || !gas.v || !gas.p || !gas.T || !gas.alpha_g)
    throw std::invalid_argument("gather_gas_cells: a primitive field is missing");
  out.x_nodes = grid.x().interior_faces();
  out.y_nodes = grid.y().interior_faces();
  const int nx = grid.nx(), ny = grid.ny();
  out.resize(static_cast<std::size_t>(nx), static_cast<std::size_t>(ny));
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * j;
      const double u = (*gas.u)(i, j), v = (*gas.v)(i, j);
      out.density[k] = (*gas.rho)(i, j);
      out.velocity_x[k] = u;
      out.velocity_y[k] = v;
      out.pressure[k] = (*gas.p)(i, j);
      out.temperature[k] = (*gas.T)(i, j);
      out.alpha_p[k] = alpha_p != nullptr ? (*alpha_p)(i, j) : 1.0 - (*gas.alpha_g)(i, j);
      out.mach[k] = std::hypot(u, v) / sound_speed(i, j);
    }
  }
  if (ghosts_left == 0 && ghosts_right == 0) {
    vorticity_z(out.x_centers(), out.y_centers(), out.velocity_x, out.velocity_y, out.vorticity);
    return;
  }
  // The columns widened by the ghosts (the faces beyond a cut are the whole grid's).
  const int wide = nx + ghosts_left + ghosts_right;
  std::vector<double> xc(static_cast<std::size_t>(wide));
  std::vector<double> u(static_cast<std::size_t>(wide) * ny), v(u.size()), w(u.size());
  for (int i = 0; i < wide; ++i) {
    const int gi = i - ghosts_left;
    xc[static_cast<std::size_t>(i)] = 0.5 * (grid.x().face(gi) + grid.x().face(gi + 1));
  }
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < wide; ++i) {
      const std::size_t k = static_cast<std::size_t>(i) + static_cast<std::size_t>(wide) * j;
      u[k] = (*gas.u)(i - ghosts_left, j);
      v[k] = (*gas.v)(i - ghosts_left, j);
    }
  }
  vorticity_z(xc, out.y_centers(), u, v, w);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      out.vorticity[static_cast<std::size_t>(i) + static_cast<std::size_t>(nx) * j] =
          w[static_cast<std::size_t>(i + ghosts_left) + static_cast<std::size_t>(wide) * j];
    }
  }
}

}  // namespace dustlift
