#include "insitu/gas_cells.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dustlift {

void GasCellArrays::resize(std::size_t nx, std::size_t ny) {
  for (auto* a : {&density, &velocity_x, &velocity_y, &pressure, &temperature, &mach, &alpha_p,
                  &vorticity, &dust_concentration})
    a->resize(nx * ny);
}

namespace {
std::vector<double> midpoints(const std::vector<double>& nodes) {
  std::vector<double> c(nodes.empty() ? 0 : nodes.size() - 1);
  for (std::size_t i = 0; i < c.size(); ++i) c[i] = 0.5 * (nodes[i] + nodes[i + 1]);
  return c;
}
}  // namespace

std::vector<double> GasCellArrays::x_centers() const {
  return midpoints(x_nodes);
}
std::vector<double> GasCellArrays::y_centers() const {
  return midpoints(y_nodes);
}

void GasCellArrays::check_sizes() const {
  const std::pair<const char*, const std::vector<double>*> arrays[] = {
      {"density", &density},
      {"velocity_x", &velocity_x},
      {"velocity_y", &velocity_y},
      {"pressure", &pressure},
      {"temperature", &temperature},
      {"mach", &mach},
      {"alpha_p", &alpha_p},
      {"vorticity", &vorticity},
      {"dust_concentration", &dust_concentration}};
  for (const auto& [name, a] : arrays)
    if (a->size() != cells())
      throw std::invalid_argument(std::string("GasCellArrays: ") + name + " has " +
                                  std::to_string(a->size()) +
                                  " values, expected nx*ny = " + std::to_string(cells()));
}

void gather_gas_cells(const Grid2D& grid, const GasPrimitives& gas, const Field2D* alpha_p,
                      const Field2D& vorticity, const Field2D* dust_concentration,
                      const std::function<double(int, int)>& sound_speed, GasCellArrays& out) {
  if (!gas.rho || !gas.u || !gas.v || !gas.p || !gas.T || !gas.alpha_g)
    throw std::invalid_argument("gather_gas_cells: a primitive field is missing");
  if (vorticity.size() != grid.size_with_ghosts())
    throw std::invalid_argument("gather_gas_cells: the vorticity is not a field of this grid");
  if (dust_concentration != nullptr && dust_concentration->size() != grid.size_with_ghosts())
    throw std::invalid_argument(
        "gather_gas_cells: the dust concentration is not a field of this grid");
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
      out.vorticity[k] = vorticity(i, j);
      out.dust_concentration[k] = dust_concentration != nullptr ? (*dust_concentration)(i, j) : 0.0;
    }
  }
}

}  // namespace dustlift
